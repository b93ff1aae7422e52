"""A key written in another unit than the contract's (SPEC: every key that carries a unit ends
in it): the message names the contract's key and the conversion, whatever the case of the
unit (power_MW, te_N); the name alone was suggested before ("did you mean 'rated_power_kw'?"),
which a user follows by renaming the key and keeping the numbers in MW."""

from __future__ import annotations

import pytest
from pydantic import ValidationError

from beltstudy.engine import InputError, parse_conveyor
from beltstudy.engine.conveyor import unit_twin
from tests.conftest import hand_conveyor_dict


@pytest.mark.parametrize("key,twin,conversion", [
    ("power_MW", "power_kw", "kW: MW x 1000"),
    ("power_w", "power_kw", "kW: W / 1000"),
    ("te_N", "te_kn", "kN: N / 1000"),
    ("te_MN", "te_kn", "kN: MN x 1000"),
    ("temperature_F", "temperature_c", "degrees Celsius: (F - 32) / 1.8"),
    ("temperature_K", "temperature_c", "degrees Celsius: K - 273.15"),
    # times and inertias (tests/engine/test_unit_keys_time.py: the scenario and drive doors)
    ("run_min", "run_s", "seconds: min x 60"),
    ("time_MIN", "time_s", "seconds: min x 60"),
    ("delay_ms", "delay_s", "seconds: ms / 1000"),
    ("run_h", "run_s", "seconds: h x 3600"),
    ("inertia_lb_ft2", "inertia_kg_m2", "kg m2: lb ft2 x 0.042140"),
])
def test_a_unit_slip_in_a_key_names_the_twin_and_the_conversion(key, twin, conversion):
    keys = ["load", "temperature_c", "power_kw", "te_kn", "run_s", "time_s", "delay_s",
            "inertia_kg_m2", "capacity_t_h", "speed_m_s"]
    assert unit_twin(key, keys) == f"did you mean '{twin}'? (in {conversion})"


def test_a_key_that_is_no_unit_slip_has_no_twin():
    keys = ["load", "temperature_c", "power_kw", "te_kn"]
    assert unit_twin("temp_c", keys) == ""  # a misspelling: difflib's word, not a unit
    assert unit_twin("power_kw", keys) == ""  # the key itself


def test_a_conveyor_key_in_mw_is_refused_with_the_conversion():
    d = hand_conveyor_dict()
    d["drives"][0]["rated_power_MW"] = 1.25
    with pytest.raises((InputError, ValidationError)) as exc:
        parse_conveyor(d)
    msg = str(exc.value)
    assert "drives.0.rated_power_MW: unknown key" in msg
    assert "did you mean 'rated_power_kw'? (in kW: MW x 1000)" in msg


@pytest.mark.parametrize("where", ["top", "belt"])
def test_a_unit_in_brackets_in_a_key_is_named_not_a_traceback(where):
    """``"speed_m_s [m/s]": 4.5`` (a unit written into the key, as a spreadsheet's header
    has it): the bracket was taken for one of Pydantic's union tags and dropped, leaving a
    top-level key no location at all (an IndexError, a 500 over REST) and a nested one the
    name of its parent ("belt: unknown key 'belt'")."""
    d = hand_conveyor_dict()
    if where == "top":
        d["speed_m_s [m/s]"] = d.pop("speed_m_s")
        key, field = "speed_m_s [m/s]", "speed_m_s"
    else:
        d["belt"] = dict(d["belt"])
        d["belt"]["width [m]"] = d["belt"].pop("width_m")
        key, field = "width [m]", "belt.width_m"
    with pytest.raises(InputError) as err:
        parse_conveyor(d)
    text = str(err.value)
    assert f"unknown key '{key}'" in text and f"{field}: required field is missing" in text
