"""Quasi-steady check of the shipped coaxial models: DC gain against held steps of our wake.

Holds 0.02 rad steps of theta0 and theta1s of each rotor for 10 s in the default
coaxial hover wake (the shipped models' resolution and trim) and compares the
inflow change averaged over 6-10 s with what each model's DC gain predicts from
the same record's load changes (:func:`aircraft.identification.quasi_steady_check`).
The shipped 6-state, 12-state and axisymmetric 6-state models are ours; the printed Eq. 5.3 model is a
reference row (another rotor's model, in our frames).

Writes ``results/coaxial_quasi_steady/``: ``table.csv`` (every step x output,
wake | model | ratio, per model), ``settling.csv`` (how far the wake itself is
from steady: the on-axis change at 1-2 s against 6-10 s), ``load_changes.csv``,
``steps.png``, ``wall_times.csv``. In ``table.csv``, ``model`` is the predicted
change and ``inflow_model`` names the model.

Run: ``rotorwake coaxial-quasi-steady`` (``--small``: tiny wake, 4 s holds, for the tests;
``--no-cache``: the wake records are computed afresh in a temporary cache shared by the
models, so the first model's wall time is the cost of the records; the committed
results are run so).
"""
from __future__ import annotations

import argparse
import contextlib
import math
import tempfile
import time
from pathlib import Path

import pandas as pd

from aircraft.configs import coaxial_compound
from aircraft.identification import IdentificationSettings, quasi_steady_check
from aircraft.identification.shipped import RECIPES
from aircraft.inflow import IdentifiedInflow
from aircraft.wake import WakeSettings

MODELS = (("ours, 6-state", "coaxial_hover_6state"), ("ours, 12-state", "coaxial_hover_12state"),
          ("ours, axisymmetric 6-state", "coaxial_hover_6state_axisymmetric"),
          ("published Eq. 5.3 (reference)", "published_eq5_3"))


def run(out_dir="results/coaxial_quasi_steady", small=False, n_jobs=2, cache=True):
    recipe = RECIPES["coaxial_hover_6state"]
    settings, hold, window = recipe.settings, 10.0, (6.0, 10.0)
    if small:
        settings = IdentificationSettings(wake=WakeSettings(azimuth_step=math.radians(20.0), wake_revolutions=1.5,
                                                            n_elements=4))
        hold, window = 4.0, (2.0, 4.0)
    config = coaxial_compound()
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    tables, walls = [], []
    checks = {}
    with contextlib.ExitStack() as stack:
        # --no-cache: a temporary cache of this run only, so the first model computes the
        # records and the others read them back; removed on the way out, error or not
        cache_dir = "default" if cache else stack.enter_context(
            tempfile.TemporaryDirectory(prefix="quasi_steady_wake_"))
        # with the default cache the first call may have computed or read the records
        first_source = "default cache" if cache else "computed"
        for label, name in MODELS:
            model = IdentifiedInflow.from_file(name)
            t0 = time.perf_counter()
            check = quasi_steady_check(model, config, ct=recipe.ct, settings=settings, hold_s=hold,
                                       window=window, n_jobs=n_jobs, progress=False, cache_dir=cache_dir)
            walls.append({"model": label, "wall_s": time.perf_counter() - t0,
                          "wake_records": "cache" if walls else first_source})
            checks[label] = check
            tables.append(check.table.assign(inflow_model=label, file=name))
    # the wake's settling and load changes belong to the records, the same for every model
    settle = next(iter(checks.values())).settling
    loads = next(iter(checks.values())).load_changes
    table = pd.concat(tables, ignore_index=True)
    table.to_csv(out / "table.csv", index=False)
    settle.to_csv(out / "settling.csv", index=False)
    loads.reset_index().to_csv(out / "load_changes.csv", index=False)
    pd.DataFrame(walls).to_csv(out / "wall_times.csv", index=False)
    fig = _figure(table)
    fig.savefig(out / "steps.png", dpi=90)
    fmt = lambda v: f"{v:.4g}"   # noqa: E731
    print(f"quasi-steady check, coaxial hover, system C_T {recipe.ct:g}, "
          f"{math.degrees(settings.wake_settings.azimuth_step):g} deg wake; {hold:g} s holds, "
          f"window {window[0]:g}-{window[1]:g} s")
    on = table[table.on_axis].pivot_table(index=["control", "output", "wake"], columns="inflow_model",
                                          values="ratio")
    print("on-axis model/wake ratio of the steady inflow change (1 = the model's DC gain is the wake's):")
    print(on.reset_index().to_string(index=False, float_format=fmt))
    for label, check in checks.items():
        print(f"{label}: {'passes' if check.passes() else 'FAILS'} the guard (every on-axis ratio within 30 % of 1)")
    print("the wake's own settling (on-axis change at 1-2 s after the step vs the late window):")
    print(settle.to_string(index=False, float_format=fmt))
    print("wall times [s]: " + ", ".join(f"{w['model']} {w['wall_s']:.0f}" for w in walls))
    print(f"tables and figure in {out}/")
    return table


def _figure(table):
    from matplotlib.figure import Figure
    controls = list(dict.fromkeys(table.control))
    fig = Figure(figsize=(3.3 * len(controls), 3.6), constrained_layout=True)
    axes = fig.subplots(1, len(controls), squeeze=False)[0]
    models = list(dict.fromkeys(table.inflow_model))
    for ax, c in zip(axes, controls):
        t = table[(table.control == c) & table.on_axis]
        first = t[t.inflow_model == models[0]]
        ax.bar(-0.3, first.wake.iloc[0], 0.18, color="k", label="wake (held step)")
        for k, m in enumerate(models):
            ax.bar(-0.1 + 0.2 * k, t[t.inflow_model == m].model.iloc[0], 0.18, label=m)
        ax.set_xticks([])
        ax.set_title(f"{first.output.iloc[0]} after a {c} step", fontsize=9)
        lim = 4.0 * abs(first.wake.iloc[0])   # a model 100x off is clipped, not allowed to hide the wake
        ax.set_ylim(-lim, lim)
        ax.axhline(0.0, color="k", lw=0.5)
        ax.grid(True, alpha=0.3)
    axes[0].set_ylabel("steady inflow change [-] (clipped at 4x the wake's)")
    axes[0].legend(fontsize=7)
    return fig


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--small", action="store_true", help="tiny wake, 4 s holds (for the tests)")
    parser.add_argument("--n-jobs", type=int, default=2, help="wake worker processes")
    parser.add_argument("--no-cache", action="store_true",
                        help="compute the wake records afresh (the committed results: wall_times.csv is their cost)")
    parser.add_argument("--out", default="results/coaxial_quasi_steady")
    args = parser.parse_args(argv)
    run(args.out, small=args.small, n_jobs=args.n_jobs, cache=not args.no_cache)


if __name__ == "__main__":
    main()
