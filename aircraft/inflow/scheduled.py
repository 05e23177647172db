"""An inflow model scheduled over a design space: :class:`ScheduledInflow`.

Identified coaxial hover models (``M, Lbar, tau`` of Eq. 5.3, in our rotor frames)
at the nodes of a rectangular grid of rotor spacing ``h/R`` and system thrust
``C_T`` are interpolated *linearly* in both (bilinear on each cell)::

    P(h, C_T) = sum_corners w_h w_CT P_node       P = M, Lbar, tau, loads_ref, inflow_ref

and the interpolated matrices become an :class:`~aircraft.inflow.IdentifiedInflow`
(delays by Padé) to which every :class:`~aircraft.inflow.InflowModel` method is
delegated, so the aircraft (:class:`aircraft.helicopter.Helicopter`) loads it like
any identified model. A point outside the grid is refused: nothing is extrapolated.
An axis with a single node (one thrust, say) accepts only that node's value.

The grid usually comes from :func:`aircraft.identification.identify_design_space`
(``result.schedule()``); :meth:`ScheduledInflow.save` / :meth:`ScheduledInflow.from_file`
write and read it as JSON. This module, like :mod:`aircraft.inflow.identified`, does
not depend on :mod:`flightid`.
"""
from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pandas as pd

from .base import InflowModel, check_rotor_names, inflow_names, load_names
from .identified import IdentifiedInflow
from .pitt_peters import InflowError

__all__ = ["ScheduledInflow", "SCHEDULE_SCHEMA"]

#: Version tag of the JSON file written by :meth:`ScheduledInflow.save`.
SCHEDULE_SCHEMA = "rotorwake-inflow-schedule-1"

#: Relative tolerance on "at a grid node / inside the grid" [-]: a value given with
#: 12 significant digits (e.g. read back from a CSV) still counts as on the node.
_REL_TOL = 1e-9

_FIELDS = ("M", "Lbar", "tau", "loads_ref", "inflow_ref")


def _axis(values, name):
    a = np.asarray(values, float)
    if a.ndim != 1 or a.size < 1 or not np.all(np.isfinite(a)):
        raise InflowError(f"{name} must be a 1-D sequence of finite numbers, got {values!r}")
    if a.size > 1 and np.any(np.diff(a) <= 0):
        raise InflowError(f"{name} must be strictly increasing, got {a.tolist()}")
    return a


def _weights(axis, x, name, unit):
    """``[(index, weight), ...]`` of the linear interpolation of ``x`` on ``axis``."""
    if isinstance(x, bool) or not isinstance(x, (int, float, np.floating, np.integer)) or not math.isfinite(x):
        raise InflowError(f"{name} must be a finite number{unit}, got {x!r}")
    x = float(x)
    lo, hi = float(axis[0]), float(axis[-1])
    tol = _REL_TOL * max(abs(lo), abs(hi), 1e-300)
    if x < lo - tol or x > hi + tol:
        where = f"the grid node {lo:g}" if axis.size == 1 else f"the grid [{lo:g}, {hi:g}]"
        raise InflowError(f"{name} = {x:g}{unit} is outside {where}: the schedule does not extrapolate")
    if axis.size == 1:
        return [(0, 1.0)]
    x = min(max(x, lo), hi)
    i = int(np.clip(np.searchsorted(axis, x, side="right") - 1, 0, axis.size - 2))
    t = (x - axis[i]) / (axis[i + 1] - axis[i])
    return [(i, 1.0 - t), (i + 1, t)]


class ScheduledInflow(InflowModel):
    """Coaxial inflow model interpolated linearly in rotor spacing and thrust.

    Parameters
    ----------
    spacings : sequence of float
        Rotor spacings ``h/R`` of the grid nodes [-] (strictly increasing).
    cts : sequence of float
        System thrust coefficients ``C_T = C_T,U + C_T,L`` of the grid nodes [-]
        (strictly increasing).
    M, Lbar, tau : array_like, shape (n_spacings, n_cts, n, n)
        Apparent mass (multiplying d/dpsi, dimensionless, as Eq. 5.3), ``Lbar`` [-]
        and delays [s] at each node, in our rotor frames.
    omega : float
        Rotor speed [rad/s] (one for the whole grid).
    loads_ref, inflow_ref : array_like, shape (n_spacings, n_cts, n)
        Trim loads (C_T, C_L, C_M per rotor) and total inflow at each node [-].
    spacing : float
        Spacing ``h/R`` of this model [-], inside the grid.
    ct : float
        System thrust coefficient of this model [-], inside the grid.
    rotors : tuple of str
        Rotor names, upper first (default ``("U", "L")``; :meth:`for_aircraft`
        takes the aircraft's).
    pade_order : int
        Padé order of each non-zero delay.
    name : str
    trusted : array_like of bool, shape (n_spacings, n_cts), optional
        Whether each node's identification passed the guideline (CR < 20 %,
        insensitivity < 10 %); carried along and reported, not enforced.

    Raises
    ------
    InflowError
        Bad grid or array shapes, non-finite entries, a point outside the grid, or
        an interpolated model that is unstable (from :class:`IdentifiedInflow`).
    """

    def __init__(self, spacings, cts, M, Lbar, tau, *, omega, loads_ref, inflow_ref, spacing, ct,
                 rotors=("U", "L"), pade_order=2, name="scheduled inflow", trusted=None):
        self.spacings = _axis(spacings, "spacings")
        self.cts = _axis(cts, "cts")
        self.rotors = check_rotor_names(rotors, error=InflowError)
        n = 3 * len(self.rotors)
        shape = (self.spacings.size, self.cts.size)
        self._grid = {}
        for key, value, tail in (("M", M, (n, n)), ("Lbar", Lbar, (n, n)), ("tau", tau, (n, n)),
                                 ("loads_ref", loads_ref, (n,)), ("inflow_ref", inflow_ref, (n,))):
            arr = np.asarray(value, float)
            if arr.shape != shape + tail:
                raise InflowError(f"{key} must have shape {shape + tail} (spacings x cts x ...), got {arr.shape}")
            if not np.all(np.isfinite(arr)):
                raise InflowError(f"{key} has non-finite entries")
            self._grid[key] = arr
        if np.any(self._grid["tau"] < 0):
            raise InflowError("tau must be non-negative [s]")
        if isinstance(omega, bool) or not isinstance(omega, (int, float, np.floating)) or not omega > 0:
            raise InflowError(f"omega must be a positive number [rad/s], got {omega!r}")
        self.omega = float(omega)
        self.pade_order = int(pade_order)
        self.trusted = (np.ones(shape, bool) if trusted is None else np.asarray(trusted, bool))
        if self.trusted.shape != shape:
            raise InflowError(f"trusted must have shape {shape}, got {self.trusted.shape}")
        self.base_name = str(name)
        mats = self.matrices(spacing, ct)
        self.spacing, self.ct = float(spacing), float(ct)
        self.name = f"{self.base_name} (h/R {self.spacing:g}, C_T {self.ct:g})"
        self.model = IdentifiedInflow.from_matrices(
            mats["M"], mats["Lbar"], mats["tau"], omega=self.omega, rotors=self.rotors, time="azimuth",
            loads_ref=mats["loads_ref"], inflow_ref=mats["inflow_ref"], pade_order=self.pade_order,
            name=self.name)

    # -- the schedule --------------------------------------------------------------
    def matrices(self, spacing, ct):
        """The interpolated ``M, Lbar, tau, loads_ref, inflow_ref`` at a point of the grid.

        Parameters
        ----------
        spacing : float
            Rotor spacing ``h/R`` [-].
        ct : float
            System thrust coefficient [-].

        Returns
        -------
        dict of numpy.ndarray
            Keys ``"M", "Lbar", "tau", "loads_ref", "inflow_ref"``.

        Raises
        ------
        InflowError
            If the point lies outside the grid (no extrapolation) or is not a number.
        """
        ws = _weights(self.spacings, spacing, "spacing", " R")
        wc = _weights(self.cts, ct, "ct", "")
        return {key: sum(a * b * self._grid[key][i, j] for i, a in ws for j, b in wc) for key in _FIELDS}

    def at(self, spacing, ct):
        """The same schedule at another point (a new :class:`ScheduledInflow`).

        Parameters
        ----------
        spacing : float
            Rotor spacing ``h/R`` [-].
        ct : float
            System thrust coefficient [-].

        Returns
        -------
        ScheduledInflow
        """
        return ScheduledInflow(self.spacings, self.cts, omega=self.omega, spacing=spacing, ct=ct,
                               rotors=self.rotors, pade_order=self.pade_order, name=self.base_name,
                               trusted=self.trusted, **self._grid)

    def for_aircraft(self, config, ct=None):
        """The schedule at an aircraft's rotor spacing (from its hub positions).

        Parameters
        ----------
        config : aircraft.AircraftConfig
            Coaxial configuration; the spacing is the vertical distance of the hubs
            over the upper rotor's radius.
        ct : float, optional
            System thrust coefficient [-] (default: the sum of ``config.trim_ct``).

        Returns
        -------
        ScheduledInflow
            Its signals carry the configuration's rotor names (upper first), which
            may differ from the schedule's (same matrices, renamed).

        Raises
        ------
        InflowError
            If ``config`` does not have as many rotors as this schedule (with valid,
            distinct names), or its spacing or thrust is outside the grid.
        """
        rotors = tuple(getattr(r, "name", None) for r in (getattr(config, "rotors", None) or ()))
        if len(rotors) != len(self.rotors):
            raise InflowError(f"config rotors {rotors} do not match the schedule's {self.rotors}")
        rotors = check_rotor_names(rotors, argument="config rotor names", error=InflowError)
        upper, lower = config.rotors
        spacing = abs(float(lower.hub_position[2]) - float(upper.hub_position[2])) / float(upper.radius)
        if ct is None:
            if not getattr(config, "trim_ct", None):
                raise InflowError("config has no trim_ct: give ct")
            ct = float(sum(config.trim_ct))
        if rotors == self.rotors:
            return self.at(spacing, ct)
        return ScheduledInflow(self.spacings, self.cts, omega=self.omega, spacing=spacing, ct=ct,
                               rotors=rotors, pade_order=self.pade_order, name=self.base_name,
                               trusted=self.trusted, **self._grid)

    def to_pandas(self) -> pd.DataFrame:
        """The grid nodes: spacing, ct, trusted and the trim thrusts of each node."""
        rows = []
        loads = load_names(self.rotors)
        for i, s in enumerate(self.spacings):
            for j, c in enumerate(self.cts):
                row = {"spacing": float(s), "ct": float(c), "trusted": bool(self.trusted[i, j])}
                row.update({n: float(v) for n, v in zip(loads, self._grid["loads_ref"][i, j]) if n.startswith("CT")})
                rows.append(row)
        return pd.DataFrame(rows)

    # -- file --------------------------------------------------------------------
    def save(self, path):
        """Write the grid (not the point) as JSON.

        Parameters
        ----------
        path : str or Path
            File to write (``.json``).

        Returns
        -------
        Path
        """
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        doc = {"schema": SCHEDULE_SCHEMA, "name": self.base_name, "rotors": list(self.rotors),
               "omega": self.omega, "pade_order": self.pade_order, "time": "azimuth",
               "spacings": self.spacings.tolist(), "cts": self.cts.tolist(),
               "trusted": self.trusted.tolist(), "inputs": load_names(self.rotors),
               "outputs": inflow_names(self.rotors),
               **{key: self._grid[key].tolist() for key in _FIELDS}}
        path.write_text(json.dumps(doc, indent=1))
        return path

    @classmethod
    def from_file(cls, path, spacing, ct, pade_order=None):
        """Read a schedule written by :meth:`save`, at a point of its grid.

        Parameters
        ----------
        path : str or Path
            JSON file.
        spacing : float
            Rotor spacing ``h/R`` [-].
        ct : float
            System thrust coefficient [-].
        pade_order : int, optional
            Padé order of the delays (default: the file's).

        Returns
        -------
        ScheduledInflow

        Raises
        ------
        InflowError
            If the file is not a schedule of this schema.
        """
        try:
            doc = json.loads(Path(path).read_text())
        except (OSError, json.JSONDecodeError) as err:
            raise InflowError(f"cannot read the inflow schedule {path}: {err}") from err
        if not isinstance(doc, dict) or doc.get("schema") != SCHEDULE_SCHEMA:
            raise InflowError(f"{path} is not an inflow schedule (schema {SCHEDULE_SCHEMA!r})")
        return cls(doc["spacings"], doc["cts"], omega=doc["omega"], spacing=spacing, ct=ct,
                   rotors=tuple(doc["rotors"]), name=doc["name"], trusted=doc["trusted"],
                   pade_order=doc["pade_order"] if pade_order is None else pade_order,
                   **{key: doc[key] for key in _FIELDS})

    # -- InflowModel: delegated to the interpolated IdentifiedInflow ----------------
    @property
    def state_names(self):
        return self.model.state_names

    @property
    def system(self):
        """The interpolated model's :class:`control.StateSpace` (seconds)."""
        return self.model.system

    @property
    def loads_ref(self):
        return self.model.loads_ref

    @property
    def inflow_ref(self):
        return self.model.inflow_ref

    def derivatives(self, x, loads, ops, rates=None):
        return self.model.derivatives(x, loads, ops, rates)

    def inflow(self, x, loads, ops):
        return self.model.inflow(x, loads, ops)

    def steady_state(self, loads, ops):
        return self.model.steady_state(loads, ops)

    def linear(self, loads, ops):
        return self.model.linear(loads, ops)
