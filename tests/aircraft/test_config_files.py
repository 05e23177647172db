"""Aircraft as data: AircraftConfig <-> TOML files.

Round trips of both aircraft (bit for bit), a hand-written minimal single-rotor
file, errors that name the file and the line or field, and the shipped files
against the factory functions field for field (so the files cannot drift from
the code).
"""
import dataclasses
import math
import re

import pytest

import aircraft
from aircraft.config_files import (ConfigFileError, FORMAT_VERSION, _schema, load_shipped_aircraft,
                                   read_aircraft, shipped_aircraft, write_aircraft)
from aircraft.configs import (AircraftConfig, ConfigError, PropellerConfig, RotorConfig, TailRotorConfig,
                              coaxial_compound, uh60_single_rotor)

FACTORIES = {"coaxial_compound": coaxial_compound, "uh60_single_rotor": uh60_single_rotor}

MINIMAL = """\
# a hand-written single-rotor helicopter: only the required fields, angles in degrees
name = "small helicopter"
mass = 1000      # kg (an integer is read as a float)
Ixx = 500.0
Iyy = 1500.0
Izz = 1200.0

[[rotors]]
name = ""
radius = 4.0
omega = 50.0
n_blades = 3
chord = 0.2
twist_deg = -8.0
root_cutout = 0.15
"""


def _differences(a, b, where=""):
    """Paths of the fields in which two (nested) config dataclasses differ, compared exactly."""
    if dataclasses.is_dataclass(a) and type(a) is type(b):
        out = []
        for f in dataclasses.fields(a):
            out += _differences(getattr(a, f.name), getattr(b, f.name), f"{where}.{f.name}" if where else f.name)
        return out
    if isinstance(a, tuple) and isinstance(b, tuple) and len(a) == len(b):
        out = []
        for k, (x, y) in enumerate(zip(a, b)):
            out += _differences(x, y, f"{where}[{k}]")
        return out
    # exact: same type and value (a float must stay a float, bit for bit)
    same = type(a) is type(b) and (a == b or (isinstance(a, float) and math.isnan(a) and math.isnan(b)))
    return [] if same else [f"{where}: {a!r} != {b!r}"]


def _write(tmp_path, text, name="aircraft.toml"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


@pytest.mark.parametrize("factory", [coaxial_compound, uh60_single_rotor,
                                     lambda: coaxial_compound(cruise=True)])
def test_round_trip_is_exact(tmp_path, factory):
    config = factory()
    path = write_aircraft(config, tmp_path / "a.toml")
    back = read_aircraft(path)
    assert back == config
    assert _differences(back, config) == []
    # writing what was read gives the same text
    assert write_aircraft(back, tmp_path / "b.toml").read_text() == path.read_text()


def test_round_trip_of_awkward_values(tmp_path):
    # floats that need all 17 digits, ints in float fields, quotes and backslashes in
    # names, a shaft tilt and an optional field set; a propeller on a single rotor
    rotor = RotorConfig(name='M"1\\', radius=0.1 + 0.2, omega=1 / 3, n_blades=5, chord=2 ** -0.5,
                        twist=-math.pi / 7, root_cutout=0.1, hinge_offset=0.0, shaft_tilt=math.radians(3.0),
                        hub_position=(0, 1e-300, -2), flap_inertia=1234.5678901234567)
    config = AircraftConfig(name="tab\there, é", rotors=(rotor,), mass=5e3, Ixx=1, Iyy=2.5, Izz=3,
                            Ixz=-0.5, propeller=PropellerConfig(twist=0.25), omega_cruise=math.e,
                            trim_ct=(1 / 300,), control_phase=-math.pi)
    back = read_aircraft(write_aircraft(config, tmp_path / "x.toml"))
    assert back == config
    # ints written for float fields come back as floats of the same value
    assert back.Ixx == 1.0 and isinstance(back.Ixx, float)
    assert back.rotors[0].hub_position == (0.0, 1e-300, -2.0)


def test_round_trip_of_a_tail_rotor_and_fuselage_lift(tmp_path):
    tail = TailRotorConfig(radius=1 / 3, omega=100.0 + 1e-13, solidity=0.2, twist=-math.pi / 11,
                           position=(-7, 0.25, -1.5), thrust_sign=-1)
    config = dataclasses.replace(uh60_single_rotor(), tail_rotor=tail, fuselage_lift_area=0.1 + 0.2)
    path = write_aircraft(config, tmp_path / "t.toml")
    assert read_aircraft(path) == config
    # degrees accepted as for every angle; a tail rotor on a coaxial is refused, naming the field
    text = path.read_text().replace(f"twist       = {-math.pi / 11!r}", "twist_deg = -10.0")
    assert read_aircraft(_write(tmp_path, text, "d.toml")).tail_rotor.twist == pytest.approx(math.radians(-10.0))
    coax = write_aircraft(coaxial_compound(), tmp_path / "c.toml").read_text()
    with pytest.raises(ConfigFileError, match="tail_rotor: only a single-rotor aircraft"):
        read_aircraft(_write(tmp_path, coax + "\n[tail_rotor]\nradius = 1.0\n", "e.toml"))
    with pytest.raises(ConfigFileError, match=r"tail_rotor: TailRotorConfig.thrust_sign must be \+1 or -1, got 2"):
        read_aircraft(_write(tmp_path, path.read_text().replace("thrust_sign = -1", "thrust_sign = 2"), "f.toml"))


def test_the_file_says_its_units_and_every_field(tmp_path):
    text = write_aircraft(coaxial_compound(), tmp_path / "c.toml").read_text()
    assert "SI" in text.splitlines()[2] and "RADIANS" in text
    assert re.search(r"^radius\s+= 9\.31164  # m$", text, re.M)
    assert re.search(r"^omega\s+= 23\.7  # rad/s$", text, re.M)
    assert "(-10 deg)" in text          # the angle in degrees beside the radians
    assert f"format_version = {FORMAT_VERSION}" in text
    for cls in (AircraftConfig, RotorConfig, PropellerConfig):
        for f in dataclasses.fields(cls):
            if f.name not in ("rotors", "propeller"):
                assert re.search(rf"^#? ?{f.name}\b", text, re.M), f.name
    # None is written as an absent key (a comment), and no propeller as no table
    text = write_aircraft(uh60_single_rotor(), tmp_path / "u.toml").read_text()
    assert re.search(r"^# flap_inertia not set", text, re.M)
    assert "[propeller]" not in text.replace("no [propeller] table", "")
    # the single rotor's tail rotor is its own table with every field
    assert re.search(r"^\[tail_rotor\]", text, re.M)
    for f in dataclasses.fields(TailRotorConfig):
        assert re.search(rf"^{f.name}\b", text.split("[tail_rotor]")[1], re.M), f.name


def test_the_schema_covers_every_dataclass_field():
    for cls in (AircraftConfig, RotorConfig, PropellerConfig, TailRotorConfig):
        assert list(_schema(cls)) == [f.name for f in dataclasses.fields(cls)]


def test_minimal_hand_written_single_rotor(tmp_path):
    config = read_aircraft(_write(tmp_path, MINIMAL))
    rotor = RotorConfig(name="", radius=4.0, omega=50.0, n_blades=3, chord=0.2, twist=math.radians(-8.0),
                        root_cutout=0.15)
    assert config == AircraftConfig(name="small helicopter", rotors=(rotor,), mass=1000.0, Ixx=500.0,
                                    Iyy=1500.0, Izz=1200.0)
    assert config.propeller is None and config.rotors[0].flap_inertia is None
    assert isinstance(config.mass, float)
    assert config.rotors[0].twist == math.radians(-8.0)


def test_hand_written_coaxial_in_degrees_equals_the_factory(tmp_path):
    # the factory's own numbers, angles in degrees: the same doubles as math.radians gives
    text = write_aircraft(coaxial_compound(), tmp_path / "c.toml").read_text()
    text = re.sub(r"^twist(\s+)= -0\.17453292519943295", r"twist_deg\1= -10.0", text, flags=re.M)
    text = re.sub(r"^control_phase(\s+)= \S+", r"control_phase_deg\1= 90.0", text, flags=re.M)
    assert len(re.findall(r"^twist_deg", text, re.M)) == 2
    assert read_aircraft(_write(tmp_path, text)) == coaxial_compound()


def test_malformed_file_names_the_file_and_line(tmp_path):
    path = _write(tmp_path, MINIMAL.replace("n_blades = 3", "n_blades 3"))
    with pytest.raises(ConfigFileError, match=r"aircraft\.toml, line 12: TOML syntax error") as err:
        read_aircraft(path)
    assert str(path) in str(err.value)
    with pytest.raises(ConfigFileError, match=r"line 2: TOML syntax error"):
        read_aircraft(_write(tmp_path, 'name = "x"\nname = "y"\n'))          # a key given twice
    latin1 = tmp_path / "latin1.toml"
    latin1.write_bytes(b'# comment\nname = "h\xe9licopt\xe8re"\n')
    with pytest.raises(ConfigFileError, match=r"latin1\.toml, line 2: not UTF-8"):
        read_aircraft(latin1)
    with pytest.raises(ConfigFileError, match="does not exist"):
        read_aircraft(tmp_path / "missing.toml")


@pytest.mark.parametrize("remove, message", [
    ("mass = 1000      # kg (an integer is read as a float)\n",
     r"missing required field mass \[kg\]; the top level needs name, mass, Ixx, Iyy, Izz"),
    ("radius = 4.0\n", r"missing required field rotors\[0\]\.radius \[m\]; a \[\[rotors\]\] table needs"),
    ("twist_deg = -8.0\n", r"missing required field rotors\[0\]\.twist \[rad"),
])
def test_missing_field_is_named(tmp_path, remove, message):
    assert remove in MINIMAL
    with pytest.raises(ConfigFileError, match=message):
        read_aircraft(_write(tmp_path, MINIMAL.replace(remove, "")))


def test_missing_field_in_the_second_rotor(tmp_path):
    text = write_aircraft(coaxial_compound(), tmp_path / "c.toml").read_text()
    first, second = text.split("[[rotors]]  # rotors[1]")
    second = re.sub(r"^radius .*\n", "", second, count=1, flags=re.M)
    with pytest.raises(ConfigFileError, match=r"c\.toml: missing required field rotors\[1\]\.radius \[m\]"):
        read_aircraft(_write(tmp_path, first + "[[rotors]]" + second, "c.toml"))
    with pytest.raises(ConfigFileError, match=r"missing required field rotors: give one \[\[rotors\]\]"):
        read_aircraft(_write(tmp_path, MINIMAL.split("[[rotors]]")[0]))


def test_unknown_field_is_named_with_the_valid_ones(tmp_path):
    with pytest.raises(ConfigFileError, match=r"unknown field rotors\[0\]\.radus \(did you mean 'radius'\?\); "
                                              r"the valid fields of a \[\[rotors\]\] table are name, radius, "
                                              r"omega, n_blades") as err:
        read_aircraft(_write(tmp_path, MINIMAL.replace("radius = 4.0", "radus = 4.0")))
    assert "flap_inertia" in str(err.value) and "twist_deg" in str(err.value)
    with pytest.raises(ConfigFileError, match=r"unknown field weight; the valid fields of the top level are "
                                              r"name, mass"):
        read_aircraft(_write(tmp_path, "weight = 9.0\n" + MINIMAL))
    with pytest.raises(ConfigFileError, match=r"unknown field propeller\.blades; .* the \[propeller\] table"):
        read_aircraft(_write(tmp_path, MINIMAL + "[propeller]\nblades = 5\n"))


@pytest.mark.parametrize("old, new, message", [
    ("n_blades = 3", "n_blades = 3.0", r"rotors\[0\]\.n_blades must be an integer .*got float 3\.0"),
    ("n_blades = 3", "n_blades = true", r"rotors\[0\]\.n_blades must be an integer .*got boolean True"),
    ("radius = 4.0", 'radius = "4 m"', r"rotors\[0\]\.radius must be a number \[m\], got string '4 m'"),
    ('name = ""', "name = 0", r"rotors\[0\]\.name must be a string"),
    ("Ixx = 500.0", "Ixx = [500.0]", r"Ixx must be a number \[kg m\^2\], got array"),
    ("chord = 0.2", "chord = 0.2\nhub_position = [0.0, 0.0, \"down\"]",
     r"rotors\[0\]\.hub_position\[2\] must be a number \[m\]"),
    ("chord = 0.2", "chord = 0.2\nhub_position = -2.0", r"rotors\[0\]\.hub_position must be an array of numbers"),
    ("[[rotors]]", "[rotors]", r"rotors must be an array of tables: write \[\[rotors\]\]"),
    ("twist_deg = -8.0", "twist_deg = -8.0\ntwist = -0.14", r"rotors\[0\]\.twist is given twice"),
    ("Izz = 1200.0", "Izz = 1200.0\nformat_version = 2", r"format_version 2 is not supported"),
])
def test_wrong_type_is_named(tmp_path, old, new, message):
    assert old in MINIMAL
    with pytest.raises(ConfigFileError, match=message):
        read_aircraft(_write(tmp_path, MINIMAL.replace(old, new)))


def test_dataclass_validation_says_which_file(tmp_path):
    path = _write(tmp_path, MINIMAL.replace("radius = 4.0", "radius = -4.0"), "neg.toml")
    with pytest.raises(ConfigError, match=r"neg\.toml: rotors\[0\]: RotorConfig\.radius must be positive") as err:
        read_aircraft(path)
    assert isinstance(err.value, ConfigFileError) and isinstance(err.value, ValueError)
    assert isinstance(err.value.__cause__, ConfigError)
    with pytest.raises(ConfigFileError, match=r"neg\.toml: AircraftConfig\.trim_ct needs one thrust coefficient"):
        read_aircraft(_write(tmp_path, MINIMAL.replace("Izz = 1200.0", "Izz = 1200.0\ntrim_ct = [0.005, 0.004]"),
                             "neg.toml"))


def test_write_refuses_what_is_not_an_aircraft(tmp_path):
    with pytest.raises(TypeError, match="AircraftConfig"):
        write_aircraft(coaxial_compound().rotors[0], tmp_path / "r.toml")


@pytest.mark.parametrize("name", sorted(FACTORIES))
def test_shipped_file_equals_the_factory_field_for_field(name):
    assert _differences(load_shipped_aircraft(name), FACTORIES[name]()) == []
    assert load_shipped_aircraft(name) == FACTORIES[name]()


def test_shipped_aircraft_are_listed_and_unknown_names_refused():
    assert shipped_aircraft() == sorted(FACTORIES)
    with pytest.raises(ConfigFileError, match=r"no shipped aircraft 'uh60'; shipped: \['coaxial_compound'"):
        load_shipped_aircraft("uh60")


@pytest.mark.parametrize("name", sorted(FACTORIES))
def test_load_aircraft_takes_a_shipped_name_a_file_or_a_configuration(name, tmp_path):
    from aircraft.config_files import load_aircraft
    config = FACTORIES[name]()
    assert load_aircraft(name) == config
    path = tmp_path / "mine.toml"
    write_aircraft(dataclasses.replace(config, name="mine"), path)
    assert load_aircraft(path).name == "mine" and load_aircraft(str(path)).rotors == config.rotors
    assert load_aircraft(config) is config


@pytest.mark.parametrize("bad, match", [("uh60", r"neither a shipped aircraft nor a TOML file; shipped: \['coax"),
                                        ("missing.toml", "missing.toml"), (3, "got 3"), ("", "got ''")])
def test_load_aircraft_refuses_what_is_not_an_aircraft(bad, match):
    from aircraft.config_files import load_aircraft
    with pytest.raises(ConfigFileError, match=match):
        load_aircraft(bad)


def test_the_package_face():
    for name in ("read_aircraft", "write_aircraft", "load_shipped_aircraft", "load_aircraft", "ConfigFileError"):
        assert name in aircraft.__all__ and hasattr(aircraft, name)
    assert issubclass(ConfigFileError, ValueError) and issubclass(ConfigFileError, ConfigError)


def test_round_trip_of_real_blades(tmp_path):
    # a planform with a NACA thickness table on one rotor, a tabulated polar on the
    # other, awkward floats: the file gives back the same BladeModels bit for bit
    from aircraft.blade import BladeModel, Polar
    table = BladeModel(stations=(0.2, 0.1 + 0.6, 1.0), chord=(0.5, 1 / 3, 0.3), twist=(0.1, 0.0, -math.pi / 40),
                       thickness=(0.3, 0.18, 0.12), compressibility=True, tip_loss=0.97)
    polar = BladeModel(polar=Polar(alpha=(-0.3, 0.0, 0.3), cl=(-1.2, 0.0, 1.2), cd=(0.05, 0.008, 0.05)))
    c = coaxial_compound()
    config = dataclasses.replace(c, rotors=(dataclasses.replace(c.rotors[0], blade=table),
                                            dataclasses.replace(c.rotors[1], blade=polar)))
    path = write_aircraft(config, tmp_path / "a.toml")
    text = path.read_text()
    assert text.count("[rotors.blade]") == 2 and text.count("[rotors.blade.polar]") == 1
    back = read_aircraft(path)
    assert back == config and back.rotors[0].blade == table and back.rotors[1].blade == polar
    assert write_aircraft(back, tmp_path / "b.toml").read_text() == text


def test_bad_blade_table_names_the_rotor_and_field(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text(MINIMAL + "\n[rotors.blade]\nstations = [0.2, 1.0]\ncord = [0.3, 0.2]\n", encoding="utf-8")
    with pytest.raises(ConfigFileError, match=r"rotors\[0\]\.blade: unknown blade field\(s\) \['cord'\]"):
        read_aircraft(path)
    path.write_text(MINIMAL + "\n[rotors.blade]\ntip_loss = 0.5\n", encoding="utf-8")
    with pytest.raises(ConfigFileError, match=r"rotors\[0\]\.blade: BladeModel.tip_loss"):
        read_aircraft(path)
