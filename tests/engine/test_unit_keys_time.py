"""A time or an inertia key in another unit names the contract's key and the conversion, as
the lengths, forces and powers do (tests/engine/test_unit_keys.py): 'scenario.run_min: 2' was
answered only "did you mean 'run_s'?", which a user follows by renaming the key and keeping 2
(2 s of running for 2 minutes, 120 s); 'inertia_lb_ft2: 60000' the same (60 000 kg m2 for
2 528 kg m2)."""

from __future__ import annotations

import pytest
from pydantic import ValidationError

from beltstudy.engine import InputError, parse_conveyor, parse_scenario
from beltstudy.engine.conveyor import unit_twin
from tests.conftest import hand_conveyor_dict

# the twin and its words, for every unit: tests/engine/test_unit_keys.py


def test_the_factors_by_hand():
    # 1 lb ft2 = 0.45359237 kg x (0.3048 m)^2 = 0.0421401 kg m2; 1 min = 60 s
    assert 0.45359237 * 0.3048 ** 2 == pytest.approx(0.042140, abs=5e-7)


def test_keys_that_only_end_like_a_unit_have_no_twin():
    keys = ["capacity_t_h", "speed_m_s", "run_s"]
    assert unit_twin("capacity_t_h", keys) == ""  # t/h is its own unit
    assert unit_twin("speed_ms", keys) == ""  # no 'speed_s'


def test_a_scenario_in_minutes_is_refused_with_the_conversion():
    with pytest.raises(InputError) as exc:
        parse_scenario({"run_min": 2, "start": {"time_min": 1.5}}, prefix="scenario.")
    msg = str(exc.value)
    assert ("scenario.run_min: unknown key 'run_min'; did you mean 'run_s'? "
            "(in seconds: min x 60)") in msg
    assert "scenario.start.time_min: unknown key 'time_min'; did you mean 'time_s'? " in msg


def test_a_drive_inertia_in_lb_ft2_is_refused_with_the_conversion():
    d = hand_conveyor_dict()
    d["drives"][0]["inertia_lb_ft2"] = 60000
    with pytest.raises((InputError, ValidationError)) as exc:
        parse_conveyor(d)
    assert ("drives.0.inertia_lb_ft2: unknown key 'inertia_lb_ft2'; did you mean "
            "'inertia_kg_m2'? (in kg m2: lb ft2 x 0.042140)") in str(exc.value)
