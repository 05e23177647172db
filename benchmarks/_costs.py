"""What the identification benchmarks share: one model's cost on another experiment's data."""
import numpy as np

__all__ = ["cost_on"]


def cost_on(structure, data, cost_table):
    """J_ave of a fitted ``structure`` against ``data`` over the pairs and bands of ``cost_table``.

    The cost is taken on the data's own frequency points in each band: the same rule
    for every model/data combination, so such J_ave are comparable with each other,
    though not with a fit's log-grid J.

    Parameters
    ----------
    structure : flightid structure
        A fitted structure (``frequency_response(omega)``, ``inputs``, ``outputs``).
    data : flightid.MeasuredResponse
        The measured responses (``element(output, input)`` -> response, coherence).
    cost_table : pandas.DataFrame
        The cost table of an identified model: rows with ``output``, ``input``,
        ``w_min``, ``w_max`` [rad/s].

    Returns
    -------
    float
        Mean CIFER cost over the table's pairs.
    """
    from flightid import cifer_cost
    costs = []
    for row in cost_table.itertuples():
        h, coh = data.element(row.output, row.input)
        band = (data.omega >= row.w_min) & (data.omega <= row.w_max)
        hm = structure.frequency_response(data.omega[band])
        i, j = structure.outputs.index(row.output), structure.inputs.index(row.input)
        costs.append(cifer_cost(hm[i, j], h[band], coh[band]))
    return float(np.mean(costs))
