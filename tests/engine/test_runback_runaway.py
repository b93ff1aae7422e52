"""A belt that runs back after its stop was taken for a belt at rest: the rest criterion
(mean speed below 1 % of design speed) holds for any backward speed, so the run ended one
rest time after the belt first passed 1 % on its way down, while it was still speeding up
backwards. A 150 m, 15 deg incline with no holdback ended 4.2 m/s backwards and speeding up,
'about 10.5 m of belt run back by then', and never reached the runaway verdict it was a
second away from. A belt running back as a whole is not at rest: the rest goes on (up to the
stop window's end), so it ends as a runaway, with the lift's pull and a holdback named."""
from __future__ import annotations

import math
import re

import numpy as np
import pytest

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.run import run_one

G = 9.81
V_D = 2.5
LIFT_M = 38.82
LENGTH_M = 150.0


def _steep(holdback: bool) -> dict:
    idler = {"roll_diameter_m": 0.127, "cema_class": "C"}
    return {
        "name": "steep150", "speed_m_s": V_D,
        "belt": {"type": "EP630/4", "width_m": 1.0, "top_cover_mm": 5,
                 "bottom_cover_mm": 2},
        "material": {"capacity_t_h": 400, "density_t_m3": 1.6},
        "profile": [{"length_m": LENGTH_M, "lift_m": LIFT_M}],  # 15 deg
        "idlers": {"carry": {**idler, "spacing_m": 1.2, "rolls": 3, "trough_deg": 35},
                   "return": {**idler, "spacing_m": 3.0, "rolls": 1}},
        "drives": [{"position": "head", "wrap_deg": 210, "friction": 0.35,
                    "pulley_diameter_m": 0.63, "inertia_kg_m2": 40,
                    "rated_power_kw": 200, "torque_limit": 1.5}],
        "takeup": {"type": "gravity", "position": "tail", "mass_kg": "auto",
                   "travel_m": 3},
        "holdback": holdback,
        "accessories": {"head_kn": 0.5, "tail_kn": 0.3},
    }


def test_a_belt_running_back_after_its_stop_runs_on_to_the_runaway_verdict():
    res = run_one(parse_conveyor(_steep(False)), Scenario(record_dt_s=0.05), model="din")
    s, ts = res.summary, res.timeseries
    msg = s["message"]
    assert "the belt ran back during the stop: its mean speed reached 5 m/s" in msg, msg
    assert "a holdback (holdback: true)" in msg
    assert "runs back after the stop" not in msg  # the run did not end with it running
    t, v = ts["t_s"].to_numpy(), ts["v_mean_m_s"].to_numpy()
    assert v[-1] == pytest.approx(-2.0 * V_D, rel=0.02)
    # by hand: the belt runs back as a rigid body under the load's lift less its
    # resistances (DIN's, the same at any speed; the feed's is 0 here, loading speed 0):
    # a = (g H m'_L - R) / M, R the running resistances of statics without the lift, M the
    # belt, load and idler rolls over the loop, the drive shaft at the belt line (its
    # J (2 / D)^2, at least its pulley's shell) and the tail pulley's shell (a welded drum as
    # a thin steel shell: 1.3 x 7850 kg/m3 x pi D (B + 0.2 m) (12 mm + 0.01 D), J (2/D)^2 = m)
    c = s["te_components_kn"]
    r_n = 1e3 * (s["te_kn"] - c["lift"] - c["feed"])
    m_l = s["load_mass_kg_m"]
    pull_n = G * LIFT_M * m_l
    assert pull_n == pytest.approx(1e3 * c["lift"], rel=1e-3)

    def shell(d_m: float) -> float:
        return 1.3 * 7850.0 * math.pi * d_m * (1.0 + 0.2) * (0.012 + 0.01 * d_m)

    mass = (LENGTH_M * (2.0 * s["belt_mass_kg_m"] + m_l + s["idler_mass_carry_kg_m"]
                        + s["idler_mass_return_kg_m"])
            + max(40.0 / 0.315 ** 2, shell(0.63)) + shell(0.8))
    a_hand = -(pull_n - r_n) / mass
    # the simulated mean acceleration from -0.5 to -1.5 design speed (after the stretch's
    # relaxation, before the runaway limit)
    k0 = int(np.flatnonzero(v < -0.5 * V_D)[0])
    k1 = int(np.flatnonzero(v < -1.5 * V_D)[0])
    a_sim = (v[k1] - v[k0]) / (t[k1] - t[k0])
    assert a_sim == pytest.approx(a_hand, rel=0.02)
    assert math.isfinite(a_sim) and a_sim < 0.0


def test_a_belt_on_its_holdback_still_rests_one_rest_time_after_its_stop():
    # the same belt on a holdback: its head pulley cannot turn back, the belt relaxes onto it
    # and rests; the run ends at rest, not at the stop window's end
    res = run_one(parse_conveyor(_steep(True)), Scenario(), model="din")
    s, ts = res.summary, res.timeseries
    assert s["stop_time_s"] is not None, s["message"]
    v = ts["v_mean_m_s"].to_numpy()
    assert abs(v[-1]) < 0.01 * V_D
    t_stop_cmd = 2.0 + 60.0 + 30.0  # the rest, the start and the run before the stop
    assert ts["t_s"].to_numpy()[-1] < t_stop_cmd + s["stop_time_s"] + 60.0


def test_a_holdback_that_takes_more_than_cemas_static_rule_is_named_with_its_peak():
    # the stop's roll-back onto the holdback: its peak force at the belt line, by the time
    # series, against CEMA's static rule (the lift's pull at rest less half the running
    # resistance without the feed, x D / 2 on the 0.63 m head pulley)
    res = run_one(parse_conveyor(_steep(True)), Scenario(), model="din")
    s, ts = res.summary, res.timeseries
    f = ts["f_holdback_kn"].to_numpy()
    # the summary's peak is every step's, the time series' at the records
    assert float(f.max()) <= s["f_holdback_kn"] <= 1.02 * float(f.max())
    c = s["te_components_kn"]
    friction_kn = c["main_carry"] + c["main_return"] + c["secondary"] + c["accessories"]
    rule_knm = (c["lift"] - 0.5 * friction_kn) * 0.63 / 2.0
    assert s["holdback_torque_knm"] == pytest.approx(rule_knm, rel=1e-3)
    torque = s["f_holdback_kn"] * 0.315
    assert torque > 1.2 * rule_knm  # the relaxing belt's peak, not the pull at rest
    t_s = ts["t_s"].to_numpy()
    after = t_s > 2.0 + 60.0 + 30.0  # after the stop command (rest 2 s, start 60, run 30)
    f_after = f[after]
    k = int(np.argmax(f_after))
    t_peak, f_peak = float(t_s[after][k]), float(f_after[k])
    pull_kn = G * LIFT_M * s["load_mass_kg_m"] / 1e3  # the loaded belt's pull at rest
    assert f_peak > 1.2 * pull_kn
    torque = f_peak * 0.315
    assert (f"the holdback took up to {f_peak:.4g} kN at the belt line after the stop (t = "
            f"{t_peak:.4g} s, read at the records; {torque:.3g} kNm on the 0.63 m head "
            f"pulley), {f_peak / pull_kn:.2f} x the loaded belt's pull at rest "
            f"({pull_kn:.4g} kN): the belt's stretch swinging back onto it; CEMA's static rule "
            f"(holdback_torque_knm) sizes it for {s['holdback_torque_knm']:.3g} kNm"
            in s["message"]), s["message"]


def test_a_holdback_holding_the_pull_at_rest_alone_is_not_noted():
    # fabric-1km on its holdback: its largest holdback force is the loaded belt's pull at
    # rest, before the start (the model credits no resistance at rest), which the static rule
    # is the design convention for
    from beltstudy.engine.conveyor import load_conveyor
    from tests.conftest import CONVEYORS

    res = run_one(load_conveyor(CONVEYORS / "fabric-1km.yaml"), Scenario(elements=40),
                  model="din")
    pull_kn = res.transient.system.hold_force_n / 1e3
    assert res.summary["f_holdback_kn"] == pytest.approx(pull_kn, rel=1e-9)
    assert "the holdback took up to" not in res.summary["message"]


def _decline(hold: bool) -> dict:
    d = _steep(False)
    d["profile"] = [{"length_m": LENGTH_M, "lift_m": -LIFT_M}]
    d["brakes"] = [{"position": "head", "force_kn": 40, "delay_s": 0.5, "hold": hold}]
    return d


def test_a_decline_whose_brake_lets_go_at_rest_runs_away_and_says_so():
    """A brake without ``hold`` is released once the belt rests (SPEC 6.1); on a loaded
    decline the net gravity pull then sets the belt off downhill again. The rest ended after
    its time whatever the forward speed: a 600 m decline ended 'ok' at 0.77 m/s forwards and
    speeding up. Running on as a whole is not rest, as running back is not: the rest goes on
    and the belt runs away, said with the brake that let go and a holding force (1.2 x the
    net gravity pull m'_L g H). With ``hold: true`` the same brake holds it at rest."""
    scn = Scenario.model_validate({"stop": {"mode": "brake", "time_s": 5},
                                   "record_dt_s": 0.05})
    res = run_one(parse_conveyor(_decline(False)), scn, model="din")
    s, ts = res.summary, res.timeseries
    msg = s["message"]
    assert s["status"] == "warning" and s["stop_time_s"] is not None
    assert ts["v_mean_m_s"].iloc[-1] == pytest.approx(2.0 * V_D, rel=0.02)
    assert "then ran away forwards during the stop" in msg, msg
    assert "brakes.0 without hold let go once it rested" in msg
    pull_kn = G * LIFT_M * s["load_mass_kg_m"] / 1e3
    need = re.search(r"brakes\[\]\.hold: true\) of at least ([0-9.]+) kN in all", msg)
    assert need and float(need.group(1)) == pytest.approx(1.2 * pull_kn, rel=2e-3)
    held = run_one(parse_conveyor(_decline(True)), scn, model="din")
    v_end = held.timeseries["v_mean_m_s"].iloc[-1]
    assert abs(v_end) < 0.01 * V_D
    assert "ran away" not in held.summary["message"]
    assert "runs on after its stop" not in held.summary["message"]


def test_a_belt_running_on_at_the_run_s_end_is_told_how_far_and_what_holds_it():
    """The words of a belt that rested and runs on forwards when its run ends (short of the
    runaway limit): since when, how fast, how far (the mean speed's integral after the rest
    began: here 0.1 m/s for 2 s then 0.2 m/s for 2 s, about 0.6 m) and the holding force."""
    from types import SimpleNamespace

    from beltstudy.engine.dynamics.simulate import runon_words

    t = np.arange(0.0, 10.01, 1.0)
    v = np.array([2.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.1, 0.1, 0.2, 0.2, 0.2])
    rec = np.zeros(t.size, dtype=[("t", float), ("v_mean", float)])
    rec["t"], rec["v_mean"] = t, v
    sys_ = SimpleNamespace(v_design=2.5, hold_force_n=-10e3)
    conv = SimpleNamespace(brakes=[SimpleNamespace(hold=False, force_kn=40.0)])
    r = {"nrec": t.size, "stopped": True, "t_stopped": 2.0}
    (words,) = runon_words(sys_, SimpleNamespace(rec=rec), r, conv)
    assert words.startswith("the belt runs on after its stop: it came to rest at t = 2 s")
    assert "since t = 6 s" in words and "0.2 m/s forwards at the run's end (t = 10 s)" in words
    assert "about 0.7 m of belt run on" in words  # from t = 3 s: 0.05 + 0.1 + 0.15 + 0.2 + 0.2
    assert "brakes.0 without hold let go once it rested" in words
    assert "of at least 12 kN in all" in words
    # at rest at the end, or never at rest: nothing
    rec2 = rec.copy()
    rec2["v_mean"][-3:] = 0.0
    assert runon_words(sys_, SimpleNamespace(rec=rec2), r, conv) == []
    assert runon_words(sys_, SimpleNamespace(rec=rec), dict(r, stopped=False), conv) == []
