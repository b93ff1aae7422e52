"""Input limits a design can reach and no more, applied the same way to files, JSON and YAML:
no text for a number anywhere, no boolean for a number, integers by value whatever their
notation, physical bounds naming the field and the bound, no control or bidi characters in
names.
"""

from __future__ import annotations

import json

import pytest
import yaml

from beltstudy.engine import InputError, parse_conveyor
from beltstudy.engine.capacity import fill_pct
from beltstudy.engine.conveyor import FILL_MAX_PCT, load_conveyor
from beltstudy.service.door.parse import loads, parse_body
from beltstudy.service.door.studyfile import _load_fraction, load_study_file, resolve_study
from beltstudy.service.errors import Invalid

from .conftest import ROOT


def _three_ways(tmp_path, study: dict) -> list[str]:
    """The refusal of ``study`` as a study file, a JSON body and a YAML body (messages)."""
    out = []
    path = tmp_path / "study.yaml"
    path.write_text(yaml.safe_dump(study), encoding="utf-8")
    for load in (
        lambda: load_study_file(path),
        lambda: resolve_study(parse_body(json.dumps(study).encode(), "application/json"),
                              strict=True),
        lambda: resolve_study(parse_body(yaml.safe_dump(study).encode(), "application/yaml")),
    ):
        with pytest.raises(Invalid) as err:
            load()
        out.append(err.value.message)
    return out


def test_text_for_a_number_is_refused_in_files_json_and_yaml(tmp_path, make_study,
                                                             make_conveyor):
    said = '"4.5" is not of type "number": write 4.5 without quotes'
    study = make_study(conveyor=make_conveyor(speed_m_s="4.5"))
    for message in _three_ways(tmp_path, study):
        assert message == f"conveyor.speed_m_s: {said}", message
    # a conveyor file read on its own (beltstudy static) and one a study names by path: the
    # same words, after the file's name (they said 'speed_m_s: Input should be a valid
    # number (got '4.5')', naming no file)
    conv = tmp_path / "conveyors" / "c.yaml"
    conv.parent.mkdir()
    conv.write_text(yaml.safe_dump(make_conveyor(speed_m_s="4.5")), encoding="utf-8")
    with pytest.raises(InputError) as err:
        load_conveyor(conv)
    assert str(err.value) == f"{conv}: speed_m_s: {said}"
    with pytest.raises(Invalid) as err:
        resolve_study(make_study(conveyor="conveyors/c.yaml"), studies_dir=tmp_path)
    assert err.value.message == f"conveyor: conveyors/c.yaml: speed_m_s: {said}"


@pytest.mark.parametrize(("field", "value", "said", "fix"), [
    ("speed_m_s", "3", '"3" is not of type "number": write 3 without quotes', ""),
    ("takeup", [1, 2], '[1,2] is not of type "object"', ": write a mapping `{key: value, ...}`"),
    ("drives", {"a": 1}, '{"a":1} is not of type "array"',
     ": write a list: one `- {...}` item per entry"),
    ("holdback", "true", '"true" is not of type "boolean": write true without quotes', ""),
    ("holdback", "maybe", '"maybe" is not of type "boolean"', ""),
    ("name", 5, '5 is not of type "string": write "5" in quotes', ""),
    ("speed_m_s", "4.5 m/s", '"4.5 m/s" is not of type "number"',
     ": write the number alone, in m/s: 4.5"),
])
def test_a_wrong_type_reads_alike_inline_in_a_file_and_on_the_command_line(
        tmp_path, capsys, make_study, make_conveyor, field, value, said, fix):
    """One fault, one wording: an inline conveyor (study file, JSON and YAML bodies), a
    conveyor file a study names, and ``beltstudy static FILE`` each name the field as
    written, the value given and what to write. The engine's own loader says the field and
    the type; the service's doors add the fix it lacks (a wrong container, a number with its
    unit: :func:`beltstudy.service.door.messages.type_fix`)."""
    from beltstudy.service.cli import main

    conv_data = make_conveyor(**{field: value})
    for message in _three_ways(tmp_path, make_study(conveyor=conv_data)):
        assert message == f"conveyor.{field}: {said}{fix}", message
    conv = tmp_path / "c.yaml"
    conv.write_text(yaml.safe_dump(conv_data), encoding="utf-8")
    study = tmp_path / "uses-file.yaml"
    study.write_text(yaml.safe_dump(make_study(conveyor="c.yaml")), encoding="utf-8")
    with pytest.raises(Invalid) as err:
        load_study_file(study)
    assert err.value.message == f"conveyor: c.yaml: {field}: {said}{fix}"
    with pytest.raises(InputError) as err:
        load_conveyor(conv)
    assert str(err.value) == f"{conv}: {field}: {said}"
    assert main(["static", str(conv)]) == 2
    assert capsys.readouterr().err == f"error: {conv}: {field}: {said}{fix}\n"


def test_a_boolean_is_no_number_in_any_axis_named_before_duplicates(tmp_path, make_study):
    # [true, 1.0] was read as [1.0, 1.0] and refused as "value 1.0 appears twice"
    for message in _three_ways(tmp_path, make_study(grid={"temperature_c": [True, 1.0]})):
        assert message == 'grid.temperature_c.0: true is not of type "number"'
    for message in _three_ways(tmp_path, make_study(grid={"takeup.mass_kg": [1000, False]})):
        assert message.startswith('grid.takeup.mass_kg.1: false is not of type "number"')
    with pytest.raises(Invalid, match=r'^scenario.run_s: true is not of type "number"'):
        resolve_study(make_study(scenario={"run_s": True}))


def test_integers_by_value_whatever_their_notation(make_study):
    # 0x10, 0o20, 0b10000 and (as YAML 1.2 reads it, not 1.1's octal) 016 are the integer 16
    text = yaml.safe_dump(make_study(grid={"temperature_c": ["A", 16]})).replace("- A", "- 0x10")
    assert loads(text, yaml_text=True)["grid"]["temperature_c"] == [16, 16]
    with pytest.raises(Invalid, match=r"^grid.temperature_c: value 16 appears twice"):
        resolve_study(parse_body(text.encode(), "application/yaml"))
    for literal in ("0x10", "016", "0o20", "0b10000", "16.0", "1_6"):
        body = yaml.safe_dump(make_study()).replace("elements: 12", f"elements: {literal}")
        assert "elements: " + literal in body
        study = resolve_study(parse_body(body.encode(), "application/yaml"))
        assert study.scenario["elements"] == 16


@pytest.mark.parametrize(("literal", "digits"), [
    ("0x" + "f" * 300, 362),       # 16**300 - 1 has 362 decimal digits
    ("0x1" + "0" * 256, 309),      # 16**256 = 2**1024: 309 digits (1.8e308)... the bound
    ("-0b1" + "0" * 1100, 332),    # 2**1100: 332 digits
    ("0o" + "7" * 400, 362),       # octal: 8**400 - 1 has 362 digits
    ("0" + "7" * 400, 400),        # a leading zero is decimal (YAML 1.2): 400 digits
    ("0x" + "f" * 100_000, 120_412),
])
def test_hex_octal_and_binary_integers_count_digits_by_value(make_study, literal, digits):
    body = yaml.safe_dump(make_study(grid={"temperature_c": ["X"]})).replace("- X",
                                                                             f"- {literal}")
    if digits <= 309:
        data = loads(body, yaml_text=True)
        assert len(str(data["grid"]["temperature_c"][0])) == digits
        return
    with pytest.raises(Invalid) as err:
        loads(body, yaml_text=True)
    assert err.value.message.startswith("grid.temperature_c.0: a number with ")
    assert "out of range (at most 309 digits)" in err.value.message
    shown = int(err.value.message.split("a number with ")[1].split()[0])
    assert abs(shown - digits) <= 1  # by value; a long text is sized from its length alone


def test_yaml_exponent_without_sign_is_a_number():
    # YAML 1.1 reads 6.0e4 as text; with numbers held to their type it would be refused
    assert loads("a: 6.0e4\nb: 1e5\nc: -2E3\nd: 1e", yaml_text=True) == {
        "a": 60000.0, "b": 100000.0, "c": -2000.0, "d": "1e"}
    conv = load_conveyor(ROOT / "studies" / "conveyors" / "valley-booster.yaml")
    assert conv.accessories.scrapers[0].pressure_n_m2 == 6.0e4


def test_yaml_exponent_with_sign_and_no_point_is_a_number():
    # YAML 1.2 floats PyYAML's 1.1 resolver reads as text (it wants a point before a signed
    # exponent): 1e-2, 35e-2, 2e+4; the conveyor, scenario and study readers all take them
    assert loads("a: 1e-2\nb: 35e-2\nc: 2e+4\nd: -1E-3\ne: 1e-\nf: e-3", yaml_text=True) == {
        "a": 0.01, "b": 0.35, "c": 20000.0, "d": -0.001, "e": "1e-", "f": "e-3"}


@pytest.mark.parametrize(("over", "message"), [
    ({"takeup": {"mass_kg": 1e300}},
     "takeup.mass_kg: Input should be less than or equal to 2000000"),
    ({"takeup": {"type": "fixed", "pretension_kn": 1e9}},
     "takeup.pretension_kn: Input should be less than or equal to 17280"),
    ({"material": {"capacity_t_h": 1e12, "density_t_m3": 1.0}},
     "material.capacity_t_h: Input should be less than or equal to 200000"),
    ({"drives": [{"pulley_diameter_m": 60.0}]},
     "drives.0.pulley_diameter_m: Input should be less than or equal to 5"),
    ({"drives": [{"rated_power_kw": 1e9}]},
     "drives.0.rated_power_kw: Input should be less than or equal to 30000"),
    ({"drives": [{"inertia_kg_m2": 1e20}]},
     "drives.0.inertia_kg_m2: Input should be less than or equal to 10000000"),
    ({"brakes": [{"force_kn": 1e6}]},
     "brakes.0.force_kn: Input should be less than or equal to 17280"),
    ({"speed_m_s": 300.0}, "speed_m_s: Input should be less than or equal to 30"),
    ({"profile": [{"length_m": 90_000.0, "lift_m": 0}] * 3},
     "profile: 270000 m of route in all; at most 200000 m"),
])
def test_absurd_magnitudes_name_their_bound(make_study, make_conveyor, over, message):
    with pytest.raises(Invalid) as err:
        resolve_study(make_study(conveyor=make_conveyor(**over)))
    assert message in err.value.message, err.value.message


def test_a_capacity_is_held_to_the_fill_it_implies(make_conveyor):
    base = make_conveyor()
    fill = fill_pct(parse_conveyor(base))  # fill is proportional to the capacity
    ok = base["material"]["capacity_t_h"] * 0.99 * FILL_MAX_PCT / fill
    assert fill_pct(parse_conveyor(make_conveyor(material={"capacity_t_h": ok}))) < 300
    over = base["material"]["capacity_t_h"] * 1.01 * FILL_MAX_PCT / fill
    with pytest.raises(InputError) as err:
        parse_conveyor(make_conveyor(material={"capacity_t_h": over}))
    assert str(err.value).startswith(f"material.capacity_t_h: {over:g} t/h fills the belt's "
                                     "cross-section to 303 % at 2 m/s; at most 300 %")


@pytest.mark.parametrize("bad", ["\x00", "\u202e", "\u2066", "\x1b[31m", "\u200b", "\u2028"])
def test_control_and_bidi_characters_are_refused_in_names(tmp_path, make_study,
                                                          make_conveyor, bad):
    for message in _three_ways(tmp_path, make_study(conveyor=make_conveyor(
            name=f"belt{bad}1"))):
        assert message.startswith(f"conveyor.name: contains U+{ord(bad[0]):04X}"), message
    with pytest.raises(Invalid, match=rf"^description: contains U\+{ord(bad[0]):04X}"):
        resolve_study(make_study(description=f"about{bad}"))
    # lines and tabs stay allowed in a description
    assert resolve_study(make_study(description="two\nlines\tand a tab")).total == 6


@pytest.mark.parametrize(("loads", "message"), [
    ([0.5, "full", 1.0], "grid.load: 'full' and 1.0 are the same load ('full' is 1 x the "
                         "design load); give one"),
    ([0, "empty"], "grid.load: 0 and 'empty' are the same load ('empty' is 0 x the design "
                   "load); give one"),
    # one fraction per carry section, all equal, is that fraction everywhere
    (["full", [1, 1.0]], "grid.load: 'full' and [1, 1.0] are the same load ([1, 1.0] is 1 x "
                         "the design load on every section); give one"),
    ([[0.5, 0.5], 0.5], "grid.load: [0.5, 0.5] and 0.5 are the same load ([0.5, 0.5] is 0.5 x "
                        "the design load on every section); give one"),
])
def test_a_load_by_name_and_its_fraction_are_one_value(make_study, loads, message):
    """full is 1 and empty 0 of the design load everywhere (engine.conveyor.section_loads):
    both in one axis would be two run ids for one run."""
    with pytest.raises(Invalid) as err:
        resolve_study(make_study(grid={"load": loads}))
    assert str(err.value) == message
    assert len(resolve_study(make_study(grid={"load": ["full", "empty", "inclines", 0.5]}))
               .runs) == 4
    # a list whose fractions differ is a load of its own
    assert _load_fraction([1, 0.5]) == [1, 0.5]


def test_yaml_base_60_is_text_as_yaml_1_2_reads_it(tmp_path):
    """YAML 1.1 (PyYAML) reads 1:30 as 90 and 1:30.5 as 90.5 (base 60): lift_m: 1:30.5 was a
    90.5 m lift, speed_m_s: 0:30 a 30 m/s belt, both silently. YAML 1.2 reads them as text,
    so a number field refuses them by name and a name may hold a time of day."""
    assert loads("a: 1:30\nb: -1:30.5\nc: 12:30\nd: 90\ne: 1.5", yaml_text=True) == {
        "a": "1:30", "b": "-1:30.5", "c": "12:30", "d": 90, "e": 1.5}
    from beltstudy.engine.conveyor import load_mapping

    path = tmp_path / "c.yaml"
    path.write_text("a: 1:30\nb: 1:30.5\nc: 016\n")
    assert load_mapping(path) == {"a": "1:30", "b": "1:30.5", "c": 16}
    conv = yaml.safe_load((ROOT / "studies" / "conveyors" / "fabric-1km.yaml").read_text())
    conv["profile"][0]["lift_m"] = "1:30.5"
    with pytest.raises(InputError, match=r'^profile\.0\.lift_m: "1:30\.5" is not of type '
                                         r'"number": write the number itself'):
        parse_conveyor(conv)


def test_a_zero_and_underscores_reads_as_yaml_1_2_without_a_crash(tmp_path):
    """``0_`` matched the YAML 1.2 integer pattern but was read as octal with no digits
    (``"" in "oO"`` holds): ValueError out of every YAML reader, a traceback from
    ``beltstudy static`` and an unhandled error in a body. YAML 1.1 read it as 0. ``0o_`` has
    no octal digit: text, refused by its field like any text."""
    from beltstudy.engine.conveyor import load_mapping

    text = "a: 0_\nb: -0_0\nc: 0o_\nd: 0o_17\n"
    want = {"a": 0, "b": 0, "c": "0o_", "d": 15}
    assert loads(text, yaml_text=True) == want
    path = tmp_path / "c.yaml"
    path.write_text(text)
    assert load_mapping(path) == want


def test_yaml_1_1_words_and_base_60_name_the_fix_on_every_path(tmp_path, make_study,
                                                             make_conveyor):
    """The conveyor file said 'write true or false' for holdback: yes; a study file, a JSON
    or YAML body and a calibration body said only '"yes" is not of type "boolean"', and a
    base-60 1:30 (YAML 1.1's 90) was refused on every path without saying what to write."""
    from beltstudy.service.calibration import read_calibration

    bool_fix = "write true or false (YAML 1.2 reads yes, no, on and off as text)"
    for message in _three_ways(tmp_path, make_study(dynamics="yes")):
        assert message == f'dynamics: "yes" is not of type "boolean": {bool_fix}', message
    for message in _three_ways(tmp_path, make_study(conveyor=make_conveyor(holdback="off"))):
        assert message == f'conveyor.holdback: "off" is not of type "boolean": {bool_fix}'
    for message in _three_ways(tmp_path, make_study(scenario={"run_s": "1:30"})):
        assert message == ('scenario.run_s: "1:30" is not of type "number": write the number '
                           "itself (YAML 1.2 reads 1:30 as text, not as YAML 1.1's base 60, 90)")
    body = {"conveyor": make_conveyor(), "model": "din", "fit": ["f"],
            "measured": [{"load": "full", "temperature_c": "-1:30.5", "power_kw": 100}]}
    with pytest.raises(Invalid) as err:
        read_calibration(body)
    assert err.value.message == (
        'measured.0.temperature_c: "-1:30.5" is not of type "number": write the number itself '
        "(YAML 1.2 reads -1:30.5 as text, not as YAML 1.1's base 60, -90.5)")
    conv = tmp_path / "c.yaml"
    conv.write_text(yaml.safe_dump(make_conveyor(speed_m_s="0:4")), encoding="utf-8")
    with pytest.raises(InputError) as err:
        load_conveyor(conv)
    assert str(err.value) == (f'{conv}: speed_m_s: "0:4" is not of type "number": write '
                              "the number itself (YAML 1.2 reads 0:4 as text, not as YAML "
                              "1.1's base 60, 4)")
