"""Is any 6-state of the Eq. 5.3 family trustworthy on our coaxial hover wake? A scan.

Identifies the shipped ``coaxial_hover_6state`` recipe (its six swashplate sweeps,
cached) to get the joint input-output lambda/C, then fits every member of
:data:`studies.analysis.six_state_scan.SIX_STATE_FAMILY` (fit band 1, 1.5
or 2 to 25 rad/s; apparent masses free, the collective diagonal or the whole
diagonal held at Pitt-Peters'; no feedthrough or a cross-rotor feedthrough) from
several starts, reduces the best with the guideline thresholds, and says which
member meets the trust target (every bound < 20 %, insensitivity < 10 %, no flat
direction, J_ave <= 100) (:func:`studies.analysis.six_state_scan.six_state_scan`).

Writes ``results/six_state_scan/``: ``table.csv`` (one row per candidate),
``pair_costs.csv`` (each candidate's 12 rotor-pair costs over 1-25 rad/s),
``scan.png`` (J_ave against the largest bound, target box), ``cyclic_pairs.png``
(the lateral cyclic responses of both rotors beside the Pareto candidates).

Run: ``rotorwake six-state-scan`` (``--n-jobs``: worker processes for the wake and
the scan). It has no small configuration; the tests check the library pieces on
exact data (``tests/aircraft/identification/test_six_state_scan.py``).
"""
from __future__ import annotations

import argparse
from pathlib import Path

from aircraft import identify_inflow
from aircraft.identification.shipped import RECIPES
from studies.analysis.six_state_scan import plot_cyclic_pairs, six_state_scan


def run(out_dir="results/six_state_scan", n_jobs=2):
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    recipe = RECIPES["coaxial_hover_6state"]
    config, condition, structure = recipe.arguments()
    # the shipped recipe's own call: the scan fits the lambda/C this produces
    shipped = identify_inflow(config, condition, structure, ct=recipe.ct, settings=recipe.settings,
                              n_jobs=n_jobs, progress=True)
    scan = six_state_scan(shipped.responses, shipped.omega, n_jobs=n_jobs, progress=True)
    table = scan.to_pandas()
    table.to_csv(out / "table.csv", index=False)
    scan.pair_costs.to_csv(out / "pair_costs.csv", index=False)
    ax = scan.plot()
    ax.figure.savefig(out / "scan.png", dpi=90, bbox_inches="tight")
    plot_cyclic_pairs(scan, shipped.responses).savefig(out / "cyclic_pairs.png", dpi=80)
    cols = ["label", "J_ave", "J_ave_reference_band", "n_free", "max_cramer_rao_pct", "n_cramer_rao_over",
            "max_insensitivity_pct", "n_flat", "slowest_pole_1_s", "m22", "meets_target", "pareto"]
    print(f"shipped coaxial_hover_6state (pipeline): J_ave {shipped.J_ave:.1f}, trusted {shipped.trusted}")
    print(table[[c for c in cols if c in table]].to_string(index=False, float_format=lambda v: f"{v:.3g}"))
    met = table[table.meets_target]
    print("candidates meeting the target: " + (", ".join(met.label) if len(met) else "none"))
    print(f"tables and figures in {out}/")
    return scan


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n-jobs", type=int, default=2, help="worker processes (wake runs and the scan)")
    parser.add_argument("--out", default="results/six_state_scan")
    args = parser.parse_args(argv)
    run(args.out, n_jobs=args.n_jobs)


if __name__ == "__main__":
    main()
