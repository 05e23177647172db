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

from .errors import DataError
from .structures import ModelStructure

__all__ = ["verify", "VerificationResult", "theil_inequality"]


def theil_inequality(predicted, measured):
    """TIC = rms(p - m) / (rms(p) + rms(m)); 0 is a perfect match, 1 the worst."""
    p = np.asarray(predicted, float)
    m = np.asarray(measured, float)
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
    """
    if isinstance(model, ModelStructure):
        model = model.to_statespace()
    t = np.asarray(t, float)
    input_names = input_names or list(model.input_labels)
    output_names = output_names or list(model.output_labels)
    u = inputs[input_names].to_numpy().T if isinstance(inputs, pd.DataFrame) else np.atleast_2d(np.asarray(inputs, float))
    z = outputs[output_names].to_numpy().T if isinstance(outputs, pd.DataFrame) else np.atleast_2d(np.asarray(outputs, float))
    if u.shape != (model.ninputs, t.size):
        raise DataError(f"inputs must be ({model.ninputs}, {t.size}), got {u.shape}")
    if z.shape != (model.noutputs, t.size):
        raise DataError(f"outputs must be ({model.noutputs}, {t.size}), got {z.shape}")
    if not (np.all(np.isfinite(u)) and np.all(np.isfinite(z))):
        raise DataError("inputs/outputs contain NaN or infinite values")
    steps = np.diff(t)
    if np.max(np.abs(steps - steps.mean())) > 1e-6 * steps.mean():
        raise DataError("t must be uniformly sampled")
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
