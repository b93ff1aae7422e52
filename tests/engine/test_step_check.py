"""Figures the step moves at a fixed mesh (engine/accuracy.py ``step_bar``, ``_half_step``):
where a drive pulley slips or the belt goes slack, a run's error bars include the run's own
mesh at half its step. The meshes refine the step with the mesh (the Courant number stays),
so an error the Courant number itself sets was invisible to them: a 100 m incline on two
vfd drives under a torque start, its tail drive slipping against a slack fixed take-up, read
a start of 14.18 s at the automatic step and 12.17, 10.54, 10.14 and 10.16 s at a half, a
quarter, an eighth and a sixteenth of it (10.57 s on twice the elements at a quarter)."""
from __future__ import annotations

import math
import re

import pytest

from beltstudy.engine.accuracy import FigureError, step_bar
from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.run import run_one


def _incline(length_m: float, lift_m: float, pretension_kn: float) -> dict:
    """A short incline on a head drive (0.7 of Te) and a tail drive (0.3), mu 0.3 on 190 deg,
    on a fixed take-up below what the steady slip check asks."""
    drive = {"wrap_deg": 190, "friction": 0.3, "pulley_diameter_m": 0.8, "torque_limit": 1.8}
    return {"name": "head-tail", "speed_m_s": 3.5,
            "belt": {"type": "EP800/4", "width_m": 1.0, "top_cover_mm": 5,
                     "bottom_cover_mm": 2, "compound": "standard"},
            "material": {"capacity_t_h": 600, "density_t_m3": 1.2},
            "profile": [{"length_m": length_m, "lift_m": lift_m}],
            "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.127, "rolls": 3,
                                 "trough_deg": 35, "cema_class": "C"},
                       "return": {"spacing_m": 3.0, "roll_diameter_m": 0.127, "rolls": 1,
                                  "cema_class": "C"}},
            "drives": [{**drive, "position": "head", "share": 0.7, "inertia_kg_m2": 60,
                        "rated_power_kw": 200},
                       {**drive, "position": "tail", "share": 0.3, "inertia_kg_m2": 30,
                        "rated_power_kw": 90}],
            "takeup": {"type": "fixed", "position": "tail", "pretension_kn": pretension_kn},
            "holdback": True, "accessories": {"head_kn": 0.5, "tail_kn": 0.3}}


def _run(conv: dict, check: bool, **scn):
    return run_one(parse_conveyor(conv),
                   Scenario(start={"control": "torque", "time_s": 3.0}, **scn),
                   model="din", check=check, remedy=False)


def test_a_start_the_step_moves_is_marginal_and_its_estimate_is_the_finer_step_s():
    """The 100 m incline: the run says its start time moves with the step, with the
    Richardson estimate of a first-order scheme, 2 f(dt / 2) - f(dt); a quarter of the step
    lies between that estimate and the half step's figure (the first order holding), and
    the deciding figures the half step moved carry its bar (method ``step``)."""
    conv = _incline(100.0, 20.0, 7.0)
    res = _run(conv, check=True)
    s = res.summary
    said = re.search(r"marginal: start_time_s ([\d.]+) s at the run's step \(([\d.e-]+) s\), "
                     r"([\d.]+) s at half of it \(about ([\d.]+) s converged, the step's first "
                     r"order\)", s["message"])
    assert said, s["message"]
    a, b, conv_s = (float(said.group(k)) for k in (1, 3, 4))
    assert a == pytest.approx(s["start_time_s"], abs=0.01)
    assert conv_s == pytest.approx(2 * b - a, abs=0.02)
    assert abs(a - b) > 0.05 * a  # the step moves it by seconds here
    quarter = _run(conv, check=False, dt_s=s["dt_used_s"] / 4).summary["start_time_s"]
    assert min(conv_s, b) - 0.02 * b <= quarter <= max(conv_s, b) + 0.02 * b
    assert "step: " in s["accuracy_methods"] and "at half the step" in s["accuracy_methods"]
    # a figure the half step moved past its mesh bar has the step's bar: Fs 3 x the move
    for name in re.findall(r"(\w+) \([\d.e+-]+ at half the step\)", s["accuracy_methods"]):
        half = float(re.search(rf"{name} \(([\d.e+-]+) at half the step\)",
                               s["accuracy_methods"]).group(1))
        assert s[f"{name}_err"] == pytest.approx(3 * abs(s[name] - half), rel=2e-3, abs=1e-6)


def test_a_start_reached_at_half_the_step_only_is_said_and_a_flat_speed_gets_no_run_s():
    """A 200 m incline (12 kN fixed take-up where the steady check asks 16.6 kN) swings at
    92-99 % of design speed from 17 s, its tail drive's slack side going slack: at the
    automatic step it never reached 99 %, at half of it it did. The run says so. Its words
    had read the rise over the whole run (2.33 m/s in 30 s) as reaching design speed in 4 s
    more and offered a run_s of 35 s, then 49 s, then 68 s; the mean speed over the run's
    last 10 s did not rise, and a 60 s run still does not get there."""
    conv = _incline(200.0, 40.0, 12.0)
    s = _run(conv, check=True).summary
    msg = s["message"]
    assert s["start_time_s"] is None
    assert re.search(r"marginal: start_time_s: the belt reached 99 % of design speed at "
                     r"half the step \([\d.]+ s\) and not at the run's step", msg), msg
    assert "a run_s of at least" not in msg, msg
    assert re.search(r"its mean speed did not rise over the last 10 s before the stop command "
                     r"\(-?[\d.e-]+ m/s2 on average\), so a longer run_s would not", msg), msg
    longer = _run(conv, check=False, run_s=60.0).summary
    assert longer["start_time_s"] is None, longer["message"]


def test_the_step_bar_is_three_times_the_half_step_s_move_where_that_is_larger():
    fe = FigureError("t_max_dyn_kn", 120.0, 1.2, 119.0, "gci3", 0.9, (118.0, 120.0, 119.5))
    wide = step_bar(fe, 126.5)
    assert wide.err == pytest.approx(19.5) and wide.converged == pytest.approx(133.0)
    assert wide.method == "step" and wide.half_step == 126.5
    kept = step_bar(fe, 120.2)
    assert kept.err == 1.2 and kept.method == "gci3" and kept.half_step == 120.2
    assert step_bar(fe, None) is fe and step_bar(fe, math.nan) is fe
    # a lowest tension of 3.07 kN at the step and 1.17 kN at half of it extrapolates below 0:
    # a tension cannot be negative, so no estimate is given (as the mesh bars do); the bar
    # stands
    low = FigureError("t_min_stop_kn", 3.07, 0.3, None, "growing", -0.3, (3.2, 3.07, 2.9))
    held = step_bar(low, 1.17)
    assert held.converged is None and held.err == pytest.approx(5.7) and held.method == "step"
