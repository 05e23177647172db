"""Constrained 12-state coaxial structures, and a comparison of them on one wake data set.

The 12-state near/far-wake model fitted to our coaxial hover wake
(:class:`~aircraft.identification.Coaxial12State` with delays and far-wake
loads, shipped as ``coaxial_hover_12state``) has four flat directions and
Cramér-Rao bounds up to ~1000 %. Most of its poorly determined parameters sit in
the collective near/far block: our collective lambda/C block is nearly rank-one
(the 6-state's diagnosis), so apparent mass and inflow gain are fixed only in
combination, and a second (far-wake) collective state adds a further free time
scale. :class:`Coaxial12StateConstrained` removes such freedoms by name:

* ``collective_far_wake=False``: the far-wake collective states ``lam0F`` are
  switched off (their rows of F and G are zero, the pole a constant -1 per
  radian of azimuth, never excited), so the collective is first order, as in the
  6-state models;
* ``a_priori``: parameters held at given values (constants of the structure, not
  parameters; tied 1c entries follow their 1s partner with its sign), e.g. the
  collective near-wake ``G`` diagonal at the inverse Pitt-Peters apparent mass
  ``3 pi / 8`` (:data:`PITT_PETERS_COLLECTIVE_GAIN`; with no lower-to-upper mass
  coupling ``G = M^-1`` has exactly this diagonal);
* ``without``: parameters removed (held at zero), e.g. the cross-rotor far-far
  cyclic couplings ``f4_10`` and ``f10_4``: on our wake ``f4_10`` forms a flat
  direction with ``f4_9`` (it scales a far-wake state that barely reaches the
  outputs), and ``f10_4`` takes its place when it alone is removed.

:func:`compare_twelve_state_variants` identifies a list of such structures from
the same wake runs (cached) and tabulates what the trust guidelines say about
each, beside each aircraft's effective roll damping (does the model leave the
bare airframe flyable?).

::

    identify_inflow(config, hover, Coaxial12StateConstrained(...))   one variant
    compare_twelve_state_variants(VARIANTS) -> TwelveStateComparison
        .table      J_ave, CR/insensitivity, flat directions, trust, Re L_p,
                    steady gain against held wake steps
        .to_pandas(), .plot()
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from .structures import _EQ62_INPUTS, _F_FREE, _PP_M11, STRUCTURES, Coaxial12State

__all__ = ["Coaxial12StateConstrained", "PITT_PETERS_COLLECTIVE_GAIN", "VARIANTS",
           "TwelveStateComparison", "compare_twelve_state_variants"]

#: Collective near-wake G diagonal (d lambda0 / d psi per unit C_T) at the inverse
#: Pitt-Peters hover apparent mass 3 pi / 8 (per rotor, Eq. 6.2 rows 1 and 7).
PITT_PETERS_COLLECTIVE_GAIN = {"g1_1": 1.0 / _PP_M11, "g7_6": 1.0 / _PP_M11}

_COLLECTIVE_FAR_ROWS = (2, 8)    # lam0F_U, lam0F_L (1-based, Eq. 6.2 order)


class Coaxial12StateConstrained(Coaxial12State):
    """:class:`Coaxial12State` (tied, with delays and far-wake loads) with freedoms removed by name.

    Parameters
    ----------
    collective_far_wake : bool
        Keep the far-wake collective states (default True: Eq. 6.3). False makes
        the collective first order (their rows of F and G zero).
    a_priori : mapping of str to float, optional
        Parameters held at these values (per radian of azimuth, as every F/G
        entry); they are constants of the structure and part of its identity
        (:meth:`spec`).
    without : iterable of str
        Parameters held at zero.
    frame : {"rotor", "printed"}

    Raises
    ------
    ValueError
        An unknown or repeated name, a name both held and removed, or a value
        that is not a finite real number.
    """

    key = "coaxial_12state_constrained"

    def __init__(self, collective_far_wake=True, a_priori=None, without=(), frame="rotor"):
        super().__init__(frame=frame, tied=True, delays=True, far_wake_loads=True)
        self.collective_far_wake = bool(collective_far_wake)
        rows_off = () if self.collective_far_wake else _COLLECTIVE_FAR_ROWS
        self._f_entries = [(i, j) for i, j in _F_FREE if i not in rows_off]
        self._g_free = [(i, j) for i, j in self._g_free if i not in rows_off]
        known = set(super().parameter_names())
        if not self.collective_far_wake:   # the names the switched-off rows carried
            known = {n for n in known if not any(n.startswith(f"{p}{r}_") for p in "fg" for r in rows_off)}
        self.a_priori = {}
        for name, value in dict(a_priori or {}).items():
            if name not in known:
                raise ValueError(f"a_priori names {name!r}, not a parameter of this structure; it has "
                                 f"{sorted(known)[:8]}...")
            try:
                value = float(value)
            except (TypeError, ValueError):
                raise ValueError(f"a_priori value of {name!r} must be a finite real number, got {value!r}") from None
            if not math.isfinite(value):
                raise ValueError(f"a_priori value of {name!r} must be a finite real number, got {value!r}")
            self.a_priori[name] = value
        if isinstance(without, str):
            without = [without]
        self.without = tuple(sorted(set(without)))
        bad = [n for n in self.without if n not in known]
        if bad:
            raise ValueError(f"without names {bad}, not parameters of this structure")
        both = sorted(set(self.without) & set(self.a_priori))
        if both:
            raise ValueError(f"{both} both held a priori and removed")

    def spec(self):
        out = super().spec()
        out["constrained"] = {"collective_far_wake": self.collective_far_wake,
                              "a_priori": dict(sorted(self.a_priori.items())), "without": list(self.without)}
        return out

    def __repr__(self):
        return (f"Coaxial12StateConstrained(collective_far_wake={self.collective_far_wake}, "
                f"a_priori={self.a_priori!r}, without={self.without!r})")

    def _entry(self, p, i, j):
        """Pattern entry (i, j) (1-based): a name, or a constant when held or removed."""
        name = self._name(p, i, j)
        base, sign = name.lstrip("-"), (-1.0 if name.startswith("-") else 1.0)
        if base in self.without:
            return 0
        if base in self.a_priori:
            return sign * self.a_priori[base]
        return name

    def _tau_pattern(self):
        """The delays' pattern with the removed ones zero and the held ones at their values."""
        tau = super()._tau_pattern()
        if tau is None:
            return None
        # delays carry no sign in the ties, so a name is the parameter itself; the
        # base class asks before the constraints are set (then there are none)
        without, held = getattr(self, "without", ()), getattr(self, "a_priori", {})
        return [[(0 if n in without else held.get(n, n)) if isinstance(n, str) else n
                 for n in row] for row in tau]

    def build(self, initial, omega, fixed=()):
        from flightid import FGCStructure
        return self._assemble(FGCStructure, *self._fgc_patterns(), initial, omega, fixed)

    def _assemble(self, cls, F, G, C, tau, initial, omega, fixed):
        """``cls(F, G, C, tau, ...)`` with this structure's parameters started at ``initial``."""
        names = set(self.parameter_names())
        init = {n: float(v) for n, v in dict(initial).items() if n in names}
        missing = names - set(init)
        if missing:
            raise KeyError(f"no initial value for {sorted(missing)[:6]}... ({len(missing)} parameters)")
        return cls(F, G, C, tau, inputs=self.inputs, outputs=self.outputs, initial=init,
                   fixed=[f for f in fixed if f in names], omega=omega, states=self.states)

    def _fgc_patterns(self):
        """``F`` (12 x 12), ``G`` (12 x inputs) patterns, ``C`` (6 x 12) and the delays' pattern."""
        F = [[0] * 12 for _ in range(12)]
        for i, j in self._f_entries:
            F[i - 1][j - 1] = self._entry("f", i, j)
        if not self.collective_far_wake:
            for r in _COLLECTIVE_FAR_ROWS:     # a stable constant pole: the state is never excited
                F[r - 1][r - 1] = -1.0
        G62 = [[0] * 10 for _ in range(12)]
        for i, j in self._g_free:
            G62[i - 1][j - 1] = self._entry("g", i, j)
        G = [[row[_EQ62_INPUTS.index(c)] for c in self.inputs] for row in G62]
        C = np.zeros((6, 12))
        for k in range(6):
            C[k, 2 * k] = C[k, 2 * k + 1] = 1.0
        return F, G, C, self._tau_pattern()

    def parameter_names(self):
        """Names of the free-able parameters (after ties, without the held and removed ones)."""
        tau = self._tau_pattern() or []
        out = ({self._name("f", i, j).lstrip("-") for i, j in self._f_entries}
               | {self._name("g", i, j).lstrip("-") for i, j in self._g_free}
               | {n for row in tau for n in row if isinstance(n, str)})
        return sorted(out - set(self.a_priori) - set(self.without))

    def initial_values(self, lam_over_c, n_points=3, coherence_min=None):
        keep = set(self.parameter_names())
        vals = super().initial_values(lam_over_c, n_points, coherence_min)
        return {k: v for k, v in vals.items() if k in keep}

    def staged_plan(self):
        keep = set(self.parameter_names())
        plan = super().staged_plan()
        for stage in plan:
            if not isinstance(stage.free, str):
                stage.free = [n for n in stage.free if n in keep]
        return [s for s in plan if isinstance(s.free, str) or s.free or s.add_pairs]

    def published_values(self, model):
        keep = set(self.parameter_names())
        return {k: v for k, v in super().published_values(model).items() if k in keep}


#: The variants compared by the study, from the shipped structure to the most constrained.
VARIANTS = {
    "shipped (Eq. 6.3 + delays + far-wake loads)": dict(),
    "first-order collective": dict(collective_far_wake=False),
    "first-order collective, Pitt-Peters collective gain": dict(
        collective_far_wake=False, a_priori=PITT_PETERS_COLLECTIVE_GAIN),
    # on our wake f4_10 ran to ~230 in a flat direction with f4_9 (it scales a far-wake
    # state that barely reaches the outputs); removing it alone let f10_4, its mirror
    # (lower far <- upper far), take the same role (12 bounds over 20 %, max 208 %)
    "first-order collective, Pitt-Peters collective gain, without far-far cross-rotor cyclic": dict(
        collective_far_wake=False, a_priori=PITT_PETERS_COLLECTIVE_GAIN, without=("f4_10", "f10_4")),
}

STRUCTURES["coaxial_12state_first_order_collective_pp"] = lambda: Coaxial12StateConstrained(
    **VARIANTS["first-order collective, Pitt-Peters collective gain, without far-far cross-rotor cyclic"])


@dataclass
class TwelveStateComparison:
    """Result of :func:`compare_twelve_state_variants`.

    Attributes
    ----------
    table : pandas.DataFrame
        One row per variant: ``J_ave`` (all responses), ``J_ave_load_pairs`` (the
        12 lambda/C), ``n_free``, ``max_cramer_rao_pct``, ``n_cramer_rao_over``
        (above the settings' bound), ``max_insensitivity_pct``, ``n_flat``,
        ``trusted``, ``Lp_real_0``/``Lp_real_1`` (effective roll damping of the
        trimmed hover aircraft at 0 and 1 rad/s [1/s], when flown),
        ``Lp_real_0_load_path_only`` / ``Lp_real_0_flap_rate_path_only`` (the
        same at 0 rad/s with the model's flap-rate inputs, then its loads,
        disconnected: :func:`aircraft.inflow.paths.without_inputs`; a tilt
        model's tilt path counts as flapping path), ``Lp_real_0_without_tilt``
        (tilt models: the tilt path disconnected), ``KR_equivalent_steady_U`` / ``_L`` (each rotor's steady on-axis lambda1s
        answer to a tip-path-plane rate as the K_R of Eq. 2.29 it amounts to),
        ``steady_ratio_<control>`` and ``quasi_steady_passes`` (model / wake steady
        on-axis inflow change after held steps, when checked), ``wall_s`` (the
        identification's).
    models : dict
        The :class:`~aircraft.identification.IdentifiedModel` of each variant.
    """

    table: pd.DataFrame
    models: dict = field(default_factory=dict)

    def to_pandas(self):
        return self.table.copy()

    def plot(self, fig=None):
        """Bars per variant (numbered in table order): max CR % (log, the 20 % bound
        dashed), flat directions, J_ave, and Re L_p at 0 rad/s when flown (above
        zero: no roll damping left below the fit band), beside the same with only
        the load path and only the flap-rate path connected; a Figure."""
        from matplotlib.figure import Figure
        t = self.table
        panels = [("max_cramer_rao_pct", "max Cramér-Rao bound [%]"), ("n_flat", "flat directions"),
                  ("J_ave", "J_ave")]
        if "Lp_real_0" in t:
            panels.append(("Lp_real_0", "Re L_p at 0 rad/s [1/s]"))
        fig = fig or Figure(figsize=(3.3 * len(panels), 3.6))
        axes = fig.subplots(1, len(panels))
        labels = [str(k + 1) for k in range(len(t))]
        paths = [c for c in ("Lp_real_0_load_path_only", "Lp_real_0_flap_rate_path_only") if c in t]
        for ax, (col, title) in zip(axes, panels):
            if col == "Lp_real_0" and paths:
                # the whole model beside each of its paths alone
                x = np.arange(len(t))
                for k, (c, name) in enumerate(zip([col] + paths, ["model", "load path only",
                                                                  "flap-rate path only"])):
                    ax.bar(x + (k - 1) * 0.27, t[c].astype(float), width=0.27, label=name)
                ax.set_xticks(x, labels)
                ax.legend(fontsize=7)
            else:
                ax.bar(labels, t[col].astype(float))
            ax.set_title(title)
            ax.set_xlabel("variant")
        axes[0].set_yscale("log")
        axes[0].axhline(20.0, color="k", lw=0.8, ls="--")
        if "Lp_real_0" in t:
            axes[-1].axhline(0.0, color="k", lw=0.8)
        fig.tight_layout()
        return fig


def compare_twelve_state_variants(variants=None, config=None, *, ct=None, settings=None, fly=True,
                                  quasi_steady=True, hold_s=10.0, window=(6.0, 10.0), n_jobs=2,
                                  cache_dir="default", progress=True, references=None):
    """Identify each constrained 12-state structure from the same coaxial hover wake data.

    Parameters
    ----------
    variants : mapping of str to dict or Coaxial12StateConstrained, optional
        Label -> :class:`Coaxial12StateConstrained` keyword arguments or a
        structure (e.g. :class:`~aircraft.identification.tilt_inputs.Coaxial12StateTilt`)
        (default :data:`VARIANTS`).
    config : aircraft.AircraftConfig, optional
        Coaxial pair (default :func:`aircraft.configs.coaxial_compound`).
    ct : float, optional
        System trim thrust coefficient (split equally, torques balanced); default
        the shipped 12-state's recipe (0.0053 + 0.0043, so its cached wake runs are
        the ones read).
    settings : IdentificationSettings, optional
    fly : bool
        Trim and linearise the hover aircraft with each model and report its
        effective roll damping ``Re L_p`` at 0 and 1 rad/s (positive: the model
        takes the roll damping away below the fit band).
    quasi_steady : bool
        Also hold 0.02 rad steps of theta0 and theta1s per rotor in the wake
        (:func:`~aircraft.identification.quasi_steady_check`; one set of records,
        cached, for every variant) and report the on-axis model/wake ratios of the
        steady inflow change: the wake's own answer below the fit band.
    hold_s, window :
        Step record length and averaging window [s] of the quasi-steady check.
    n_jobs, cache_dir, progress :
        As :func:`~aircraft.identification.identify_inflow` (the wake runs are the
        same for every variant: one data set, cached after the first).
    references : mapping of str to IdentifiedInflow or str, optional
        Models flown beside the variants for their roll damping only (a shipped
        model's name, e.g. ``"published_eq6_8_6_9"``, or an inflow model): rows
        with the ``Lp_*`` columns and nothing fitted. Only with ``fly``.

    Returns
    -------
    TwelveStateComparison
    """
    from .pipeline import IdentificationSettings, identify_inflow
    from .regenerate import RECIPES
    recipe = RECIPES["coaxial_hover_12state"]
    ct = recipe.ct if ct is None else ct
    settings = recipe.settings if settings is None else settings
    if not isinstance(settings, IdentificationSettings):
        raise TypeError(f"settings must be an IdentificationSettings, got {type(settings).__name__}")
    if config is None:
        from aircraft.configs import coaxial_compound
        config = coaxial_compound()
    variants = dict(VARIANTS if variants is None else variants)
    if not variants:
        raise ValueError("variants is empty: give at least one label -> keyword arguments")
    references = _references(references) if fly else {}
    rows, models = [], {}
    for label, kwargs in variants.items():
        structure = kwargs if isinstance(kwargs, Coaxial12StateConstrained) else Coaxial12StateConstrained(**kwargs)
        t0 = time.perf_counter()
        model = identify_inflow(config, None, structure, ct=ct, settings=settings, name=label,
                                n_jobs=n_jobs, cache_dir=cache_dir, progress=progress)
        wall = time.perf_counter() - t0
        p = model.parameters
        free = p[p.status == "free"]
        cr = free.cramer_rao_pct.to_numpy(float)
        ct_ = model.cost_table
        loads = ct_[~ct_.input.str.contains("beta")]
        deg = model.fit.degeneracy
        row = {"variant": label, "J_ave": model.J_ave, "J_ave_load_pairs": float(loads.J.mean()),
               "n_free": len(free), "max_cramer_rao_pct": float(np.nanmax(np.where(np.isfinite(cr), cr, np.inf))),
               "n_cramer_rao_over": int((~(cr < model.settings.cramer_rao_max)).sum()),
               "max_insensitivity_pct": float(free.insensitivity_pct.max()),
               "n_flat": 0 if deg is None else len(deg.flat_directions), "trusted": model.trusted,
               "wall_s": wall}
        if fly:
            row.update(_roll_damping(model))
        if quasi_steady:
            from .quasi_steady import quasi_steady_check
            check = quasi_steady_check(model, config, ct=ct, settings=settings, hold_s=hold_s, window=window,
                                       n_jobs=n_jobs, cache_dir=cache_dir, progress=False)
            on = check.table[check.table.on_axis]
            row.update({f"steady_ratio_{c}": float(r) for c, r in zip(on.control, on.ratio)})
            row["quasi_steady_passes"] = check.passes()
        rows.append(row)
        models[label] = model
    for label, inflow in references.items():
        rows.append({"variant": label, **_roll_damping_of(inflow)})
    return TwelveStateComparison(pd.DataFrame(rows), models)


def _references(references):
    """{label: IdentifiedInflow} from labels to inflow models or shipped models' names."""
    from aircraft.inflow import IdentifiedInflow
    out = {}
    for label, inflow in dict(references or {}).items():
        if isinstance(inflow, str):
            inflow = IdentifiedInflow.from_file(inflow)
        if not isinstance(inflow, IdentifiedInflow):
            raise TypeError(f"reference {label!r} must be an IdentifiedInflow or a shipped model's name, "
                            f"got {type(inflow).__name__}")
        out[label] = inflow
    return out


def _roll_damping(model):
    """Effective roll damping Re L_p [1/s] of the hover aircraft flying ``model``: at 0
    and 1 rad/s, and at 0 rad/s with each of its input paths alone (the flap-rate
    inputs disconnected, then the loads), which says which path takes it away."""
    return _roll_damping_of(model.to_inflow())


def _roll_damping_of(inflow):
    from aircraft.inflow.paths import without_inputs
    out = _lp(inflow, [0.0, 1.0])
    row = {"Lp_real_0": out[0], "Lp_real_1": out[1]}
    if inflow.uses_flap_rates:
        tilted = getattr(inflow, "uses_flap_tilts", False)

        def _with_tilt(model):
            # a tilt model's flapping path is its flap rates and its tilts together
            from aircraft.inflow.tilt import TiltInflow
            return TiltInflow.from_inflow(model, inflow.tilt_matrix, inflow.tilt_names) if tilted else model
        row["Lp_real_0_load_path_only"] = _lp(without_inputs(inflow, inflow.rate_names), [0.0])[0]
        row["Lp_real_0_flap_rate_path_only"] = _lp(_with_tilt(without_inputs(inflow, inflow.load_names)), [0.0])[0]
        if tilted:
            row["Lp_real_0_without_tilt"] = _lp(inflow.without_tilts(), [0.0])[0]
        row.update(_steady_curvature(inflow))
    return row


def _steady_curvature(inflow):
    """Each rotor's steady on-axis wake-curvature gain as an equivalent K_R [-].

    Eq. 2.29 at zero frequency gives ``lambda1s = -K_R * beta1s_dot / Omega`` for the
    full tip-path-plane rate (body rate included) that the aircraft feeds the flap-
    rate inputs, so ``-Omega`` times the model's DC gain lambda1s_r / beta1s_dot_r is
    the K_R it acts with in a steady roll (analytical 1.5, the dissertation's
    identified 1.44)."""
    import control
    from aircraft.configs import coaxial_compound
    omega = float(coaxial_compound().rotors[0].omega)
    sys = inflow.system
    gain = np.real(np.asarray(control.dcgain(sys)))
    outs, ins = list(sys.output_labels), list(sys.input_labels)
    return {f"KR_equivalent_steady_{r}": -omega * float(gain[outs.index(f"lam1s_{r}"), ins.index(f"beta1s_dot_{r}")])
            for r in inflow.rotors}


def _lp(inflow, omega):
    from aircraft.configs import coaxial_compound
    from aircraft.helicopter import HelicopterSettings, effective_derivative, linearize, trim
    from aircraft.helicopter.tilt_coupling import helicopter_for
    tr = trim(helicopter_for(coaxial_compound(), inflow, HelicopterSettings(n_span=8, n_average=1)))
    return [float(v.real) for v in effective_derivative(linearize(tr), "p", "p", omega)]
