"""Main job: hover control comparison (dissertation §7.5), built up stage by stage.

Stage 1 (available now): the identification pipeline end to end on the embedded
default configuration (:mod:`studies.identification_demo`: six sweeps -> joint
input-output -> 6-state coaxial fit -> reduction -> verification), printing its
cost table.  Later stages (Dynamic-Climb vs wake-identified aircraft, EMF/DMO
designs for cases A, B, C) plug in here as the aircraft and controllers
packages land; each stage writes its tables and figures under ``results/``.

Run: ``make study`` or ``python -m studies.hover_control_comparison``.
"""
from __future__ import annotations

import argparse

from studies.identification_demo import run_demo


def main(argv=None):
    parser = argparse.ArgumentParser(description="Hover control comparison (dissertation §7.5)")
    parser.add_argument("--seed", type=int, default=0, help="seed of all random inputs/noise")
    parser.add_argument("--out", default="results", help="output folder")
    args = parser.parse_args(argv)
    print("[stage 1] identification pipeline on the embedded 6-state coaxial truth")
    cost = run_demo(seed=args.seed, out_dir=f"{args.out}/identification_demo")
    print(f"[stage 1] done: J_ave = {cost.J.mean():.2f} over {len(cost)} responses")


if __name__ == "__main__":
    main()
