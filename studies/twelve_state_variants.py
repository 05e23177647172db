"""Constrained 12-state coaxial hover models on one wake data set: what each constraint buys.

Identifies :data:`aircraft.identification.twelve_state_variants.VARIANTS` (the shipped
12-state structure, then the collective made first order, then its near-wake gain held
at Pitt-Peters', then the far-far cyclic coupling that forms a flat direction removed)
from the shipped ``coaxial_hover_12state`` recipe's wake runs (six swashplate and four
tip-path-plane sweeps, cached), and tabulates the trust guidelines per variant beside
the effective roll damping of the hover aircraft flying it
(:func:`aircraft.identification.twelve_state_variants.compare_twelve_state_variants`).

Writes ``results/twelve_state_variants/``: ``table.csv``, ``parameters.csv`` (every
variant's parameters, CR and insensitivity), ``cost_tables.csv``, ``variants.png``.

Run: ``rotorwake twelve-state-variants`` (``--small``: tiny wake, 2 variants, for the tests).
"""
from __future__ import annotations

import argparse
import math
from pathlib import Path

import pandas as pd

from aircraft.identification import IdentificationSettings
from aircraft.identification.twelve_state_variants import VARIANTS, compare_twelve_state_variants
from aircraft.wake import WakeSettings


def run(out_dir="results/twelve_state_variants", small=False, n_jobs=2):
    variants, settings = VARIANTS, None
    if small:
        labels = list(VARIANTS)
        variants = {k: VARIANTS[k] for k in (labels[0], labels[-1])}
        settings = IdentificationSettings(wake=WakeSettings(azimuth_step=math.radians(20.0), wake_revolutions=1.5,
                                                            n_elements=4), sweep_s=12.0, doublet_s=3.0,
                                          noise_floor_s=3.0)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    result = compare_twelve_state_variants(variants, settings=settings, n_jobs=n_jobs, progress=not small)
    table = result.to_pandas()
    table.to_csv(out / "table.csv", index=False)
    pd.concat([m.parameters.assign(variant=k) for k, m in result.models.items()]) \
        .to_csv(out / "parameters.csv", index=False)
    pd.concat([m.cost_table.assign(variant=k) for k, m in result.models.items()]) \
        .to_csv(out / "cost_tables.csv", index=False)
    result.plot().savefig(out / "variants.png", dpi=90)
    pd.set_option("display.width", 200)
    print("12-state coaxial hover variants, one wake data set (the shipped recipe's):")
    print(table.to_string(index=False, float_format=lambda v: f"{v:.4g}"))
    for k, m in result.models.items():
        fails = m.trust_failures()
        print(f"{k}: {'trusted' if not fails else 'NOT trusted: ' + ' | '.join(fails)}")
    print(f"tables and figure in {out}/")
    return table


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--small", action="store_true", help="tiny wake, two variants (for the tests)")
    parser.add_argument("--n-jobs", type=int, default=2, help="wake worker processes")
    parser.add_argument("--out", default="results/twelve_state_variants")
    args = parser.parse_args(argv)
    run(args.out, small=args.small, n_jobs=args.n_jobs)


if __name__ == "__main__":
    main()
