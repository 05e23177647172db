"""Is the coaxial hover wake's low-frequency cyclic response converged in wake length?

The question: the lower rotor's on-axis cyclic response lambda1s_L/theta1s_L has
a flat magnitude but a phase that drifts by ~60 deg between 0.7 and 5 rad/s, which
no first-order (Eq. 5.3) row can fit. This study sweeps theta1s_L and theta0_U
(the same seeds and inputs as the identification) on the default coaxial hover
wake and on wakes with three times the far wake (10 -> 30 revolutions) and twice
the free wake (4 -> 8 revolutions), and tabulates the differences of the responses
(``aircraft.identification.wake_sensitivity``).

Writes ``results/wake_length_check/``: ``table.csv`` (every variant, pair and
tabulated frequency), ``max_difference.csv`` (largest change per variant and pair
above 1.5 rad/s and over the whole band, at coherence >= 0.8), ``responses.png``,
``wall_times.csv``.

Run: ``rotorwake wake-length-check`` (about 6 minutes on 2 cores without a cache;
``--small``: a tiny wake and 12 s sweeps from 3 rad/s, for the tests).
"""
from __future__ import annotations

import argparse
import math
from pathlib import Path

import pandas as pd

from aircraft import load_aircraft
from aircraft.configs import coaxial_compound
from aircraft.identification.structures import Coaxial6State
from aircraft.identification.shipped import RECIPES
from aircraft.identification.wake_sensitivity import wake_setting_sensitivity
from aircraft.wake import WakeSettings

CONTROLS = ["theta1s_L", "theta0_U"]
OUTPUTS = ["lam0_U", "lam1s_U", "lam1c_U", "lam0_L", "lam1s_L", "lam1c_L"]
FREQUENCIES = (0.7, 1.0, 1.5, 2.0, 3.0, 5.0, 7.0, 10.0, 15.0, 20.0)
VARIANTS = {"far wake 30 rev": {"far_wake_revolutions": 30.0}, "free wake 8 rev": {"wake_revolutions": 8.0}}
#: the pairs the summary prints (on-axis, and the cross-rotor cyclic one)
SHOWN = [("theta1s_L", "lam1s_L"), ("theta1s_L", "lam1s_U"), ("theta1s_L", "lam1c_L"), ("theta0_U", "lam0_U"),
         ("theta0_U", "lam0_L")]


def run(out_dir="results/wake_length_check", small=False, n_jobs=2, cache_dir="default", aircraft=None):
    """Run the check; ``aircraft``: a coaxial configuration with rotors U and L, shipped name or
    TOML file (:func:`aircraft.config_files.load_aircraft`; default the coaxial compound)."""
    recipe = RECIPES["coaxial_hover_6state"]
    base, sweep_s, variants = recipe.settings.wake_settings, recipe.settings.sweep_s, VARIANTS
    w_min = recipe.settings.w_min
    if small:
        base = WakeSettings(azimuth_step=math.radians(20.0), wake_revolutions=1.5, n_elements=4,
                            far_wake_revolutions=3.0)
        sweep_s, w_min, variants = 12.0, 3.0, {"far wake 6 rev": {"far_wake_revolutions": 6.0}}
    # the identification's seeds (its sweep k has seed k), so the base records are its own
    seeds = [Coaxial6State().excitations.index(c) for c in CONTROLS]
    config = coaxial_compound() if aircraft is None else load_aircraft(aircraft)
    res = wake_setting_sensitivity(config, variants, base=base, ct=recipe.ct, controls=CONTROLS,
                                   seeds=seeds,
                                   outputs=OUTPUTS, frequencies=FREQUENCIES, sweep_s=sweep_s,
                                   amplitude=recipe.settings.amplitude, w_min=w_min,
                                   w_max=recipe.settings.w_max, n_jobs=n_jobs, cache_dir=cache_dir,
                                   progress=not small)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    res.table.to_csv(out / "table.csv", index=False)
    high = res.max_difference(1.5, coherence_min=0.8).assign(band="1.5 rad/s and up")
    whole = res.max_difference(coherence_min=0.8).assign(band="whole band")
    summary = pd.concat([high, whole], ignore_index=True)
    summary.to_csv(out / "max_difference.csv", index=False)
    pd.DataFrame([{"variant": k, "wall_s": v, "changes": str(res.settings.get(k, {}))}
                  for k, v in res.wall_s.items()]).to_csv(out / "wall_times.csv", index=False)
    res.plot().savefig(out / "responses.png", dpi=80)
    t = res.table
    print("wake-length check (coaxial hover): response differences to the default wake, coherence >= 0.8")
    print(summary[summary.apply(lambda r: (r.control, r.output) in SHOWN, axis=1)].to_string(
        index=False, float_format=lambda v: f"{v:.2f}"))
    on = t[(t.control == "theta1s_L") & (t.output == "lam1s_L")]
    print("lam1s_L/theta1s_L phase [deg] by frequency [rad/s]:")
    print(on.pivot_table(index="omega_rad_s", columns="variant", values="phase_deg", sort=False).round(1)
          .to_string())
    print("wall times [s]:", {k: round(v, 1) for k, v in res.wall_s.items()})
    return res


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--small", action="store_true", help="tiny wake, 12 s sweeps from 3 rad/s (for the tests)")
    parser.add_argument("--n-jobs", type=int, default=2, help="wake worker processes")
    parser.add_argument("--no-cache", action="store_true", help="compute the wake records afresh")
    parser.add_argument("--aircraft", default=None,
                        help="a shipped aircraft's name or an aircraft TOML file (default: coaxial_compound)")
    parser.add_argument("--out", default="results/wake_length_check")
    args = parser.parse_args(argv)
    run(args.out, small=args.small, n_jobs=args.n_jobs, cache_dir=None if args.no_cache else "default",
        aircraft=args.aircraft)


if __name__ == "__main__":
    main()
