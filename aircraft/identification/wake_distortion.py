"""Wake distortion K_R(omega) of a single rotor in hover from tip-path-plane sweeps (§4.7, Fig. 4.39).

Procedure (§4.7): sweep the three swashplate controls with the flapping held,
then the two tip-path-plane coordinates (prescribed ``beta1s``, ``beta1c`` sweeps
of the rigid-flap wake, which move the flap rates independently of the pitch);
form the joint input-output responses ``lambda / [C, beta_dot]`` (Eq. 4.11), and
from the lateral and longitudinal rows of Eq. 2.29,
``M22 lam1s' + Lbar22 lam1s = dC_L - Lbar22 K_R beta1s*`` (Eq. 4.12), get

    K_R(omega) = -(1 / Lbar22) (lam1s / beta1s*)(omega) / (lam1s / C_L)(omega)      (Eq. 4.18)

with ``beta* = d beta / d psi = beta_dot / Omega``; likewise ``lam1c / beta1c*`` over
``lam1c / C_M`` for the longitudinal axis (``Lbar33 = Lbar22`` in hover). With the
Pitt-Peters ``Lbar22 = -sqrt(C_T/2)`` this is Eq. 4.19 (default); ``lbar="identified"``
takes Lbar22 from the inverted low-frequency lambda/C of the same data instead.

Constant K_R for a flight-dynamics user (the ``kr`` of :class:`aircraft.inflow.PittPeters`):
:attr:`WakeDistortionResult.kr_constant` is the real constant closest to the
complex K_R(omega) in the coherence-weighted least-squares sense (CIFER weight
W_gamma, Eq. 3.14) over the flight-dynamics band (default 1-10 rad/s), both
axes together; it is the gain that best reproduces the lambda/beta* responses
there. Reported beside it: the low-frequency value (real part at the lowest
coherent frequencies), the weighted mean of |K_R| (Fig. 4.39 plots the magnitude)
and the analytical potential-flow value 1.5 of Ref. 82 that §4.7 compares with
(:data:`aircraft.inflow.KR_ANALYTICAL`; §4.7 identifies 1.44 from its free wake).

Sign convention: ours (:mod:`aircraft.inflow.pitt_peters`), in which K_R > 0 means
that a tip-path-plane rate acts like a moment of the opposite sign, as in Eq. 2.29.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from .structures.base import _low_frequency_inverse

__all__ = ["KR_CONTROLS", "WakeDistortionResult", "kr_frequency_response", "wake_distortion_from_runs",
           "identify_wake_distortion"]

#: Excitations of §4.7: swashplate controls (flapping held) and the tip-path-plane coordinates.
KR_CONTROLS = ("theta0", "theta1s", "theta1c", "beta1s", "beta1c")
_INPUTS = ["CT", "CL", "CM", "beta1s_dot", "beta1c_dot"]
_OUTPUTS = ["lam0", "lam1s", "lam1c"]
#: (axis, inflow output, moment input, flap-rate input)
_AXES = (("1s", "lam1s", "CL", "beta1s_dot"), ("1c", "lam1c", "CM", "beta1c_dot"))


def kr_frequency_response(lam_over_u, rotor_omega, lbar22, weighted=None):
    """K_R(omega) of Eq. 4.18 from the joint input-output responses, per axis.

    Parameters
    ----------
    lam_over_u : flightid.MeasuredResponse
        lambda over (C, beta_dot): outputs ``lam1s``, ``lam1c``; inputs ``CL``, ``CM``,
        ``beta1s_dot``, ``beta1c_dot`` (flap rates in rad/s).
    rotor_omega : float
        Rotor speed Omega [rad/s] (``beta* = beta_dot / Omega``).
    lbar22 : float
        Lbar22 (= Lbar33 in hover) [-], negative in our convention (Pitt-Peters
        ``-sqrt(C_T / 2)``).
    weighted : flightid.MeasuredResponse, optional
        The same responses with the magnitude-weighted coherence, reported beside
        ``lam_over_u``'s in a column ``coherence_weighted``.

    Returns
    -------
    pandas.DataFrame
        Columns ``omega`` [rad/s], ``axis`` ("1s", "1c"), ``kr`` (complex),
        ``coherence`` (the smaller of the two responses' coherences), and
        ``coherence_weighted`` when ``weighted`` is given.

    Raises
    ------
    ValueError
        ``rotor_omega`` not positive, ``lbar22`` zero or not finite.
    flightid.errors.SignalNameError
        A needed signal is missing.
    """
    if not (isinstance(rotor_omega, (int, float, np.floating)) and math.isfinite(rotor_omega) and rotor_omega > 0):
        raise ValueError(f"rotor_omega must be a positive rotor speed [rad/s], got {rotor_omega!r}")
    if not (isinstance(lbar22, (int, float, np.floating)) and math.isfinite(lbar22) and lbar22 != 0):
        raise ValueError(f"lbar22 must be a finite non-zero Lbar22 [-], got {lbar22!r}")
    frames = []
    for axis, out, moment, rate in _AXES:
        h_c, coh_c = lam_over_u.element(out, moment)
        h_b, coh_b = lam_over_u.element(out, rate)
        # per beta* = beta_dot / Omega: lam / beta* = Omega lam / beta_dot
        with np.errstate(divide="ignore", invalid="ignore"):
            kr = -(rotor_omega * h_b) / (lbar22 * h_c)
        ok = np.isfinite(kr)
        frame = pd.DataFrame({"omega": lam_over_u.omega[ok], "axis": axis, "kr": kr[ok],
                              "coherence": np.minimum(coh_c, coh_b)[ok]})
        if weighted is not None:
            frame["coherence_weighted"] = np.minimum(weighted.element(out, moment)[1],
                                                     weighted.element(out, rate)[1])[ok]
        frames.append(frame)
    return pd.concat(frames, ignore_index=True)


def _weights(coherence, coherence_min):
    from flightid.fitting import coherence_weight
    w = coherence_weight(coherence)
    return np.where(coherence >= coherence_min, w, 0.0)


@dataclass
class WakeDistortionResult:
    """K_R(omega) in hover and its constant values (see the module notes for the definitions).

    Attributes
    ----------
    table : pandas.DataFrame
        ``omega`` [rad/s], ``axis``, ``kr`` (complex), ``coherence``.
    lbar22 : float
        Lbar22 used in Eq. 4.18 [-].
    lbar_source : str
        ``"pitt_peters"`` (-sqrt(C_T/2), Eq. 4.19) or ``"identified"``.
    fit_range : (float, float)
        Band of the constant fit [rad/s].
    coherence_min : float
        Points below this coherence get no weight.
    coherence_kind : str
        Which coherence ``table.coherence`` is (``"propagated"`` or ``"weighted"``,
        see :func:`wake_distortion_from_runs`); the other is in its own column when
        computed.
    rotor_omega : float
        Rotor speed [rad/s].
    ct : float
        Trim thrust coefficient.
    responses : flightid.MeasuredResponse or None
        The joint input-output lambda / (C, beta_dot) responses.
    trim : aircraft.wake.WakeTrim or None
    wall_s : float
        Wall time of the computation [s] (wake runs included).
    """

    table: pd.DataFrame
    lbar22: float
    lbar_source: str
    fit_range: tuple
    coherence_min: float
    rotor_omega: float
    ct: float
    responses: object = None
    trim: object = None
    wall_s: float = float("nan")
    low_frequency_points: int = 3
    notes: dict = field(default_factory=dict)
    coherence_kind: str = "weighted"

    def _in_band(self, axis=None):
        t = self.table
        sel = (t.omega >= self.fit_range[0]) & (t.omega <= self.fit_range[1])
        if axis is not None:
            sel &= t.axis == axis
        return t[sel]

    def _constant(self, axis=None, magnitude=False):
        t = self._in_band(axis)
        w = _weights(t.coherence.to_numpy(), self.coherence_min)
        if not w.sum() > 0:
            raise ValueError(f"no K_R point in {self.fit_range} rad/s has coherence >= {self.coherence_min}")
        vals = np.abs(t.kr.to_numpy()) if magnitude else np.real(t.kr.to_numpy())
        # real K minimising sum w |K_R(omega) - K|^2 is the weighted mean of Re K_R
        return float(np.sum(w * vals) / np.sum(w))

    @property
    def kr_constant(self) -> float:
        """Best real constant over the fit range, both axes (weighted least squares) [-]."""
        return self._constant()

    @property
    def kr_magnitude_mean(self) -> float:
        """Coherence-weighted mean of |K_R(omega)| over the fit range, both axes [-]."""
        return self._constant(magnitude=True)

    def _low_points(self, axis):
        """The points of ``axis`` that :attr:`kr_low_frequency` averages: the lowest
        ``low_frequency_points`` frequencies with coherence >= ``coherence_min``."""
        t = self.table[(self.table.axis == axis) & (self.table.coherence >= self.coherence_min)]
        return t.sort_values("omega").head(self.low_frequency_points)

    @property
    def kr_low_frequency(self) -> float:
        """Mean Re K_R over the lowest ``low_frequency_points`` coherent frequencies of each axis [-].

        These need not be low frequencies: :meth:`low_frequency_table` says where they lie."""
        vals = []
        for axis, *_ in _AXES:
            vals += list(np.real(self._low_points(axis).kr.to_numpy()))
        if not vals:
            raise ValueError(f"no K_R point has coherence >= {self.coherence_min}")
        return float(np.mean(vals))

    def low_frequency_table(self) -> pd.DataFrame:
        """Where :attr:`kr_low_frequency` comes from, per axis.

        Returns
        -------
        pandas.DataFrame
            ``axis``; ``low_frequency_points_omega_min`` / ``_max`` [rad/s] and
            ``low_frequency_points_coherence_mean`` of the averaged points, and their
            mean ``re_kr_low_frequency_points`` [-] (NaN, not averaged, when an axis has
            no coherent point); beside them ``omega_band_bottom`` [rad/s], the first
            frequency of the fit range, with its ``kr_magnitude_band_bottom`` [-] and
            ``coherence_band_bottom`` (which may be below the threshold).
        """
        rows = []
        t = self.table
        for axis in sorted(set(t.axis)):
            used = self._low_points(axis)
            a = t[(t.axis == axis) & (t.omega >= self.fit_range[0])].sort_values("omega")
            bottom = a.iloc[0]
            rows.append({"axis": axis, "low_frequency_points_omega_min": used.omega.min(),
                         "low_frequency_points_omega_max": used.omega.max(),
                         "low_frequency_points_coherence_mean": used.coherence.mean(),
                         "re_kr_low_frequency_points": float(np.mean(np.real(used.kr))) if len(used) else np.nan,
                         "omega_band_bottom": bottom.omega, "kr_magnitude_band_bottom": abs(bottom.kr),
                         "coherence_band_bottom": bottom.coherence})
        return pd.DataFrame(rows)

    def constants(self) -> pd.DataFrame:
        """The constant values, per axis and together, beside the literature."""
        from aircraft.inflow import KR_ANALYTICAL
        rows = []
        for axis in ("1s", "1c", None):
            try:
                row = {"axis": axis or "both", "kr_constant": self._constant(axis),
                       "kr_magnitude_mean": self._constant(axis, magnitude=True), "note": ""}
            except ValueError as err:   # said in the table, not a silent NaN
                row = {"axis": axis or "both", "kr_constant": np.nan, "kr_magnitude_mean": np.nan,
                       "note": str(err)}
            rows.append(row)
        out = pd.DataFrame(rows)
        try:
            out["kr_low_frequency"] = self.kr_low_frequency
        except ValueError as err:
            out["kr_low_frequency"] = np.nan
            out["note"] = out.note.where(out.note != "", str(err))
        if self.responses is not None:
            # K_R scales with 1/Lbar22 (Eq. 4.18): the same constant with the data's own Lbar22
            lb = _identified_lbar22(self.responses, self.low_frequency_points)
            out["lbar22_identified"] = lb
            out["kr_constant_with_lbar22_identified"] = out.kr_constant * self.lbar22 / lb
        out["kr_analytical_ref82"] = KR_ANALYTICAL
        out["kr_dissertation_fig4_39"] = 1.44     # printed best constant of §4.7 (reference)
        return out

    def to_pandas(self) -> pd.DataFrame:
        """Long table: omega [rad/s], axis, kr_real, kr_imag, kr_magnitude, kr_phase_deg, coherence
        (and the other coherence when computed), in_band."""
        t = self.table
        kr = t.kr.to_numpy()
        return pd.DataFrame({"omega": t.omega, "axis": t.axis, "kr_real": kr.real, "kr_imag": kr.imag,
                             "kr_magnitude": np.abs(kr), "kr_phase_deg": np.degrees(np.angle(kr)),
                             "coherence": t.coherence,
                             **{c: t[c] for c in ("coherence_weighted", "coherence_propagated") if c in t},
                             "in_band": (t.omega >= self.fit_range[0]) & (t.omega <= self.fit_range[1])})

    def plot(self, fig=None):
        """|K_R(omega)|, its phase and the coherence per axis, with the constants (Fig. 4.39); a Figure."""
        from matplotlib.figure import Figure
        from aircraft.inflow import KR_ANALYTICAL
        fig = fig or Figure(figsize=(7.5, 7.0), constrained_layout=True)
        am, ap, ac = fig.subplots(3, 1, sharex=True)
        for axis, *_ in _AXES:
            t = self.table[self.table.axis == axis]
            am.semilogx(t.omega, np.abs(t.kr), label=f"|K_R| {axis} axis (free wake)")
            ap.semilogx(t.omega, np.degrees(np.angle(t.kr)), label=axis)
            line, = ac.semilogx(t.omega, t.coherence, label=f"{axis} ({self.coherence_kind})")
            for col in ("coherence_weighted", "coherence_propagated"):
                if col in t:
                    ac.semilogx(t.omega, t[col], ls="--", color=line.get_color(),
                                label=f"{axis} ({col.split('_')[1]})")
        best = float(self.constants().set_index("axis").loc["both", "kr_constant"])
        if np.isfinite(best):
            am.axhline(best, color="k", ls="--", label=f"best constant {best:.2f}")
        am.axhline(KR_ANALYTICAL, color="r", ls=":", label=f"analytical (Ref. 82) {KR_ANALYTICAL:g}")
        am.axhline(1.44, color="gray", ls="-.", lw=0.8, label="dissertation Fig. 4.39: 1.44")
        for a in (am, ap, ac):
            a.axvspan(*self.fit_range, color="0.9", zorder=0)
            a.grid(True, which="both", alpha=0.3)
        am.set_ylabel("|K_R| [-]")
        ap.set_ylabel("phase [deg]")
        ac.set_ylabel("coherence")
        ac.set_ylim(0, 1.05)
        ac.set_xlabel("omega [rad/s]")
        am.legend(fontsize=7)
        ac.legend(fontsize=7)
        am.set_title(f"K_R(omega), hover, C_T = {self.ct:.4f}, Lbar22 = {self.lbar22:.4f} ({self.lbar_source})",
                     fontsize=9)
        return fig

    def summary(self) -> str:
        """Constants and fit range, as text."""
        c = self.constants()
        return (f"K_R from tip-path-plane sweeps (hover, C_T {self.ct:.5f}, Lbar22 {self.lbar22:.4f} "
                f"from {self.lbar_source}, fit range {self.fit_range[0]:g}-{self.fit_range[1]:g} rad/s, wall "
                f"{self.wall_s:.0f} s)\n" + c.to_string(index=False, float_format=lambda v: f"{v:.3f}"))


def _identified_lbar22(responses, n_points):
    """Lbar22 from the inverted low-frequency lambda/C (mean of the 1s and 1c diagonals)."""
    inv = _low_frequency_inverse(responses, n_points, outputs=list(_OUTPUTS), inputs=list(_INPUTS[:3]))
    return float(0.5 * (inv[1, 1] + inv[2, 2]))


def _check_fit_range(fit_range, coherence_min):
    try:
        lo, hi = (float(b) for b in fit_range)
    except (TypeError, ValueError) as err:
        raise ValueError(f"fit_range must be (w_lo, w_hi) in rad/s, got {fit_range!r}") from err
    if not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo < hi):
        raise ValueError(f"fit_range must satisfy 0 < w_lo < w_hi [rad/s], got {fit_range!r}")
    if not 0 <= coherence_min < 1:
        raise ValueError(f"coherence_min must lie in [0, 1), got {coherence_min!r}")
    return lo, hi


def wake_distortion_from_runs(runs, controls, rotor_omega, ct, *, w_min=0.7, w_max=30.0, lbar="pitt_peters",
                              fit_range=(1.0, 10.0), coherence_min=0.6, low_frequency_points=3,
                              coherence="propagated"):
    """K_R(omega) from time histories of the five §4.7 excitations (no wake needed).

    Parameters
    ----------
    runs : dict
        ``{control: pandas.DataFrame}`` for each of :data:`KR_CONTROLS` (or the
        names in ``controls``): columns ``t`` [s], the control [rad], ``CT``, ``CL``,
        ``CM``, ``beta1s_dot``, ``beta1c_dot`` [rad/s], ``lam0``, ``lam1s``, ``lam1c``.
    controls : sequence of str
        The run of each excitation, in :data:`KR_CONTROLS` order (keys of ``runs``;
        each run's column of the same name is its input, e.g. ``"beta1s"``).
    rotor_omega : float
        Rotor speed [rad/s].
    ct : float
        Trim thrust coefficient (Lbar22 = -sqrt(C_T/2) for ``lbar="pitt_peters"``).
    w_min, w_max : float
        Band of the frequency responses [rad/s].
    lbar : {"pitt_peters", "identified"} or float
        Lbar22 of Eq. 4.18: Pitt-Peters (Eq. 4.19), the inverted low-frequency
        lambda/C of these data, or a given value.
    fit_range : (float, float)
        Band of the constant K_R [rad/s].
    coherence_min : float
        Points below this coherence get no weight.
    low_frequency_points : int
        Lowest coherent frequencies averaged for the low-frequency value.
    coherence : {"propagated", "weighted"}
        Coherence of the joint input-output responses that K_R's coherence is the
        smaller of (:func:`flightid.joint_input_output`). ``"propagated"`` (default)
        carries the five-input inversion's error amplification and follows the
        Monte Carlo scatter of the inverted responses; ``"weighted"``, the
        magnitude-weighted combination of Eqs. 3.23-3.25, reads low wherever the
        inverted terms nearly cancel, even when every single-input response is
        coherent. The other one is reported beside it (``coherence_weighted`` or
        ``coherence_propagated`` in :attr:`WakeDistortionResult.table`).

    Returns
    -------
    WakeDistortionResult

    Raises
    ------
    ValueError
        Bad ``ct``, ``fit_range``, ``lbar``, ``coherence``, or fewer than five excitations.
    """
    from flightid import combine_responses, frequency_response, joint_input_output
    fit_range = _check_fit_range(fit_range, coherence_min)
    if not (isinstance(ct, (int, float, np.floating)) and math.isfinite(ct) and ct > 0):
        raise ValueError(f"ct must be a positive thrust coefficient, got {ct!r}")
    controls = list(controls)
    if len(controls) != len(KR_CONTROLS):
        raise ValueError(f"K_R needs the five excitations {KR_CONTROLS} (one per input of lambda/(C, beta_dot)), "
                         f"got {controls}")
    missing = [c for c in controls if c not in runs]
    if missing:
        raise ValueError(f"no run for excitations {missing}")
    if isinstance(lbar, str) and lbar not in ("pitt_peters", "identified"):
        raise ValueError(f"lbar must be 'pitt_peters', 'identified' or a number, got {lbar!r}")
    if coherence not in ("propagated", "weighted"):
        raise ValueError(f"coherence must be 'propagated' or 'weighted', got {coherence!r}")
    if not isinstance(lbar, str) and not (isinstance(lbar, (int, float, np.floating)) and math.isfinite(lbar)
                                          and lbar < 0):
        raise ValueError(f"lbar must be 'pitt_peters', 'identified' or a negative Lbar22, got {lbar!r}")
    simo = []
    for c in controls:
        df = runs[c]
        base = df.iloc[0]
        y = (df[_INPUTS + _OUTPUTS] - base[_INPUTS + _OUTPUTS]).to_numpy()
        u = (df[c] - base[c]).to_numpy()
        simo.append(frequency_response(df["t"].to_numpy(), u, y, w_min=w_min, w_max=w_max, input_name=c,
                                       output_names=_INPUTS + _OUTPUTS))
    measured = combine_responses(simo)
    # Eq. 4.11: the swashplate sweeps move no flap rate (flapping held): structural zeros
    zeros = np.zeros((len(_INPUTS), len(controls)), bool)
    zeros[3:, :3] = True
    other = "weighted" if coherence == "propagated" else "propagated"
    responses, beside = (joint_input_output(measured.select(_OUTPUTS), measured.select(_INPUTS),
                                            structural_zeros=zeros, coherence=kind) for kind in (coherence, other))
    if isinstance(lbar, str):
        if lbar == "pitt_peters":
            lbar22 = -math.sqrt(ct / 2.0)
        elif lbar == "identified":
            lbar22 = _identified_lbar22(responses, low_frequency_points)
        source = lbar
    else:
        lbar22, source = float(lbar), "given"
    table = kr_frequency_response(responses, float(rotor_omega), lbar22, weighted=beside)
    if other == "propagated":
        table = table.rename(columns={"coherence_weighted": "coherence_propagated"})
    return WakeDistortionResult(table=table, lbar22=lbar22, lbar_source=source, fit_range=fit_range,
                                coherence_min=float(coherence_min), rotor_omega=float(rotor_omega), ct=float(ct),
                                responses=responses, low_frequency_points=int(low_frequency_points),
                                coherence_kind=coherence)


def identify_wake_distortion(config, *, ct=0.0061, settings=None, lbar="pitt_peters", fit_range=(1.0, 10.0),
                             n_jobs=2, cache_dir="default", progress=True, coherence="propagated"):
    """K_R(omega) of a single rotor in hover from the free wake (§4.7).

    Trims the wake in hover at ``ct``, runs one sweep of each of :data:`KR_CONTROLS`
    (the swashplate sweeps are those of :func:`identify_inflow` with the same
    settings, so their cached runs are shared), then
    :func:`wake_distortion_from_runs`.

    Parameters
    ----------
    config : aircraft.AircraftConfig
        A single-rotor configuration (rigid-flap wake: the tip-path-plane inputs are prescribed).
    ct : float
        Trim thrust coefficient.
    settings : IdentificationSettings, optional
        Wake resolution, sweep length and amplitude (default ``IdentificationSettings()``).
    lbar : {"pitt_peters", "identified"} or float
        Lbar22 of Eq. 4.18 (see :func:`wake_distortion_from_runs`).
    fit_range : (float, float)
        Band of the constant K_R [rad/s].
    n_jobs : int
        Wake worker processes.
    coherence : {"propagated", "weighted"}
        Coherence K_R is judged by (see :func:`wake_distortion_from_runs`).
    cache_dir : str or None
        Wake run cache (see :func:`aircraft.wake.run_sweeps`).
    progress : bool

    Returns
    -------
    WakeDistortionResult

    Raises
    ------
    ValueError
        A configuration with more than one rotor, or a free-flapping wake.
    PipelineError
        The wake trim fails.
    """
    from aircraft.wake import FlightCondition, SweepSpec, run_sweeps
    from .pipeline import IdentificationSettings, PipelineError
    t0 = time.perf_counter()
    if len(config.rotors) != 1:
        raise ValueError(f"identify_wake_distortion is for a single rotor, got {len(config.rotors)} rotors")
    s = settings or IdentificationSettings()
    if getattr(s.wake_settings, "free_flapping", False):
        raise ValueError("K_R needs prescribed tip-path-plane sweeps: use a rigid-flap wake (free_flapping=False)")
    _check_fit_range(fit_range, 0.6)
    specs = [SweepSpec(c, kind="sweep", amplitude=s.amplitude, duration=s.sweep_s, w_min=s.w_min, w_max=s.w_max,
                       seed=k) for k, c in enumerate(KR_CONTROLS)]
    out = run_sweeps(config, s.wake_settings, FlightCondition(), specs, trim={"ct": float(ct)}, n_jobs=n_jobs,
                     cache_dir=cache_dir, progress=progress)
    trim = out["trim"]
    if not trim.converged:
        raise PipelineError(f"wake trim did not converge (residual {trim.residual:.2e})")
    runs = {sp.control: out[sp.name] for sp in specs}
    res = wake_distortion_from_runs(runs, list(KR_CONTROLS), float(config.rotors[0].omega), trim.outputs["CT"],
                                    w_min=s.w_min, w_max=s.w_max, lbar=lbar, fit_range=fit_range,
                                    coherence_min=s.coherence_min, coherence=coherence)
    res.trim = trim
    res.wall_s = time.perf_counter() - t0
    return res
