"""Calibration (SPEC 7.3) rows and fitted names as users write them: a per-section load as a
list, a pasted copy of one state, a zero reading, a time column, a start the model refuses,
names that set one parameter twice, and a fitted value beyond the published range."""

from __future__ import annotations

import pytest

from beltstudy.engine import InputError, load_conveyor, parse_conveyor, solve_steady
from beltstudy.engine.calibration import calibrate, measurements_from_rows
from tests.conftest import CONVEYORS


@pytest.fixture(scope="module")
def slope():
    """slope-5pct (2 km, 100 m lift) with the plant's 18 t counterweight."""
    conv = load_conveyor(CONVEYORS / "slope-5pct.yaml")
    return conv.model_copy(update={"takeup": conv.takeup.model_copy(
        update={"mass_kg": 18000.0})})


def test_a_per_section_load_list_is_taken_as_in_a_scenario():
    """load [1, 1, 1, 0, 0] (SPEC: 'as in a scenario', the schema's list[float]) was refused
    'measured.0.load: expected a number, got [1.0, ...]'; it is the load the text "1,1,1,0,0"
    gives, and its problems are named by the element."""
    rows = measurements_from_rows([
        {"load": [1, 1, 1, 0, 0], "temperature_c": 10, "power_kw": 900},
        {"load": "1,1,1,0,0", "temperature_c": 10, "power_kw": 900}])
    assert rows[0].load == rows[1].load == [1.0, 1.0, 1.0, 0.0, 0.0]
    with pytest.raises(InputError, match=r"^measured\.0\.load\.1: expected a number, got 'x'"):
        measurements_from_rows([{"load": [1, "x"], "temperature_c": 10, "power_kw": 900}])
    with pytest.raises(InputError, match=r"^measured\.0\.load: an empty list: give one load "
                                         "fraction per carry section"):
        measurements_from_rows([{"load": [], "temperature_c": 10, "power_kw": 900}])


def test_a_pasted_copy_does_not_make_the_other_state_an_outlier(slope):
    """Rows 620 kW at (0.5, 10 C) and 800 kW at (0.8, 5 C) twice (a pasted copy): two states,
    one name. The outlier test left row 0 with the two copies, which agree exactly (a residual
    scale of 0), and named it an outlier with an 'unbounded' studentized residual and advice to
    drop it. Two states for one name leave one degree of freedom among states: no outlier
    judgement; the copy is noted."""
    rows = measurements_from_rows([
        {"load": 0.5, "temperature_c": 10, "power_kw": 620},
        {"load": 0.8, "temperature_c": 5, "power_kw": 800},
        {"load": 0.8, "temperature_c": 5, "power_kw": 800}])
    cal = calibrate(slope, rows, "din", ["f_carry"])
    assert not any("outlier" in t for t in [cal.message, *cal.notes])
    assert cal.status == "ok", cal.message
    assert any(n.startswith("row 2 repeats row 1 exactly") for n in cal.notes)


@pytest.mark.parametrize(("col", "words"), [
    ("power_kw", "a measured power_kw must not be 0 (got 0): each residual is relative to its "
                 "reading, and 0 gives it no scale; give the steady state's power at the drive "
                 "pulleys [kW]"),
    ("te_kn", "a measured te_kn must not be 0 (got 0): each residual is relative to its "
              "reading, and 0 gives it no scale; give the steady state's peripheral force at "
              "the drive pulleys [kN]"),
])
def test_a_zero_reading_must_not_be_0(col, words):
    """power_kw 0 read 'a measured power_kw is not 0 (negative: regenerating) (got 0)', a
    statement, not what to do."""
    with pytest.raises(InputError) as exc:
        measurements_from_rows([{"load": 1, "temperature_c": 1, col: 0}])
    assert str(exc.value).startswith(f"measured.0.{col}: {words}")


def test_a_time_column_says_calibration_takes_steady_states():
    """A time_s column was answered "did you mean 'te_kn'?"."""
    with pytest.raises(InputError) as exc:
        measurements_from_rows([{"time_s": 0, "load": 0.5, "temperature_c": 10,
                                 "power_kw": 620}])
    assert str(exc.value) == (
        "measured.0: unknown column 'time_s': calibration takes steady states, one row each, "
        "not a time series: give each steady stretch of the log as one row (its mean load, "
        "temperature and power) and drop 'time_s'")


@pytest.mark.parametrize(("fit", "fixed", "message"), [
    (["f_carry=5"], {}, "fit: 'f_carry=5': the start of f_carry is out of the model's range: a "
     "friction factor between 0 and 1 (DIN 22101: 0.010 to about 0.04; got 5); start it "
     "within that range (f_carry=START)"),
    (["f"], {"f_return": 0.01}, "fit: 'f' is both fitted and fixed: it sets f_carry and "
     "f_return to one value, and f_return is held at 0.01 (--param, or the request's params): "
     "fit f_carry instead, with f_return held, or stop holding f_return to fit 'f'"),
    (["f_carry", "f"], {}, "fit: 'f' sets a parameter another fitted name sets: f_carry, which "
     "'f_carry' sets too ('f' sets f_carry and f_return to one value); fit one of them, not "
     "both"),
    (["f_carry"], {"f_carry": 0.02}, "fit: 'f_carry' is both fitted and fixed: f_carry is held "
     "at 0.02 (--param, or the request's params); fit it or hold it, not both"),
])
def test_fitted_names_are_refused_naming_what_the_user_wrote(slope, fit, fixed, message):
    """--fit f_carry=5 was refused as 'models.din.f_carry: ...' (a study's field); --fit f
    --param f_return=0.01 as "'f' is both fitted and fixed" (f is not held: f_return is);
    --fit f_carry --fit f as 'sets a parameter another fitted name sets' without which."""
    rows = measurements_from_rows([{"load": 0.5, "temperature_c": 10, "power_kw": 620}])
    with pytest.raises(InputError) as exc:
        calibrate(slope, rows, "din", [n.split("=")[0] for n in fit], fixed=fixed, starts={
            n.split("=")[0]: float(n.split("=")[1]) for n in fit if "=" in n})
    assert str(exc.value).startswith(message), str(exc.value)


def test_a_fit_beyond_the_published_range_notes_the_conveyor_file(slope):
    """Power of a 3 km plant rising 150 m (DIN, f_carry 0.025) fitted on the 2 km, 100 m file:
    f_carry 0.054, past DIN 22101's 0.010 to about 0.04 that DIN's own check quotes, passed as
    'ok' with no note. It is noted with the range and the file's length and lift; the plant's
    own file fits 0.025 without it."""
    data = slope.model_dump(mode="json", by_alias=True)
    data["profile"] = [{"length_m": 3000, "lift_m": 150}]
    longer = parse_conveyor(data)
    states = [(0.2, 18), (0.5, 6), (0.8, 22), (1.0, 9)]
    rows = measurements_from_rows([{"load": ld, "temperature_c": t, "power_kw": solve_steady(
        longer, model="din", params={"f_carry": 0.025}, temperature_c=t,
        load=ld).summary["power_kw"]} for ld, t in states])
    cal = calibrate(slope, rows, "din", ["f_carry"])
    assert cal.fit["f_carry"]["value"] > 0.04
    note = next(n for n in cal.notes if n.startswith("f_carry "))
    assert "lies above the published range (DIN 22101: 0.010 to about 0.04; model din's own " \
           "check quotes it)" in note
    assert "a plant longer or higher than the file" in note and "(length_m, lift_m)" in note
    own = calibrate(longer, rows, "din", ["f_carry"])
    assert own.fit["f_carry"]["value"] == pytest.approx(0.025, rel=1e-5)
    assert not any("published range" in n for n in own.notes)
