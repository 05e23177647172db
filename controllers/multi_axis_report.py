"""The report of a multi-axis design: its tables, a printable summary, and the files that hold them.

:func:`multi_axis_tables` gathers every table of a
:class:`~controllers.multi_axis_result.MultiAxisResult` (and, when given, of its
:func:`~controllers.multi_axis_check.global_check` and
:func:`~controllers.multi_axis_joint.joint_check`) under one name each;
:func:`write_multi_axis_report` writes them as CSV files, with one HQ window per
axis as a PNG, and returns the paths; :func:`multi_axis_summary` is the text a
script prints. A table indexed by a named index (the axis, an assumption's item)
is written with that index as its first column; the others without an index.

Files written (``<name>.csv`` per table of :func:`multi_axis_tables`):

* ``axes.csv``: :meth:`~controllers.multi_axis_result.MultiAxisResult.to_pandas` (gains, crossover, DRB, DRP,
  GM/PM, OLOP margin and onset, specs met, unmet and limiting specs);
* ``specs.csv``: every spec of every axis on the simultaneous closed loop;
* ``limits.csv``: :func:`limits_table`;
* ``limits_assumptions.csv``: :data:`~controllers.actuator_limits.LIMITS_ASSUMPTIONS`;
* ``coupling.csv``: :meth:`~controllers.multi_axis_result.MultiAxisResult.coupling`;
* ``sweeps.csv``: :attr:`~controllers.multi_axis_result.MultiAxisResult.history`;
* ``global_check.csv``: the ``check`` table, when one is given;
* ``joint_check.csv``: :meth:`JointCheckResult.to_pandas` of ``joint``, when one is given;
* ``hq_window_<axis>.png``: :meth:`~controllers.multi_axis_result.MultiAxisResult.plot`, when ``figures`` is true.
"""
from __future__ import annotations

import math
from pathlib import Path

import pandas as pd

from .actuator_limits import LIMITS_ASSUMPTIONS
from .multi_axis_result import MultiAxisResult
from .multi_axis_joint import JointCheckResult

__all__ = ["limits_table", "limits_assumptions_table", "multi_axis_tables", "multi_axis_summary",
           "write_multi_axis_report", "AXES_SUMMARY_COLUMNS", "CHECK_SUMMARY_COLUMNS"]

#: columns of the axes table that :func:`multi_axis_summary` prints
AXES_SUMMARY_COLUMNS = ("K_phi", "K_Iphi", "K_p", "crossover", "drb", "drp_db", "gm_db", "pm_deg",
                        "olop_margin_db", "olop_onset", "specs_met", "unmet", "limiting")
#: columns of the global check's table that :func:`multi_axis_summary` prints
CHECK_SUMMARY_COLUMNS = ("dmo_crossover", "search_crossover", "ratio", "beaten", "dmo_K_phi", "search_K_phi",
                         "dmo_K_p", "search_K_p", "search_mimo_met", "search_mimo_crossover", "points",
                         "feasible_points")
_LIMITS_COLUMNS = ("axis", "stick", "rate_limit_deg_s", "travel_deg", "stick_amplitude", "command_gain",
                   "full_stick_command")


def _check_result(result):
    if not isinstance(result, MultiAxisResult):
        raise TypeError(f"result must be a MultiAxisResult (from design_multi_axis), got {type(result).__name__}")


def _check_table(check):
    if check is not None and not isinstance(check, pd.DataFrame):
        raise TypeError(f"check must be a pandas.DataFrame (from global_check) or None, got {type(check).__name__}")


def _check_joint(joint):
    if joint is not None and not isinstance(joint, JointCheckResult):
        raise TypeError(f"joint must be a JointCheckResult (from joint_check) or None, got {type(joint).__name__}")


def limits_table(result):
    """Per axis: the actuator limits its OLOP was graded with and what a full stick commands.

    Parameters
    ----------
    result : MultiAxisResult
        From :func:`controllers.multi_axis_design.design_multi_axis`.

    Returns
    -------
    pandas.DataFrame
        One row per axis graded by an OLOP (an axis without limits is left out):
        ``stick`` (the pilot input), ``rate_limit_deg_s`` [deg/s] and ``travel_deg``
        [deg] of the actuator (mixer units shown in degrees), ``stick_amplitude``
        [stick units], ``command_gain`` (command model gain [command units per stick
        unit]) and ``full_stick_command`` (their product: attitude [rad] or rate
        [rad/s, m/s]). ``attrs["assumptions"]`` holds
        :data:`~controllers.actuator_limits.LIMITS_ASSUMPTIONS`.

    Raises
    ------
    TypeError
        ``result`` is not a MultiAxisResult.

    Examples
    --------
    >>> import control
    >>> from controllers import DMOSettings, design_multi_axis
    >>> plant = control.ss([[-1.5, 0], [1.0, 0]], [[5.0], [0]], [[1.0, 0], [0, 1.0]], 0,
    ...                    inputs=["delta_lat"], outputs=["p", "phi"])
    >>> quick = DMOSettings(global_samples=0, max_steps=1, polish_evaluations=0)   # one DMO step, no search
    >>> res = design_multi_axis(plant, axes=["roll"], settings=quick, crossover_start={"roll": 10.0},
    ...                         max_sweeps=1, progress=False)    # one DMO step from 10 rad/s
    >>> limits_table(res)[["axis", "rate_limit_deg_s", "travel_deg"]].to_string(index=False)
    'axis  rate_limit_deg_s  travel_deg\\nroll              40.0         8.0'
    """
    _check_result(result)
    rows = []
    for axis, lim in result.limits.items():
        if lim is None:
            continue
        cm = result.emf.loops[axis].command_model
        rows.append({"axis": axis, "stick": result.emf.channels[axis].stick,
                     "rate_limit_deg_s": math.degrees(lim.rate_limit),
                     "travel_deg": math.degrees(lim.position_limit), "stick_amplitude": lim.stick_amplitude,
                     "command_gain": cm.gain, "full_stick_command": lim.stick_amplitude * cm.gain})
    table = pd.DataFrame(rows, columns=list(_LIMITS_COLUMNS))
    table.attrs["assumptions"] = LIMITS_ASSUMPTIONS
    return table


def limits_assumptions_table():
    """The assumed actuator limits and full-stick commands, one row per assumption, with its reason.

    Returns
    -------
    pandas.DataFrame
        Index ``item`` (e.g. ``"full_stick.yaw"``), column ``assumption`` (the value and why):
        :data:`~controllers.actuator_limits.LIMITS_ASSUMPTIONS` as a table.

    Examples
    --------
    >>> limits_assumptions_table().columns.tolist(), limits_assumptions_table().index.name
    (['assumption'], 'item')
    """
    return pd.Series(LIMITS_ASSUMPTIONS, name="assumption").rename_axis("item").to_frame()


def multi_axis_tables(result, check=None, joint=None):
    """Every table of a multi-axis design's report, by the name of its file.

    Parameters
    ----------
    result : MultiAxisResult
        From :func:`controllers.multi_axis_design.design_multi_axis`.
    check : pandas.DataFrame, optional
        From :func:`controllers.multi_axis_check.global_check` on ``result``; added as
        ``"global_check"`` when given.
    joint : JointCheckResult, optional
        From :func:`controllers.multi_axis_joint.joint_check` on ``result``; its
        :meth:`~controllers.multi_axis_joint.JointCheckResult.to_pandas` added as
        ``"joint_check"`` when given.

    Returns
    -------
    dict
        Name -> pandas.DataFrame, in this order: ``"axes"`` (index axis),
        ``"specs"`` (the spec tables of every axis, with an ``axis`` column),
        ``"limits"`` (:func:`limits_table`), ``"limits_assumptions"`` (index item),
        ``"coupling"``, ``"sweeps"``, with ``check`` ``"global_check"`` and with
        ``joint`` ``"joint_check"`` (both index axis). Units are those of the tables'
        sources (rad/s, dB, deg, s).

    Raises
    ------
    TypeError
        ``result`` is not a MultiAxisResult, ``check`` not a DataFrame or ``joint`` not a
        JointCheckResult.

    Examples
    --------
    >>> import control
    >>> from controllers import DMOSettings, design_multi_axis
    >>> plant = control.ss([[-1.5, 0], [1.0, 0]], [[5.0], [0]], [[1.0, 0], [0, 1.0]], 0,
    ...                    inputs=["delta_lat"], outputs=["p", "phi"])
    >>> quick = DMOSettings(global_samples=0, max_steps=1, polish_evaluations=0)   # one DMO step, no search
    >>> res = design_multi_axis(plant, axes=["roll"], settings=quick, crossover_start={"roll": 10.0},
    ...                         max_sweeps=1, progress=False)    # one DMO step from 10 rad/s
    >>> tables = multi_axis_tables(res)
    >>> list(tables)
    ['axes', 'specs', 'limits', 'limits_assumptions', 'coupling', 'sweeps']
    >>> tables["axes"].loc["roll", "specs_met"]         # specs met on the closed loop, of those graded
    '11/11'
    """
    _check_result(result)
    _check_table(check)
    _check_joint(joint)
    tables = {"axes": result.to_pandas(),
              "specs": pd.concat([t.assign(axis=a) for a, t in result.specs.items()], ignore_index=True),
              "limits": limits_table(result), "limits_assumptions": limits_assumptions_table(),
              "coupling": result.coupling(), "sweeps": result.history}
    if check is not None:
        tables["global_check"] = check
    if joint is not None:
        tables["joint_check"] = joint.to_pandas()
    return tables


def _fmt(v):
    return f"{v:.3g}"


def multi_axis_summary(result, check=None, *, design=True, axes_table=None):
    """The lines a script prints about a multi-axis design (and its global check).

    Parameters
    ----------
    result : MultiAxisResult
        From :func:`controllers.multi_axis_design.design_multi_axis`.
    check : pandas.DataFrame, optional
        From :func:`controllers.multi_axis_check.global_check`; its comparison is appended.
    design : bool
        Include the design's part (False: only the check's, e.g. printed after the check
        of a design whose summary was printed before it).
    axes_table : pandas.DataFrame, optional
        ``result.to_pandas()`` when already computed (saves recomputing it).

    Returns
    -------
    str
        With ``design``, the axes table's :data:`AXES_SUMMARY_COLUMNS` (three significant
        figures) and a line saying whether the sweeps converged and the design's wall time
        [s]; with ``check``, its :data:`CHECK_SUMMARY_COLUMNS`.

    Raises
    ------
    TypeError
        ``result`` is not a MultiAxisResult or ``check``/``axes_table`` not a DataFrame.

    Examples
    --------
    >>> import control
    >>> from controllers import DMOSettings, design_multi_axis
    >>> plant = control.ss([[-1.5, 0], [1.0, 0]], [[5.0], [0]], [[1.0, 0], [0, 1.0]], 0,
    ...                    inputs=["delta_lat"], outputs=["p", "phi"])
    >>> quick = DMOSettings(global_samples=0, max_steps=1, polish_evaluations=0)   # one DMO step, no search
    >>> res = design_multi_axis(plant, axes=["roll"], settings=quick, crossover_start={"roll": 10.0},
    ...                         max_sweeps=1, progress=False)    # one DMO step from 10 rad/s
    >>> multi_axis_summary(res).splitlines()[-1].startswith("converged: False after 1 sweep(s)")
    True
    """
    _check_result(result)
    _check_table(check)
    if axes_table is not None and not isinstance(axes_table, pd.DataFrame):
        raise TypeError(f"axes_table must be a pandas.DataFrame or None, got {type(axes_table).__name__}")
    lines = []
    if design:
        axes = result.to_pandas() if axes_table is None else axes_table
        lines += [axes[list(AXES_SUMMARY_COLUMNS)].to_string(float_format=_fmt),
                  f"converged: {result.converged} after {result.sweeps} sweep(s); design {result.wall_time:.0f} s"]
    if check is not None:
        lines.append(check[list(CHECK_SUMMARY_COLUMNS)].to_string(float_format=_fmt))
    return "\n".join(lines)


def write_multi_axis_report(result, folder, *, check=None, joint=None, figures=True, dpi=110):
    """Write the report of a multi-axis design: its CSV tables and one HQ window per axis.

    Parameters
    ----------
    result : MultiAxisResult
        From :func:`controllers.multi_axis_design.design_multi_axis`.
    folder : str or pathlib.Path
        Folder written into (created if missing); files of the same names are replaced.
    check : pandas.DataFrame, optional
        From :func:`controllers.multi_axis_check.global_check` on ``result``; written as
        ``global_check.csv`` when given.
    joint : JointCheckResult, optional
        From :func:`controllers.multi_axis_joint.joint_check` on ``result``; written as
        ``joint_check.csv`` when given.
    figures : bool
        Also save ``hq_window_<axis>.png`` per axis (:meth:`~controllers.multi_axis_result.MultiAxisResult.plot`).
    dpi : float
        Resolution of the figures [dots per inch].

    Returns
    -------
    dict
        Name -> pathlib.Path of each file written: the names of
        :func:`multi_axis_tables` (``<name>.csv``) and ``"hq_window_<axis>"``
        (``<name>.png``).

    Raises
    ------
    TypeError
        ``result`` is not a MultiAxisResult, ``check`` not a DataFrame or ``joint`` not a
        JointCheckResult.
    ValueError
        ``dpi`` is not a positive finite number.

    Examples
    --------
    >>> import tempfile
    >>> import control
    >>> from controllers import DMOSettings, design_multi_axis
    >>> plant = control.ss([[-1.5, 0], [1.0, 0]], [[5.0], [0]], [[1.0, 0], [0, 1.0]], 0,
    ...                    inputs=["delta_lat"], outputs=["p", "phi"])
    >>> quick = DMOSettings(global_samples=0, max_steps=1, polish_evaluations=0)   # one DMO step, no search
    >>> res = design_multi_axis(plant, axes=["roll"], settings=quick, crossover_start={"roll": 10.0},
    ...                         max_sweeps=1, progress=False)    # one DMO step from 10 rad/s
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     paths = write_multi_axis_report(res, tmp, figures=False)
    ...     sorted(p.name for p in paths.values())
    ['axes.csv', 'coupling.csv', 'limits.csv', 'limits_assumptions.csv', 'specs.csv', 'sweeps.csv']
    """
    _check_result(result)
    _check_table(check)
    _check_joint(joint)
    if isinstance(dpi, bool) or not isinstance(dpi, (int, float)) or not (math.isfinite(dpi) and dpi > 0):
        raise ValueError(f"dpi must be a positive finite number, got {dpi!r}")
    out = Path(folder)
    out.mkdir(parents=True, exist_ok=True)
    paths = {}
    for name, table in multi_axis_tables(result, check, joint).items():
        paths[name] = out / f"{name}.csv"
        # a named index (axis, item) is a column of the file; a plain row number is not
        table.to_csv(paths[name], index=table.index.name is not None)
    if figures:
        for axis, fig in result.plot().items():
            paths[f"hq_window_{axis}"] = out / f"hq_window_{axis}.png"
            fig.savefig(paths[f"hq_window_{axis}"], dpi=dpi)
    return paths
