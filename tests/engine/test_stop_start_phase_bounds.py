"""A stop and a start are read within their phases (engine/dynamics/simulate.py): a belt
running backwards at the stop command made no stop (it read "stopped in 0.006 s", and a brake
"never acted ... stop.mode: coast for the stop this was"), and a belt that first reached 99 %
of design speed after the stop command, running away in its coast, made no start (a 1.47 km
route read a start of 38.4 s, 16 s into its coast)."""
from __future__ import annotations

from beltstudy.engine.conveyor import Scenario, load_mapping, parse_conveyor
from beltstudy.engine.run import run_one
from tests.conftest import CONVEYORS


def test_a_belt_running_back_at_the_stop_command_has_no_stop_time():
    """slope-5pct (2 km, +100 m, loaded) with its gravity take-up at the head and only 300 kg
    on it: the head drive cannot pass the start's force, the loaded incline runs back, and at
    the stop command its mean speed is below zero. A stop is the mean speed falling below
    1 % of design speed (SPEC 4) from running: there is none to time."""
    d = load_mapping(CONVEYORS / "slope-5pct.yaml")
    d["takeup"] = {"type": "gravity", "position": "head", "mass_kg": 300, "travel_m": 10}
    d["brakes"] = [{"position": "head", "force_kn": "auto", "delay_s": 0.5}]
    scn = Scenario(elements=60, start={"control": "s-curve", "time_s": 20}, run_s=5,
                   stop={"mode": "brake", "time_s": 20}, record_dt_s=0.1)
    res = run_one(parse_conveyor(d), scn, model="din", remedy=False, check=False)
    s, ts = res.summary, res.timeseries
    t, v = ts["t_s"].to_numpy(), ts["v_mean_m_s"].to_numpy()
    at_cmd = v[t <= 2.0 + 20.0 + 5.0 + 1e-9][-1]
    assert at_cmd < -0.01 * 4.5, at_cmd  # running back at the stop command
    assert s["stop_time_s"] is None and s["stop_distance_m"] is None
    assert s["stop_wave_ratio"] is None
    assert "never acted in the stop" not in s["message"]
    assert "never reached 99 % of design speed during the start" in s["message"]


def test_a_start_first_at_speed_after_the_stop_command_is_no_start():
    """A 1.47 km decline (ST5400, 7.01 m/s, 6 450 t/h, three vfd drives at 14.3 s, CEMA at
    -22.6 C) with too little pretension on its fixed take-up: at the stop command its mean
    speed is about two thirds of design speed, and in the coast it runs away down the decline,
    passing 99 % of design speed on the way. The start phase ends at the stop command (SPEC
    6.4), so it has no start time; the run says the runaway."""
    d = {
        "name": "decline-runaway", "speed_m_s": 7.01,
        "belt": {"type": "ST5400", "width_m": 2.2, "compound": "standard"},
        "material": {"capacity_t_h": 6450.0, "density_t_m3": 1.08, "loading_speed_m_s": 0.0},
        "profile": [
            {"length_m": 267.0, "lift_m": -46.8, "curve_radius_m": 576.0,
             "horizontal_radius_m": 1410.0},
            {"length_m": 386.9, "lift_m": -5.37},
            {"length_m": 323.7, "lift_m": -59.42, "curve_radius_m": 673.0},
            {"length_m": 493.0, "lift_m": -12.8, "horizontal_radius_m": 741.0,
             "superelevation_deg": 4.2}],
        "idlers": {"carry": {"spacing_m": 1.99, "roll_diameter_m": 0.152, "rolls": 3,
                             "trough_deg": 35, "cema_class": "E"},
                   "return": {"spacing_m": 3.42, "roll_diameter_m": 0.152, "rolls": 1,
                              "cema_class": "C"}},
        "drives": [
            {"position": "head", "wrap_deg": 180, "friction": 0.26, "share": 0.458,
             "pulley_diameter_m": 0.8, "inertia_kg_m2": 995.0, "torque_limit": 1.95,
             "control": "vfd"},
            {"position": "return", "wrap_deg": 180, "friction": 0.38, "share": 0.218,
             "pulley_diameter_m": 0.8, "inertia_kg_m2": 615.0, "torque_limit": 1.42,
             "control": "vfd", "at_m": 455.3, "rated_power_kw": 594.0},
            {"position": "return", "wrap_deg": 240, "friction": 0.4, "share": 0.324,
             "pulley_diameter_m": 0.8, "inertia_kg_m2": 610.0, "torque_limit": 1.81,
             "control": "vfd", "at_m": 436.8, "rated_power_kw": 949.0}],
        "takeup": {"type": "fixed", "position": "head", "pretension_kn": 8.23,
                   "travel_m": 25.5},
        "brakes": [{"force_kn": 325.0, "delay_s": 0.03, "drive": 1}],
        "holdback": False,
        "accessories": {"head_kn": 2.6, "tail_kn": 1.3},
    }
    scn = Scenario(elements=60, temperature_c=-22.6, load="full",
                   start={"control": "s-curve", "time_s": 14.3}, run_s=7.7,
                   stop={"mode": "coast"}, record_dt_s=0.1)
    res = run_one(parse_conveyor(d), scn, model="cema", remedy=False, check=False)
    s, ts = res.summary, res.timeseries
    t, v = ts["t_s"].to_numpy(), ts["v_mean_m_s"].to_numpy()
    t_cmd = 2.0 + 14.3 + 7.7
    before = t <= t_cmd + 1e-9
    assert v[before].max() < 0.99 * 7.01  # not at speed within the start phase
    assert v.max() >= 0.99 * 7.01  # but after it, in the coast
    assert s["start_time_s"] is None
    assert "ran away forwards during the stop" in s["message"], s["message"]
