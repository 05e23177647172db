"""Constrained 12-state coaxial structures compared on one wake data set.

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

import time
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from aircraft.identification.structures.constrained import VARIANTS, Coaxial12StateConstrained

__all__ = ["TwelveStateComparison", "compare_twelve_state_variants"]


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
                                  cache_dir="default", progress=True, references=None, reproduce="if_trusted"):
    """Identify each constrained 12-state structure from the same coaxial hover wake data.

    Parameters
    ----------
    variants : mapping of str to dict or Coaxial12StateConstrained, optional
        Label -> :class:`Coaxial12StateConstrained` keyword arguments or a
        structure (e.g. :class:`~aircraft.identification.structures.tilt.Coaxial12StateTilt`)
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
    reproduce : bool or "if_trusted"
        As :func:`~aircraft.identification.identify_inflow`: the second wake data set
        of the reproduction check (one set, cached, for every variant that needs it).
    references : mapping of str to IdentifiedInflow or str, optional
        Models flown beside the variants for their roll damping only (a shipped
        model's name, e.g. ``"published_eq6_8_6_9"``, or an inflow model): rows
        with the ``Lp_*`` columns and nothing fitted. Only with ``fly``.

    Returns
    -------
    TwelveStateComparison
    """
    from aircraft.identification.pipeline import IdentificationSettings, identify_inflow
    from aircraft.identification.shipped import RECIPES
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
                                n_jobs=n_jobs, cache_dir=cache_dir, progress=progress, reproduce=reproduce)
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
               "reproduction": model.trust.limits["reproduction"],
               "wall_s": wall}
        if fly:
            row.update(_roll_damping(model))
        if quasi_steady:
            from aircraft.identification.quasi_steady import quasi_steady_check
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
