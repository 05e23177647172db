"""Meta-test: every public function and class has a numpydoc docstring.

Like python-control's ``test_docstrings.py``: the public API is what the packages
export in ``__all__`` (package ``__init__`` and every public module). Checked:

1. every public function and class has a docstring;
2. a function or (non-dataclass) class that takes parameters has a numpydoc
   ``Parameters`` section naming each of them;
3. a parameter whose name says it is a physical quantity (time, frequency,
   speed, density, length) states its unit in square brackets, e.g. ``[rad/s]``.

Dataclasses are exempt from rule 2 (their fields are documented where they are
declared, with ``#:`` comments or in the class docstring) but not from rule 1.
Items that do not pass yet are listed in ``KNOWN_GAPS`` with the reason; an entry
that starts passing must be removed (checked), so the list only shrinks and any
new public function must comply.
"""
import dataclasses
import importlib
import inspect
import pkgutil
import re

import pytest

PACKAGES = ("flightid", "aircraft", "controllers")

# Parameter names that are physical quantities: their description needs a unit.
PHYSICAL = {"omega", "dt", "duration", "w_min", "w_max", "w_lo", "w_hi", "frequency", "bandwidth",
            "cutoff", "delay", "sensor_delay", "pulse_width", "speed", "forward_speed", "rho", "radius",
            "rc", "rc0", "nu", "rate_limit", "wall_time_s"}

# Known gaps when this test was written, each with its reason. Remove an entry
# when its docstring is fixed (test_known_gaps_are_still_gaps fails until then).
_PARAMS_SECTION_MISSING = "no numpydoc Parameters section yet (module owned by another work stream)"
_PARAM_UNDOCUMENTED = "Parameters section does not name every parameter yet"
KNOWN_GAPS = {
    "controllers.specs.spec_by_name": "no docstring yet",
    **{name: _PARAMS_SECTION_MISSING for name in (
        "aircraft.helicopter.airframe.propeller_loads",
        "aircraft.helicopter.linearize.default_steps",
        "aircraft.helicopter.linearize.modes",
        "aircraft.inflow.base.flap_rate_names",
        "aircraft.inflow.base.inflow_names", "aircraft.inflow.base.load_names",
        "aircraft.inflow.base.rotor_suffix",
        "aircraft.inflow.pitt_peters.pitt_peters_matrices",
        "aircraft.wake.far_wake.far_wake_segments", "aircraft.wake.outputs.flap_rate_mbc",
        "aircraft.wake.sweeps.sweep_inputs",
        "controllers.emf.FrequencyFunction", "controllers.emf.fit_equivalent_delay",
        "controllers.emf.fit_inverse_plant",
        "controllers.metrics.attitude_bandwidth", "controllers.metrics.crossover_frequency",
        "controllers.metrics.damping_in_band", "controllers.metrics.disturbance_rejection_bandwidth",
        "controllers.metrics.disturbance_rejection_peak", "controllers.metrics.frequency_response_of",
        "controllers.metrics.nichols_margin",
        "controllers.metrics.open_loop_onset_point", "controllers.metrics.rms_response",
        "controllers.plants.DelayedLTI", "controllers.plants.first_order_actuator",
        "controllers.plants.second_order_actuator", "controllers.specs.default_specs",
        "flightid.fitting.cifer_cost",
        "flightid.fitting.coherence_weight", "flightid.plotting.bode_with_coherence",
        "flightid.response.combine_responses", "flightid.structures.FGCStructure",
        "flightid.structures.GainDelayStructure", "flightid.sweeps.doublet",
        "flightid.sweeps.multistep_3211", "flightid.sweeps.shaped_noise",
        "flightid.verification.theil_inequality")},
    **{name: _PARAM_UNDOCUMENTED for name in (
        "aircraft.inflow.identified.mltau_statespace", "aircraft.inflow.pitt_peters.momentum_inflow",
        "aircraft.wake.trim.run_wake",
        "flightid.joint.joint_input_output", "flightid.reduction.reduce",
        "flightid.response.MeasuredResponse", "flightid.response.frequency_response")},
}

_SECTION = re.compile(r"^(\w[\w ]*)\n-{3,}\s*$", re.M)


def _public_objects():
    seen = {}
    for package in PACKAGES:
        root = importlib.import_module(package)
        modules = [root] + [importlib.import_module(m.name)
                            for m in pkgutil.walk_packages(root.__path__, package + ".")
                            if not m.name.rsplit(".", 1)[-1].startswith("_")]
        for module in modules:
            for name in getattr(module, "__all__", ()):
                obj = getattr(module, name)
                if (inspect.isfunction(obj) or inspect.isclass(obj)) and obj.__module__.startswith(PACKAGES):
                    seen.setdefault(f"{obj.__module__}.{obj.__qualname__}", obj)
    return dict(sorted(seen.items()))


PUBLIC = _public_objects()


def _sections(doc):
    """{section title: body} of a numpydoc docstring."""
    marks = list(_SECTION.finditer(doc))
    return {m.group(1).strip(): doc[m.end():marks[k + 1].start() if k + 1 < len(marks) else len(doc)]
            for k, m in enumerate(marks)}


def _documented_parameters(body):
    """{name: description, type line included} of a numpydoc Parameters section."""
    out, current = {}, []
    for line in body.splitlines():
        if line and not line[0].isspace():
            head, _, kind = line.partition(":")
            current = [n.strip().lstrip("*") for n in head.split(",") if n.strip()]
            for n in current:
                out[n] = kind.strip() + " "
        else:
            for n in current:
                out[n] += line.strip() + " "
    return out


def _parameters(obj):
    target = obj
    if inspect.isclass(obj):
        if obj.__init__ is object.__init__:
            return []
        target = obj.__init__
    try:
        sig = inspect.signature(target)
    except (TypeError, ValueError):
        return []
    return [p.name for p in sig.parameters.values()
            if p.name not in ("self", "cls") and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)]


def _problems(name, obj):
    doc = inspect.getdoc(obj) or ""
    if not doc.strip():
        return ["no docstring"]
    if inspect.isclass(obj) and (dataclasses.is_dataclass(obj) or issubclass(obj, BaseException)):
        return []
    params = _parameters(obj)
    if not params:
        return []
    if inspect.isclass(obj):   # numpydoc: parameters in the class or the __init__ docstring
        doc = doc + "\n\n" + (inspect.getdoc(obj.__init__) or "")
    sections = _sections(doc)
    if "Parameters" not in sections:
        return [f"no Parameters section for ({', '.join(params)})"]
    documented = _documented_parameters(sections["Parameters"])
    problems = [f"parameter {p!r} not in Parameters" for p in params if p not in documented]
    problems += [f"physical parameter {p!r} states no [unit]" for p in params
                 if p in PHYSICAL and p in documented and "[" not in documented[p]]
    return problems


def test_the_public_api_is_found():
    # guards the walker itself: a broken walk would pass every check vacuously
    assert len(PUBLIC) > 100
    for name in ("flightid.fitting.fit", "aircraft.wake.trim.trim_wake", "controllers.dmo.dmo",
                 "aircraft.provenance.write_manifest"):
        assert name in PUBLIC


@pytest.mark.parametrize("name", [n for n in PUBLIC if n not in KNOWN_GAPS])
def test_public_docstring(name):
    problems = _problems(name, PUBLIC[name])
    assert not problems, f"{name}: " + "; ".join(problems)


def test_known_gaps_are_still_gaps():
    fixed = [n for n in KNOWN_GAPS if n in PUBLIC and not _problems(n, PUBLIC[n])]
    gone = [n for n in KNOWN_GAPS if n not in PUBLIC]
    assert not fixed, f"docstrings now complete, remove from KNOWN_GAPS: {fixed}"
    assert not gone, f"no longer public, remove from KNOWN_GAPS: {gone}"


def test_the_checker_catches_what_it_claims():
    def undocumented(x, omega):
        """Does something.

        Parameters
        ----------
        omega : float
            Rotor speed.
        """
    def documented(x, omega):
        """Does something.

        Parameters
        ----------
        x : float
            A value [-].
        omega : float
            Rotor speed [rad/s].
        """
    problems = _problems("f", undocumented)
    assert "parameter 'x' not in Parameters" in problems
    assert "physical parameter 'omega' states no [unit]" in problems
    assert _problems("g", documented) == []
    assert _problems("h", lambda y: None) == ["no docstring"]


def _docstrings_and_comments(path):
    """(line, text) of every docstring and comment of one source file."""
    import ast
    import io
    import tokenize
    source = path.read_text()
    found = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            doc = ast.get_docstring(node, clean=False)
            if doc:
                found.append((node.body[0].lineno, doc))
    for tok in tokenize.generate_tokens(io.StringIO(source).readline):
        if tok.type == tokenize.COMMENT:
            found.append((tok.start[0], tok.string))
    return found


@pytest.mark.slow
def test_library_text_carries_no_issue_numbers_and_no_readme_pointers():
    """Docstrings and comments say what they mean: no "issue 9, item 1", no "session 9", no "see README".

    The README is a short front page and the issue tracker is not part of the
    package; the findings live in the docs (one page per study) and in each
    ``results/<study>/README.md``.
    """
    from pathlib import Path
    root = Path(__file__).resolve().parents[1]
    pattern = re.compile(r"[Ii]ssue[ #-]*[0-9]+|[Ii]ssue's|[Ss]ession [0-9]+|README")
    hits = [f"{path.relative_to(root)}:{line}: {pattern.search(text).group(0)}"
            for package in PACKAGES + ("studies",)
            for path in sorted((root / package).rglob("*.py"))
            for line, text in _docstrings_and_comments(path) if pattern.search(text)]
    assert not hits, hits
