"""constraints.txt is the environment `make test`, `make study`, `make docs` and CI install.

pyproject.toml states what the code needs (lower bounds); constraints.txt pins the one set of
versions the tests and the committed results are checked with, so that a fresh machine gets the
same environment rather than whatever is newest that day. These tests keep the two files
consistent (every requirement pinned, inside its specifier; the lock well formed) and check that
the running environment is the pinned one, except under `make test-latest`, which sets
ROTORWAKE_UNPINNED because testing other versions is its point.

Run as a script (as `make test-latest` does), it lists the installed versions that differ from
the pins.
"""
import os
import re
import sys
from importlib import metadata
from pathlib import Path

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10, which `make test-latest` may run on: the same parser
    import tomli as tomllib

import pytest
from packaging.requirements import Requirement
from packaging.utils import canonicalize_name
from packaging.version import InvalidVersion, Version

ROOT = Path(__file__).resolve().parents[1]
PYPROJECT = ROOT / "pyproject.toml"
CONSTRAINTS = ROOT / "constraints.txt"
_PIN = re.compile(r"([A-Za-z0-9][A-Za-z0-9._-]*)==(\S+)")


def _pins(text):
    """The pins of a constraints text ({normalised name: Version}) and what is wrong with it."""
    pins, problems, names = {}, [], []
    for number, line in enumerate(text.splitlines(), 1):
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        match = _PIN.fullmatch(line)
        try:
            version = Version(match[2]) if match else None
        except InvalidVersion:
            version = None
        if version is None:
            problems.append(f"constraints.txt line {number}: {line!r} is not name==version")
            continue
        name = canonicalize_name(match[1])
        if name in pins:
            problems.append(f"constraints.txt line {number}: {match[1]} is pinned a second time")
        pins.setdefault(name, version)
        names.append(match[1])
    if names != sorted(names, key=str.lower):
        problems.append("constraints.txt: the pins are not sorted case-insensitively by name")
    return pins, problems


def _requirements(text):
    """(where, Requirement) for every requirement of a pyproject text that applies to this Python."""
    project = tomllib.loads(text)["project"]
    groups = [("dependencies", "", project.get("dependencies", []))]
    groups += [(f"extra {extra!r}", extra, found)
               for extra, found in project.get("optional-dependencies", {}).items()]
    return [(where, requirement) for where, extra, found in groups
            for requirement in map(Requirement, found)
            if requirement.marker is None or requirement.marker.evaluate({"extra": extra})]


def _unpinned(requirements, pins):
    """The requirements the pins leave open or contradict, each named with its pin and specifier."""
    problems = []
    for where, requirement in requirements:
        pin = pins.get(canonicalize_name(requirement.name))
        if pin is None:
            problems.append(f"{requirement.name} ({where}: {requirement.specifier or 'any'}) "
                            "is not pinned in constraints.txt")
        elif not requirement.specifier.contains(pin, prereleases=True):
            problems.append(f"{requirement.name}=={pin} in constraints.txt is outside "
                            f"pyproject.toml's {requirement.specifier} ({where})")
    return problems


def _installed():
    """{normalised name: version} of the distributions this interpreter imports from."""
    found = {}
    for dist in metadata.distributions():
        if dist.metadata["Name"]:  # the first found on sys.path is the one imported
            found.setdefault(canonicalize_name(dist.metadata["Name"]), dist.version)
    return found


def _mismatches(pins, installed):
    """The pinned distributions installed at another version than their pin."""
    return [f"{name}: pinned {pin}, installed {installed[name]}" for name, pin in sorted(pins.items())
            if name in installed and Version(installed[name]) != pin]


def test_every_requirement_is_pinned_inside_its_specifier():
    text = CONSTRAINTS.read_text()
    resolved = re.search(r"^# Resolved on CPython (\d+)\.(\d+)", text, re.M)
    assert resolved, "constraints.txt's header does not say which Python it was resolved on"
    if sys.version_info[:2] < (int(resolved[1]), int(resolved[2])):  # make test-latest on an older Python
        pytest.skip(f"constraints.txt is resolved on CPython {resolved[1]}.{resolved[2]}: its pins "
                    "need not cover the requirements of this older Python")
    pins, _ = _pins(text)
    assert _unpinned(_requirements(PYPROJECT.read_text()), pins) == []


def test_constraints_are_unique_sorted_exact_pins():
    assert _pins(CONSTRAINTS.read_text())[1] == []


def test_the_environment_is_the_pinned_one():
    if os.environ.get("ROTORWAKE_UNPINNED"):
        pytest.skip("ROTORWAKE_UNPINNED is set: this run (make test-latest) tests other versions on purpose")
    assert _mismatches(_pins(CONSTRAINTS.read_text())[0], _installed()) == []


BAD_PYPROJECT = """
[project]
dependencies = ["numpy>=1.26", "scipy>=1.11", 'tomli>=1.1; python_version < "3"']
[project.optional-dependencies]
docs = ["sphinx>=7.2"]
"""


def test_the_checks_report_what_is_wrong():
    pins, problems = _pins("# a header\n\nnumpy==1.25.0\nNumPy==1.26.4\nscipy>=1.11\nb==1\na==1.x\n")
    assert problems == ["constraints.txt line 4: NumPy is pinned a second time",
                        "constraints.txt line 5: 'scipy>=1.11' is not name==version",
                        "constraints.txt line 7: 'a==1.x' is not name==version",
                        "constraints.txt: the pins are not sorted case-insensitively by name"]
    requirements = _requirements(BAD_PYPROJECT)
    assert [str(r) for _, r in requirements] == ["numpy>=1.26", "scipy>=1.11", "sphinx>=7.2"]
    assert _unpinned(requirements, pins) == [
        "numpy==1.25.0 in constraints.txt is outside pyproject.toml's >=1.26 (dependencies)",
        "scipy (dependencies: >=1.11) is not pinned in constraints.txt",
        "sphinx (extra 'docs': >=7.2) is not pinned in constraints.txt"]
    assert _mismatches(pins, {"numpy": "1.26.4", "b": "1.0", "other": "3"}) == [
        "numpy: pinned 1.25.0, installed 1.26.4"]


if __name__ == "__main__":
    differ = _mismatches(_pins(CONSTRAINTS.read_text())[0], _installed())
    print("Installed versions that differ from constraints.txt:" if differ else
          "Every installed pinned distribution is at its constraints.txt version.", *differ, sep="\n  ")
