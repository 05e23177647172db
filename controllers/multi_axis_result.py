"""The outcome of a multi-axis EMF design: per-axis table, inter-axis coupling, HQ windows.

:func:`controllers.multi_axis_design.design_multi_axis` returns a
:class:`MultiAxisResult`; its :meth:`~MultiAxisResult.to_pandas` is the per-axis
table (gains, crossover, DRB, margins, OLOP, specs met, what limits each axis),
:meth:`~MultiAxisResult.coupling` the closed loop's inter-axis couplings and
:meth:`~MultiAxisResult.plot` one HQ window per axis.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import control
import numpy as np
import pandas as pd

from . import metrics as m
from .actuator_limits import olop_point
from .multi_axis import MultiAxisEMF

__all__ = ["MultiAxisResult"]


@dataclass
class MultiAxisResult:
    """Outcome of :func:`design_multi_axis`.

    Attributes
    ----------
    emf : MultiAxisEMF
        Final design, every loop closed on the full plant.
    designs : dict
        Axis -> :class:`AxisEMFDesign` of the last sweep (the axis's design plant).
    dmo_results : dict
        Axis -> last :class:`controllers.DMOResult` (None where the DMO found no feasible start).
    specs : dict
        Axis -> spec table on the final simultaneous closed loop.
    spec_lists : dict
        Axis -> the spec objects graded (final boundaries).
    history : pandas.DataFrame
        One row per sweep and axis: gains, crossover, relative gain change, DMO message.
    converged : bool
        The last sweep moved no gain by more than the tolerance.
    messages : dict
        Axis -> what the DMO said (or why it could not meet the specs).
    wall_time : float
        [s].
    guard_other_axes : bool
        Whether each axis was tuned against the other loops' margins too (guards).
    guard_level : {"auto", 1, 2}
        The guards' level rule (:func:`controllers.multi_axis_guard.guard_specs`).
    tuned_from : dict
        Axis -> the PIDGains its last DMO run started from (the guards' floor).
    tuned_with : dict
        Axis -> tuple of the other axes whose loops were closed during its last DMO run.
    boundaries : mapping or None
        The Level boundaries the caller supplied (spec name -> values), as given.
    speed : {"hover", "forward"}
        The flight regime whose specs the design graded.
    """

    emf: MultiAxisEMF
    designs: dict
    dmo_results: dict
    specs: dict
    spec_lists: dict
    history: pd.DataFrame
    converged: bool
    messages: dict
    wall_time: float
    sweeps: int = 0
    #: axis -> ActuatorLimits graded by the OLOP (None: no OLOP on that axis)
    limits: dict = field(default_factory=dict)
    guard_other_axes: bool = False
    guard_level: object = "auto"
    tuned_from: dict = field(default_factory=dict)
    tuned_with: dict = field(default_factory=dict)
    boundaries: object = None
    speed: str = "hover"
    _coupling: pd.DataFrame | None = field(default=None, repr=False)

    def to_pandas(self):
        """Per axis: gains, crossover, DRB, margins (MIMO loop), specs met and the limiting ones.

        Returns
        -------
        pandas.DataFrame
            Index axis; ``crossover_design`` is the single-axis design plant's crossover
            (equal to the MIMO one at the sweeps' fixed point); ``unmet`` names every
            Level-1 spec missed on the simultaneous closed loop; ``limiting`` the
            DMO's limiting spec(s) above the final boundary; ``olop_margin_db`` the
            open-loop onset point's dB below the approximate Level 1 line and ``olop_onset``
            its onset frequency [rad/s] (``inf``: the full stick never reaches the rate
            limit; NaN: no limits given). The eigenvalue specs
            (EigLcG1, EigDpG1) grade every pole of the simultaneous closed loop, so
            they read the same on every axis.
        """
        rows = []
        for a in self.emf.axes:
            view, g, t = self.emf.axis_view(a), self.emf.loops[a].gains, self.specs[a]
            gm, pm, _, wc = m.gain_phase_margins(view.broken_loop())
            graded = t[t.kind != "objective"]
            res = self.dmo_results.get(a)
            lim = self.limits.get(a)
            olop = (olop_point(view.broken_loop(), view.mixer_response_pilot(), lim.stick_amplitude, lim)
                    if lim is not None else {"onset_frequency": np.nan, "margin_db": np.nan})
            rows.append({"axis": a, "response_type": self.emf.channels[a].response_type, "K_phi": g.K_phi,
                         "K_Iphi": g.K_Iphi, "K_p": g.K_p, "crossover": wc,
                         "crossover_design": m.crossover_frequency(self.designs[a].broken_loop()),
                         "crossover_boundary": res.crossover_boundary if res is not None else np.nan,
                         "drb": m.disturbance_rejection_bandwidth(view.disturbance_response()),
                         "drp_db": m.disturbance_rejection_peak(view.disturbance_response()),
                         "gm_db": gm, "pm_deg": pm, "olop_margin_db": olop["margin_db"],
                         "olop_onset": olop["onset_frequency"], "tau_eq": self.emf.loops[a].equivalent_delay,
                         "specs_met": f"{int(graded.met.sum())}/{len(graded)}",
                         "unmet": ", ".join(graded.spec[~graded.met.astype(bool)]),
                         "limiting": ", ".join(res.limiting) if res is not None else self.messages[a]})
        return pd.DataFrame(rows).set_index("axis")

    def coupling(self, omega=None, horizon=4.0, dt=0.01):
        """Inter-axis coupling of the simultaneous closed loop, per pilot axis and responding axis.

        Parameters
        ----------
        omega : array, optional
            Frequencies [rad/s] of the peak-gain ratio (default 0.1-10 rad/s).
        horizon : float
            ADS-33E-PRF pitch-roll coupling horizon [s]: peak off-axis change up to
            ``horizon`` over the on-axis change at ``horizon``, for a step of the pilot's stick.
        dt : float
            Time step of the step responses [s].

        Returns
        -------
        pandas.DataFrame
            Rows (stick axis, responding axis != stick axis): ``peak_gain_ratio`` =
            max |y_off/stick| / max |y_on/stick| over ``omega`` (attitude, or height
            for heave), ``step_ratio`` (the ADS-33 ratio, units of the signals: rad/rad,
            m/rad, ...), and ``off_peak`` the peak off-axis attitude and ``off_rate_peak``
            the peak rate per unit stick step [rad, rad/s, m, m/s].
        """
        if self._coupling is not None and omega is None:
            return self._coupling
        w = np.geomspace(0.1, 10.0, 200) if omega is None else np.asarray(omega, float)
        cl = self.emf.closed_loop()
        t = np.arange(0.0, horizon + dt / 2, dt)
        rows = []
        for j in self.emf.axes:
            u = np.zeros((cl.ninputs, t.size))
            u[cl.input_labels.index(f"stick_s_{j}")] = 1.0
            y = control.forced_response(cl, t, u).outputs
            on = np.max(np.abs(self.emf.command_response(j, j).response(w)))
            on_step = abs(y[cl.output_labels.index(f"att_{j}"), -1])
            for i in self.emf.axes:
                if i == j:
                    continue
                off = y[cl.output_labels.index(f"att_{i}")]
                rate = y[cl.output_labels.index(f"rate_{i}")]
                rows.append({"stick": j, "response": i,
                             "peak_gain_ratio": float(np.max(np.abs(self.emf.command_response(i, j).response(w))) / on),
                             "step_ratio": float(np.max(np.abs(off)) / on_step) if on_step > 0 else np.nan,
                             "off_peak": float(np.max(np.abs(off))), "off_rate_peak": float(np.max(np.abs(rate)))})
        table = pd.DataFrame(rows)
        if omega is None:
            self._coupling = table
        return table

    def plot(self, axes=None, ncols=4):
        """One HQ window per axis (every spec of the axis, graded on the simultaneous closed loop).

        Parameters
        ----------
        axes : sequence of str, optional
            Axes drawn (default all).
        ncols : int
            Panels per row.

        Returns
        -------
        dict
            Axis -> matplotlib Figure (its label and legend name the axis).
        """
        from .hqwindow import hq_window
        figs = {}
        for a in axes or self.emf.axes:
            # "(axis) ..." is shortened to the axis name on the charts; the legend carries the whole label
            label = (f"({a}) {a} axis, loop broken at the {self.emf.channels[a].stick} actuator, "
                     "every other loop closed")
            fig = hq_window([self.emf.axis_view(a)], self.spec_lists[a], labels=[label], ncols=ncols)
            fig.set_label(f"{a} axis HQ window")
            figs[a] = fig
        return figs
