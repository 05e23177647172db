"""Fit a model structure to measured frequency responses with the CIFER cost.

Cost of one response (Eqs. 3.13-3.14)::

    J = 20/n_w * sum_n W_gamma [ W_g (|T_c| - |T|)^2 + W_p (angle T_c - angle T)^2 ]

with magnitudes in dB, phases in degrees, W_gamma = [1.58 (1 - exp(-gamma^2))]^2,
W_g = 1, W_p = 0.01745, on n_w log-spaced frequencies per response (the
dissertation omits "dB" in Eq. 3.13; CIFER and Tischler & Remple use dB, and
the guideline J_ave < 100 only makes sense in dB). J_ave is the mean over the
responses. Normalised Cramér-Rao bounds and insensitivities follow Eqs. 3.15-3.16
with the Gauss-Newton Hessian of J_sum.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd
from scipy.optimize import least_squares
from threadpoolctl import threadpool_limits

from .degeneracy import (DegeneracyReport, MultiStartReport, NoInformationError, block_singular_values,
                         hessian_report, multistart_report, square_components)
from .errors import IdentificationError, InputValueError, UnstableModelError
from .response import MeasuredResponse
from .sensitivity import _cramer_rao_insensitivity, _jacobian, _penalty_gradient, _residual_jacobian
from .statistics import parameter_statistics, residual_scaled_errors
from .structures import ModelStructure

__all__ = ["fit", "FitResult", "cifer_cost", "coherence_weight", "COHERENCE_FLOOR", "JACOBIANS"]

W_GAIN = 1.0
W_PHASE = 0.01745
#: A response needs at least 3 fitted points with coherence >= COHERENCE_FLOOR to
#: carry information; below 0.2 the weight W_gamma is < 8 % of its maximum and
#: the estimate is mostly noise (Tischler & Remple put the usable floor at 0.4-0.6).
COHERENCE_FLOOR = 0.2
#: How :func:`fit` differentiates the residual: scipy's forward differences in the
#: optimizer and central differences for the bounds (the default), or the
#: structure's analytic derivatives (:mod:`flightid.sensitivity`).
JACOBIANS = ("finite-difference", "analytic")


def coherence_weight(coherence):
    """W_gamma = [1.58 (1 - exp(-gamma^2))]^2 (Eq. 3.14); gamma^2 is the coherence."""
    return (1.58 * (1.0 - np.exp(-np.asarray(coherence)))) ** 2


def _wrap_deg(x):
    return (x + 180.0) % 360.0 - 180.0


def cifer_cost(model_response, data_response, coherence):
    """CIFER cost J (Eq. 3.13) of one response from complex arrays on the same grid."""
    r = _pair_residual(np.asarray(model_response), np.asarray(data_response), np.asarray(coherence))
    return float(np.sum(r ** 2))


def _pair_residual(h_model, h_data, coh):
    n = h_data.size
    wg = np.sqrt(20.0 / n * coherence_weight(coh))
    dmag = 20 * np.log10(np.maximum(np.abs(h_model), 1e-300)) - 20 * np.log10(np.maximum(np.abs(h_data), 1e-300))
    dph = _wrap_deg(np.degrees(np.angle(h_model) - np.angle(h_data)))
    return np.concatenate([wg * np.sqrt(W_GAIN) * dmag, wg * np.sqrt(W_PHASE) * dph])


@dataclass
class _PairData:
    output: str
    input: str
    i: int
    j: int
    omega: np.ndarray
    h: np.ndarray
    coh: np.ndarray


def _sample_pair(data, out, inp, lo, hi, n_omega):
    h, coh = data.element(out, inp)
    w = data.omega
    if lo < w[0] * (1 - 1e-9) or hi > w[-1] * (1 + 1e-9) or not lo < hi:
        raise IdentificationError(f"frequency range ({lo:.4g}, {hi:.4g}) rad/s for {out}/{inp} "
                                  f"lies outside the data ({w[0]:.4g}..{w[-1]:.4g})")
    wn = np.geomspace(lo, hi, n_omega)
    lw = np.log(w)
    mag = np.interp(np.log(wn), lw, np.log(np.maximum(np.abs(h), 1e-300)))
    ph = np.interp(np.log(wn), lw, np.unwrap(np.angle(h)))
    c = np.interp(np.log(wn), lw, coh)
    return wn, np.exp(mag) * np.exp(1j * ph), c


def _source_of(sources, out, inp):
    """The first measured response that holds the (output, input) pair, or None."""
    for src in sources:
        if out in src.output_labels and inp in src.input_labels:
            return src
    return None


def _default_range(data, out, inp, coherence_min):
    _, coh = data.element(out, inp)
    good = np.flatnonzero(coh >= coherence_min)
    if good.size < 5:
        return None
    return data.omega[good[0]], data.omega[good[-1]]


@dataclass
class FitResult:
    """Outcome of :func:`fit`.

    Attributes
    ----------
    structure : ModelStructure
        The structure with fitted values.
    parameters : DataFrame
        parameter, value, status, cramer_rao_pct, insensitivity_pct.
    cost_table : DataFrame
        output, input, w_min, w_max [rad/s], J for each response fitted.
    J_ave : float
        Mean cost over the responses (also the ``J_ave`` column of ``cost_table``).
    data : MeasuredResponse or list of MeasuredResponse
        The measured responses fitted.
    success : bool
    message : str
    """

    structure: ModelStructure
    parameters: pd.DataFrame
    cost_table: pd.DataFrame
    J_ave: float
    data: object
    success: bool
    message: str
    n_omega: int
    pairs: list = field(default_factory=list)
    degeneracy: DegeneracyReport | None = None
    multistart: MultiStartReport | None = None
    skipped_pairs: list = field(default_factory=list)
    #: residual-scaled standard errors {parameter: value} where the method gives them
    #: directly (Fourier-transform fits); None: computed on demand (:attr:`statistics`)
    standard_errors: dict | None = None
    #: "cifer" (fit to frequency responses) or a Fourier-transform method name
    method: str = "cifer"

    @property
    def statistics(self) -> pd.DataFrame:
        """Parameter table with the residual-scaled standard errors beside CIFER's bounds.

        Columns: parameter, value, status, cramer_rao_pct, insensitivity_pct (as in
        :attr:`parameters`), standard_error (absolute) and standard_error_pct.
        See :func:`flightid.statistics.parameter_statistics` for the convention.
        """
        return parameter_statistics(self)

    def residual_scaled_errors(self, covariance="white", bias=None, noise="residual", alone=False) -> np.ndarray:
        """Standard errors of the free parameters scaled by the fit's residual variance,
        in the order of ``structure.free_names`` (:func:`flightid.statistics.residual_scaled_errors`
        with its ``covariance``, ``bias``, ``noise`` and ``alone``)."""
        if getattr(self, "_jac_res", None) is None:     # one Jacobian for every convention asked
            problem = _Problem(self.structure, self.pairs, 0.0)
            x = np.array([self.structure.values[n] for n in self.structure.free_names])
            fn = lambda v: problem.residuals(v, with_penalty=False)     # noqa: E731
            self._jac_res = (_jacobian(fn, x), fn(x))
        runs = [p.omega.size for p in self.pairs for _ in range(2)]     # magnitude, phase
        return residual_scaled_errors(*self._jac_res, covariance=covariance, bias=bias, noise=noise,
                                      segments=runs, alone=alone)

    def reference_residuals(self, reference) -> np.ndarray:
        """The fitted model's residual against ``reference`` (a MeasuredResponse, e.g. of a
        noise-free simulation of the model) on the fit's own grids and coherence weights."""
        if not isinstance(reference, MeasuredResponse) or not self.pairs:
            raise IdentificationError("reference must be a MeasuredResponse, for a fit to frequency responses")
        return np.concatenate([_pair_residual(self.structure.frequency_response(p.omega)[p.i, p.j],
                                              _sample_pair(reference, p.output, p.input, p.omega[0], p.omega[-1],
                                                           p.omega.size)[1], p.coh) for p in self.pairs])

    @property
    def condition_number(self) -> float:
        """Condition number of the Hessian in relative parameter units (inf if singular)."""
        return self.degeneracy.condition_number if self.degeneracy is not None else float("nan")

    @property
    def flat_directions(self) -> pd.DataFrame:
        """Flat directions of J: eigenvalue ratio, relative CR %, parameters moving together."""
        return self.degeneracy.flat_directions.copy()

    @property
    def singular_value_ratios(self) -> pd.DataFrame:
        """sigma_min/sigma_max of model and data for the square blocks checked, over frequency."""
        return self.degeneracy.singular_values.copy()

    @property
    def warnings(self) -> list:
        """What J cannot see: flat directions, parameters without influence, rank-deficient
        square blocks, skipped incoherent responses, disagreeing starts."""
        out = list(self.degeneracy.warnings) if self.degeneracy is not None else []
        if self.skipped_pairs:
            out.append(f"responses skipped (fewer than 3 points with coherence >= {COHERENCE_FLOOR}): "
                       f"{self.skipped_pairs}")
        if self.multistart is not None and not self.multistart.agree:
            out.append(self.multistart.summary())
        return out

    @property
    def model(self):
        """The fitted model as a named :class:`control.StateSpace` (Padé delays)."""
        return self.structure.to_statespace()

    @property
    def cramer_rao(self) -> pd.Series:
        """Normalised Cramér-Rao bounds [%] of the free parameters (Eq. 3.16)."""
        t = self.parameters[self.parameters.status == "free"]
        return pd.Series(t.cramer_rao_pct.values, index=t.parameter.values, name="cramer_rao_pct")

    @property
    def insensitivity(self) -> pd.Series:
        """Normalised insensitivities [%] of the free parameters (Eq. 3.15)."""
        t = self.parameters[self.parameters.status == "free"]
        return pd.Series(t.insensitivity_pct.values, index=t.parameter.values, name="insensitivity_pct")

    @property
    def costs(self) -> dict:
        """{(output, input): J}."""
        return {(r.output, r.input): r.J for r in self.cost_table.itertuples()}

    def to_pandas(self) -> pd.DataFrame:
        """The parameter table (value, status, Cramér-Rao %, insensitivity %)."""
        return self.parameters.copy()

    def plot(self, fig=None):
        """Bode overlay of data and model with coherence for every fitted response."""
        from .plotting import bode_with_coherence
        if self.data is None:
            raise IdentificationError("this fit holds no frequency response to plot (several inputs "
                                      "fitted by a Fourier-transform method)")
        sources = self.data if isinstance(self.data, list) else [self.data]
        omega = np.unique(np.concatenate([src.omega for src in sources]))
        frd = self.structure.to_frd(omega, name="model")
        pairs = [(p.output, p.input) for p in self.pairs]
        return bode_with_coherence([(src, "data") for src in sources] + [(frd, "model")], pairs,
                                   fig=fig)

    def summary(self) -> str:
        lines = [f"J_ave = {self.J_ave:.2f} over {len(self.cost_table)} responses"]
        lines.append(self.cost_table.to_string(index=False, float_format=lambda v: f"{v:.3g}"))
        lines.append(self.parameters.to_string(index=False, float_format=lambda v: f"{v:.4g}"))
        if self.degeneracy is not None:
            lines.append(self.degeneracy.summary())
        if self.multistart is not None:
            lines.append(self.multistart.summary())
        if not self.success:
            lines.append(f"FIT FAILED: {self.message}")
        return "\n".join(lines)


def _informative(coherence):
    return int(np.sum(np.asarray(coherence) >= COHERENCE_FLOOR)) >= min(3, np.size(coherence))


def _range_for(frequency_ranges, data, o, u, coherence_min):
    if isinstance(frequency_ranges, dict) and (o, u) in frequency_ranges:
        return tuple(frequency_ranges[(o, u)])
    if frequency_ranges is not None and not isinstance(frequency_ranges, dict):
        if len(frequency_ranges) != 2:
            raise IdentificationError("frequency_ranges must be (w_lo, w_hi) or a dict of them")
        return tuple(frequency_ranges)
    rng = _default_range(data, o, u, coherence_min)
    if rng is None:
        raise IdentificationError(f"{o}/{u} has too few points with coherence >= {coherence_min}")
    return rng


def _prepare_pairs(structure, sources, pairs, frequency_ranges, n_omega, coherence_min):
    """Sample every fitted pair on its log grid; drop (default pairs) or refuse (explicit
    pairs) responses without coherent points. Returns (pair_data, skipped)."""
    explicit = pairs is not None
    if pairs is None:
        pairs = []
        for i, o in enumerate(structure.outputs):
            for j, u in enumerate(structure.inputs):
                src = _source_of(sources, o, u)
                if src is None:
                    continue   # no data
                h = np.abs(structure.frequency_response(src.omega))
                # structurally zero in the model (to the rounding of a modal evaluation)
                if np.all(h[i, j] <= 1e-12 * max(h.max(), 1e-300)):
                    continue
                if _default_range(src, o, u, coherence_min) is not None:
                    pairs.append((o, u))
        if not pairs:
            raise NoInformationError(f"no response has coherence >= {coherence_min} on enough points")
    pair_data, skipped = [], []
    for o, u in pairs:
        if o not in structure.outputs or u not in structure.inputs:
            raise IdentificationError(f"pair {o}/{u} is not an (output, input) of the structure")
        data = _source_of(sources, o, u)
        if data is None:
            raise IdentificationError(f"no measured response holds {o}/{u}")
        lo, hi = _range_for(frequency_ranges, data, o, u, coherence_min)
        wn, h, c = _sample_pair(data, o, u, lo, hi, n_omega)
        if not (np.all(np.isfinite(h)) and np.all(np.isfinite(c))):
            raise IdentificationError(f"the measured response {o}/{u} holds NaN or infinite values "
                                      f"in ({lo:.4g}, {hi:.4g}) rad/s")
        if not _informative(c):
            if explicit:
                raise NoInformationError(
                    f"{o}/{u} has no coherent point: fewer than 3 of its {n_omega} fitted frequencies in "
                    f"({lo:.4g}, {hi:.4g}) rad/s reach coherence {COHERENCE_FLOOR} (max {np.max(c):.3g}); "
                    "the data carry no information on it")
            skipped.append((o, u))
            continue
        pair_data.append(_PairData(o, u, structure.outputs.index(o), structure.inputs.index(u), wn, h, c))
    if not pair_data:
        raise NoInformationError(
            f"no response has a coherent point: every candidate ({skipped}) has fewer than 3 fitted "
            f"frequencies with coherence >= {COHERENCE_FLOOR}; the data carry no information")
    return pair_data, skipped


class _Problem:
    """The weighted CIFER residual of a structure over sampled pairs, with the
    stability penalty of §6.4.1 (one model evaluation over all pairs' grids)."""

    def __init__(self, structure, pair_data, stability_margin, jacobian="finite-difference"):
        self.structure = structure
        self.free = structure.free_names
        self.pairs = pair_data
        self.omega = np.concatenate([p.omega for p in pair_data])
        edges = np.cumsum([0] + [p.omega.size for p in pair_data])
        self.slices = [slice(a, b) for a, b in zip(edges[:-1], edges[1:])]
        self.margin = stability_margin
        self.has_dynamics = structure.poles().size > 0
        # The penalty acts slightly inside the boundary (``buffer``) so the optimum
        # of a fit pressed against it lands strictly stable; its weight is raised
        # until the re-check passes (a finite penalty alone trades a tiny violation
        # for cost).
        self.buffer = 1e-4 * max(1.0, abs(stability_margin))
        self.weight = 1e3
        self.lower = np.array([0.0 if n in structure.delay_names else -np.inf for n in self.free])
        # analytic only where the structure's derivatives describe its response
        self.analytic = jacobian == "analytic" and structure._has_sensitivities()
        if self.analytic:
            self._maps = structure._reference_maps(self.free)
            self._weights = []
            for p in pair_data:
                wg = np.sqrt(20.0 / p.h.size * coherence_weight(p.coh))
                self._weights.append((wg * np.sqrt(W_GAIN), wg * np.sqrt(W_PHASE)))

    def jacobian(self, x, with_penalty=True):
        """d(residuals)/dx: analytic where available, else central differences."""
        if not self.analytic:
            return _jacobian(lambda v: self.residuals(v, with_penalty=with_penalty), x)
        jac = _residual_jacobian(self.structure, dict(zip(self.free, x)), self.pairs, self._weights, self._maps)
        if with_penalty and self.has_dynamics:
            jac = np.vstack([jac, self._penalty_gradient(x)[None, :]])
        return jac

    def _penalty_gradient(self, x):
        """d(stability penalty)/dx (:func:`flightid.sensitivity._penalty_gradient`)."""
        return _penalty_gradient(lambda v: self._penalty(dict(zip(self.free, v))), x)

    def residuals(self, x, with_penalty=True):
        vals = dict(zip(self.free, x))
        h = self.structure.frequency_response(self.omega, vals)
        parts = [_pair_residual(h[p.i, p.j, sl], p.h, p.coh) for p, sl in zip(self.pairs, self.slices)]
        if with_penalty and self.has_dynamics:
            parts.append(np.array([self._penalty(vals)]))
        return np.concatenate(parts)

    def _penalty(self, vals):
        """The stability penalty (§6.4.1) at the parameter values ``vals`` (a dict)."""
        try:
            worst = np.max(self.structure.poles(vals).real) + self.margin + self.buffer
        except IdentificationError:   # e.g. a singular M on the way: no state-space form
            worst = 1.0
        return self.weight * max(0.0, worst)

    def _dead(self, x):
        h = self.structure.frequency_response(self.omega, dict(zip(self.free, x)))
        return [k for k, (p, sl) in enumerate(zip(self.pairs, self.slices)) if not np.any(h[p.i, p.j, sl] != 0)]

    def revive(self, x):
        """Start values for zero-valued parameters that alone feed a fitted pair whose
        model response is identically zero. In dB such a pair sits at -inf with a
        zero gradient, so the optimizer cannot leave it (e.g. a stage that frees
        the gains of newly added responses at 0). Each such parameter starts where
        its (probed) response has the data's median magnitude, with the sign whose
        phase fits better. Pairs with a live model response are never touched."""
        x = np.array(x, float)
        dead = self._dead(x)
        for k in range(x.size):
            if not dead:
                break
            if x[k] != 0 or self.lower[k] == 0:        # delays stay as given
                continue
            probe = x.copy()
            probe[k] = 1.0
            hp = self.structure.frequency_response(self.omega, dict(zip(self.free, probe)))
            live = [d for d in dead if np.any(hp[self.pairs[d].i, self.pairs[d].j, self.slices[d]] != 0)]
            if not live:
                continue
            ratio = np.median([np.median(np.abs(self.pairs[d].h)) /
                               np.median(np.abs(hp[self.pairs[d].i, self.pairs[d].j, self.slices[d]]))
                               for d in live])
            trials = []
            for v in (ratio, -ratio):
                probe[k] = v
                trials.append((float(np.sum(self.residuals(probe, with_penalty=True) ** 2)), v))
            x[k] = min(trials)[1]
            dead = self._dead(x)
        return x

    def solve(self, x0, max_nfev, revive=False):
        """Least squares from ``x0``; returns (sol, fitted structure, stable)."""
        x = np.maximum(np.asarray(x0, float), self.lower)
        if revive:
            x = self.revive(x)
        self.weight = 1e3
        for _ in range(4):
            sol = least_squares(self.residuals, x, jac=self.jacobian if self.analytic else "2-point",
                                bounds=(self.lower, np.full_like(x, np.inf)), x_scale="jac", method="trf",
                                max_nfev=max_nfev or 200 * (len(x) + 1),
                                xtol=1e-12, ftol=1e-12)
            x = sol.x
            fitted = self.structure.with_values(dict(zip(self.free, x)))
            stable = not self.has_dynamics or fitted.is_stable(margin=self.margin)
            if stable:
                break
            self.weight *= 100.0
        return sol, fitted, stable


def _start_points(x0, lower, starts, seed, spread):
    """Start 0 is the given initial guess; the others scatter it (seeded): each
    non-zero parameter by a factor in [1 - spread, 1 + spread], each zero one by
    +-spread times the typical free-parameter magnitude."""
    rng = np.random.default_rng(seed)
    nz = np.abs(x0[x0 != 0])
    typical = float(np.median(nz)) if nz.size else 1.0
    points = [x0]
    for _ in range(starts - 1):
        f = rng.uniform(-1.0, 1.0, x0.size)
        x = np.where(x0 != 0, x0 * (1.0 + spread * f), spread * typical * f)
        points.append(np.maximum(x, lower))
    return points


def fit(structure: ModelStructure, responses, *, pairs=None, frequency_ranges=None,
        n_omega=20, coherence_min=0.6, stability_margin=0.0, require_stable=True,
        max_nfev=None, starts=1, seed=None, start_spread=0.5, square_blocks=None,
        multistart_cost_tol=None, multistart_parameter_rtol=0.02, revive_dead_pairs=False,
        jacobian="finite-difference") -> FitResult:
    """Minimise the CIFER cost of ``structure`` against measured responses.

    Parameters
    ----------
    structure : ModelStructure
        Its free parameters are adjusted, fixed ones kept (staged fits:
        :func:`flightid.fit_staged`, or ``structure.fix([...])`` / ``.free([...])``).
    responses : MeasuredResponse or sequence of MeasuredResponse
        Responses with coherence (e.g. from :func:`joint_input_output`); with
        several, each pair is taken from the first response that holds it
        (grids may differ between responses).
    pairs : list of (output, input), optional
        Responses to fit. Default: every pair the structure and data share whose
        coherence reaches ``coherence_min`` on 5+ points and whose model response
        is not structurally zero; of those, pairs with fewer than 3 fitted points
        of coherence >= :data:`COHERENCE_FLOOR` are skipped (listed in
        ``FitResult.skipped_pairs``). An explicit pair without such points raises
        :class:`NoInformationError`.
    frequency_ranges : tuple or dict, optional
        ``(w_lo, w_hi)`` [rad/s] for all pairs, or ``{(output, input): (lo, hi)}``.
        Default: from the first to the last frequency with coherence >= ``coherence_min``.
    n_omega : int
        Log-spaced frequency points per response (CIFER uses 20).
    coherence_min : float
        Coherence threshold for the default pairs and ranges.
    stability_margin : float
        Eigenvalues must satisfy Re < -margin [1/s] (§6.4.1): enforced by a penalty
        during the fit and checked after it.
    require_stable : bool
        Raise :class:`UnstableModelError` if the fitted model is unstable.
    max_nfev : int, optional
        Model evaluations per start (default 200 per free parameter).
    starts : int
        Number of starts: the given initial values, and ``starts - 1`` seeded
        scatterings of them (``start_spread``). The lowest stable cost wins;
        ``FitResult.multistart`` reports whether the starts agree.
    seed : int, optional
        Seed of the start scattering.
    start_spread : float
        Relative scatter of the extra starts (0.5: factors in [0.5, 1.5]).
    square_blocks : list of (outputs, inputs), optional
        Square blocks whose singular-value ratios are compared between model and
        data. Default: the square connected components of the fitted pairs
        (e.g. the 2 x 2 collective block of a coaxial rotor). ``[]`` disables.
    multistart_cost_tol, multistart_parameter_rtol : float
        Agreement criteria of the starts: J_ave spread (default 1 % of the best
        J_ave, at least 1e-6) and relative parameter spread (2 %).
    revive_dead_pairs : bool
        A fitted pair whose model response is identically zero at the start sits
        at -inf dB with zero gradient. With True, zero-valued parameters that
        feed such a pair start at the data's median magnitude with the better
        sign (see ``_Problem.revive``); default False keeps the given start.
    jacobian : {"finite-difference", "analytic"}
        How the residual is differentiated (:data:`JACOBIANS`). "analytic" uses the
        structure's exact derivatives (state-space, M/Lbar, gain/delay forms with
        exact delays; :mod:`flightid.sensitivity`) in the optimizer and for the
        bounds: one evaluation per Jacobian instead of one per parameter, the way to
        refit structures with a hundred or more free parameters. A structure
        without them (e.g. a subclass adding a term to its response) falls back to
        differences. The optimum agrees with the default's to the optimizer's
        tolerance, not bit for bit.

    Returns
    -------
    FitResult
        ``success`` is False when the optimizer did not converge or a free
        parameter has no influence on the fitted responses (``warnings`` says which).

    Raises
    ------
    NoInformationError
        No response has a coherent point (e.g. coherence zero everywhere).
    UnstableModelError
        Every start ended unstable and ``require_stable`` is set.

    Examples
    --------
    >>> import numpy as np, control
    >>> from flightid import frequency_sweep, frequency_response
    >>> t, u = frequency_sweep(0.5, 20.0, 60.0, 0.01, seed=0)
    >>> y = control.forced_response(control.tf([4.0], [1.0, 2.0]), t, u).outputs     # 4 / (s + 2)
    >>> data = frequency_response(t, u, y, w_min=0.5, w_max=20.0, output_names=["y"])
    >>> from flightid import FGCStructure, fit
    >>> structure = FGCStructure([["f"]], [["g"]], [[1.0]], inputs=["u"], outputs=["y"],
    ...                          initial={"f": -1.0, "g": 1.0})             # x' = f x + g u, y = x
    >>> result = fit(structure, data)
    >>> {k: round(v, 1) for k, v in result.structure.values.items()}, bool(result.J_ave < 1)
    ({'f': -2.0, 'g': 4.0}, True)
    """
    if not (isinstance(jacobian, str) and jacobian in JACOBIANS):
        raise InputValueError(f"jacobian must be one of {JACOBIANS}, got {jacobian!r}")
    free = structure.free_names
    if not free:
        raise IdentificationError("the structure has no free parameters")
    bad = [n for n in structure.names if not np.isfinite(structure.values[n])]
    if bad:
        raise InputValueError(f"initial value(s) of parameter(s) {bad} are NaN or infinite: give finite "
                              "start values (structure initial / with_values)")
    sources = [responses] if isinstance(responses, MeasuredResponse) else list(responses)
    if not sources or not all(isinstance(src, MeasuredResponse) for src in sources):
        raise IdentificationError("responses must be a MeasuredResponse or a non-empty sequence of them "
                                  "(use frequency_response / joint_input_output)")
    have_o = {o for src in sources for o in src.output_labels}
    have_i = {i for src in sources for i in src.input_labels}
    missing_o = [o for o in structure.outputs if o not in have_o]
    missing_i = [i for i in structure.inputs if i not in have_i]
    if missing_o or missing_i:
        raise IdentificationError(f"data lacks the structure's outputs {missing_o} / inputs {missing_i}")
    if n_omega < 3:
        raise IdentificationError("n_omega must be at least 3")
    if not (isinstance(starts, (int, np.integer)) and starts >= 1):
        raise IdentificationError(f"starts must be a positive integer, got {starts!r}")
    if not (np.isfinite(start_spread) and start_spread >= 0):
        raise IdentificationError(f"start_spread must be a finite number >= 0, got {start_spread!r}")
    pair_data, skipped = _prepare_pairs(structure, sources, pairs, frequency_ranges, n_omega, coherence_min)

    # the fit evaluates small dense matrices thousands of times: BLAS threads only
    # add contention (measured 3x slower on a loaded 2-core machine)
    with threadpool_limits(1):
        return _fit(structure, sources, pair_data, skipped, n_omega, stability_margin, require_stable,
                    max_nfev, starts, seed, start_spread, square_blocks, multistart_cost_tol,
                    multistart_parameter_rtol, revive_dead_pairs, jacobian)


def _fit(structure, sources, pair_data, skipped, n_omega, stability_margin, require_stable, max_nfev,
         starts, seed, start_spread, square_blocks, multistart_cost_tol, multistart_parameter_rtol,
         revive_dead_pairs, jacobian):
    free = structure.free_names
    problem = _Problem(structure, pair_data, stability_margin, jacobian)
    x0 = np.array([structure.values[n] for n in free])
    records, outcomes, first_error = [], [], None
    for k, xs in enumerate(_start_points(x0, problem.lower, starts, seed, start_spread)):
        sol, fitted, stable = problem.solve(xs, max_nfev, revive_dead_pairs)
        j_ave = float(np.mean([cifer_cost(fitted.frequency_response(p.omega)[p.i, p.j], p.h, p.coh)
                               for p in pair_data]))
        rec = {"start": k, "J_ave": j_ave if stable or not require_stable else np.nan,
               "success": bool(sol.success) and stable,
               "note": "" if stable else "unstable", **dict(zip(free, sol.x))}
        records.append(rec)
        if stable or not require_stable:
            outcomes.append((j_ave, k, sol, fitted))
        elif first_error is None:
            first_error = UnstableModelError(f"fitted model violates Re(p) < -{stability_margin} 1/s: "
                                             f"poles {np.round(fitted.poles(), 4)}")
    if not outcomes:
        raise first_error
    j_best, best, sol, fitted = min(outcomes, key=lambda o: o[0])
    values = dict(zip(free, sol.x))
    multistart = None
    if starts > 1:
        tol = multistart_cost_tol if multistart_cost_tol is not None else max(0.01 * j_best, 1e-6)
        multistart = multistart_report(records, free, best, cost_tol=tol,
                                       parameter_rtol=multistart_parameter_rtol)

    costs = []
    for p in pair_data:
        hm = fitted.frequency_response(p.omega)[p.i, p.j]
        costs.append({"output": p.output, "input": p.input, "w_min": p.omega[0],
                      "w_max": p.omega[-1], "J": cifer_cost(hm, p.h, p.coh)})
    cost_table = pd.DataFrame(costs)
    j_ave = float(cost_table.J.mean())
    cost_table["J_ave"] = j_ave
    cost_table.attrs["J_ave"] = j_ave

    jac = problem.jacobian(sol.x, with_penalty=False)
    cr, ins = _cramer_rao_insensitivity(None, sol.x, jac=jac)
    report = hessian_report(jac, free, sol.x)
    ranges = {(p.output, p.input): (p.omega[0], p.omega[-1]) for p in pair_data}
    blocks = square_components(ranges) if square_blocks is None else list(square_blocks)

    def element(o, u, w):
        src = _source_of(sources, o, u)
        if src is None:
            return None
        lo, hi = max(w[0], src.omega[0]), min(w[-1], src.omega[-1])
        return _sample_pair(src, o, u, lo, hi, w.size)[1] if lo < hi else None

    if blocks:
        report.singular_values, sv_warnings = block_singular_values(fitted, element, blocks, ranges)
        report.warnings.extend(sv_warnings)
    table = fitted.parameter_table()
    table["cramer_rao_pct"] = np.nan
    table["insensitivity_pct"] = np.nan
    for k, n in enumerate(free):
        row = table.parameter == n
        scale = abs(values[n]) if values[n] != 0 else np.nan
        # a parameter on a flat direction, or one that went to ~0, has a relative bound
        # beyond the float range: that is inf (said as such), not a warning
        with np.errstate(over="ignore", divide="ignore"):
            table.loc[row, "cramer_rao_pct"] = 100.0 * np.float64(cr[k]) / scale
            table.loc[row, "insensitivity_pct"] = 100.0 * np.float64(ins[k]) / scale
    success, message = bool(sol.success), str(sol.message)
    if report.no_influence:
        success = False
        message = (f"parameters {report.no_influence} have no influence on the fitted responses: the data "
                   f"carry no information on them (fix or remove them); optimizer: {sol.message}")
    data_out = sources[0] if len(sources) == 1 else sources
    return FitResult(fitted, table, cost_table, j_ave, data_out, success, message, n_omega, pair_data,
                     degeneracy=report, multistart=multistart, skipped_pairs=skipped)
