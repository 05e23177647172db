"""The commands of the ``rotorwake`` command line: one :class:`Study` per study.

The registry the command line (:mod:`studies.cli`), ``rotorwake results``, the
docs' study pages and the tests read: each study's sub-command, module, one-line
summary, rough run time, results folders and what makes a second run faster.
Nothing here computes a number, and nothing heavy is imported.
"""
from __future__ import annotations

from dataclasses import dataclass, field

__all__ = ["Study", "STUDIES"]


@dataclass(frozen=True)
class Study:
    """One command of the ``rotorwake`` command line.

    Parameters
    ----------
    command : str
        Sub-command name.
    module : str
        Study module whose ``main`` runs it.
    summary : str
        One line for ``rotorwake --help``.
    minutes : float
        Rough wall time on 2 cores with an empty cache [min].
    outputs : tuple of str
        Results folders written, relative to ``--out`` (``{out}`` is the option's
        value; the default below applies when it is not given).
    default_out : str
        Default of the study's ``--out`` option.
    cached_note : str
        What makes a second run faster, if anything.
    in_results : bool
        Whether ``rotorwake results`` regenerates it.
    variants : dict
        ``{"--option=value": (minutes, outputs, cached_note)}`` for options that
        change the run time and the folders written.
    """

    command: str
    module: str
    summary: str
    minutes: float
    outputs: tuple = ("{out}",)
    default_out: str = ""
    cached_note: str = ""
    in_results: bool = True
    variants: dict = field(default_factory=dict)


STUDIES = {s.command: s for s in (
    Study("main", "studies.hover_control_comparison",
          "main job: hover control comparison, cases A/B/C on our wake-identified 12-state model (§7.5)", 3.0,
          outputs=("{out}/identification_demo", "{out}/hover_control_comparison"), default_out="results",
          variants={"--identified=published": (2.0, ("{out}/identification_demo",
                                                     "{out}/hover_control_comparison_published"),
                                               "cases B/C on the dissertation's Eq. 5.3 model instead"),
                    "--free-drift": (2.0, ("{out}/identification_demo", "{out}/hover_control_comparison_free_drift"),
                                     "u and v left free in the roll design plants (Eq. 7.21 literally)"),
                    "--regenerate": (45.0, ("{out}/identification_demo", "{out}/hover_control_comparison"),
                                     "re-identifies our 6- and 12-state models from the free wake first; "
                                     "wake runs cached under .cache/wake (a few minutes after)")}),
    Study("identification-demo", "studies.identification_demo",
          "identification pipeline on an embedded 6-state truth (sweeps -> fit -> reduce -> verify)", 0.5,
          default_out="results/identification_demo", in_results=False),
    Study("wake-identification", "studies.wake_identification",
          "3-state inflow model of the single rotor identified from our free wake (Tables 4.1-4.2)", 3.0,
          default_out="results/wake_identification", cached_note="wake runs cached under .cache/wake"),
    Study("off-rotor-models", "studies.off_rotor_models",
          "off-rotor induced velocity at the tail and a wing under the hub, hover and mu = 0.1 "
          "(Eqs. 2.39-2.40, §4.6)", 25.0,
          default_out="results/off_rotor_models",
          cached_note="wake runs cached under .cache/wake; --small under a minute",
          variants={"--coarse": (5.0, ("{out}",), "wake runs cached under .cache/wake")}),
    Study("coaxial-wake-identification", "studies.coaxial_wake_identification",
          "6- and 12-state coaxial inflow models identified from our free wake (Eq. 5.3, §6.3)", 45.0,
          default_out="results/coaxial_wake_identification",
          cached_note="wake runs cached under .cache/wake (about 6 min after)"),
    Study("coaxial-quasi-steady", "studies.coaxial_quasi_steady",
          "steady gain of the shipped coaxial models against held steps of our wake (the quasi-steady guard)",
          3.0, default_out="results/coaxial_quasi_steady",   # 142 s measured with --no-cache
          cached_note="wake runs cached under .cache/wake (seconds after)"),
    Study("twelve-state-variants", "studies.twelve_state_variants",
          "constrained 12-state coaxial hover models on one wake data set: trust and roll damping per constraint",
          12.0, default_out="results/twelve_state_variants",
          cached_note="wake runs cached under .cache/wake (the shipped 12-state's; about 40 min without them)"),
    Study("six-state-scan", "studies.six_state_scan",
          "is any 6-state of the Eq. 5.3 family (band, a priori masses, feedthrough) trustworthy on our wake?",
          10.0, default_out="results/six_state_scan",   # 565 s measured, wake cached
          cached_note="wake runs cached under .cache/wake (the shipped 6-state's; about 6 min more without them)"),
    Study("coaxial-design-space", "studies.coaxial_design_space",
          "6-state coaxial inflow model across rotor spacing x thrust, scheduled", 25.0,
          default_out="results/coaxial_design_space",
          cached_note="wake runs cached under .cache/wake (about 3 min after)",
          variants={"--no-cache": (40.0, ("{out}",), "the wake runs recomputed, so timing.csv holds the data "
                                                      "sets' wall times")}),
    Study("coaxial-hover-poles", "studies.coaxial_hover_poles",
          "coaxial aircraft hover poles with two inflow models (Tables 7.1/7.2)", 0.5,
          default_out="results/coaxial_hover_poles"),
    Study("bare-airframe", "studies.bare_airframe",
          "bare-airframe responses of the coaxial with five inflow models (Figs. 7.3-7.11)", 1.0,
          default_out="results/bare_airframe"),
    Study("coaxial-forward-flight", "studies.coaxial_forward_flight",
          "coaxial at 200 kt: Eq. 6.5 inflow model from our coarse wake (Table 6.3, Eqs. 6.12-6.13) and "
          "the bare airframe against Isolated Rotors (Figs. 7.7-7.10)", 30.0,
          default_out="results/coaxial_forward_flight",
          cached_note="wake runs cached under .cache/wake (the fit and reduction remain)",
          variants={"--near-wake-only": (10.0, ("{out}",), "the 72-parameter near-wake half; wake runs cached "
                                                            "under .cache/wake"),
                    "--candidate-structures": (35.0, ("{out}",), "also the smaller candidate structures on the "
                                                                 "same records, trust verdicts in structures.csv")}),
    Study("rotor-truth-check", "studies.rotor_truth_check",
          "rotor-level truth check: free wake with free flapping vs blade-element rotor with "
          "identified / Dynamic-Climb / Pitt-Peters inflow (§7.2.2)", 10.0,
          default_out="results/rotor_truth_check", cached_note="wake runs cached under .cache/wake"),
    Study("free-wake-flight", "studies.free_wake_flight",
          "the free wake flown with the aircraft (MFW only): hover coning response to collective, shaft "
          "fixed and free in heave, against the identified 3-state and Pitt-Peters (Figs. 7.1-7.2)", 5.0,
          default_out="results/free_wake_flight"),
    Study("forward-flight-identification", "studies.forward_flight_identification",
          "single rotor over mu = 0-0.3 (Eqs. 4.7-4.8 structure) vs Pitt-Peters, and K_R(omega) in hover "
          "(§4.4, Figs. 4.34-4.36, §4.7)", 20.0, default_out="results/forward_flight_identification",
          cached_note="wake runs cached under .cache/wake",
          variants={"--wake=coarse": (4.0, ("{out}",), "wake runs cached under .cache/wake"),
                    "--no-cache": (13.0, ("{out}",), "the wake runs recomputed, so its wall times are the data sets'")}),
    Study("wake-length-check", "studies.wake_length_check",
          "coaxial hover cyclic/collective responses on 3x the far wake and 2x the free wake",
          6.0, default_out="results/wake_length_check", cached_note="wake runs cached under .cache/wake"),
    Study("wake-geometry-check", "studies.wake_geometry_check",
          "hover tip-vortex trajectory of the single rotor (contraction, descent) against Landgrebe's "
          "measured generalised wake", 2.0,
          default_out="results/wake_geometry_check"),
    Study("roll-design-sensitivity", "studies.roll_design_sensitivity",
          "which cyclic each stick drives (control phase), 100/200 kt lift-offset trims, case A against the "
          "rotor assumptions (flap frequency, Lock number, control phase)", 6.0,
          default_out="results/roll_design_sensitivity"),
    Study("harrington-hover-power", "studies.harrington_hover_power",
          "hover power of a full-scale coaxial rotor and its lower rotor alone (Harrington, NACA TN-2318) "
          "with real blades, ours against the measured", 8.0,
          default_out="results/harrington_hover_power"),
    Study("multi-axis-hover-design", "studies.multi_axis_hover_design",
          "four-axis EMF design of the coaxial in hover with actuator limits in the OLOP: per-axis HQ windows, "
          "coupling, a global search that tries to beat each axis's DMO answer, and a joint search over every "
          "axis's gains at once", 8.0,
          default_out="results/multi_axis_hover_design"),
    Study("multi-axis-hover-design-single-rotor", "studies.multi_axis_hover_design_single_rotor",
          "the same four-axis hover design, global and joint checks on the UH-60-like single rotor (Pitt-Peters)", 10.0,
          default_out="results/multi_axis_hover_design_single_rotor"),
    Study("multi-axis-forward-flight-design", "studies.multi_axis_forward_flight_design",
          "four-axis EMF design of the coaxial compound in forward flight (propeller trimmed, u held) against "
          "every axis's forward-flight specs, with the hover study's HQ windows and global check", 5.0,
          default_out="results/multi_axis_forward_flight_design"),
    Study("pitt-peters-hover-check", "studies.pitt_peters_hover_check",
          "linearised Pitt-Peters against Tables 4.1-4.2 and forward flight", 0.2,
          default_out="results/pitt_peters_hover_check"),
    Study("trim-sweeps", "studies.trim_sweeps",
          "both aircraft trimmed and linearised from hover to maximum speed: controls, attitudes, "
          "power and eigenvalues against speed, modes named and tracked; the 200 kt propeller models", 1.0, default_out="results/trim_sweeps"),
)}
