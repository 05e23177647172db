"""The coaxial 6-state hover model across a design space: :func:`identify_design_space`.

::

    for each rotor spacing h/R x system thrust C_T of the grid:
        coaxial_compound() with the lower hub moved (spaced_config)
        ─► identify_inflow(..., structure, ct=C_T)   (wake runs through the executor, cached;
                                                      default "coaxial_6state")
    ─► DesignSpaceResult: key coefficients per point (cross-rotor M and Lbar, CR %,
       insensitivity %, J_ave, trusted), .to_pandas(), .plot()
    ─► .schedule(spacing, ct): aircraft.inflow.ScheduledInflow, the identified
       matrices interpolated linearly in h/R and C_T (no extrapolation);
       require_trusted=True: over the largest sub-grid of trusted points only

This is the dissertation's recommendation 2 (identify the inflow across the design
space). The points are identified one after another; each one's independent wake
runs (six sweeps, a doublet and a zero-input run) fan out through the executor of
:func:`aircraft.wake.run_sweeps`, so a point costs what one
:func:`identify_inflow` costs (coarse wake: about 3 min of 2 idle cores).
``scheduler`` is passed on to :func:`identify_inflow` once it takes one (a Dask
scheduler for the wake runs); until then giving one raises.
"""
from __future__ import annotations

import dataclasses
import inspect
import itertools
import math
import time
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from .pipeline import IdentificationSettings, PipelineError, identify_inflow
from .structures import get_structure
from .structures.hover import Coaxial6State

__all__ = ["DesignSpaceError", "DesignPoint", "DesignSpaceResult", "KEY_PARAMETERS", "SPACINGS", "THRUSTS",
           "DEFAULT_STRUCTURE", "spaced_config", "identify_design_space"]

#: Default grid: rotor spacings h/R [-] (0.14 is Table B.1's) ...
SPACINGS = (0.10, 0.14, 0.20, 0.30)
#: ... and system thrust coefficients [-] (0.0096 is the dissertation's split 0.0053 + 0.0043).
THRUSTS = (0.0075, 0.0096)

#: The coefficients tabulated per point: the cross-rotor couplings of M and Lbar
#: (upper <- lower: 14, 25; lower <- upper: 41, 52; in the 6-state structure these are
#: all of Lbar's off-diagonal terms) beside the diagonal Lbar (own-rotor gains).
KEY_PARAMETERS = ("m14", "m41", "m25", "m52", "l14", "l41", "l25", "l52", "l11", "l44", "l22", "l55")

_STRUCTURE = Coaxial6State("rotor")
#: The structure :func:`identify_design_space` fits unless told otherwise (free apparent masses).
DEFAULT_STRUCTURE = "coaxial_6state"


class DesignSpaceError(ValueError):
    """A design-space grid, configuration or result that cannot be used."""


def spaced_config(config=None, spacing=0.14):
    """A coaxial configuration with its lower rotor moved to ``spacing`` radii below the upper.

    Parameters
    ----------
    config : aircraft.AircraftConfig, optional
        Coaxial configuration: two rotors with distinct names, the upper one first
        (default :func:`aircraft.configs.coaxial_compound`, rotors ``"U"``, ``"L"``).
        Only the lower hub's vertical position changes (``dataclasses.replace``);
        the upper hub and the rotor names stay.
    spacing : float
        Hub-to-hub distance over the upper rotor's radius, ``h/R`` [-], > 0.

    Returns
    -------
    aircraft.AircraftConfig
        ``config`` itself if it already has this spacing (so its cached wake runs
        are reused), else a copy named ``"<name>, h/R <spacing>"``.

    Raises
    ------
    DesignSpaceError
        If ``config`` is not a coaxial pair (two rotors, distinct names) or
        ``spacing`` is not a positive number.

    Examples
    --------
    >>> from aircraft.configs import coaxial_compound
    >>> cfg = spaced_config(coaxial_compound(), 0.2)
    >>> upper, lower = cfg.rotors
    >>> (upper.name, lower.name), round((lower.hub_position[2] - upper.hub_position[2]) / upper.radius, 9)
    (('U', 'L'), 0.2)
    """
    from aircraft.configs import coaxial_compound
    config = coaxial_compound() if config is None else config
    _coaxial_names(config)
    if isinstance(spacing, bool) or not isinstance(spacing, (int, float, np.floating)) \
            or not math.isfinite(spacing) or spacing <= 0:
        raise DesignSpaceError(f"spacing must be a positive number of radii, got {spacing!r}")
    upper, lower = config.rotors
    radius = float(upper.radius)
    z_lower = float(upper.hub_position[2]) + float(spacing) * radius    # body z down: lower is below
    if math.isclose(z_lower, float(lower.hub_position[2]), rel_tol=0.0, abs_tol=1e-9 * radius):
        return config
    x, y, _ = lower.hub_position
    moved = dataclasses.replace(lower, hub_position=(x, y, z_lower))
    return dataclasses.replace(config, rotors=(upper, moved), name=f"{config.name}, h/R {float(spacing):g}")


def _coaxial_names(config):
    """The (upper, lower) rotor names of a coaxial configuration; DesignSpaceError otherwise."""
    from aircraft.inflow.base import check_rotor_names
    names = tuple(getattr(r, "name", None) for r in (getattr(config, "rotors", None) or ()))
    try:
        return check_rotor_names(names, 2, argument="config rotor names", error=DesignSpaceError)
    except DesignSpaceError as err:
        raise DesignSpaceError(f"a coaxial configuration (two rotors, upper first, distinct names) is needed: "
                               f"{err}") from None


def _grid_axis(values, name):
    try:
        a = [float(v) for v in values]
    except (TypeError, ValueError) as err:
        raise DesignSpaceError(f"{name} must be a sequence of numbers, got {values!r}") from err
    if not a or any(not math.isfinite(v) or v <= 0 for v in a):
        raise DesignSpaceError(f"{name} must be a non-empty sequence of positive numbers, got {values!r}")
    if any(b <= c for c, b in zip(a, a[1:])):
        raise DesignSpaceError(f"{name} must be strictly increasing, got {a}")
    return tuple(a)


@dataclass
class DesignPoint:
    """One grid point of :func:`identify_design_space`.

    Attributes
    ----------
    spacing : float
        Rotor spacing h/R [-].
    ct : float
        System thrust coefficient [-] requested of the trim.
    model : IdentifiedModel or None
        The identification (None if it failed).
    error : str or None
        Why the identification failed (trim, excitation, unstable model).
    wall_s : float
        Wall time of this point [s].
    """

    spacing: float
    ct: float
    model: object = None
    error: str | None = None
    wall_s: float = 0.0

    @property
    def ok(self) -> bool:
        """Identified, with a stable model (usable in a schedule)."""
        return self.model is not None and self.error is None


@dataclass
class DesignSpaceResult:
    """Outcome of :func:`identify_design_space`.

    Attributes
    ----------
    spacings, cts : tuple of float
        Grid axes: h/R [-] and system C_T [-].
    points : list of DesignPoint
        Row-major: spacing outer, thrust inner.
    wall_s : float
        Wall time of the whole grid [s].
    settings : IdentificationSettings
    meta : dict
        The configuration's name and the structure's label.
    structure : InflowStructure, optional
        The structure fitted at every point (default: the free-mass coaxial 6-state).
    """

    spacings: tuple
    cts: tuple
    points: list
    wall_s: float = 0.0
    settings: object = None
    meta: dict = field(default_factory=dict)
    structure: object = None

    @property
    def fitted_structure(self):
        """The structure of the points (the free-mass coaxial 6-state when none was recorded)."""
        return _STRUCTURE if self.structure is None else self.structure

    def _thrust_names(self):
        """The trim thrust signals of the rotors, ``CT_U, CT_L`` with the default names."""
        return [n for n in self.fitted_structure.loads if n.startswith("CT")]

    def point(self, spacing, ct) -> DesignPoint:
        """The grid point at (``spacing`` [-], ``ct`` [-]); DesignSpaceError if there is none."""
        for p in self.points:
            if math.isclose(p.spacing, spacing, rel_tol=1e-9) and math.isclose(p.ct, ct, rel_tol=1e-9):
                return p
        raise DesignSpaceError(f"no grid point at h/R {spacing}, C_T {ct} (grid {self.spacings} x {self.cts})")

    @property
    def failed(self) -> list:
        return [p for p in self.points if not p.ok]

    def to_pandas(self) -> pd.DataFrame:
        """Long table: one row per (point, key parameter).

        Columns: spacing, ct, parameter, value, status, cramer_rao_pct,
        insensitivity_pct, J_ave, trusted, CT_U, CT_L (the wake trim's), wall_s,
        error (``CT_<rotor>`` with the structure's rotor names). A failed point has
        one row with its error and no parameter.
        """
        thrusts = self._thrust_names()
        rows = []
        for p in self.points:
            base = {"spacing": p.spacing, "ct": p.ct, "wall_s": round(p.wall_s, 1)}
            if p.model is None:
                rows.append({**base, "parameter": None, "status": "failed", "trusted": False, "error": p.error})
                continue
            m = p.model
            params = m.parameters.set_index("parameter")
            o = m.trim.outputs
            for name in KEY_PARAMETERS:
                r = params.loc[name]
                rows.append({**base, "parameter": name, "value": float(r.value), "status": r.status,
                             "cramer_rao_pct": float(r.cramer_rao_pct), "insensitivity_pct": float(r.insensitivity_pct),
                             "J_ave": m.J_ave, "trusted": m.trusted, **{n: float(o[n]) for n in thrusts},
                             "error": p.error})
        cols = ["spacing", "ct", "parameter", "value", "status", "cramer_rao_pct", "insensitivity_pct", "J_ave",
                "trusted", *thrusts, "wall_s", "error"]
        return pd.DataFrame(rows).reindex(columns=cols)

    def summary_table(self) -> pd.DataFrame:
        """Wide table: one row per point, the key values, J_ave, max CR %, max insensitivity %,
        trusted, the trim thrusts, error, ``trust_failures`` (the trust check's reasons,
        joined by " | "; empty when trusted) and wall_s."""
        thrusts = self._thrust_names()
        rows = []
        for p in self.points:
            row = {"spacing": p.spacing, "ct": p.ct}
            if p.model is not None:
                m = p.model
                params = m.parameters.set_index("parameter")
                free = params[params.status == "free"]
                row.update({n: float(params.loc[n, "value"]) for n in KEY_PARAMETERS})
                row.update({"J_ave": m.J_ave, "max_cramer_rao_pct": float(free.cramer_rao_pct.max()),
                            "max_insensitivity_pct": float(free.insensitivity_pct.max()), "trusted": m.trusted,
                            **{n: float(m.trim.outputs[n]) for n in thrusts},
                            "error": p.error, "trust_failures": _trust_failures(m)})
            else:
                row.update({"trusted": False, "error": p.error})
            row["wall_s"] = round(p.wall_s, 1)
            rows.append(row)
        return pd.DataFrame(rows)

    def plot(self, parameters=KEY_PARAMETERS[:8], fig=None):
        """Key coefficients against spacing, one line per thrust; a matplotlib Figure.

        Parameters
        ----------
        parameters : sequence of str
            Parameters to draw, one panel each (default: the cross-rotor M and Lbar).
        fig : matplotlib.figure.Figure, optional
            Figure to draw into (default: a new one).

        Returns
        -------
        matplotlib.figure.Figure
            Error bars: the Cramér-Rao bound (one sigma); hollow markers: parameters
            above the guideline (CR > 20 % or insensitivity > 10 %) or eliminated.
        """
        from matplotlib.figure import Figure
        table = self.to_pandas().dropna(subset=["parameter"])
        unknown = [p for p in parameters if p not in KEY_PARAMETERS]
        if unknown:
            raise DesignSpaceError(f"unknown parameters {unknown}; choose from {KEY_PARAMETERS}")
        fig = fig or Figure(figsize=(3.2 * min(4, len(parameters)), 2.8 * math.ceil(len(parameters) / 4)))
        ncol = min(4, len(parameters))
        axes = fig.subplots(math.ceil(len(parameters) / ncol), ncol, squeeze=False).ravel()
        for ax, name in zip(axes, parameters):
            sub = table[table.parameter == name]
            for k, ct in enumerate(self.cts):
                line = sub[np.isclose(sub.ct, ct)].sort_values("spacing")
                if line.empty:
                    continue
                sigma = (line.value.abs() * line.cramer_rao_pct / 100.0).where(line.status == "free", 0.0)
                color = f"C{k}"
                ax.errorbar(line.spacing, line.value, yerr=sigma.to_numpy(), color=color, marker="",
                            capsize=2, label=f"C_T {ct:g}")
                good = (line.status == "free") & (line.cramer_rao_pct < 20) & (line.insensitivity_pct < 10)
                ax.plot(line.spacing[good], line.value[good], "o", color=color)
                ax.plot(line.spacing[~good], line.value[~good], "o", mfc="none", color=color)
            ax.axhline(0.0, color="0.7", lw=0.5)
            ax.set_title(name)
            ax.set_xlabel("h/R")
        for ax in axes[len(parameters):]:
            ax.set_visible(False)
        axes[0].legend(fontsize=7)
        fig.suptitle("coaxial 6-state hover model across the design space (hollow: not well identified)",
                     fontsize=9)
        fig.tight_layout()
        return fig

    def trusted_subgrid(self):
        """The largest rectangular sub-grid whose every node is identified and trusted.

        Returns
        -------
        tuple of (tuple of float, tuple of float)
            Its spacings h/R [-] and thrusts C_T [-] (the most nodes; on a tie the
            one with the most thrusts, then the first in grid order). Both empty
            when no point is trusted. The retained spacings (or thrusts) need not be
            neighbours on the grid: an untrusted row or column is skipped.

        Examples
        --------
        >>> from types import SimpleNamespace
        >>> pts = [DesignPoint(s, c, SimpleNamespace(trusted=(s, c) != (0.2, 0.0075)))
        ...        for s in (0.1, 0.2, 0.3) for c in (0.0075, 0.0096)]
        >>> DesignSpaceResult((0.1, 0.2, 0.3), (0.0075, 0.0096), pts).trusted_subgrid()
        ((0.1, 0.3), (0.0075, 0.0096))
        """
        ok = np.array([[self.point(s, c).ok and bool(self.point(s, c).model.trusted) for c in self.cts]
                       for s in self.spacings], bool)
        best = ((), ())
        # a fixed set of thrusts keeps every spacing trusted at all of them: try each set
        for k in range(len(self.cts), 0, -1):
            for cols in itertools.combinations(range(len(self.cts)), k):
                rows = [i for i in range(len(self.spacings)) if ok[i, list(cols)].all()]
                if len(rows) * k > len(best[0]) * len(best[1]):
                    best = (tuple(self.spacings[i] for i in rows), tuple(self.cts[j] for j in cols))
        return best

    def schedule(self, spacing=None, ct=None, *, require_trusted=False, pade_order=None, name=None):
        """The identified models interpolated over the grid (an aircraft inflow model).

        Parameters
        ----------
        spacing : float, optional
            Rotor spacing h/R [-] of the returned model (default: the first node's).
        ct : float, optional
            System thrust coefficient [-] (default: the first node's).
        require_trusted : bool
            ``False``: every grid point is a node (each one's trust is carried in
            ``ScheduledInflow.trusted``). ``True``: only trusted points are nodes, on
            the largest rectangular sub-grid of trusted points
            (:meth:`trusted_subgrid`): untrusted or failed points are left out and
            the schedule interpolates across them.
        pade_order : int, optional
            Padé order of the delays (default: the identification settings').
        name : str, optional

        Returns
        -------
        aircraft.inflow.ScheduledInflow

        Raises
        ------
        DesignSpaceError
            Without ``require_trusted``, if a grid point failed (the grid would have
            a hole); with it, if fewer than two trusted nodes remain (nothing to
            interpolate).
        aircraft.inflow.InflowError
            If the point is outside the (sub-)grid or the interpolated model is unstable.
        """
        from aircraft.inflow import ScheduledInflow
        if not isinstance(require_trusted, (bool, np.bool_)):
            raise DesignSpaceError(f"require_trusted must be True or False, got {require_trusted!r}")
        if require_trusted:
            spacings, cts = self.trusted_subgrid()
            if len(spacings) * len(cts) < 2:
                trusted = [f"h/R {p.spacing:g}, C_T {p.ct:g}" for p in self.points if p.ok and p.model.trusted]
                raise DesignSpaceError(
                    f"require_trusted: {len(trusted)} trusted point(s) of {len(self.points)} "
                    f"({', '.join(trusted) or 'none'}); a schedule needs at least two trusted nodes on a "
                    "rectangular sub-grid to interpolate")
        else:
            spacings, cts = self.spacings, self.cts
            if self.failed:
                raise DesignSpaceError("cannot schedule over a grid with failed points: " + "; ".join(
                    f"h/R {p.spacing:g}, C_T {p.ct:g}: {p.error}" for p in self.failed))
        structure = self.fitted_structure
        shape = (len(spacings), len(cts))
        n = len(structure.outputs)
        grid = {k: np.zeros(shape + (n, n)) for k in ("M", "Lbar", "tau")}
        grid.update(loads_ref=np.zeros(shape + (n,)), inflow_ref=np.zeros(shape + (n,)))
        trusted = np.zeros(shape, bool)
        omegas = set()
        for i, s in enumerate(spacings):
            for j, c in enumerate(cts):
                m = self.point(s, c).model
                mats = m.fit.structure.matrices()
                grid["M"][i, j], grid["Lbar"][i, j], grid["tau"][i, j] = mats["M"], mats["Lbar"], mats["tau"]
                grid["loads_ref"][i, j], grid["inflow_ref"][i, j] = m._refs()
                trusted[i, j] = m.trusted
                omegas.add(round(m.omega, 9))
        if len(omegas) != 1:
            raise DesignSpaceError(f"the grid mixes rotor speeds {sorted(omegas)} rad/s")
        order = pade_order if pade_order is not None else (self.settings.pade_order if self.settings else 2)
        label = self.meta.get("structure", "coaxial 6-state")
        return ScheduledInflow(spacings, cts, omega=omegas.pop(),
                               spacing=spacings[0] if spacing is None else spacing,
                               ct=cts[0] if ct is None else ct, rotors=structure.rotors,
                               pade_order=order, name=name or f"{label} scheduled in h/R and C_T",
                               trusted=trusted, **grid)


def _trust_failures(model):
    """The trust check's reasons, joined (a stand-in model without them: empty)."""
    failures = getattr(model, "trust_failures", None)
    return " | ".join(failures()) if callable(failures) else ""


def _design_structure(structure):
    """(instance, label) of a coaxial M/Lbar/tau structure; DesignSpaceError otherwise."""
    if isinstance(structure, str) and structure == DEFAULT_STRUCTURE:
        return _STRUCTURE, "coaxial 6-state"      # the instance the study has always fitted
    try:
        inst = get_structure(structure)
    except (ValueError, TypeError) as err:
        raise DesignSpaceError(f"structure: {err}") from err
    if getattr(inst, "form", None) != "mltau" or len(inst.rotors) != 2 or len(inst.outputs) != 6:
        raise DesignSpaceError(f"structure must be a coaxial 6-state M/Lbar/tau structure (two rotors) "
                               f"(a schedule interpolates M, Lbar, tau), got {structure!r}")
    return inst, (structure if isinstance(structure, str) else inst.key)


def _for_rotors(structure, names):
    """``structure`` with the configuration's rotor names: renamed when it has its class's
    default names, else they must already be ``names`` (DesignSpaceError)."""
    try:
        return structure.for_rotors(names)
    except ValueError as err:
        raise DesignSpaceError(f"structure rotors do not match the configuration's: {err}") from None


def _scheduler_kwargs(scheduler):
    if scheduler is None:
        return {}
    if "scheduler" not in inspect.signature(identify_inflow).parameters:
        raise DesignSpaceError("this aircraft.identify_inflow takes no scheduler= (the Dask executor is not "
                               "available in this version); leave scheduler=None for the local pool")
    return {"scheduler": scheduler}


def identify_design_space(spacings=SPACINGS, cts=THRUSTS, *, structure=DEFAULT_STRUCTURE, config=None,
                          condition=None, settings=None, n_jobs=2, cache_dir="default", progress=True,
                          scheduler=None, on_error="record"):
    """Identify a coaxial 6-state hover model at every (spacing, thrust) of a grid.

    Parameters
    ----------
    spacings : sequence of float
        Rotor spacings h/R [-], strictly increasing (default :data:`SPACINGS`).
    cts : sequence of float
        System thrust coefficients [-], strictly increasing (default
        :data:`THRUSTS`); each is shared equally by the rotors, torques balanced.
    structure : str or InflowStructure
        The coaxial 6-state M/Lbar/tau structure fitted at every point: a key of
        :data:`aircraft.identification.STRUCTURES` or an instance (default
        :data:`DEFAULT_STRUCTURE`, free apparent masses; the shipped model's is
        ``"coaxial_6state_axisymmetric_pp_collective_mass"``). Every point uses the
        same six swashplate sweeps whatever the structure, so the wake runs are shared.
    config : aircraft.AircraftConfig, optional
        Coaxial configuration whose lower hub is moved (default
        :func:`aircraft.configs.coaxial_compound`); its rotor names name the
        signals (a structure with its class's default names is renamed to them).
    condition : aircraft.wake.FlightCondition, optional
        Flight condition (default hover).
    settings : IdentificationSettings, optional
        Identification settings of every point (wake resolution, sweep length).
    n_jobs : int
        Wake worker processes of the executor.
    cache_dir : str or None
        Wake run cache (see :func:`aircraft.wake.run_sweeps`).
    progress : bool
        Progress bars (one line per point, plus the pipeline's).
    scheduler : str or dask.distributed.Client, optional
        Passed on to :func:`identify_inflow` where it accepts one (Dask executor).
    on_error : {"record", "raise"}
        ``"record"``: a point whose identification fails (trim, excitation,
        records too short for the band, unstable model) is kept with its error
        and the others go on;
        ``"raise"``: the first failure raises.

    Returns
    -------
    DesignSpaceResult

    Raises
    ------
    DesignSpaceError
        Bad grid, ``structure``, ``on_error`` or ``scheduler`` (before any wake run).
    PipelineError, aircraft.wake.WakeTrimError, aircraft.inflow.InflowError, flightid.IdentificationError
        With ``on_error="raise"``, the first failed point.
    """
    from aircraft.inflow import InflowError
    spacings = _grid_axis(spacings, "spacings")
    cts = _grid_axis(cts, "cts")
    if on_error not in ("record", "raise"):
        raise DesignSpaceError(f"on_error must be 'record' or 'raise', got {on_error!r}")
    if settings is not None and not isinstance(settings, IdentificationSettings):
        raise DesignSpaceError(f"settings must be an IdentificationSettings, got {type(settings).__name__}")
    extra = _scheduler_kwargs(scheduler)
    struct, label = _design_structure(structure)
    configs = {s: spaced_config(config, s) for s in spacings}   # validates config before any run
    struct = _for_rotors(struct, _coaxial_names(next(iter(configs.values()))))
    from aircraft.wake.trim import WakeTrimError     # the wake (numba) only once the input is valid
    from flightid import IdentificationError         # e.g. records too short for the sweep band
    t0 = time.perf_counter()
    points = []
    for s in spacings:
        for c in cts:
            if progress:
                print(f"design space: h/R {s:g}, C_T {c:g} ({len(points) + 1}/{len(spacings) * len(cts)})",
                      flush=True)
            t1 = time.perf_counter()
            model = None
            try:
                model = identify_inflow(configs[s], condition, struct, ct=c, settings=settings,
                                        name=f"{label}, h/R {s:g}, C_T {c:g}", n_jobs=n_jobs,
                                        cache_dir=cache_dir, progress=progress, **extra)
                model.to_inflow()        # an unstable identified model cannot be scheduled: say so here
                points.append(DesignPoint(s, c, model, None, time.perf_counter() - t1))
            except (PipelineError, WakeTrimError, InflowError, IdentificationError, np.linalg.LinAlgError) as err:
                if on_error == "raise":
                    raise
                # the model (if any) stays for the table; the point is left out of a schedule
                points.append(DesignPoint(s, c, model, f"{type(err).__name__}: {err}", time.perf_counter() - t1))
    return DesignSpaceResult(spacings, cts, points, time.perf_counter() - t0, settings or IdentificationSettings(),
                             {"config": getattr(config, "name", "coaxial_compound()"), "structure": label},
                             struct)
