"""Inputs read beyond the catalogue's rows or in an unusual sense are said in the run's message
or refused (``beltstudy.engine.checks.input_notes``): an idler roll diameter between two
catalogue rows, a loading speed above the belt speed or against the travel, a belt width
outside DIN 22107's roll table, a trough angle outside CEMA's tables.

Hand numbers: the hand conveyor of tests/conftest.py (1 km rising 50 m, m'_L 50 kg/m at 4 m/s,
so I_m = 200 kg/s, B = 1 m) and the rows of engine/data/idlers.csv (class C: 0.127 m 13.0 kg/m
A_i 8.0 N, 0.152 m 17.0 kg/m A_i 6.7 N).
"""

from __future__ import annotations

import math

import pytest

from beltstudy.engine import catalog
from beltstudy.engine.conveyor import InputError, parse_conveyor
from beltstudy.engine.loop import CARRY, build_loop, shell_floor_notes
from beltstudy.engine.statics import solve_steady
from tests.conftest import hand_conveyor_dict

#: DIN summing each resistance (no C factor): the feed is read below 80 m only.
SHORT = [{"length_m": 60, "lift_m": 3}]


def _catalogue_idlers(d_m: float, cema_class: str | None = "C") -> dict:
    s = {"roll_diameter_m": d_m, **({"cema_class": cema_class} if cema_class else {})}
    return {"carry": {"spacing_m": 1.25, "rolls": 3, "trough_deg": 35, **s},
            "return": {"spacing_m": 2.5, "rolls": 1, **s}}


# ------------------------------------------------------------------ idler roll diameters
def test_a_roll_between_two_rows_is_interpolated_and_said():
    """0.133 m was read as the 0.127 m row (13.0 kg/m); between 0.127 and 0.152 m (w = 0.24)
    the shell's mass, linear in D, is 13.0 + 0.24 x 4.0 = 13.96 kg/m, and the seals' torque
    A_i D linear in D gives (0.76 x 8.0 x 0.127 + 0.24 x 6.7 x 0.152) / 0.133 = 7.644 N."""
    row = catalog.idler(0.133, "C")
    assert row.rotating_mass_kg_m == pytest.approx(13.96, rel=1e-9)
    assert row.seal_drag_n == pytest.approx(
        (0.76 * 8.0 * 0.127 + 0.24 * 6.7 * 0.152) / 0.133, rel=1e-9)
    conv = parse_conveyor(hand_conveyor_dict(idlers=_catalogue_idlers(0.133)))
    loop = build_loop(conv, "full")
    carry = loop.strand == CARRY
    assert loop.mR_kg_m[carry & (loop.roll_diameter_m > 0)].max() == pytest.approx(
        13.96 / 1.25, rel=1e-9)
    msg = solve_steady(conv, model="din").message
    assert ("note: idlers.carry.roll_diameter_m 0.133 m is no catalogue row: rotating mass "
            "14 kg a set") in msg
    assert "interpolated between the class C rows of 0.127 m and 0.152 m" in msg
    assert "idlers.return.rotating_mass_kg (or rotating_mass_per_roll_kg) and seal_drag_n" in msg


def test_a_catalogue_row_and_given_values_carry_no_note():
    # 6 in as a file spells it (0.1524 m) is the 0.152 m row
    assert catalog.idler(0.1524, "C").rotating_mass_kg_m == 17.0
    conv = parse_conveyor(hand_conveyor_dict(idlers=_catalogue_idlers(0.1524)))
    assert "roll_diameter_m" not in solve_steady(conv, model="din").message
    # the hand conveyor's 0.133 m sets give their mass and drag: the catalogue is not read
    assert "roll_diameter_m" not in solve_steady(parse_conveyor(hand_conveyor_dict()),
                                                 model="din").message


def test_a_roll_beyond_the_class_rows_is_scaled_from_the_nearest_and_said():
    """Class B holds 0.102 and 0.127 m: a 0.133 m B roll is the 0.127 m row's scaled, its
    shell's mass x 0.133 / 0.127 (12.0 -> 12.567 kg/m), its seals' torque kept (A_i 8.0 ->
    8.0 x 0.127 / 0.133 = 7.639 N)."""
    row = catalog.idler(0.133, "B")
    assert row.rotating_mass_kg_m == pytest.approx(12.0 * 0.133 / 0.127, rel=1e-9)
    assert row.seal_drag_n == pytest.approx(8.0 * 0.127 / 0.133, rel=1e-9)
    conv = parse_conveyor(hand_conveyor_dict(idlers=_catalogue_idlers(0.133, "B")))
    msg = solve_steady(conv, model="din").message
    assert ("scaled from the class B row of 0.127 m, beyond the class's rolls (0.102, 0.127 m)"
            in msg)


def test_a_set_without_its_class_says_the_class_taken_where_the_classes_differ():
    """Without cema_class a 0.152 m set read class C's row (the file's first, the lightest:
    17.0 kg/m, A_i 6.7 N) silently, where D is 18.5 kg/m and E 20.0 kg/m, A_i 12.5 N (+87 %).
    The class taken stays C; the note names it, the classes' range and the fields to give."""
    assert catalog.idler(0.152).cema_class == "C"
    d = hand_conveyor_dict(idlers=_catalogue_idlers(0.152, None))
    msg = solve_steady(parse_conveyor(d), model="din").message
    assert ("note: idlers.carry.cema_class is not given: the 0.152 m roll is read as class C, "
            "the lightest of C, D, E (engine/data/idlers.csv): rotating mass 17 kg a set (17 kg "
            "per m of belt width; 17 to 20 kg/m over the classes) and seal drag 6.7 N a set "
            "(6.7 to 12.5 N over the classes); idlers.carry.cema_class, or the roll maker's "
            "rotating_mass_kg and seal_drag_n, give the set's own") in msg
    assert "note: idlers.return.cema_class is not given" in msg
    # the drag given, the mass (17 to 20 kg/m: 18 % of 17) still differs by class
    d["idlers"]["carry"]["seal_drag_n"] = 6.0
    msg = solve_steady(parse_conveyor(d), model="din").message
    carry = next(n for n in msg.split("; note: ") if "idlers.carry.cema_class" in n)
    assert "rotating mass 17 kg a set" in carry and "seal drag" not in carry
    # the class given, or both values: no note
    for carry in ({"cema_class": "C"}, {"seal_drag_n": 6.0, "rotating_mass_kg": 15.0}):
        d["idlers"]["carry"] = {**_catalogue_idlers(0.152, None)["carry"], **carry}
        msg = solve_steady(parse_conveyor(d), model="din").message
        assert "idlers.carry.cema_class" not in msg
    # 0.127 m: B, C and D share A_i 8.0 N; with the mass given no class changes what is read
    # (within CLASS_SPREAD_NOTE); 0.194 m is class F's alone
    d = hand_conveyor_dict(idlers=_catalogue_idlers(0.127, None))
    for strand in ("carry", "return"):
        d["idlers"][strand]["rotating_mass_kg"] = 15.0
    assert "cema_class" not in solve_steady(parse_conveyor(d), model="din").message
    d = hand_conveyor_dict(idlers=_catalogue_idlers(0.194, None))
    assert "cema_class" not in solve_steady(parse_conveyor(d), model="din").message


def test_the_example_conveyors_give_their_idler_classes():
    """So the class note of a set without cema_class changes no example study's rows."""
    from beltstudy.engine.conveyor import load_conveyor

    root = __import__("pathlib").Path(__file__).resolve().parents[2] / "studies" / "conveyors"
    files = sorted(root.glob("*.yaml"))
    assert files
    for path in files:
        conv = load_conveyor(path)
        for strand in (conv.idlers.carry, conv.idlers.return_):
            assert catalog.idler_note(strand, conv.belt.width_m, "idlers.x") == "", path


# ------------------------------------------------------------------ loading speed
def _feed_run(v0: float, **over):
    d = hand_conveyor_dict(profile=SHORT, **over)
    d["material"] = {**d["material"], "loading_speed_m_s": v0}
    return solve_steady(parse_conveyor(d), model="din")


def test_a_feed_faster_than_the_belt_pushes_it_and_is_said():
    res = _feed_run(6.0)
    # F_bA = I_m (v - v0) = 200 kg/s x (4 - 6) m/s = -0.4 kN
    assert res.summary["te_components_kn"]["feed"] == pytest.approx(-0.4, rel=1e-9)
    assert ("note: material.loading_speed_m_s 6 m/s is above the belt speed 4 m/s: the "
            "material fed pushes the belt") in res.message
    assert "loading_speed" not in _feed_run(2.0).message


def test_a_feed_against_the_travel_at_the_belt_speed_does_not_crash():
    """v0 = -v with skirts: F_f's mean speed (v + v0) / 2 was 0 (ZeroDivisionError); the
    skirt friction while accelerating is now that from rest, and said."""
    feed = {"feed": [{"at_m": 0, "share": 1.0, "skirt_length_m": 3}]}
    d_mat = {**hand_conveyor_dict()["material"], **feed}
    rest = _feed_run(0.0, material={**d_mat, "loading_speed_m_s": 0.0})
    back = _feed_run(-4.0, material=d_mat)
    # F_bA = 200 x (4 + 4) = 1.6 kN; the secondary resistances are those fed at rest
    assert back.summary["te_components_kn"]["feed"] == pytest.approx(1.6, rel=1e-9)
    assert back.summary["te_components_kn"]["secondary"] == pytest.approx(
        rest.summary["te_components_kn"]["secondary"], rel=1e-12)
    assert "-4 m/s is against the belt's travel" in back.message
    assert "that from rest, a lower bound" in back.message
    assert math.isfinite(back.summary["te_kn"])


def test_a_loading_speed_the_c_factor_does_not_read_is_said():
    d = hand_conveyor_dict()  # 1 km: DIN's C holds the feed
    d["material"] = {**d["material"], "loading_speed_m_s": 1.0}
    msg = solve_steady(parse_conveyor(d), model="din").message
    assert "material.loading_speed_m_s 1 m/s is not read: DIN 22101's secondary" in msg


@pytest.mark.parametrize("bad", [float("nan"), float("inf")])
def test_a_non_finite_loading_speed_is_refused(bad):
    d = hand_conveyor_dict()
    d["material"] = {**d["material"], "loading_speed_m_s": bad}
    with pytest.raises(InputError, match="material.loading_speed_m_s"):
        parse_conveyor(d)


# ------------------------------------------------------------------ widths, trough angles
def test_a_width_and_a_trough_angle_beyond_the_tables_are_said():
    d = hand_conveyor_dict()
    d["belt"] = {**d["belt"], "width_m": 0.3}
    d["material"] = {**d["material"], "capacity_t_h": 50}
    msg = solve_steady(parse_conveyor(d), model="din").message
    assert ("note: belt.width_m 0.3 m is outside DIN 22107's roll table (0.4 to 3.2 m, "
            "engine/data/trough.csv): the middle roll of the 0.4 m belt is used") in msg
    d = hand_conveyor_dict()
    d["idlers"]["carry"]["trough_deg"] = 55
    msg = solve_steady(parse_conveyor(d), model="din").message
    assert "note: idlers.carry.trough_deg 55 deg is outside the tables" in msg
    assert "that of 45 deg (0.72" in msg
    assert "trough_deg" not in solve_steady(parse_conveyor(hand_conveyor_dict()),
                                            model="din").message


# ------------------------------------------------------------------ drive fields not read
def _drive_notes(**drive) -> list[str]:
    d = hand_conveyor_dict()
    d["drives"] = [{**d["drives"][0], **drive}]
    msg = solve_steady(parse_conveyor(d), model="din").message
    return [m for m in msg.split("; ") if "drives.0." in m]


def test_drive_fields_the_coupling_does_not_read_are_said():
    """A fill time without a fill-controlled coupling and a motor inertia without a fluid
    coupling change nothing in the run (the vfd drive's shaft turns as one with its motor):
    each is said, with the field, its value and what reads it; given where they are read (a
    fill-controlled coupling on a dol drive), nothing is said."""
    notes = _drive_notes(coupling_fill_s=40, motor_inertia_kg_m2=30, inertia_kg_m2=100)
    assert any(n.startswith("note: drives.0.coupling_fill_s 40 s is not read") and
               "coupling: fluid_fill_controlled" in n and "coupling is none" in n
               for n in notes), notes
    assert any(n.startswith("note: drives.0.motor_inertia_kg_m2 30 kg m2 is not read") and
               "inertia_kg_m2 (100 kg m2) holds it all" in n for n in notes), notes
    assert _drive_notes(control="dol", coupling="fluid_fill_controlled", coupling_fill_s=40,
                        motor_inertia_kg_m2=30, inertia_kg_m2=100) == []
    assert _drive_notes(control="dol", coupling="fluid", coupling_fill_s=40,
                        motor_inertia_kg_m2=30, inertia_kg_m2=100) == [
        n for n in _drive_notes(control="dol", coupling="fluid", coupling_fill_s=40)
        if "coupling_fill_s" in n]
    assert _drive_notes() == []


def test_drive_fields_left_out_are_not_said_after_the_conveyor_is_dumped_and_read_again():
    """A study's runs (and a part-load run's sized conveyor, engine/sizing.py) are validated
    again from the whole dumped conveyor, which marks every field as given. The hand
    conveyor's vfd drive gives no coupling_fill_s and no inertia: read that way it was told
    'drives.0.coupling_fill_s 20 s is not read' (its default) and that its given inertia, 0 kg
    m2, is below its pulley's shell. Neither was given, so nothing is said either way; a fill
    time given on it (40 s) still is."""
    conv = parse_conveyor(hand_conveyor_dict())
    again = parse_conveyor(conv.model_dump(mode="json", by_alias=True))
    assert "coupling_fill_s" in again.drives[0].model_fields_set  # the round trip marks it
    assert [m for m in solve_steady(again, model="din").message.split("; ")
            if "drives.0." in m] == []
    assert shell_floor_notes(again, build_loop(again)) == []
    d = hand_conveyor_dict()
    d["drives"] = [{**d["drives"][0], "coupling_fill_s": 40}]
    given = parse_conveyor(parse_conveyor(d).model_dump(mode="json", by_alias=True))
    assert any(m.startswith("note: drives.0.coupling_fill_s 40 s is not read")
               for m in solve_steady(given, model="din").message.split("; "))


def test_a_torque_limit_on_a_dol_drive_is_said_to_be_not_read():
    """``torque_limit`` caps a vfd drive's force at torque_limit x P_N / v; a dol motor gives
    its curve's torque (docs/dynamics.md: 'torque_limit does not apply'). A dol drive with
    torque_limit 0.3 was run with no word: its cap would be 0.3 x 400 kW / 4 m/s = 30 kN, below
    the hand conveyor's lift alone (m'_L g H = 50 x 9.81 x 50 = 24.5 kN) plus its resistances,
    yet the run reached that force and more. It is now said; the default (1.5) and a vfd drive
    are not, the vfd's cap being read (its own warning)."""
    from beltstudy.engine import parse_scenario, run_one

    dol = {"control": "dol", "rated_power_kw": 400, "inertia_kg_m2": 100}
    notes = _drive_notes(torque_limit=0.3, **dol)
    assert any(n.startswith("note: drives.0.torque_limit 0.3 is not read") and
               "control: dol" in n and "motor_curve" in n for n in notes), notes
    fluid = _drive_notes(torque_limit=0.3, coupling="fluid", **dol)
    assert any("torque through its fluid coupling" in n for n in fluid), fluid
    assert _drive_notes(**dol) == []
    assert not any("torque_limit" in n and "not read" in n
                   for n in _drive_notes(torque_limit=0.3, rated_power_kw=400))
    # the note is true: the dol drive's force passes the 30 kN it would cap
    d = hand_conveyor_dict()
    d["drives"] = [{**d["drives"][0], "torque_limit": 0.3, **dol}]
    scenario = parse_scenario({"start": {"time_s": 20}, "run_s": 2, "stop": {"mode": "coast"}})
    summary = run_one(parse_conveyor(d), scenario, model="din").summary
    cap_kn = 0.3 * 400.0 / 4.0
    assert summary["te_kn"] > cap_kn + 5.0
    assert summary["drive1_force_max_kn"] > cap_kn + 5.0


def test_spec_6_1_s_drive_block_is_taken_and_its_unread_motor_curve_said():
    """SPEC 6.1 prints one drive block with ``control: vfd`` and a ``motor_curve`` (a dol
    motor's torque against speed): the contract's own example is taken, the curve checked,
    and, a vfd drive's speed loop setting its force up to ``torque_limit``, said not to be
    read. It is not: a run with the curve and one without give the same summary to the last
    digit (a curve of 0.3 x rated torque, far below what the hand conveyor needs, would stall a
    motor that read it)."""
    from beltstudy.engine import parse_scenario, run_one

    spec = {"control": "vfd", "friction_kinetic": 0.30, "coupling": "none",
            "coupling_fill_s": 20, "flywheel_kg_m2": 0, "trip_s": 0.0,
            "motor_curve": [[0.0, 1.6], [0.8, 2.2], [0.97, 1.0], [1.0, 0.0]]}
    notes = _drive_notes(**spec)
    assert [n for n in notes if "motor_curve" in n] == [
        "note: drives.0.motor_curve is not read: it is the torque of a motor on the line "
        "(control: dol), and drive 1 is a vfd drive, whose speed loop sets its force up to "
        "torque_limit (1.5 x its rated torque), and control: dol runs the motor on its curve"]
    # read by a dol drive, a curve is not said
    assert not any("motor_curve" in n for n in _drive_notes(**{**spec, "control": "dol"}))
    scenario = parse_scenario({"start": {"time_s": 10}, "run_s": 1, "stop": {"mode": "coast"}})
    rows = []
    for curve in ([[0.0, 0.3], [0.5, 0.3], [1.0, 0.0]], None):
        d = hand_conveyor_dict()
        d["drives"] = [{**d["drives"][0], "rated_power_kw": 400, "motor_curve": curve}]
        summary = run_one(parse_conveyor(d), scenario, model="din").summary
        rows.append({k: v for k, v in summary.items() if k not in ("message", "elapsed_s")})
    assert rows[0] == rows[1]
    assert rows[0]["drive_force_max_kn"] > 0.3 * 400.0 / 4.0 + 5.0
