"""Constrained 12-state coaxial hover models on one wake data set: what each constraint buys.

Identifies :data:`studies.analysis.twelve_state_variants.VARIANTS` (the shipped
12-state structure, then the collective made first order, then its near-wake gain held
at Pitt-Peters', then the far-far cyclic coupling that forms a flat direction removed)
and last :class:`~aircraft.identification.structures.tilt.Coaxial12StateTilt` (tip-path-plane
tilt inputs; the shipped ``coaxial_hover_12state_tilt`` structure)
from the shipped ``coaxial_hover_12state`` recipe's wake runs (six swashplate and four
tip-path-plane sweeps, cached), and tabulates the trust guidelines per variant beside
the effective roll damping of the hover aircraft flying it
(:func:`studies.analysis.twelve_state_variants.compare_twelve_state_variants`).

The printed Eq. 6.8-6.9 model (our frames) is flown beside them as a reference row.
Then the wake's own steady gains (:func:`aircraft.identification.steady_gains.wake_steady_gains`:
held swashplate steps, flap-rate ramps, held tilts; cached records) are estimated and
each model is driven by those records' loads and flap rates.
Writes ``results/twelve_state_variants/``: ``table.csv``, ``parameters.csv`` (every
variant's parameters, CR and insensitivity), ``cost_tables.csv``, ``variants.png``,
``reproduction.csv`` (the variants otherwise trusted, on a second wake data set started
1e-7 R away: each parameter's shift against its bound, for the final structure refitted
there, the part the verdict judges, and for the whole identification again: column ``part``),
``guideline.csv`` (each variant's parameters outside the bounds, kept or not by the
guideline's keep rule, with the reason: :func:`aircraft.identification.trust.trust_check`);
``steady_gains.csv`` (the wake's G_C, G_R, G_T, long), ``steady_observations.csv`` (each
record window's changes), ``steady_compare.csv`` (per model, record window and on-axis
output: wake and model change), ``steady_gains.png``.

Run: ``rotorwake twelve-state-variants``. It has no small configuration: on a tiny wake
(20 deg steps, 1.5 revolutions, 12 s sweeps) the lambda/beta_dot responses carry no
coherent point and the staged fit stops, so the tests check the library pieces
(``tests/aircraft/identification/test_twelve_state_variants.py``) and this run is the committed one.
"""
from __future__ import annotations

import argparse
from pathlib import Path

import pandas as pd

from aircraft.identification.steady_gains import wake_steady_gains
from aircraft.identification.structures.tilt import Coaxial12StateTilt
from aircraft.identification.structures.constrained import VARIANTS
from studies.analysis.twelve_state_variants import compare_twelve_state_variants

REFERENCE = "Eq. 6.8-6.9 printed, our frames (reference: flown only)"
#: the last row: tip-path-plane tilt inputs (aircraft.identification.structures.tilt)
TILT = "tilt inputs, flap rates into the near wake only, no f1_7 (coaxial_hover_12state_tilt)"


def run(out_dir="results/twelve_state_variants", n_jobs=2):
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    # the printed Eq. 6.8-6.9 model in our frames flown beside them: a 12-state with
    # flap-rate inputs whose steady curvature path leaves the roll damping alone
    result = compare_twelve_state_variants({**VARIANTS, TILT: Coaxial12StateTilt()}, n_jobs=n_jobs, progress=True,
                                           references={REFERENCE: "published_eq6_8_6_9"})
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
    guideline = []
    for k, m in result.models.items():
        check = m.trust           # the guideline with its keep rule (aircraft.identification.trust)
        guideline.append(check.table.assign(variant=k, model_passes=check.passes))
        print(f"{k}: {'trusted' if check.passes else 'NOT trusted: ' + ' | '.join(check.failures)}"
              + "".join(f"\n    {r.parameter}: {r.reason}" for r in check.table.itertuples() if r.verdict == "kept"))
    pd.concat(guideline, ignore_index=True).to_csv(out / "guideline.csv", index=False)
    reproduced = [m.reproduction.to_pandas().assign(variant=k) for k, m in result.models.items()
                  if m.reproduction is not None]
    if reproduced:
        # the trust rule's last part, run for the variants the rest of it trusts
        pd.concat(reproduced, ignore_index=True).to_csv(out / "reproduction.csv", index=False)
    steady_gains(result, out, n_jobs=n_jobs)
    print(f"tables and figures in {out}/")
    return table


def steady_gains(result, out, n_jobs=2):
    """The wake's steady gains on the variants' recipe, and each model against its records."""
    from aircraft.configs import coaxial_compound
    from aircraft.identification.shipped import RECIPES
    from aircraft.inflow import IdentifiedInflow
    recipe = RECIPES["coaxial_hover_12state"]
    gains = wake_steady_gains(coaxial_compound(), recipe.ct, settings=recipe.settings, n_jobs=n_jobs, progress=True)
    gains.to_pandas().to_csv(out / "steady_gains.csv", index=False)
    gains.changes.to_csv(out / "steady_observations.csv")
    models = {**result.models,
              "shipped coaxial_hover_12state": IdentifiedInflow.from_file("coaxial_hover_12state"),
              REFERENCE: IdentifiedInflow.from_file("published_eq6_8_6_9")}
    compare = pd.concat([gains.compare(m).assign(model=k) for k, m in models.items()], ignore_index=True)
    compare.to_csv(out / "steady_compare.csv", index=False)
    last = list(result.models)[-1]
    gains.plot(models={f"variant {len(result.models) - 1}": result.models[list(result.models)[-2]],
                       f"variant {len(result.models)} (tilt inputs)": result.models[last],
                       "Eq. 6.8-6.9 printed": models[REFERENCE]}) \
        .savefig(out / "steady_gains.png", dpi=90)
    blind = gains.rate_only()
    print(f"wake's steady gains ({gains.wall_s:.0f} s; regressor condition number {gains.condition_number:.3g}):")
    print("  equivalent steady K_R (Eq. 2.29 at 0 rad/s), with the tilt input: "
          + ", ".join(f"{r} {v:.2f}" for r, v in gains.equivalent_kr.items())
          + "; rate only (tilt read as rate): " + ", ".join(f"{r} {v:.2f}" for r, v in blind.equivalent_kr.items()))
    on = [f"{o}/{i} {gains.tilt_gain.loc[o, i]:+.3f}" for i in gains.tilt_gain.columns
          for o in gains.tilt_gain.index if o == i.replace("beta", "lam", 1)]
    print("  on-axis tilt gains [1/rad]: " + ", ".join(on))
    wide = compare.pivot_table(index=["record", "window", "output"], columns="model", values="ratio", sort=False)
    print("  model / wake, on-axis steady change per record window:")
    print(wide.rename(columns=lambda c: c[:28]).to_string(float_format=lambda v: f"{v:.3g}"))
    return gains


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n-jobs", type=int, default=2, help="wake worker processes")
    parser.add_argument("--out", default="results/twelve_state_variants")
    args = parser.parse_args(argv)
    run(args.out, n_jobs=args.n_jobs)


if __name__ == "__main__":
    main()
