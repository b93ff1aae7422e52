"""What avoids a drive's slip in the start (engine/remedy.py), found by rerunning the start."""

from __future__ import annotations

import re

import pytest

from beltstudy.engine.conveyor import Scenario, load_conveyor, parse_conveyor
from beltstudy.engine.errors import InputError
from beltstudy.engine.run import run_one
from tests.conftest import CONVEYORS


def test_the_take_up_and_start_time_that_avoid_a_start_slip_are_found_and_are_the_least():
    """A 60 s start of the 16.8 km overland slips (take-up sized by statics for start-up
    slip). Asked for, the run finds the take-up and the start time that avoid it by rerunning
    the start: each, applied alone, gives a whole cycle without slip, and 5 % less of it still
    slips (the search brackets the least to 2 %); the message names both."""
    conv = load_conveyor(CONVEYORS / "overland-16km.yaml")
    scn = Scenario(start={"time_s": 60}, elements=200)
    said: list[str] = []
    s = run_one(conv, scn, model="din", remedy=True, say=said.append).summary
    assert max(s["drive1_slip_s"], s["drive2_slip_s"]) > 0.0
    # the slip's search is said first (its stop sags past the limit too: that search follows)
    assert said[0] == ("a drive slips in the start: rerunning the start to find the take-up and "
                       "the start time that avoid it (about a dozen reruns)")
    m, t = s["slip_free_takeup_mass_kg"], s["slip_free_start_time_s"]
    assert m > s["takeup_mass_kg"] and t > 60.0
    assert f"a take-up of {m:,.0f} kg" in s["message"] and f"a start of {t:.0f} s" in s["message"]

    def slip_s(mass, start_s):
        c = conv.model_copy(update={"takeup": conv.takeup.model_copy(update={"mass_kg": mass})})
        r = run_one(c, Scenario(start={"time_s": start_s}, elements=200), model="din").summary
        return r["drive1_slip_s"] + r["drive2_slip_s"]

    base = s["takeup_mass_kg"]
    assert slip_s(m, 60.0) == 0.0 and slip_s(0.95 * m, 60.0) > 0.0
    assert slip_s(base, t) == 0.0 and slip_s(base, 0.95 * t) > 0.0
    # without the option, nothing is searched
    plain = run_one(conv, scn, model="din").summary
    assert plain["slip_free_takeup_mass_kg"] is None and plain["slip_free_start_time_s"] is None


def test_a_dol_start_that_slips_is_offered_the_take_up_alone():
    """Dol drives start on their motor curve whatever start.time_s is (the same conveyor's
    20 s and 60 s starts give the same start), so the remedy searches only the take-up: the
    start time is None, the message says why, and the take-up it names avoids the slip."""
    data = load_conveyor(CONVEYORS / "slope-5pct.yaml").model_dump(mode="json", by_alias=True)
    data["drives"][0]["control"] = "dol"
    data["takeup"]["mass_kg"] = 20000
    conv = parse_conveyor(data)
    scn = Scenario(elements=60, run_s=10, stop={"mode": "coast"})
    said: list[str] = []
    s = run_one(conv, scn, model="din", remedy=True, say=said.append).summary
    assert s["drive1_slip_s"] > 0.0
    assert said and "a dol start does not read start.time_s" in said[0]
    assert s["slip_free_start_time_s"] is None
    m = s["slip_free_takeup_mass_kg"]
    assert m is not None and m > 20000
    assert f"slip in the start avoided by a take-up of {m:,.0f} kg (found by" in s["message"]
    assert "or by a start of" not in s["message"] and "no start up to" not in s["message"]
    fixed = parse_conveyor({**data, "takeup": {**data["takeup"], "mass_kg": m}})
    assert run_one(fixed, scn, model="din").summary["drive1_slip_s"] == 0.0


def test_the_remedy_reruns_the_run_s_own_mesh_so_a_valid_fixed_step_stays_valid():
    """A fixed step just under the stability limit of the run's mesh is a valid input. The
    remedy's reruns asked for the count of elements the run used (62 for 60 asked: the
    loop's cut adds two), built a finer mesh (64) whose limit is below that step, and the
    run was refused. Asking for the run's own count, the reruns use its mesh: the run
    answers, and the take-up it names avoids the slip with that same step."""
    data = load_conveyor(CONVEYORS / "slope-5pct.yaml").model_dump(mode="json", by_alias=True)
    data["drives"][0]["control"] = "dol"
    data["takeup"]["mass_kg"] = 20000
    conv = parse_conveyor(data)
    scn = Scenario(elements=60, run_s=10, stop={"mode": "coast"}, dt_s=1.0)
    with pytest.raises(InputError) as exc:
        run_one(conv, scn, model="din")
    limit = float(re.search(r"stability limit ([\d.e-]+) s", str(exc.value)).group(1))
    scn = scn.model_copy(update={"dt_s": 0.99 * limit})
    s = run_one(conv, scn, model="din", remedy=True).summary
    assert s["elements_used"] == 62 and s["dt_used_s"] == pytest.approx(0.99 * limit)
    assert s["drive1_slip_s"] > 0.0
    m = s["slip_free_takeup_mass_kg"]
    assert m is not None and m > 20000
    fixed = parse_conveyor({**data, "takeup": {**data["takeup"], "mass_kg": m}})
    assert run_one(fixed, scn, model="din").summary["drive1_slip_s"] == 0.0


def test_a_slip_in_the_stop_alone_is_not_announced_as_a_start_slip():
    """fabric-1km's 3 s controlled stop slips its drive during the stop only (the start does
    not slip). The remedy's first rerun of the start finds no slip and searches nothing; the
    progress line "a drive slips in the start: rerunning ..." is not said (it was, before
    the search confirmed the start slipped), and no slip-free figure of the start is filled
    (the stop's own search, tests/engine/test_remedy_stop.py, is what is said)."""
    conv = load_conveyor(CONVEYORS / "fabric-1km.yaml")
    scn = Scenario(elements=100, stop={"mode": "controlled", "time_s": 3})
    said: list[str] = []
    s = run_one(conv, scn, model="din", remedy=True, say=said.append).summary
    assert s["drive1_slip_s"] > 0.0 and "slipped on its pulley during the stop" in s["message"]
    assert not any("slips in the start" in line for line in said)
    assert "slip in the start" not in s["message"]
    assert s["slip_free_takeup_mass_kg"] is None and s["slip_free_start_time_s"] is None


#: A 600 m incline rising 95 m with two head dol drives through constant-fill fluid couplings
#: (a conveyor unlike the examples): its start slips drive 2, and the least take-up that
#: avoids the slip grows with the mesh (18.9 t on 53 elements, 20.2 t on 103, 22.1 t on 205).
INCLINE_DOL = {
    "name": "incline-dol", "speed_m_s": 2.5,
    "belt": {"type": "ST1600", "width_m": 1.0},
    "material": {"capacity_t_h": 1200, "density_t_m3": 1.6},
    "profile": [{"length_m": 600, "lift_m": 95}],
    "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.133, "rolls": 3,
                         "trough_deg": 35, "cema_class": "D"},
               "return": {"spacing_m": 3.0, "roll_diameter_m": 0.133, "rolls": 1,
                          "cema_class": "C"}},
    "drives": [{"position": "head", "wrap_deg": 210, "friction": 0.35, "share": 0.5,
                "pulley_diameter_m": 1.0, "inertia_kg_m2": 300, "control": "dol",
                "coupling": "fluid"}] * 2,
    "takeup": {"type": "gravity", "position": "tail", "mass_kg": "auto", "travel_m": 6},
    "holdback": True,
    "accessories": {"head_kn": 1.0, "tail_kn": 0.5},
}


def test_a_checked_run_s_slip_free_take_up_holds_on_the_finer_mesh_too():
    """The remedy's take-up is the least that avoids the slip on the run's own mesh, at the
    edge of the slip there; a finer mesh sharpens the start's front and deepens the slack
    side's dip, so on the incline above the 18,921 kg found on 53 elements slipped drive 2
    again on the error bars' mesh twice as fine (0.13 s of slip on 109 elements). A checked
    run now tries each figure on that finer mesh and, where it still slips, gives the
    figure found there, naming both: that take-up starts without slip on both meshes."""
    conv = parse_conveyor(INCLINE_DOL)
    scn = Scenario(elements=50, run_s=10, stop={"mode": "coast"})
    plain = run_one(conv, scn, model="din", remedy=True).summary
    s = run_one(conv, scn, model="din", remedy=True, check=True).summary
    n, fine_n = s["elements_used"], 2 * s["elements_used"]
    m_run, m = plain["slip_free_takeup_mass_kg"], s["slip_free_takeup_mass_kg"]
    assert m_run is not None and m is not None and m > m_run
    assert f"a take-up of {m:,.0f} kg (found by" in s["message"]
    assert (f"a take-up of {m_run:,.0f} kg, enough on this mesh ({n} elements), still slipped "
            f"on one twice as fine ({fine_n} elements") in s["message"]

    def slip_s(mass, elements):
        c = parse_conveyor({**INCLINE_DOL, "takeup": {**INCLINE_DOL["takeup"], "mass_kg": mass}})
        r = run_one(c, scn.model_copy(update={"elements": elements}), model="din").summary
        return r["drive1_slip_s"] + r["drive2_slip_s"]

    assert slip_s(m_run, 50) == 0.0 and slip_s(m_run, fine_n) > 0.0  # the run's figure
    assert slip_s(m, 50) == 0.0 and slip_s(m, fine_n) == 0.0  # the figure given


def test_a_too_short_start_is_searched_past_six_times_itself_to_the_rigid_body_start():
    """A 10 s start of a 3 km belt slipped and was searched only up to 6 x 10 = 60 s, so the
    run said 'a longer start would not: rerunning the start found no start up to 6 x this
    one', though the same belt starts without slip in 87 s. The search now goes at least to
    2 x the rigid body's start time (remedy.time_top_s): the drives at the statics' 1.5 Te
    accelerate the moving mass M at a = 0.5 Te / M, and an s-curve of T peaks at 2 v / T, so
    T_rigid = 2 v M / (0.5 Te) = 4 v M / Te. The hand conveyor (1 km, 4 m/s) started in 2 s
    (searched to 12 s before): the start time found lies past 12 s, within the new limit,
    and a start of that time has no slip."""
    from beltstudy.engine.design import moving_mass_kg
    from beltstudy.engine.remedy import time_top_s
    from beltstudy.engine.statics import solve_steady
    from tests.conftest import hand_conveyor_dict

    conv = parse_conveyor(hand_conveyor_dict())
    scn = Scenario(start={"time_s": 2.0}, run_s=5, elements=40)
    st = solve_steady(conv, model="din")
    t_rigid = 4.0 * 4.0 * moving_mass_kg(conv, st) / st.te_n
    assert time_top_s(conv, scn, st, stop=False) == pytest.approx(2.0 * t_rigid, rel=1e-12)
    assert 2.0 * t_rigid > 6.0 * 2.0
    s = run_one(conv, scn, model="din", remedy=True).summary
    assert s["drive1_slip_s"] > 0.0
    t = s["slip_free_start_time_s"]
    assert t is not None and 12.0 < t <= 2.0 * t_rigid
    assert "a longer start did not as far as searched" not in s["message"]
    assert f"a start of {t:.0f} s" in s["message"]
    again = run_one(conv, scn.model_copy(update={"start": scn.start.model_copy(
        update={"time_s": t})}), model="din").summary
    assert again["drive1_slip_s"] == 0.0


def test_a_too_short_controlled_stop_is_searched_to_the_rigid_body_stop():
    """The stop's search the same way: a 0.2 s controlled stop of the hand conveyor makes its
    head drive brake the belt past its grip; searched to 6 x 0.2 = 1.2 s alone it found no
    stop.time_s. The reverse s-curve of T asks a peak deceleration 2 v / T, within the
    coast's Te / M from T = 2 M v / Te (the drives then never brake): the search now reaches
    2 x that, finds a stop time past 1.2 s, and that stop has no slip in the stop."""
    from beltstudy.engine.design import moving_mass_kg
    from beltstudy.engine.remedy import time_top_s
    from beltstudy.engine.statics import solve_steady
    from tests.conftest import hand_conveyor_dict

    conv = parse_conveyor(hand_conveyor_dict())
    scn = Scenario(start={"time_s": 60.0}, run_s=5, elements=40,
                   stop={"mode": "controlled", "time_s": 0.2})
    st = solve_steady(conv, model="din")
    t_rigid = 2.0 * moving_mass_kg(conv, st) * 4.0 / st.te_n
    assert time_top_s(conv, scn, st, stop=True) == pytest.approx(2.0 * t_rigid, rel=1e-12)
    msg = run_one(conv, scn, model="din", remedy=True).summary["message"]
    assert "drive 1 (head) slipped on its pulley during the stop" in msg
    found = re.search(r"slip in the stop avoided by a stop\.time_s of ([0-9.]+) s", msg)
    assert found and 1.2 < float(found.group(1)) <= 2.0 * t_rigid
    assert "a longer stop did not as far as searched" not in msg
    again = run_one(conv, scn.model_copy(update={"stop": scn.stop.model_copy(
        update={"time_s": float(found.group(1))})}), model="din").summary["message"]
    assert "slipped on its pulley" not in again
