"""One registry of inflow structures, complete on import; shared excitation settings; the
shipped-model command."""
import dataclasses
import subprocess
import sys
from pathlib import Path

import pytest

from aircraft.identification import (STRUCTURES, IdentificationSettings, InflowStructure, OffRotorSettings,
                                     get_structure, register_structure)
from aircraft.identification.excitation import ExcitationSettings
from aircraft.inflow.model_files import load_record, shipped_models

ROOT = Path(__file__).resolve().parents[3]


@pytest.mark.slow
def test_every_shipped_structure_is_known_right_after_importing_the_package():
    # a fresh interpreter: nothing but the package itself imported (no registration by side effect)
    keys = sorted({(load_record(n).settings.get("structure") or {}).get("key") for n in shipped_models()} - {None})
    assert "coaxial_12state_tilt" in keys
    code = ("import sys, aircraft.identification as ai\n"
            f"keys = {keys!r}\n"
            "print([ai.get_structure(k).key for k in keys])\n"
            "print(sorted(m for m in sys.modules if m.startswith('studies')))")
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, check=True)
    lines = out.stdout.strip().splitlines()
    assert lines[-1] == "[]"                                   # no research module needed
    assert len(eval(lines[0])) == len(keys)


def test_every_registered_factory_builds_an_inflow_structure():
    for key, factory in STRUCTURES.items():
        assert isinstance(factory(), InflowStructure), key


def test_register_structure_adds_and_refuses_clashes():
    class Mine(InflowStructure):
        key = "test_mine"
    register_structure("test_mine", Mine)
    try:
        assert isinstance(get_structure("test_mine"), Mine)
        register_structure("test_mine", Mine)                  # the same again: fine
        with pytest.raises(ValueError, match="already registered"):
            register_structure("test_mine", lambda: Mine())
    finally:
        del STRUCTURES["test_mine"]
    with pytest.raises(ValueError, match="non-empty"):
        register_structure("", Mine)
    with pytest.raises(TypeError, match="callable"):
        register_structure("x", 3)
    with pytest.raises(ValueError, match="unknown inflow structure"):
        get_structure("test_mine")


def test_identification_and_off_rotor_settings_share_one_excitation():
    shared = {f.name for f in dataclasses.fields(ExcitationSettings)}
    for cls in (IdentificationSettings, OffRotorSettings):
        assert issubclass(cls, ExcitationSettings)
        assert shared <= {f.name for f in dataclasses.fields(cls)}
    # the same validation, each with its own error class
    with pytest.raises(ValueError, match="fit_range"):
        IdentificationSettings(fit_range=(0.1, 5.0))
    from aircraft.identification.off_rotor import OffRotorError
    with pytest.raises(OffRotorError, match="fit_range"):
        OffRotorSettings(fit_range=(0.1, 5.0))
    with pytest.raises(ValueError, match="n_omega"):
        IdentificationSettings(n_omega=2)
    with pytest.raises(ValueError, match="coherence_min"):
        IdentificationSettings(coherence_min=1.0)


@pytest.mark.slow
@pytest.mark.shipped_files
def test_shipped_models_command_checks_the_files():
    out = subprocess.run([sys.executable, "-m", "studies.cli", "shipped-models", "--check", "--list"], cwd=ROOT,
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stdout + out.stderr
    assert "all shipped models match their recipes" in out.stdout
    assert "coaxial_hover_12state_tilt" in out.stdout
