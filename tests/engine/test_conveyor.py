"""The conveyor and scenario contract: validation errors name the field and the fix; the
scenario's load patterns per profile section."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml

from beltstudy.engine.conveyor import (
    InputError,
    Scenario,
    load_conveyor,
    load_mapping,
    parse_conveyor,
    parse_scenario,
    section_loads,
)
from tests.conftest import CONVEYORS, hand_conveyor_dict
from tests.engine.conftest import hand_conv, hand_drive, two_sections


@pytest.mark.parametrize("path", sorted(CONVEYORS.glob("*.yaml")), ids=lambda p: p.name)
def test_examples_load(path):
    conv = load_conveyor(path)
    assert conv.length_m > 0


def _err(d) -> str:
    with pytest.raises(InputError) as ei:
        parse_conveyor(d)
    msg = str(ei.value)
    assert "\n" not in msg
    return msg


def test_negative_length():
    msg = _err(hand_conveyor_dict(profile=[{"length_m": -5, "lift_m": 0}]))
    assert "profile.0.length_m" in msg and "greater than 0" in msg


def test_zero_speed():
    msg = _err(hand_conveyor_dict(speed_m_s=0))
    assert "speed_m_s" in msg


def test_unknown_belt_type_lists_valid():
    d = hand_conveyor_dict()
    d["belt"] = {"type": "ST2100", "width_m": 1.2}
    msg = _err(d)
    assert "belt.type" in msg and "ST2100" in msg and "ST2000" in msg


@pytest.mark.parametrize("given,meant", [
    ("ST-1600", "'ST1600'"), ("St 1600", "'ST1600'"), ("EP 630/4", "'EP630/4'"),
    ("EP630-4", "'EP630/4'"),
    ("EP 630/4 5+2", "'EP630/4' with top_cover_mm: 5 and bottom_cover_mm: 2"),
])
def test_a_catalogue_belt_spelled_as_handbooks_do_is_named(given, meant):
    """Belt makers and handbooks write ST 1600, St-1600, EP 630/4 5+2 (carcass, then top +
    bottom covers in mm): the message names the catalogue's spelling and the covers' keys."""
    d = hand_conveyor_dict()
    d["belt"] = {"type": given, "width_m": 1.0}
    assert f"did you mean {meant}?" in _err(d)


@pytest.mark.parametrize("given", ["EP500/3", "ST1800", "EP500/3 5+2"])
def test_a_belt_not_in_the_catalogue_is_not_swapped_for_another_rating(given):
    """EP500/3 was answered "did you mean 'EP400/3'?" and ST1800 "did you mean 'ST1600'?": a
    belt 20 % and 11 % weaker, one edit away from a user who takes the hint. A belt the
    catalogue lacks is now given by its own data, and no weaker belt is suggested."""
    d = hand_conveyor_dict()
    d["belt"] = {"type": given, "width_m": 1.0}
    msg = _err(d)
    assert "belt.type" in msg and "did you mean" not in msg
    assert "leave out type" in msg
    for key in ("rating_kn_m", "modulus_kn_m", "carcass_mass_kg_m2", "mass_kg_m",
                "top_cover_mm", "bottom_cover_mm"):
        assert key in msg
    d["belt"] = {"width_m": 1.0, "rating_kn_m": 500, "modulus_kn_m": 3500, "mass_kg_m": 12.5,
                 "top_cover_mm": 5, "bottom_cover_mm": 2}  # the fix the message asks for
    assert parse_conveyor(d).belt.rating_kn_m == 500


@pytest.mark.parametrize("word,needle", [
    ("counterweight", "type: gravity"), ("Counterweight", "type: gravity"),
    ("winch", "type: fixed (give pretension_kn)"), ("screw", "type: fixed"),
])
def test_a_take_up_named_as_handbooks_do_names_its_type(word, needle):
    """'counterweight' and 'screw' take-ups are the contract's gravity and fixed."""
    d = hand_conveyor_dict()
    d["takeup"]["type"] = word
    msg = _err(d)
    assert "takeup.type" in msg and needle in msg


def test_misspelt_key_suggests_nearest():
    d = hand_conveyor_dict()
    d["idlers"]["carry"]["spacng_m"] = 1.2
    msg = _err(d)
    assert "idlers.carry.spacng_m" in msg and "did you mean 'spacing_m'" in msg
    d = hand_conveyor_dict(speeed_m_s=3)
    assert "did you mean 'speed_m_s'" in _err(d)


def test_a_wrap_or_trough_angle_written_in_radians_is_refused_with_its_degrees():
    """A handbook's wrap of 3.67 rad (210 deg) typed into wrap_deg was taken as a 3.67 deg wrap:
    e^(0.35 x 0.064) = 1.02, so the auto take-up hung about 350 t on a 0.9 m belt with only a
    safety-factor warning. Below 2 pi deg (a wrap that grips nothing) and below pi / 3 deg for
    a trough (a flat set is 0) the value is refused, naming the field and its degrees; the
    shallowest wraps and troughs in use are taken."""
    d = hand_conveyor_dict()
    d["drives"][0]["wrap_deg"] = 3.67
    msg = _err(d)
    assert "drives.0.wrap_deg" in msg and "radians" in msg and "210.3 deg" in msg
    d = hand_conveyor_dict()
    d["idlers"]["carry"]["trough_deg"] = 0.61
    msg = _err(d)
    assert "idlers.carry.trough_deg" in msg and "radians" in msg and "34.95 deg" in msg
    # a value that as radians is no real angle either is not offered as one (1e-300 was told
    # 'reads as radians, 5.73e-299 deg: write that'; 0.05 rad is 2.9 deg, below 2 pi deg too)
    for tiny in (1e-300, 0.05):
        d = hand_conveyor_dict()
        d["drives"][0]["wrap_deg"] = tiny
        msg = _err(d)
        assert "drives.0.wrap_deg" in msg and "no real wrap angle" in msg, msg
        assert "reads as radians" not in msg and "give the wrap angle in degrees" in msg, msg
    d = hand_conveyor_dict()
    d["drives"][0]["wrap_deg"] = 60.0
    d["idlers"]["carry"]["trough_deg"] = 0.0
    d["idlers"]["return"].update(rolls=2, trough_deg=10.0)  # a V-return (one roll is flat)
    parse_conveyor(d)


@pytest.mark.parametrize("where,key,value,needles", [
    ("material", "capacity_tph", 720, ["'capacity_t_h'", "metric t/h", "short tons/h x 0.90718"]),
    ("drives.0", "mu", 0.35, ["is 'friction'"]),
    ("profile.0", "angle_deg", 3, ["lift_m = length_m x sin(angle)"]),
    ("material", "density_kg_m3", 1000, ["'density_t_m3'", "kg/m3 / 1000"]),
    ("profile.0", "lift_ft", 164, ["'lift_m'", "ft x 0.3048"]),
    ("drives.0", "lagging", "ceramic", ["'friction'", "lagging"]),
    ("drives.0", "wrap_rad", 3.67, ["'wrap_deg'", "rad x 57.296"]),
])
def test_a_key_in_a_handbook_unit_names_its_si_twin_and_the_conversion(where, key, value,
                                                                        needles):
    """Keys a user copies from a handbook (t/h as tph, kg/m3, ft, rad, a pulley's lagging)
    name the contract's key and how to convert; 'lagging' was answered "did you mean
    'coupling'?"."""
    d = hand_conveyor_dict()
    node = d
    for part in where.split("."):
        node = node[int(part)] if part.isdigit() else node[part]
    node[key] = value
    msg = _err(d)
    assert f"{where}.{key}: unknown key" in msg
    for needle in needles:
        assert needle in msg


@pytest.mark.parametrize("path,value,needle", [
    (("material", "density_t_m3"), 1600, "1.6 t/m3 if 1600 is kg/m3"),
    (("idlers", "carry", "spacing_m"), 1200, "1.2 m if 1200 is mm"),
    (("drives", 0, "pulley_diameter_m"), 800, "0.8 m if 800 is mm"),
    (("drives", 0, "friction"), 35, "0.35 if 35 is %"),
    (("drives", 0, "efficiency"), 95, "a fraction, 0.95 if 95 is %"),
    (("drives", 0, "rated_power_kw"), 1_250_000, "in kilowatts, 1250 kW if 1250000 is W"),
    (("accessories", "head_kn"), 20_000, "in kilonewtons, 20 kN if 20000 is N"),
    (("speed_m_s",), 270, "in metres per second, 4.5 m/s if 270 is m/min"),
])
def test_a_value_out_of_range_in_another_unit_says_which(path, value, needle):
    """A density in kg/m3, a pitch or diameter in mm, a friction or an efficiency in % fail
    their bound and the message says what the value is in the field's unit."""
    d = hand_conveyor_dict()
    node = d
    for part in path[:-1]:
        node = node[part]
    node[path[-1]] = value
    msg = _err(d)
    assert ".".join(str(p) for p in path) in msg and needle in msg


@pytest.mark.parametrize("kelvin,needle", [(293.15, "20 C if 293.15 is K"),
                                           (253, "-20.15 C if 253 is K")])
def test_a_temperature_in_kelvin_says_its_degrees_celsius(kelvin, needle):
    """An ambient of 293.15 (20 C in kelvin) fails the 80 C bound; the message gives the
    degrees Celsius it means (T - 273.15). 85 C, past the bound but no kelvin temperature of
    the range, gets no hint."""
    with pytest.raises(InputError) as exc:
        parse_scenario({"temperature_c": kelvin})
    assert "temperature_c" in str(exc.value) and needle in str(exc.value)
    with pytest.raises(InputError) as exc:
        parse_scenario({"temperature_c": 85})
    assert " is K" not in str(exc.value)


def test_shares_must_sum_to_one():
    d = hand_conveyor_dict()
    d["drives"][0]["share"] = 0.6
    assert "shares sum to 0.6" in _err(d)


def test_a_belt_without_mass_is_refused():
    d = hand_conveyor_dict()
    d["belt"] = {"width_m": 1.0, "rating_kn_m": 500, "modulus_kn_m": 6000,
                 "carcass_mass_kg_m2": 0.0, "top_cover_mm": 0, "bottom_cover_mm": 0}
    msg = _err(d)
    assert "belt.carcass_mass_kg_m2" in msg and "greater than or equal to 0.1" in msg


def test_bounds_beyond_practice_name_the_field():
    d = hand_conveyor_dict()
    d["idlers"]["carry"]["spacing_m"] = 9e15
    assert "idlers.carry.spacing_m" in _err(d)
    d = hand_conveyor_dict()
    d["belt"]["width_m"] = 5e-324
    assert "belt.width_m" in _err(d)


def test_lift_longer_than_length():
    assert "lift_m" in _err(hand_conveyor_dict(profile=[{"length_m": 10, "lift_m": 12}]))


def test_fixed_takeup_mass_is_an_error():
    d = hand_conveyor_dict(takeup={"type": "fixed", "mass_kg": 1000})
    assert "pretension_kn" in _err(d)


@pytest.mark.parametrize("value", [float("nan"), float("inf")])
def test_a_non_finite_number_is_named_as_such_not_as_a_bound(value):
    """YAML's .nan and .inf pass no bound: the error says the number must be finite."""
    d = hand_conveyor_dict(profile=[{"length_m": 500, "lift_m": 0, "curve_radius_m": value},
                                    {"length_m": 500, "lift_m": 50}])
    msg = _err(d)
    assert "profile.0.curve_radius_m: Input should be a finite number" in msg
    assert "less than or equal" not in msg


def test_custom_belt_needs_fields():
    d = hand_conveyor_dict()
    del d["belt"]["modulus_kn_m"]
    assert "modulus_kn_m" in _err(d)


def test_scenario_errors():
    with pytest.raises(InputError, match="stop.mode"):
        parse_scenario({"stop": {"mode": "slam", "time_s": 3}})
    with pytest.raises(InputError, match="run_s"):
        parse_scenario({"run_s": -1})
    with pytest.raises(InputError, match="did you mean 'temperature_c'"):
        parse_scenario({"temperatur_c": 3})
    assert parse_scenario({"scenario": {"load": 0.5}}).load_fraction == 0.5
    assert Scenario(load="empty").load_fraction == 0.0


def test_section_loads_of_each_pattern():
    conv = two_sections()
    assert section_loads("full", conv) == (1.0, 1.0)
    assert section_loads("empty", conv) == (0.0, 0.0)
    assert section_loads("inclines", conv) == (1.0, 0.0)
    assert section_loads("declines", conv) == (0.0, 1.0)
    assert section_loads([0.5, 1.2], conv) == (0.5, 1.2)
    assert section_loads(1.2, conv) == (1.2, 1.2)
    with pytest.raises(InputError, match=r"scenario.load: 3 fractions for 2 profile sections"):
        section_loads([1, 1, 1], conv)
    with pytest.raises(InputError, match=r"less than or equal to 1.3"):
        parse_scenario({"load": 1.4})
    assert parse_scenario({"load": "inclines"}).load == "inclines"
    assert parse_scenario({"load": [0, 1]}).load == [0.0, 1.0]


@pytest.mark.parametrize("over, field", [
    ({"brakes": [{"drive": 3}]}, "brakes.0.drive"),
    ({"drives": [hand_drive(control="dol", motor_curve=[[0.0, 1.5], [0.5, 1.2], [0.4, 1.0],
                                                        [1.0, 0.0]])]}, "increase"),
    ({"drives": [hand_drive(control="dol", motor_curve=[[0.0, 1.5], [0.9, 2.0], [1.0, 0.4]])]},
     "zero-torque point"),
    ({"drives": [hand_drive(coupling="fluid")]}, "needs control: dol"),
    # a vfd drive's curve is taken (SPEC 6.1) but still checked
    ({"drives": [hand_drive(motor_curve=[[0.0, 0.3], [0.5, 0.4]])]}, "zero-torque point"),
    ({"drives": [hand_drive(control="dol",
                            motor_curve=[[i / 20, 2.0 - i / 10] for i in range(21)])]},
     "motor_curve: List should have at most 16 items"),
    ({"brakes": [{"position": "head", "force_curve": [[0.1 * i, 0.05 * i] for i in range(17)]}]},
     "force_curve: List should have at most 16 items"),
    ({"drives": [hand_drive(share=0.6), hand_drive(share=0.6, position="tail")]},
     "drives.0 (head) 0.6 + drives.1 (tail) 0.6"),
    ({"drives": [hand_drive(friction=0.35, friction_kinetic=0.9)]},
     "friction_kinetic 0.9 is above friction 0.35"),
])
def test_bad_drive_and_brake_input_names_the_field(over, field):
    with pytest.raises(InputError) as exc:
        hand_conv(**over)
    assert field in str(exc.value)


def test_speed_loop_bandwidth_is_checked_where_it_is_set():
    """``drives[i].speed_loop_rad_s``: accepted on the vfd master, refused with a reason on a
    dol drive, outside 0.1-50 rad/s, and on a drive that follows the master's torque."""
    assert hand_conv(drives=[hand_drive(speed_loop_rad_s=3.0)]).drives[0].speed_loop_rad_s == 3.0
    with pytest.raises(InputError, match="needs control: vfd"):
        hand_conv(drives=[hand_drive(control="dol", speed_loop_rad_s=3.0)])
    with pytest.raises(InputError, match=r"drives.0.speed_loop_rad_s: .*outside 0.1 to 50 rad/s"):
        hand_conv(drives=[hand_drive(speed_loop_rad_s=0.01)])
    with pytest.raises(InputError, match=r"drives.1.speed_loop_rad_s: drive 2 follows"):
        hand_conv(drives=[hand_drive(share=0.6), hand_drive(share=0.4, speed_loop_rad_s=3.0)])


def test_rated_power_auto_is_the_same_as_leaving_it_out():
    """``rated_power_kw: auto`` reads as the take-up mass's and brake force's ``auto`` do: the
    design basis sizes it (the steady motor power x 1.25), exactly as when the key is left out; a word
    other than auto is refused naming the field."""
    from beltstudy.engine.conveyor import DRIVE_EFFICIENCY
    from beltstudy.engine.statics import solve_steady

    auto = hand_conv(drives=[hand_drive(rated_power_kw="auto")])
    assert auto.drives[0].rated_power_kw is None
    left_out = hand_conv(drives=[hand_drive()])
    assert left_out.drives[0].rated_power_kw is None
    given = hand_conv(drives=[hand_drive(rated_power_kw=400.0)])
    assert given.drives[0].rated_power_kw == 400.0
    # the utilisation is the motor power needed (pulley power / efficiency) over the rating
    # used: 1 / 1.25 for the auto size (sized on that motor power)
    u_auto = solve_steady(auto, model="din").summary["drive1_utilisation"]
    u_left = solve_steady(left_out, model="din").summary["drive1_utilisation"]
    assert u_auto == u_left == pytest.approx(1.0 / 1.25, rel=1e-12)
    assert DRIVE_EFFICIENCY == 0.95  # the rating is 1.25 x Te v / 0.95
    with pytest.raises(InputError, match=r"drives.0.rated_power_kw"):
        hand_conv(drives=[hand_drive(rated_power_kw="big")])


# ------------------------------------------------------------------ file encodings, keys twice
def _small_yaml() -> str:
    return (CONVEYORS / "slope-5pct.yaml").read_text(encoding="utf-8")


def test_a_file_not_in_utf8_is_one_line_naming_the_byte(tmp_path):
    path = tmp_path / "latin1.yaml"
    path.write_bytes("name: x\n# Förderband 30° Neigung\n".encode("latin-1"))
    with pytest.raises(InputError) as ei:
        load_mapping(path)
    assert str(ei.value) == (f"{path}: not UTF-8 text (byte 0xf6 at line 2, column 4): "
                             "save it as UTF-8")


@pytest.mark.parametrize("encoding", ["utf-8-sig", "utf-16"])
def test_utf8_with_bom_and_utf16_with_bom_read_as_utf8(tmp_path, encoding):
    """Excel's "CSV UTF-8" and Notepad's "Unicode" (UTF-16 with its byte order mark)."""
    text = "# Förderband 30° Neigung\n" + _small_yaml()
    path = tmp_path / "conv.yaml"
    path.write_bytes(text.encode(encoding))
    assert load_mapping(path) == yaml.safe_load(_small_yaml())
    assert load_conveyor(path).name == "slope-5pct"


@pytest.mark.parametrize("encoding, words", [
    ("utf-16-le", "UTF-16 or UTF-32 without a byte order mark"),
    ("utf-32-be", "UTF-16 or UTF-32 without a byte order mark"),
    ("utf-32", "UTF-32 text (it starts with a UTF-32 byte order mark)"),
])
def test_wide_text_without_its_mark_or_utf32_names_the_encoding(tmp_path, encoding, words):
    """UTF-16 or UTF-32 without a byte order mark decodes as UTF-8 with NUL bytes between
    its letters (the key 'n\\0a\\0m\\0e\\0' was then unknown); UTF-32's mark begins with
    UTF-16's."""
    path = tmp_path / "conv.yaml"
    path.write_bytes(_small_yaml().encode(encoding))
    with pytest.raises(InputError) as ei:
        load_mapping(path)
    assert words in str(ei.value) and str(ei.value).endswith("save it as UTF-8")


def test_a_key_given_twice_is_refused_with_both_lines(tmp_path):
    path = tmp_path / "twice.yaml"
    path.write_text("name: x\nbelt:\n  width_m: 1.2\nspeed_m_s: 2.5\nspeed_m_s: 25\n")
    with pytest.raises(InputError) as ei:
        load_mapping(path)
    assert str(ei.value) == (f"{path}: line 5: key 'speed_m_s' given twice (first at line 4); "
                             "give each key once")
    path.write_text("belt: {width_m: 1.2, type: ST2000, width_m: 1.4}\n")
    with pytest.raises(InputError, match=r"line 1: key 'width_m' given twice \(first at line 1"):
        load_mapping(path)
    path.write_text("base: &b {x: 1, y: 2}\nd:\n  <<: *b\n  x: 3\n")  # a merge may be overridden
    assert load_mapping(path)["d"] == {"x": 3, "y": 2}
    js = tmp_path / "twice.json"
    js.write_text('{"name": "x", "belt": {"width_m": 1.2, "width_m": 1.4}}')
    with pytest.raises(InputError, match=r"twice.json: key 'width_m' given twice"):
        load_mapping(js)


def _with(path: str, value) -> dict:
    """The hand conveyor with one field set (a dotted path, list indices as numbers)."""
    d = hand_conveyor_dict()
    node = d
    keys = path.split(".")
    for k in keys[:-1]:
        node = node[int(k)] if isinstance(node, list) else node.setdefault(k, {})
    node[int(keys[-1]) if isinstance(node, list) else keys[-1]] = value
    return d


def test_integers_and_booleans_are_read_as_yaml_1_2_reads_them(tmp_path):
    # YAML 1.1 (PyYAML) reads 0210 as octal 136 and 0289 as text: a wrap angle written
    # with a leading zero became 136 degrees. YAML 1.2's core schema reads both as decimal,
    # and its booleans are true and false only (YAML 1.1 took holdback: yes as true and
    # position: on as a boolean, refused as "got True").
    path = tmp_path / "zeros.yaml"
    path.write_text("a: 0210\nb: -0289\nc: 0o20\nd: 0x10\ne: 0\nf: 1_6\ng: 007.5\n")
    assert load_mapping(path) == {"a": 210, "b": -289, "c": 16, "d": 16, "e": 0, "f": 16,
                                  "g": 7.5}
    path.write_text("a: yes\nb: [on, off, No]\nc: true\nd: FALSE\n")
    assert load_mapping(path) == {"a": "yes", "b": ["on", "off", "No"], "c": True, "d": False}
    text = (CONVEYORS / "slope-5pct.yaml").read_text()
    assert "holdback: true " in text
    path.write_text(text.replace("holdback: true ", "holdback: yes  "))
    with pytest.raises(InputError) as err:
        load_conveyor(path)
    assert str(err.value) == (f'{path}: holdback: "yes" is not of type "boolean": write true '
                              "or false (YAML 1.2 reads yes, no, on and off as text)")
    assert "wrap_deg: 210," in text
    path.write_text(text.replace("wrap_deg: 210,", "wrap_deg: 0210,"))
    assert load_conveyor(path).drives[0].wrap_deg == 210


@pytest.mark.parametrize("path, value, needle", [
    # a motor curve's points are finite, speeds within 1.2 and torques within 10 x rated
    ("drives.0.motor_curve", [[0.0, float("nan")], [0.5, 2.0], [1.0, 0.0]],
     "drives.0: motor_curve point 0 [0, nan]"),
    ("drives.0.motor_curve", [[0.0, 1e300], [1.0, 0.0]], "motor_curve point 0 [0, 1e+300]"),
    ("drives.0.motor_curve", [[0.0, 2.0], [float("inf"), 0.0]], "motor_curve point 1 [inf, 0]"),
    ("drives.0.torque_limit", 1e6, "drives.0.torque_limit"),
    ("sag_limit_pct.carry", 90.0, "sag_limit_pct.carry"),
    ("safety_factor_min", 0.5, "safety_factor_min"),
    ("safety_factor_min", 1e9, "safety_factor_min"),
    ("brakes", [{"position": "head", "force_kn": 10.0}] * 13, "brakes"),
    # a belt stiffens under fast loading: its dynamic modulus is at least the static one
    ("belt.dynamic_modulus_kn_m", 10.0, "belt.dynamic_modulus_kn_m: 10 kN/m is below the "
                                        "static modulus 60000 kN/m"),
    # an edge distance that leaves no loaded width names itself, not the capacity
    ("material.edge_distance_m", 0.5, "material.edge_distance_m: 0.5 m on each side"),
    # one pulley is wrapped less than a full turn; DIN 22101's pulleys start at 100 mm
    ("drives.0.wrap_deg", 500.0, "drives.0.wrap_deg"),
    ("drives.0.wrap_deg", 360.0, "drives.0.wrap_deg"),
    ("drives.0.pulley_diameter_m", 0.001, "drives.0.pulley_diameter_m"),
    # CEMA's flowability classes end at a 30 deg surcharge (Table 4-1); tan(89 deg) = 57
    # would credit the belt with a heap 57 times that of 45 deg
    ("material.surcharge_deg", 89.0, "material.surcharge_deg: Input should be less than or "
                                     "equal to 30"),
    ("material.surcharge_deg", 30.5, "material.surcharge_deg"),
    # a carriage travel x stores 2 x of belt: on the 1 000 m route the loop holds 2 000 m
    ("takeup.travel_m", 1e9, "takeup.travel_m: 1e+09 m of carriage travel would store 2e+09 m "
                             "of belt in the take-up loop, more than the whole belt loop "
                             "(2000 m, twice the 1000 m route); give at most 1000 m"),
    ("takeup.travel_m", 1000.5, "give at most 1000 m"),
])
def test_values_beyond_any_conveyor_name_their_field(path, value, needle):
    assert needle in _err(_with(path, value))


def test_values_at_the_bounds_are_taken():
    for path, value in (("drives.0.torque_limit", 10.0), ("sag_limit_pct.carry", 50.0),
                        ("safety_factor_min", 1.0), ("belt.dynamic_modulus_kn_m", 60000.0),
                        ("material.edge_distance_m", 0.1), ("drives.0.wrap_deg", 359.0),
                        ("drives.0.pulley_diameter_m", 0.1),
                        ("material.surcharge_deg", 30.0), ("material.surcharge_deg", 0.0),
                        ("takeup.travel_m", 1000.0),
                        ("drives.0", hand_drive(control="dol",
                                                motor_curve=[[0.0, 10.0], [1.2, 0.0]]))):
        parse_conveyor(_with(path, value))


def test_a_folder_or_a_device_is_named_for_what_it_is(tmp_path):
    """A folder or /dev/null given as the conveyor file was 'file not found', though it is
    there: the message says what it is."""
    with pytest.raises(InputError, match=r": is a folder, not a file; give a file in it$"):
        load_conveyor(tmp_path)
    if Path("/dev/null").exists():
        with pytest.raises(InputError, match=r"^/dev/null: not a regular file"):
            load_conveyor("/dev/null")
    with pytest.raises(InputError, match=r"missing.yaml: file not found$"):
        load_conveyor(tmp_path / "missing.yaml")


def test_a_file_name_the_system_refuses_is_an_input_error(tmp_path):
    """A name over the file system's 255 bytes raises OSError in the check for the file
    itself: it is an InputError naming the file, as a file not found is."""
    name = tmp_path / ("a" * 300 + ".yaml")
    with pytest.raises(InputError, match="cannot read it: file name too long: a name of 305 bytes, at most 255"):
        load_conveyor(name)


def test_a_scenario_key_holding_no_mapping_says_so():
    """``scenario: []`` is a scenario file with no fields, not an unknown key 'scenario'."""
    with pytest.raises(InputError, match=r"^scenario: expected a mapping of its fields .*got list"):
        parse_scenario({"scenario": []})


def test_a_record_spacing_beyond_a_minute_is_refused():
    """A time series of a cycle's two ends is no time series: record_dt_s at most 60 s."""
    parse_scenario({"record_dt_s": 60.0})
    with pytest.raises(InputError, match=r"record_dt_s: Input should be less than or equal to 60"):
        parse_scenario({"record_dt_s": 1e6})


@pytest.mark.parametrize(("curve", "reach"), [([[0.0, 0.0], [5.0, 0.0]], "0"),
                                              ([[0.0, 0.5], [3.0, 0.8]], "0.8")])
def test_a_brake_force_curve_reaches_the_full_force(curve, reach):
    """force_kn is the brake's force (the auto size, the stop-time estimate, the grip check and
    brake_force_kn take it so): a curve that never reaches 1 would brake with less than all of
    them say (all zeros: not at all); it is refused naming the field. One that reaches 1 is
    taken."""
    d = hand_conveyor_dict(brakes=[{"position": "head", "force_kn": 50, "force_curve": curve}])
    msg = _err(d)
    assert msg.startswith("brakes.0: force_curve: its fractions reach " + reach + " of force_kn"), msg
    ok = hand_conveyor_dict(brakes=[{"position": "head", "force_kn": 50,
                                     "force_curve": [[0.0, 0.5], [3.0, 1.0]]}])
    assert parse_conveyor(ok).brakes[0].force_curve[-1] == (3.0, 1.0)


def _idlers_with(strand: str, **over) -> dict:
    d = hand_conveyor_dict()
    d["idlers"][strand] = {**d["idlers"][strand], **over}
    return d


@pytest.mark.parametrize(("d", "message"), [
    # the skirt boards stand on the belt: 3 m apart on a 1 m belt understates their drag
    # (ISO 5048's F = mu2 I_v^2 rho g l / (v^2 b1^2) falls as 1 / b1^2) by a factor of 9 or more
    (hand_conveyor_dict(material={"capacity_t_h": 300, "density_t_m3": 1.0, "feed": [
        {"at_m": 0, "share": 1.0, "skirt_length_m": 6, "skirt_width_m": 3.0}]}),
     "material.feed.0.skirt_width_m: 3 m between the skirt boards is not less than the belt "
     "width 1 m"),
    # one roll carries the belt flat: the capacity took it flat while the trough angle was read
    # elsewhere
    (_idlers_with("carry", rolls=1, trough_deg=35),
     "idlers.carry: trough_deg 35 with rolls: 1: a set of one roll carries the belt flat"),
    (_idlers_with("return", rolls=1, trough_deg=10),
     "idlers.return: trough_deg 10 with rolls: 1"),
    # the motor is part of inertia_kg_m2: a larger part left the pulley side at 0 (clamped)
    # and the whole above the inertia the file gives
    (hand_conveyor_dict(drives=[{"position": "head", "control": "dol", "coupling": "fluid",
                                 "inertia_kg_m2": 60, "motor_inertia_kg_m2": 100}]),
     "drives.0: motor_inertia_kg_m2 100 is above inertia_kg_m2 60"),
])
def test_contradictory_parts_of_a_conveyor_are_refused_by_field(d, message):
    msg = _err(d)
    assert msg.startswith(message), msg


def test_the_parts_within_their_whole_are_taken():
    d = hand_conveyor_dict(material={"capacity_t_h": 300, "density_t_m3": 1.0, "feed": [
        {"at_m": 0, "share": 1.0, "skirt_length_m": 6, "skirt_width_m": 0.66}]},
        drives=[{"position": "head", "control": "dol", "coupling": "fluid",
                 "inertia_kg_m2": 60, "motor_inertia_kg_m2": 40}])
    d["idlers"]["return"] = {**d["idlers"]["return"], "rolls": 2, "trough_deg": 10}
    conv = parse_conveyor(d)
    assert conv.material.feed[0].skirt_width_m == 0.66 and conv.drives[0].motor_inertia_kg_m2 == 40


def test_a_blank_conveyor_name_is_refused():
    """name is required free text: spaces alone name nothing (results, reports and the design
    table show the conveyor by it)."""
    assert _err(hand_conveyor_dict(name="   ")).startswith("name: is blank (spaces only)")
    assert parse_conveyor(hand_conveyor_dict(name=" belt 1 ")).name == " belt 1 "


def test_a_cover_written_in_metres_is_refused_with_the_millimetres_it_means():
    """top_cover_mm 0.005 and bottom_cover_mm 0.002 (5 and 2 mm in metres) were read as
    millimetres: fabric-1km's EP800/4 lost its covers, its mass fell from 15.45 to 7.41 kg/m
    (1 m x (7.4 kg/m2 carcass + 7 mm x 1.15 kg/m2/mm), against 7.41 with 0.007 mm) and it said
    ok. Each is now refused naming the field and the millimetres; 0 (a bare carcass) and the
    catalogue's thinnest 2 mm stay valid."""
    d = yaml.safe_load((CONVEYORS / "fabric-1km.yaml").read_text())
    d["belt"].update(top_cover_mm=0.005, bottom_cover_mm=0.002)
    msg = _err(d)
    assert "belt.top_cover_mm: a rubber cover is 0 (none) or at least 0.2 mm thick" in msg
    assert "in millimetres, 5 mm if 0.005 is m" in msg
    assert "belt.bottom_cover_mm" in msg and "2 mm if 0.002 is m" in msg
    d["belt"].update(top_cover_mm=5, bottom_cover_mm=0)
    assert parse_conveyor(d).belt.bottom_cover_mm == 0


def test_takeup_at_m_at_an_end_names_return_only():
    """A take-up at the tail given at_m is told the position that goes with at_m: return, the
    only strand a take-up may sit along (position: carry is refused), not 'carry or return'."""
    msg = _err(hand_conveyor_dict(
        takeup={"type": "gravity", "position": "tail", "at_m": 150, "mass_kg": "auto"}))
    assert "takeup" in msg and "goes with position return (along the return strand)" in msg
    assert "carry" not in msg
    drive = {"position": "head", "at_m": 100, "wrap_deg": 200, "friction": 0.35, "share": 1.0,
             "pulley_diameter_m": 1.0}
    assert "goes with position carry or return" in _err(hand_conveyor_dict(drives=[drive]))


def test_a_load_or_a_sampled_share_in_per_cent_gets_the_fraction():
    """A load of 80 (per cent) and an accuracy sample of 5 (per cent) named the bound only; the
    friction coefficient and efficiency already said '0.35 if 35 is %'."""
    from beltstudy.engine.conveyor import parse_scenario
    from service.cli.common import parse_load

    with pytest.raises(InputError) as ei:
        parse_scenario({"load": 80})
    assert "scenario.load" in str(ei.value) or "load" in str(ei.value)
    assert "a fraction of the design load, 0.8 if 80 is %" in str(ei.value), str(ei.value)
    with pytest.raises(InputError, match=r"--load: .*\(got 80\): 0\.8 if 80 is %"):
        parse_load("80")
    # a load in range (a surge of 1.2) and one beyond any per cent reading get no such hint
    assert parse_scenario({"load": 1.2}).load == 1.2
    with pytest.raises(InputError) as ei:
        parse_scenario({"load": 500})
    assert "if 500 is %" not in str(ei.value)


def test_a_fabric_rating_without_its_plies_is_offered_the_catalogues_type():
    """'EP630' listed the catalogue but offered nothing ('st2000' got 'did you mean
    ST2000?'); an unknown compound ran 'arctic' into 'valid:' without a separator."""
    import re

    from beltstudy.engine import catalog

    with pytest.raises(InputError, match=r"unknown belt type 'EP630': a fabric belt's type names "
                                         r"its plies too; did you mean 'EP630/4'\?"):
        catalog.belt("EP630")
    with pytest.raises(InputError) as ei:
        parse_conveyor({**hand_conveyor_dict(),
                        "belt": {**hand_conveyor_dict()["belt"], "compound": "arctic"}})
    assert re.search(r"unknown compound 'arctic'(; did you mean '[^']+'\? |; )valid: ",
                     str(ei.value)), str(ei.value)


def test_a_value_just_past_its_bound_is_not_read_as_a_per_cent():
    """A load of 1.5 (a surge past the largest, 1.3) was told "0.015 if 1.5 is %", and a
    friction of 1.08 "0.0108 if 1.08 is %": no one writes those per cents, and the conveyor's
    own check reads a load as a per cent only from 2. The per cent reading starts at 2 for a
    load and at 5 for a friction coefficient (5 % = 0.05, below DIN 22101's 0.1 for a wet
    bare pulley); the bound is still named."""
    from beltstudy.engine.conveyor import parse_scenario
    from service.cli.common import parse_load

    with pytest.raises(InputError) as ei:
        parse_scenario({"load": 1.5})
    assert "is %" not in str(ei.value) and "1.3" in str(ei.value), str(ei.value)
    with pytest.raises(InputError) as ei:
        parse_load("1.5")
    assert "is %" not in str(ei.value) and "1.3" in str(ei.value), str(ei.value)
    drive = {"position": "head", "wrap_deg": 200, "friction": 1.08, "share": 1.0,
             "pulley_diameter_m": 1.0}
    said = _err(hand_conveyor_dict(drives=[drive]))
    assert "friction" in said and "is %" not in said, said
    said = _err(hand_conveyor_dict(drives=[{**drive, "friction": 35}]))
    assert "0.35 if 35 is %" in said, said


def test_a_large_figure_in_words_has_no_exponent_below_ten_million():
    """Words printed ``:.4g`` wrote 19 740 t as "1.974e+04 t" and a fill of 80 400 % as
    "8.04e+04 %". ``gnum`` writes a figure below ten million out to its significant figures
    (and back to the same number by float), and keeps the exponent above."""
    from beltstudy.engine.wording import gnum

    assert gnum(19740.3) == "19740" and float(gnum(19740.3)) == 19740.0
    assert gnum(80412.0, 3) == "80400"
    assert gnum(1234.5) == "1234" or gnum(1234.5) == "1235"
    assert gnum(0.000123456) == f"{0.000123456:.4g}"
    assert gnum(3.97e11, 3) == "3.97e+11"
    assert gnum(-19740.3) == "-19740"
    assert gnum(float("inf")) == "inf"
