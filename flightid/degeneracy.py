"""What the CIFER cost cannot see: flat directions, rank-deficient blocks, start dependence.

A fit can reach a small J and still be meaningless (§6.4; found on a coaxial
hover fit): a direction in parameter space along which J does not change (the
parameters move together, their Cramér-Rao bounds are huge, the optimum is not
unique), a square block of the response matrix whose small singular value the
element-wise cost ignores, or an optimum that depends on the start. This
module computes the reports :func:`flightid.fit` attaches to its result:

* :class:`DegeneracyReport` -- conditioning of the Gauss-Newton Hessian
  ``H = 2 Jr^T Jr`` in *relative* parameter units (``D H D``, ``D = diag|theta|``,
  so a direction "all collective M and Lbar scaled together" has equal
  components), its flat directions with the parameters that move together,
  parameters with no influence at all, and for square blocks the model's and
  the data's singular-value ratios ``sigma_min / sigma_max`` over frequency;
* :class:`MultiStartReport` -- costs and parameters reached from several
  seeded starts, and whether they agree.

:class:`NoInformationError` is raised when the data hold no information for a
fit (no coherent point).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from .errors import IdentificationError

__all__ = ["NoInformationError", "DegeneracyReport", "MultiStartReport", "FLAT_RATIO",
           "FLAT_CR_PCT", "SV_RATIO_MIN", "SV_RATIO_MISMATCH"]

#: A Hessian eigenvalue below ``FLAT_RATIO`` times the largest (relative units)
#: spans a flat direction. Rounding of the central-difference Jacobian puts an
#: exact redundancy near 1e-16..1e-20; a degenerate coaxial hover fit
#: sat at 1e-13; well-posed fits of up to ~50 parameters stay above ~1e-9.
FLAT_RATIO = 1e-10
#: ... or one along which the relative Cramér-Rao bound exceeds 10,000 %
#: (the parameters may move by 100 times their size at the 2-sigma level).
FLAT_CR_PCT = 1e4
#: A square data block with ``sigma_min / sigma_max`` below this is nearly rank
#: deficient: the element-wise cost does not constrain its small singular value.
SV_RATIO_MIN = 0.1
#: Model and data singular-value ratios differing by more than this factor at
#: some frequency: the model's block has a different rank structure.
SV_RATIO_MISMATCH = 2.0


class NoInformationError(IdentificationError):
    """The data carry no information for the fit (no coherent point in any response)."""


def _relative_scale(values):
    """Per-parameter unit for relative perturbations: |theta|, or 1 where theta = 0."""
    v = np.abs(np.asarray(values, dtype=float))
    return np.where(v > 0, v, 1.0)


@dataclass
class DegeneracyReport:
    """Flat directions and singular-value ratios of a fit (attached to ``FitResult``).

    Attributes
    ----------
    parameters : list of str
        Free parameters, in Hessian order.
    eigenvalues : ndarray
        Eigenvalues of the relative-unit Hessian ``D H D``, ascending.
    eigenvectors : ndarray
        Matching unit eigenvectors (columns), relative units.
    condition_number : float
        ``lambda_max / lambda_min`` of ``D H D`` (inf when singular).
    flat_directions : DataFrame
        One row per flat direction: ``eigenvalue_ratio`` (lambda / lambda_max),
        ``cramer_rao_pct`` (relative bound along the direction, %), ``parameters``
        (the names that move together, largest share first, as "+a -b"), and
        ``components`` (dict name -> component).
    no_influence : list of str
        Parameters whose Jacobian column is zero: the fitted responses do not
        depend on them at all.
    singular_values : DataFrame
        For every square block checked: block, omega [rad/s], ``sv_ratio_data``,
        ``sv_ratio_model``.
    warnings : list of str
        Human-readable findings (empty when nothing is degenerate).
    """

    parameters: list
    eigenvalues: np.ndarray
    eigenvectors: np.ndarray
    condition_number: float
    flat_directions: pd.DataFrame
    no_influence: list = field(default_factory=list)
    singular_values: pd.DataFrame = field(default_factory=lambda: pd.DataFrame(
        columns=["block", "omega", "sv_ratio_data", "sv_ratio_model"]))
    warnings: list = field(default_factory=list)

    @property
    def is_degenerate(self) -> bool:
        """True when there is a flat direction or a parameter without influence."""
        return bool(len(self.flat_directions) or self.no_influence)

    def to_pandas(self) -> pd.DataFrame:
        """The flat-direction table."""
        return self.flat_directions.copy()

    def summary(self) -> str:
        lines = [f"Hessian condition number (relative units): {self.condition_number:.3g}"]
        if not self.warnings:
            lines.append("no flat direction, no rank-deficient square block")
        lines += self.warnings
        return "\n".join(lines)

    def plot(self, fig=None):
        """Singular-value ratios of model and data over frequency, one axis per block."""
        from matplotlib.figure import Figure
        blocks = list(dict.fromkeys(self.singular_values.block)) if len(self.singular_values) else []
        if fig is None:
            fig = Figure(figsize=(4.5 * max(1, len(blocks)), 3.2), constrained_layout=True)
        axes = fig.subplots(1, max(1, len(blocks)), squeeze=False)[0]
        for ax, b in zip(axes, blocks):
            t = self.singular_values[self.singular_values.block == b]
            ax.loglog(t.omega, t.sv_ratio_data, "-", label="data")
            ax.loglog(t.omega, t.sv_ratio_model, "--", label="model")
            ax.axhline(SV_RATIO_MIN, color="0.6", lw=0.8)
            ax.set_title(b, fontsize=8)
            ax.set_xlabel("omega [rad/s]")
            ax.set_ylabel("sigma_min / sigma_max")
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=7)
        return fig


def hessian_report(jac, names, values, *, flat_ratio=FLAT_RATIO, flat_cr_pct=FLAT_CR_PCT):
    """Eigen-analysis of ``H = 2 Jr^T Jr`` in relative parameter units.

    Parameters
    ----------
    jac : ndarray (n_residuals, n_free)
        Jacobian of the weighted CIFER residuals (``J_sum = sum r^2``).
    names : list of str
    values : array_like
        Fitted parameter values (define the relative units).
    flat_ratio, flat_cr_pct : float
        Flatness criteria (see :data:`FLAT_RATIO`, :data:`FLAT_CR_PCT`).

    Returns
    -------
    DegeneracyReport
        Without singular-value ratios (see :func:`block_singular_values`).
    """
    names = list(names)
    d = _relative_scale(values)
    col = np.linalg.norm(jac, axis=0)
    # a column exactly (or to rounding) zero: J does not depend on the parameter
    ref = np.max(col * d) if col.size else 0.0
    no_influence = [n for n, c, dk in zip(names, col, d) if not c * dk > 1e-12 * ref]
    h = 2.0 * (jac * d[None, :]).T @ (jac * d[None, :])
    eigval, eigvec = np.linalg.eigh(h)
    eigval = np.maximum(eigval, 0.0)          # rounding can give tiny negatives
    lmax = eigval.max() if eigval.size else 0.0
    cond = float(lmax / eigval.min()) if eigval.size and eigval.min() > 0 else np.inf
    rows, warnings = [], []
    for k in range(eigval.size):
        ratio = eigval[k] / lmax if lmax > 0 else 0.0
        cr = 200.0 / np.sqrt(eigval[k]) if eigval[k] > 0 else np.inf
        if not (ratio < flat_ratio or cr > flat_cr_pct):
            continue
        v = eigvec[:, k] / np.max(np.abs(eigvec[:, k]))
        order = np.argsort(-np.abs(v))
        movers = [i for i in order if abs(v[i]) >= 0.2]
        text = " ".join(f"{'+' if v[i] > 0 else '-'}{names[i]}" for i in movers)
        rows.append({"eigenvalue_ratio": ratio, "cramer_rao_pct": cr, "parameters": text,
                     "components": {names[i]: float(v[i]) for i in movers}})
        warnings.append(f"flat direction (eigenvalue ratio {ratio:.2g}, relative CR {cr:.3g} %): "
                        f"{text} move together; J cannot tell them apart")
    if no_influence:
        warnings.insert(0, f"parameters with no influence on the fitted responses: {no_influence}")
    flat = pd.DataFrame(rows, columns=["eigenvalue_ratio", "cramer_rao_pct", "parameters", "components"])
    return DegeneracyReport(names, eigval, eigvec, cond, flat, no_influence, warnings=warnings)


def square_components(pairs):
    """Square blocks formed by the connected components of the fitted (output, input) pairs.

    Two pairs are connected when they share an output or an input; a component
    with as many outputs as inputs (at least two) is returned as
    ``(outputs, inputs)``.
    """
    pairs = list(pairs)
    parent = {}

    def find(a):
        while parent.setdefault(a, a) != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    for o, u in pairs:
        parent[find(("o", o))] = find(("i", u))
    groups = {}
    for o, u in pairs:
        g = groups.setdefault(find(("o", o)), ([], []))
        if o not in g[0]:
            g[0].append(o)
        if u not in g[1]:
            g[1].append(u)
    return [g for g in groups.values() if len(g[0]) == len(g[1]) >= 2]


def block_singular_values(structure, element, blocks, ranges, n_points=30):
    """Model and data ``sigma_min / sigma_max`` of square blocks over frequency.

    Parameters
    ----------
    structure : ModelStructure
        The fitted structure.
    element : callable (output, input, omega) -> complex ndarray or None
        The measured response of one pair on a frequency grid (None if absent).
    blocks : list of (outputs, inputs)
    ranges : dict {(output, input): (w_lo, w_hi)}
        Fitted frequency ranges; a block is checked over the intersection of
        its elements' ranges (the whole data range for unfitted elements).
    n_points : int
        Log-spaced frequencies per block.

    Returns
    -------
    (DataFrame, list of str)
        The table (block, omega, sv_ratio_data, sv_ratio_model) and warnings.
    """
    rows, warnings = [], []
    for outputs, inputs in blocks:
        outputs, inputs = list(outputs), list(inputs)
        if len(outputs) != len(inputs):
            raise IdentificationError(f"block {outputs} x {inputs} is not square")
        label = f"[{', '.join(outputs)}] / [{', '.join(inputs)}]"
        spans = [ranges[(o, u)] for o in outputs for u in inputs if (o, u) in ranges]
        if not spans:
            continue
        lo, hi = max(s[0] for s in spans), min(s[1] for s in spans)
        if not lo < hi:
            continue
        w = np.geomspace(lo, hi, n_points)
        data = np.zeros((len(outputs), len(inputs), w.size), dtype=complex)
        for a, o in enumerate(outputs):
            for b, u in enumerate(inputs):
                h = element(o, u, w)
                if h is None:
                    raise IdentificationError(f"square block {label}: the data lack {o}/{u}")
                data[a, b] = h
        oi = [structure.outputs.index(o) for o in outputs]
        ii = [structure.inputs.index(u) for u in inputs]
        model = structure.frequency_response(w)[np.ix_(oi, ii)]
        sv_d = np.linalg.svd(np.moveaxis(data, -1, 0), compute_uv=False)
        sv_m = np.linalg.svd(np.moveaxis(model, -1, 0), compute_uv=False)
        rd = sv_d[:, -1] / np.maximum(sv_d[:, 0], 1e-300)
        rm = sv_m[:, -1] / np.maximum(sv_m[:, 0], 1e-300)
        for k in range(w.size):
            rows.append({"block": label, "omega": w[k], "sv_ratio_data": rd[k], "sv_ratio_model": rm[k]})
        if np.min(rd) < SV_RATIO_MIN:
            k = int(np.argmin(rd))
            warnings.append(f"square block {label} is nearly rank-deficient in the data "
                            f"(sigma_min/sigma_max = {rd[k]:.3g} at {w[k]:.3g} rad/s): the element-wise "
                            "cost does not constrain its small singular value")
        mismatch = np.abs(np.log(np.maximum(rm, 1e-300) / np.maximum(rd, 1e-300)))
        if np.max(mismatch) > np.log(SV_RATIO_MISMATCH):
            k = int(np.argmax(mismatch))
            warnings.append(f"square block {label}: model sigma_min/sigma_max = {rm[k]:.3g} vs data "
                            f"{rd[k]:.3g} at {w[k]:.3g} rad/s (factor > {SV_RATIO_MISMATCH:g})")
    table = pd.DataFrame(rows, columns=["block", "omega", "sv_ratio_data", "sv_ratio_model"])
    return table, warnings


@dataclass
class MultiStartReport:
    """Outcome of a multi-start fit (``fit(..., starts=N, seed=...)``).

    Attributes
    ----------
    table : DataFrame
        One row per start: start, J_ave (NaN if the start failed), success,
        best (bool), note, and one column per free parameter.
    cost_spread : float
        Largest minus smallest J_ave over the starts that converged.
    parameter_spread : Series
        Per parameter, (max - min) / |best value| over converged starts.
    agree : bool
        All converged starts reached the best cost within ``cost_tol`` and
        every parameter within ``parameter_rtol``, and at least two converged.
    cost_tol, parameter_rtol : float
        The agreement criteria used.
    """

    table: pd.DataFrame
    cost_spread: float
    parameter_spread: pd.Series
    agree: bool
    cost_tol: float
    parameter_rtol: float

    def to_pandas(self) -> pd.DataFrame:
        return self.table.copy()

    def summary(self) -> str:
        ok = int(self.table.J_ave.notna().sum())
        worst = self.parameter_spread.idxmax() if len(self.parameter_spread) else "-"
        spread = self.parameter_spread.max() if len(self.parameter_spread) else 0.0
        return (f"{ok}/{len(self.table)} starts converged; J_ave spread {self.cost_spread:.3g}; "
                f"largest relative parameter spread {spread:.3g} ({worst}); "
                f"{'starts agree' if self.agree else 'starts DISAGREE: optimum not unique or local minima'}")


def multistart_report(records, names, best_index, *, cost_tol, parameter_rtol):
    """Assemble a :class:`MultiStartReport` from per-start records (dicts)."""
    table = pd.DataFrame(records)
    table["best"] = table.start == best_index
    done = table[table.J_ave.notna()]
    best = table.loc[table.start == best_index].iloc[0]
    if len(done):
        cost_spread = float(done.J_ave.max() - done.J_ave.min())
        scale = np.abs(np.array([best[n] for n in names], dtype=float))
        span = done[names].max() - done[names].min()
        spread = pd.Series(span.values / np.where(scale > 0, scale, 1.0), index=names, name="relative_spread")
    else:
        cost_spread, spread = np.nan, pd.Series(np.nan, index=names, name="relative_spread")
    agree = bool(len(done) >= 2 and cost_spread <= cost_tol and np.all(spread.values <= parameter_rtol))
    return MultiStartReport(table, cost_spread, spread, agree, cost_tol, parameter_rtol)
