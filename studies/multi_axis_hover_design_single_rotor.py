"""Four-axis hover control design of the UH-60-like single rotor (Pitt-Peters inflow).

The same study as :mod:`studies.multi_axis_hover_design` (same tables, HQ windows,
coupling and global check) on the single main rotor aircraft; this module only
selects the aircraft and its results folder
(``results/multi_axis_hover_design_single_rotor/``).

Run: ``rotorwake multi-axis-hover-design-single-rotor``.
"""
from __future__ import annotations

import sys

from studies import multi_axis_hover_design

__all__ = ["main"]


def main(argv=None):
    """Run :func:`studies.multi_axis_hover_design.main` for the single rotor (same options)."""
    argv = list(sys.argv[1:] if argv is None else argv)
    if not any(a == "--aircraft" or a.startswith("--aircraft=") for a in argv):
        argv = ["--aircraft", "single-rotor", *argv]
    return multi_axis_hover_design.main(argv)


if __name__ == "__main__":
    main()
