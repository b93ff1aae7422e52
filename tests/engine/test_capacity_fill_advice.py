"""An over-filled belt is refused with the figures that pass: the largest capacity and the
lowest speed (the fill is the design volume flow over the ISO 5048 cross-section's flow at
design speed, so it falls as 1 / speed). Each figure, taken, must pass the same check."""
from __future__ import annotations

import re

import pytest

from beltstudy.engine import InputError, parse_conveyor
from beltstudy.engine.capacity import fill_pct
from beltstudy.engine.conveyor import FILL_MAX_PCT, load_mapping
from tests.conftest import CONVEYORS


def test_the_refusal_names_a_capacity_and_a_speed_that_pass():
    data = load_mapping(CONVEYORS / "slope-5pct.yaml")
    ok = parse_conveyor(data)
    fill = fill_pct(ok)
    # a capacity that fills the cross-section 1.5 x the limit
    data["material"]["capacity_t_h"] = ok.material.capacity_t_h * 1.5 * FILL_MAX_PCT / fill
    with pytest.raises(InputError) as err:
        parse_conveyor(data)
    text = str(err.value)
    cap = float(re.search(r"capacity of at most ([0-9.]+) t/h", text).group(1))
    speed = float(re.search(r"speed of at least ([0-9.]+) m/s", text).group(1))
    # by hand: the limit's share of the asked capacity, and the speed 1.5 x faster, each
    # rounded at three figures towards passing (within 1 %)
    hand_cap, hand_speed = data["material"]["capacity_t_h"] / 1.5, 1.5 * ok.speed_m_s
    assert hand_cap * 0.99 <= cap <= hand_cap
    assert hand_speed <= speed <= hand_speed * 1.01
    taken = dict(data, material=dict(data["material"], capacity_t_h=cap))
    assert fill_pct(parse_conveyor(taken)) <= FILL_MAX_PCT
    faster = dict(data, speed_m_s=speed)
    assert fill_pct(parse_conveyor(faster)) <= FILL_MAX_PCT


def test_a_speed_beyond_speed_m_s_bound_is_not_offered():
    """A 0.1 m belt (a width typed in the wrong unit) was told 'a speed of at least 1210 m/s',
    which speed_m_s's own bound (30 m/s) then refuses: the refusal says no speed within it
    would do, and offers the capacity and a wider belt."""
    data = load_mapping(CONVEYORS / "slope-5pct.yaml")
    data["belt"]["width_m"] = 0.1
    with pytest.raises(InputError) as err:
        parse_conveyor(data)
    text = str(err.value)
    assert "speed of at least" not in text, text
    assert "no speed within speed_m_s's bound of 30 m/s would do" in text
    assert "a wider belt (belt.width_m, now 0.1 m)" in text
    cap = float(re.search(r"capacity of at most ([0-9.]+) t/h", text).group(1))
    taken = dict(data, material=dict(data["material"], capacity_t_h=cap))
    assert fill_pct(parse_conveyor(taken)) <= FILL_MAX_PCT
