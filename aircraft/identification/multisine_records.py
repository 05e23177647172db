"""Multisine records of :func:`aircraft.identification.identify_inflow_multisine`.

The excited controls are divided between one or more records marched side by
side; each record is an orthogonal multisine of its own controls
(:class:`aircraft.wake.MultisineSpec`). The frequency response of every control
comes from the record that excites it (:func:`flightid.mimo_response` on that
record's controls), and the columns are assembled into the full
control-to-signal matrix in the order of the excited controls, ready for
:func:`flightid.joint_input_output`.
"""
from __future__ import annotations

__all__ = ["split_controls", "record_responses"]


def split_controls(controls, records):
    """Divide ``controls`` between ``records`` records, as evenly as possible.

    Controls are dealt out in turn (the first to record 0, the second to record 1,
    ...), so upper- and lower-rotor controls and swashplate and tip-path-plane
    inputs spread over the records.

    Parameters
    ----------
    controls : sequence of str
        Excited controls (unique names).
    records : int
        Number of records, between 1 and ``len(controls)``.

    Returns
    -------
    list of tuple of str
        The controls of each record, in their order in ``controls``.

    Raises
    ------
    ValueError
        ``records`` is not a whole number in ``[1, len(controls)]``.

    Examples
    --------
    >>> split_controls(["a", "b", "c", "d", "e"], 2)
    [('a', 'c', 'e'), ('b', 'd')]
    >>> split_controls(["a", "b"], 1)
    [('a', 'b')]
    """
    controls = list(controls)
    if isinstance(records, bool) or not isinstance(records, int) or not 1 <= records <= len(controls):
        raise ValueError(f"records must be a whole number from 1 to the {len(controls)} excited controls, "
                         f"got {records!r}")
    return [tuple(controls[k::records]) for k in range(records)]


def record_responses(records, signals, *, w_min, w_max, order=None):
    """Control-to-signal frequency responses assembled from several multisine records.

    Parameters
    ----------
    records : sequence of (pandas.DataFrame, sequence of str)
        Each record's time history (column ``"t"`` [s], the controls [rad] and the
        signals) and the controls it excites. Every control must be excited by
        exactly one record.
    signals : sequence of str
        Output signals (columns of every record).
    w_min, w_max : float
        Frequency range [rad/s] (:func:`flightid.mimo_response`).
    order : sequence of str, optional
        Input order of the result (default: the records' controls in turn).

    Returns
    -------
    flightid.MeasuredResponse
        Shape ``(len(signals), n_controls, n_freq)``: each column from the
        record that excites that control (perturbations about the record's first
        sample), with its partial coherence.

    Raises
    ------
    ValueError
        No records, or a control excited by more than one record, or ``order``
        not a permutation of the excited controls.
    flightid.errors.SingularInputError
        A record's inputs cannot be separated.

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> t = np.arange(0, 40, 0.01)
    >>> u = np.sin(1.3 * t) + np.sin(4.1 * t)
    >>> df = pd.DataFrame({"t": t, "a": u, "y": 2 * u})
    >>> r = record_responses([(df, ["a"])], ["y"], w_min=2.0, w_max=5.0)
    >>> r.input_labels, bool(np.allclose(abs(r.frdata[0, 0]), 2.0, rtol=1e-6))
    (['a'], True)
    """
    from flightid import combine_responses, mimo_response
    records = list(records)
    if not records:
        raise ValueError("records must hold at least one (DataFrame, controls) pair")
    signals = list(signals)
    excited = [c for _, controls in records for c in controls]
    if len(set(excited)) != len(excited):
        raise ValueError(f"records must excite each control once, got {excited}")
    order = excited if order is None else list(order)
    if sorted(order) != sorted(excited):
        raise ValueError(f"order must be a permutation of the excited controls {excited}, got {order}")
    parts = []
    for df, controls in records:
        controls = list(controls)
        y = (df[signals] - df[signals].iloc[0]).to_numpy()
        u = (df[controls] - df[controls].iloc[0]).to_numpy()
        parts.append(mimo_response(df["t"].to_numpy(), u, y, w_min=w_min, w_max=w_max,
                                   input_names=controls, output_names=signals))
    # one record: its MIMOResponse as it is (multiple/input coherence kept)
    measured = parts[0] if len(parts) == 1 else combine_responses(parts)
    return measured if order == excited else measured.select(inputs=order)
