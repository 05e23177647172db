"""The Examples in the library's docstrings run, and the public entry points have one.

Every ``>>>`` example in ``flightid``, ``aircraft`` and ``controllers`` is collected
with :mod:`doctest` and run as a test of its own (numbers are printed rounded, so
they hold on any machine). Examples that would run a wake for minutes are marked
``# doctest: +SKIP`` where they stand; the entry points listed in
:data:`ENTRY_POINTS` must carry an ``Examples`` section.
"""
import doctest
import importlib
import pkgutil

import pytest

PACKAGES = ("flightid", "aircraft", "controllers")

#: What a user calls first, package by package: each has an Examples section.
ENTRY_POINTS = (
    "flightid.frequency_response", "flightid.fit", "flightid.reduce", "flightid.verify",
    "flightid.read_flight_data", "flightid.fit_transfer_function", "flightid.identify",
    "flightid.frequency_sweep",
    "aircraft.coaxial_compound", "aircraft.read_aircraft",
    "aircraft.helicopter.trim", "aircraft.helicopter.linearize", "aircraft.helicopter.mixing_matrix",
    "aircraft.inflow.PittPeters", "aircraft.inflow.IdentifiedInflow",
    "aircraft.wake.run_sweeps",
    "aircraft.identification.identify_inflow", "aircraft.identification.get_structure",
    "aircraft.identification.flight_condition", "aircraft.identification.trust_check",
    "aircraft.identification.IdentificationSettings",
    "aircraft.provenance.settings_hash",
    "controllers.specs_for", "controllers.EMFDesign", "controllers.dmo",
)


def _modules():
    for package in PACKAGES:
        root = importlib.import_module(package)
        yield root
        for info in pkgutil.walk_packages(root.__path__, package + "."):
            if ".gpu" in info.name:          # needs a CUDA device to import its kernels
                continue
            yield importlib.import_module(info.name)


def _doctests():
    finder = doctest.DocTestFinder(exclude_empty=True)
    seen = set()
    for module in _modules():
        for test in finder.find(module):
            if test.examples and test.name not in seen:
                seen.add(test.name)
                yield test


DOCTESTS = sorted(_doctests(), key=lambda t: t.name)
#: examples that run a design (several seconds each): left out of the quick set (make test-quick)
SLOW_EXAMPLES = {"controllers.dmo.dmo", "controllers.multi_axis_design.design_multi_axis",
                 "controllers.multi_axis_joint.joint_check", "controllers.multi_axis_report.multi_axis_summary",
                 "controllers.multi_axis_report.multi_axis_tables", "controllers.multi_axis_report.limits_table",
                 "controllers.multi_axis_report.write_multi_axis_report"}


@pytest.mark.parametrize("test", [pytest.param(t, marks=pytest.mark.slow) if t.name in SLOW_EXAMPLES else t
                                  for t in DOCTESTS], ids=[t.name for t in DOCTESTS])
def test_docstring_example_runs(test):
    report = []
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    result = runner.run(test, out=report.append)
    assert result.failed == 0, "".join(report)


@pytest.mark.parametrize("name", ENTRY_POINTS)
def test_entry_point_has_an_example(name):
    module, _, attr = name.rpartition(".")
    obj = getattr(importlib.import_module(module), attr)
    doc = obj.__doc__ or ""
    assert "Examples\n" in doc and ">>>" in doc, f"{name} has no Examples section"
