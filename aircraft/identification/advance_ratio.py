"""The single-rotor 3-state inflow model identified over advance ratio, beside Pitt-Peters.

::

    identify_over_advance_ratio   one identification per mu (hover 3-state at mu = 0, the
                                  forward-flight structure above), in one call
    AdvanceRatioSweep             the models; .to_pandas() (every M, Lbar entry per mu beside
                                  the linearised Pitt-Peters), .plot() (the entries vs mu)

``M`` entries are reported as ``M/Omega`` [s] (the way the tables of the forward-flight
models print them); ``Lbar`` is dimensionless.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from .forward_flight import identify_forward_flight, pitt_peters_forward
from .structures.forward import FORWARD_FIT_PAIRS

__all__ = ["identify_over_advance_ratio", "AdvanceRatioSweep", "ADVANCE_RATIO_COEFFICIENTS"]

#: (label, matrix, (row, column)) of the entries tabulated and plotted; the three
#: groups are the diagonal M, the diagonal Lbar and the longitudinal Lbar couplings.
ADVANCE_RATIO_COEFFICIENTS = (
    ("M11/Omega [s]", "M", (0, 0)), ("M22/Omega [s]", "M", (1, 1)), ("M33/Omega [s]", "M", (2, 2)),
    ("Lbar11", "Lbar", (0, 0)), ("Lbar22", "Lbar", (1, 1)), ("Lbar33", "Lbar", (2, 2)),
    ("Lbar13", "Lbar", (0, 2)), ("Lbar31", "Lbar", (2, 0)))

_GROUPS = (("apparent mass M/Omega [s]", ("M11/Omega [s]", "M22/Omega [s]", "M33/Omega [s]")),
           ("Lbar diagonal [-]", ("Lbar11", "Lbar22", "Lbar33")),
           ("Lbar couplings [-]", ("Lbar13", "Lbar31")))


@dataclass
class AdvanceRatioSweep:
    """Identified 3-state models over advance ratio (from :func:`identify_over_advance_ratio`).

    Attributes
    ----------
    models : dict
        ``{mu: IdentifiedModel}``.
    alpha : float
        Shaft angle of attack [rad] of every condition.
    omega : float
        Rotor speed [rad/s].
    """

    models: dict
    alpha: float = 0.0
    omega: float = 27.0
    _pp_cache: dict = field(default_factory=dict, repr=False)

    @property
    def mus(self):
        """The advance ratios, ascending."""
        return sorted(self.models)

    def _pitt_peters(self, ct, mu):
        key = (round(float(ct), 12), round(float(mu), 12))
        if key not in self._pp_cache:
            self._pp_cache[key] = pitt_peters_forward(ct, mu, self.alpha, self.omega)
        return self._pp_cache[key]

    def to_pandas(self) -> pd.DataFrame:
        """Every tabulated entry per advance ratio beside the linearised Pitt-Peters.

        Returns
        -------
        pandas.DataFrame
            Columns ``mu``, ``coefficient``, ``ours``, ``cramer_rao_pct``,
            ``insensitivity_pct``, ``status`` (free, or fixed/removed by the
            reduction, ``tied`` to another entry, ``not in model``), ``pitt_peters``
            (linearised at the wake's trimmed C_T), ``trusted`` (the model's verdict)
            and ``J_ave``.
        """
        rows = []
        for mu in self.mus:
            model = self.models[mu]
            mats = model.fit.structure.matrices()
            p = model.parameters.set_index("parameter")
            pp_m, pp_l = self._pitt_peters(model.trim.outputs["CT"], mu)
            trusted = bool(model.trusted)
            for label, mat, (i, j) in ADVANCE_RATIO_COEFFICIENTS:
                scale = 1.0 / model.omega if mat == "M" else 1.0
                name = f"{'m' if mat == 'M' else 'l'}{i + 1}{j + 1}"
                if name in p.index:
                    cr, ins, status = p.loc[name, "cramer_rao_pct"], p.loc[name, "insensitivity_pct"], \
                        p.loc[name, "status"]
                else:
                    cr, ins = np.nan, np.nan
                    status = "tied" if mats[mat][i, j] != 0 else "not in model"
                pp = pp_m[i, j] * scale if mat == "M" else pp_l[i, j]
                rows.append({"mu": float(mu), "coefficient": label, "ours": float(mats[mat][i, j]) * scale,
                             "cramer_rao_pct": float(cr), "insensitivity_pct": float(ins), "status": status,
                             "pitt_peters": float(pp), "trusted": trusted, "J_ave": model.J_ave})
        return pd.DataFrame(rows)

    def plot(self, fig=None, n_points=31):
        """Each tabulated entry against advance ratio: ours (markers) and Pitt-Peters (lines).

        Three panels as the forward-flight comparison figures of the reference
        (diagonal M, diagonal Lbar, Lbar couplings). Untrusted models are drawn
        with open markers.

        Parameters
        ----------
        fig : matplotlib.figure.Figure, optional
        n_points : int
            Advance ratios of the Pitt-Peters lines.

        Returns
        -------
        matplotlib.figure.Figure
        """
        from matplotlib.figure import Figure
        fig = fig or Figure(figsize=(12, 4))
        axes = fig.subplots(1, 3)
        table = self.to_pandas()
        ct = float(np.mean([m.trim.outputs["CT"] for m in self.models.values()]))
        grid = np.linspace(0.0, max(self.mus), n_points)
        lines = {lab: [] for lab, *_ in ADVANCE_RATIO_COEFFICIENTS}
        for mu in grid:
            pm, pl = self._pitt_peters(ct, mu)
            for lab, mat, (i, j) in ADVANCE_RATIO_COEFFICIENTS:
                lines[lab].append(pm[i, j] / self.omega if mat == "M" else pl[i, j])
        for ax, (title, labels) in zip(axes, _GROUPS):
            for k, lab in enumerate(labels):
                color = f"C{k}"
                ax.plot(grid, lines[lab], "-", color=color, label=f"{lab} Pitt-Peters")
                rows = table[table.coefficient == lab]
                for trusted, face in ((True, color), (False, "none")):
                    sel = rows[rows.trusted == trusted]
                    if len(sel):
                        ax.plot(sel.mu, sel.ours, "o", color=color, markerfacecolor=face,
                                label=f"{lab} identified" + ("" if trusted else " (not trusted)"))
            ax.set_title(title)
            ax.set_xlabel("advance ratio mu [-]")
            ax.grid(True, alpha=0.3)
            ax.legend(fontsize=6)
        fig.tight_layout()
        return fig


def identify_over_advance_ratio(config, mus, *, alpha=0.0, ct=0.0061, settings=None, pattern="eq4_3",
                                n_jobs=2, cache_dir="default", progress=True, start="pitt_peters", pairs=FORWARD_FIT_PAIRS):
    """Identify the single-rotor 3-state inflow model at each advance ratio of ``mus``.

    ``mu = 0`` is identified with the hover 3-state structure (diagonal, cyclic
    rows tied: what hover symmetry leaves), every ``mu > 0`` with
    :func:`identify_forward_flight` (the longitudinal couplings of the
    forward-flight structure). All share ``settings``, the shaft angle and the trim
    thrust, so the entries are comparable across ``mu``.

    Parameters
    ----------
    config : aircraft.AircraftConfig
        A single-rotor configuration.
    mus : sequence of float
        Advance ratios, each >= 0, no repeats.
    alpha : float
        Shaft angle of attack [rad] (positive tilts the disk back).
    ct : float
        Trim thrust coefficient [-].
    settings : IdentificationSettings or dict, optional
        One for every mu, or ``{mu: IdentificationSettings}`` (a mu it lacks gets the
        defaults): e.g. a larger sweep amplitude where the wake's own unsteadiness is
        as large as the response.
    pattern : {"eq4_3", "full"}
        Forward-flight structure pattern (:class:`SingleRotorForward`).
    n_jobs : int
        Wake worker processes.
    cache_dir : str or None
        Wake run cache (see :func:`aircraft.wake.run_sweeps`).
    progress : bool
    start, pairs
        Forward-flight start and fitted responses (:func:`identify_forward_flight`).

    Returns
    -------
    AdvanceRatioSweep

    Raises
    ------
    ValueError
        Empty ``mus``, a negative, non-finite or repeated advance ratio, settings for
        an advance ratio not in ``mus``, or a configuration with more than one rotor.
    PipelineError
        A wake trim fails.

    Examples
    --------
    >>> from aircraft import uh60_single_rotor
    >>> sweep = identify_over_advance_ratio(uh60_single_rotor(), [0.0, 0.1, 0.2])   # doctest: +SKIP
    >>> sweep.to_pandas().pivot(index="coefficient", columns="mu", values="ours")   # doctest: +SKIP
    >>> identify_over_advance_ratio(uh60_single_rotor(), [])
    Traceback (most recent call last):
    ...
    ValueError: mus must hold at least one advance ratio, got []
    """
    from .conditions import flight_condition
    from .pipeline import identify_inflow
    from .structures.hover import SingleRotor3State
    mus = list(mus)
    if not mus:
        raise ValueError(f"mus must hold at least one advance ratio, got {mus!r}")
    for mu in mus:
        if isinstance(mu, bool) or not isinstance(mu, (int, float, np.integer, np.floating)) \
                or not np.isfinite(mu) or mu < 0:
            raise ValueError(f"mus must be finite advance ratios >= 0, got {mu!r}")
    if len(set(float(m) for m in mus)) != len(mus):
        raise ValueError(f"mus must not repeat an advance ratio, got {mus!r}")
    if len(config.rotors) != 1:
        raise ValueError(f"identify_over_advance_ratio is for a single rotor, got {len(config.rotors)} rotors")
    per_mu = {float(k): v for k, v in settings.items()} if isinstance(settings, dict) else None
    if per_mu is not None and set(per_mu) - {float(m) for m in mus}:
        raise ValueError(f"settings names advance ratios not in mus: {sorted(set(per_mu) - set(map(float, mus)))}")
    models = {}
    for mu in sorted(float(m) for m in mus):
        settings_mu = per_mu.get(mu) if per_mu is not None else settings
        if mu == 0.0:
            models[mu] = identify_inflow(config, flight_condition(config, 0.0, alpha), SingleRotor3State(),
                                         ct=float(ct), settings=settings_mu, name="single rotor mu = 0 (hover)",
                                         n_jobs=n_jobs, cache_dir=cache_dir, progress=progress)
        else:
            models[mu] = identify_forward_flight(config, mu, alpha=alpha, ct=ct, pattern=pattern,
                                                 settings=settings_mu, n_jobs=n_jobs, cache_dir=cache_dir,
                                                 progress=progress, start=start, pairs=pairs)
    return AdvanceRatioSweep(models, alpha=float(alpha), omega=float(config.rotors[0].omega))
