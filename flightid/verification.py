"""Time-domain verification of identified models (§3.3.6).

Drive the identified model with measured inputs (e.g. the loads of a doublet
run, not used in the identification) and compare its outputs with the measured
outputs: Theil inequality coefficient (TIC) and RMS error per output.
Guidelines (Tischler & Remple): TIC < 0.25-0.3 acceptable; J_rms < 1-2.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd
import control
from matplotlib.figure import Figure

from ._validation import names_in, real_array
from .errors import DataError, SignalNameError
from .structures import ModelStructure

__all__ = ["verify", "VerificationResult", "theil_inequality"]


def theil_inequality(predicted, measured):
    """TIC = rms(p - m) / (rms(p) + rms(m)); 0 is a perfect match, 1 the worst."""
    p = real_array("predicted", predicted)
    m = real_array("measured", measured)
    if p.shape != m.shape or p.size == 0:
        raise DataError(f"predicted and measured must be non-empty and of one shape, got "
                        f"{p.shape} and {m.shape}")
    den = np.sqrt(np.mean(p ** 2)) + np.sqrt(np.mean(m ** 2))
    if den == 0:
        return 0.0
    return float(np.sqrt(np.mean((p - m) ** 2)) / den)


@dataclass
class VerificationResult:
    """Measured vs predicted outputs with per-output metrics (``metrics`` DataFrame)."""

    t: np.ndarray
    measured: np.ndarray
    predicted: np.ndarray
    output_names: list
    metrics: pd.DataFrame

    def to_pandas(self) -> pd.DataFrame:
        return self.metrics.copy()

    def plot(self, fig=None):
        """Overlay of measured and predicted outputs; returns a Figure."""
        n = len(self.output_names)
        if fig is None:
            fig = Figure(figsize=(8, 2.0 * n), constrained_layout=True)
        axes = fig.subplots(n, 1, squeeze=False, sharex=True)[:, 0]
        for k, name in enumerate(self.output_names):
            axes[k].plot(self.t, self.measured[k], "k-", label="measured")
            axes[k].plot(self.t, self.predicted[k], "r--", label="model")
            tic = self.metrics.loc[k, "TIC"]
            axes[k].set_ylabel(name)
            axes[k].set_title(f"{name}: TIC = {tic:.3f}", fontsize=9)
            axes[k].grid(alpha=0.3)
        axes[0].legend(fontsize=8)
        axes[-1].set_xlabel("t [s]")
        return fig


def _signals(kind, data, names):
    """(n_signals, n) float array from a DataFrame (columns ``names``) or an array."""
    if isinstance(data, pd.DataFrame):
        names_in(f"{kind} column", names, data.columns)
        data = data[names].to_numpy().T
    elif isinstance(data, pd.Series):
        data = data.to_numpy()
    return np.atleast_2d(real_array(kind, data))


def verify(model, t, inputs, outputs, *, input_names=None, output_names=None,
           remove_initial=True) -> VerificationResult:
    """Simulate ``model`` with measured ``inputs`` and compare with ``outputs``.

    Parameters
    ----------
    model : control.StateSpace / LTI or ModelStructure
        Identified model (a structure is converted with Padé delays).
    t : array_like
        Uniform time [s].
    inputs : array_like (n_inputs, n) or DataFrame
        Measured model inputs (perturbations, or absolute with ``remove_initial``).
    outputs : array_like (n_outputs, n) or DataFrame
        Measured outputs.
    input_names, output_names : list of str, optional
        With DataFrames, the columns to use (default: the model's signal names).
    remove_initial : bool
        Subtract each signal's initial (trim) value first.

    Returns
    -------
    VerificationResult

    Examples
    --------
    >>> import numpy as np, control
    >>> from flightid import frequency_sweep, frequency_response
    >>> t, u = frequency_sweep(0.5, 20.0, 60.0, 0.01, seed=0)
    >>> y = control.forced_response(control.tf([4.0], [1.0, 2.0]), t, u).outputs     # 4 / (s + 2)
    >>> data = frequency_response(t, u, y, w_min=0.5, w_max=20.0, output_names=["y"])
    >>> from flightid import FGCStructure, fit, verify
    >>> structure = FGCStructure([["f"]], [["g"]], [[1.0]], inputs=["u"], outputs=["y"],
    ...                          initial={"f": -1.0, "g": 1.0})
    >>> check = verify(fit(structure, data).structure, t, u[None], y[None])
    >>> bool(check.metrics.TIC.iloc[0] < 0.05)          # Theil inequality: 0 is a perfect match
    True
    """
    if isinstance(model, ModelStructure):
        model = model.to_statespace()
    if not isinstance(model, control.LTI):
        raise DataError(f"model must be a python-control LTI system or a ModelStructure, got "
                        f"{type(model).__name__}")
    if not model.isctime():
        raise DataError("model must be continuous-time (dt = 0)")
    if isinstance(model, control.StateSpace) and not all(
            np.all(np.isfinite(np.asarray(m, float))) for m in (model.A, model.B, model.C, model.D)):
        raise DataError("model matrices contain NaN or infinite values")
    t = real_array("t", t)
    if t.ndim != 1 or t.size < 2:
        raise DataError(f"t must be a 1-D array of at least 2 samples [s], got shape {t.shape}")
    input_names = list(input_names) if input_names else list(model.input_labels)
    output_names = list(output_names) if output_names else list(model.output_labels)
    if len(input_names) != model.ninputs:
        raise SignalNameError(f"{len(input_names)} input names {input_names} for a model with "
                              f"{model.ninputs} inputs {list(model.input_labels)}")
    if len(output_names) != model.noutputs:
        raise SignalNameError(f"{len(output_names)} output names {output_names} for a model with "
                              f"{model.noutputs} outputs {list(model.output_labels)}")
    u = _signals("inputs", inputs, input_names)
    z = _signals("outputs", outputs, output_names)
    if u.shape != (model.ninputs, t.size):
        raise DataError(f"inputs must be ({model.ninputs}, {t.size}), got {u.shape}")
    if z.shape != (model.noutputs, t.size):
        raise DataError(f"outputs must be ({model.noutputs}, {t.size}), got {z.shape}")
    steps = np.diff(t)
    if steps.min() <= 0 or np.max(np.abs(steps - steps.mean())) > 1e-6 * steps.mean():
        raise DataError("t must be increasing and uniformly sampled [s]")
    if remove_initial:
        u = u - u[:, :1]
        z = z - z[:, :1]
    sim = control.forced_response(model, t, u)
    y = np.atleast_2d(sim.outputs)
    if not np.all(np.isfinite(y)):
        raise DataError("the model's simulated outputs are not finite: the model is unstable "
                        "or numerically ill-conditioned (check its poles)")
    rows = []
    for k, name in enumerate(output_names):
        err = y[k] - z[k]
        rows.append({"output": name, "TIC": theil_inequality(y[k], z[k]),
                     "rms_error": float(np.sqrt(np.mean(err ** 2))),
                     "rms_measured": float(np.sqrt(np.mean(z[k] ** 2)))})
    return VerificationResult(t, z, y, output_names, pd.DataFrame(rows))
