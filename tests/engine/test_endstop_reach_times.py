"""The take-up end-stop warning (engine/dynamics/simulate.py, ``endstop_words``) named the
kernel's first touch of any stop as the time (t = 0.0 s for a carriage whose rest position is
an end of its travel, pressing on it from rest), and named the ends as if the belt always
stretches as it runs. A tail drive with its gravity take-up at the head runs shorter than at
rest (its carry strand, the slack side, loses more tension than its return gains): its
carriage runs to the low end, was told it reached 'the running end (... the belt stretched
...)' at t = 0.0 s and offered a heavier take-up, with which it still hit. Now each end the
carriage reached is named with the time the records first hold it there, the running end is
the one on the running position's side, and where the running position lies beyond the
travel only a longer travel is offered, with the need named."""
from __future__ import annotations

import re

import numpy as np
import pytest

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.run import run_one

G = 9.81
IDLERS = {"carry": {"spacing_m": 1.5, "roll_diameter_m": 0.127, "rolls": 3, "trough_deg": 35,
                    "cema_class": "C"},
          "return": {"spacing_m": 3.0, "roll_diameter_m": 0.127, "rolls": 1,
                     "cema_class": "C"}}
HEAD_KN, TAIL_KN = 1.0, 0.5


def _tail_drive(mass_kg="auto") -> dict:
    """1.2 km rising 12 m, ST1000 at 3.5 m/s, 1000 t/h, one tail drive, a gravity take-up at
    the head on 0.1 m of travel."""
    return {"name": "taildrive_endstop", "speed_m_s": 3.5,
            "belt": {"type": "ST1000", "width_m": 1.0, "compound": "standard"},
            "material": {"capacity_t_h": 1000, "density_t_m3": 1.2, "loading_speed_m_s": 0.0},
            "profile": [{"length_m": 1200, "lift_m": 12}], "idlers": IDLERS,
            "drives": [{"position": "tail", "wrap_deg": 200, "friction": 0.35, "share": 1.0,
                        "pulley_diameter_m": 0.8, "inertia_kg_m2": 300, "rated_power_kw": 400,
                        "torque_limit": 1.5}],
            "takeup": {"type": "gravity", "position": "head", "mass_kg": mass_kg,
                       "travel_m": 0.1},
            "holdback": False, "accessories": {"head_kn": HEAD_KN, "tail_kn": TAIL_KN}}


def _head_drive() -> dict:
    """2 km rising 40 m, ST1600 at 4.5 m/s, 1800 t/h, one head drive, a gravity take-up at the
    tail on 0.15 m of travel."""
    d = _tail_drive()
    idl = {k: {**v, "roll_diameter_m": 0.152} for k, v in IDLERS.items()}
    idl["carry"]["cema_class"] = "D"
    d.update(name="cold_endstop", speed_m_s=4.5,
             belt={"type": "ST1600", "width_m": 1.2, "compound": "standard"},
             material={"capacity_t_h": 1800, "density_t_m3": 1.6, "loading_speed_m_s": 0.0},
             profile=[{"length_m": 2000, "lift_m": 40}], idlers=idl,
             drives=[{**d["drives"][0], "position": "head", "wrap_deg": 210,
                      "pulley_diameter_m": 1.25, "inertia_kg_m2": 1500, "rated_power_kw": 900}],
             takeup={"type": "gravity", "position": "tail", "mass_kg": "auto", "travel_m": 0.15},
             holdback=True, accessories={"head_kn": 2.0, "tail_kn": 1.0})
    return d


def _run(d: dict):
    """The default cycle (2 s rest, 60 s s-curve start, 30 s run, coast), records every
    0.1 s."""
    return run_one(parse_conveyor(d), Scenario(elements=40, record_dt_s=0.1), model="din")


def _endstop_words(msg: str) -> str:
    said = re.search(r"take-up carriage reached .*? would avoid it", msg)
    assert said, msg
    return said.group(0)


def _first_at(t: np.ndarray, x: np.ndarray, end: float) -> float:
    """The first record time holding the carriage at ``end`` (1e-7 m), after it first left
    it where it starts there."""
    at = np.abs(x - end) <= 1e-7
    if at[0]:
        at[:int(np.flatnonzero(~at)[0])] = False
    return float(t[np.flatnonzero(at)[0]])


def test_a_carriage_running_shorter_than_at_rest_is_named_at_its_running_end_in_time():
    res = _run(_tail_drive())
    s, ts = res.summary, res.timeseries
    words = _endstop_words(s["message"])
    # by hand, linear belt (E B), the take-up's tension T_tu held at the head: at rest the
    # strands hang from it by gravity alone (the tail drive holds the lift); running, the carry
    # runs from T2 at the tail up to T_tu less the head pulley's resistance, the return from
    # T_tu down to T1 less the tail's. The carriage moves by half the length change:
    # x_run = L / (2 E B) (mean dT carry + mean dT return), about -0.101 m
    t_tu, length, lift = s["takeup_tension_kn"], 1200.0, 12.0
    w_belt = s["belt_mass_kg_m"] * G * lift / 1e3
    w_load = s["load_mass_kg_m"] * G * lift / 1e3
    dt_carry = 0.5 * ((s["t2_kn"] - (t_tu - w_belt - w_load)) + (-HEAD_KN))
    dt_return = 0.5 * (0.0 + (s["t1_kn"] - TAIL_KN - (t_tu - w_belt)))
    x_hand = 0.5 * length * (dt_carry + dt_return) / s["belt_modulus_kn"]
    x_said = float(re.search(r"running position (-[\d.]+) m", words).group(1))
    assert x_said == pytest.approx(x_hand, rel=0.03)  # the sag law's chord adds a little
    assert x_said < -0.1  # beyond the travel: the window runs from -0.1 to 0 m
    assert f"the running stretch alone needs {-x_said:g} m" in words
    # the time series: the carriage reached -0.1 m in the start, not at t = 0; its rest
    # position (0 m) is the other end's stop, on which it rests: no hit there
    t, x = ts["t_s"].to_numpy(), ts["x_takeup_m"].to_numpy()
    assert x.min() == pytest.approx(-0.1, abs=1e-9) and x.max() == pytest.approx(0.0, abs=1e-9)
    t_lo = _first_at(t, x, -0.1)
    assert 5.0 < t_lo < 62.0  # in the start (2 s rest, 60 s s-curve)
    run = re.search(r"take-up carriage reached the running end \(carriage drawn in: the belt "
                    r"shortened more than the travel allows\) at t = ([\d.]+) s at up to", words)
    assert run, words
    # a record every 0.1 s: the first one at the stop is up to one spacing after the touch
    assert float(run.group(1)) == pytest.approx(t_lo, abs=0.15)
    assert "rest end" not in words and "stretched" not in words
    # only the travel helps where the running position lies beyond it: a heavier take-up
    # leaves the stretch to the drive force (a 35 t take-up, twice the auto one, still hits)
    assert "heavier take-up" not in words and "gentler" not in words
    heavy = _run(_tail_drive(mass_kg=35000)).summary["message"]
    assert "heavier take-up" not in _endstop_words(heavy)
    assert "reached the running end (carriage drawn in" in heavy


def test_a_carriage_resting_on_an_end_is_timed_when_it_reaches_the_other():
    """A head drive whose running stretch (0.172 m) needs more than its 0.15 m of travel: the
    carriage rests on its rest end's stop (0 m) and reaches the running end (0.15 m) in the
    start, where the kernel's first hit is its press on the rest end from t = 0."""
    res = _run(_head_drive())
    words = _endstop_words(res.summary["message"])
    t, x = res.timeseries["t_s"].to_numpy(), res.timeseries["x_takeup_m"].to_numpy()
    assert x.max() == pytest.approx(0.15, abs=1e-9)
    t_run = _first_at(t, x, 0.15)
    assert 5.0 < t_run < 62.0
    run = re.search(r"take-up carriage reached the running end \(counterweight at its lowest: "
                    r"the belt stretched more than the travel allows\) at t = ([\d.]+) s at up "
                    r"to", words)
    assert run, words
    assert float(run.group(1)) == pytest.approx(t_run, abs=0.15)
    assert "rest end" not in words
    assert "the running stretch alone needs 0.172 m" in words and "heavier" not in words
