"""A design sized over its cases: the largest of each size, what set it and where
(engine/sizing.py)."""

from __future__ import annotations

import pytest

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.design import auto_sizes, rotating_parts
from beltstudy.engine.errors import InputError
from beltstudy.engine.sizing import DesignCase, SizingError, governed_at, size_over_cases
from beltstudy.engine.statics import solve_steady
from tests.conftest import hand_conveyor_dict
from tests.engine.conftest import steep_incline

BRAKED = hand_conveyor_dict(brakes=[{"position": "head", "force_kn": "auto", "delay_s": 0.5}])
CASES = [
    DesignCase("din", (), 20.0),
    DesignCase("din", (("f_carry", 0.03),), 20.0),
    DesignCase("cema", (), -20.0),
]


def _each(conv, cases, stop_s=None):
    out = []
    for c in cases:
        scn = Scenario(load="full", temperature_c=c.temperature_c, elements=c.elements)
        if stop_s is not None:
            scn = scn.model_copy(update={"stop": scn.stop.model_copy(
                update={"mode": "brake", "time_s": stop_s})})
        out.append(auto_sizes(conv, scn, model=c.model, params=dict(c.params)))
    return out


def _first_largest(values):
    return max(range(len(values)), key=lambda i: (values[i], -i))


def test_each_size_is_the_largest_over_the_cases_with_what_set_it_and_where():
    conv = parse_conveyor(BRAKED)
    sized = size_over_cases(conv, CASES, load="full", stop_times=[8.0])
    each = _each(conv, CASES)

    masses = [s["takeup_mass_kg"] for s in each]
    i = _first_largest(masses)
    assert sized.takeup.value == masses[i]
    assert (sized.takeup.governed_by, sized.takeup.case) == (each[i]["takeup_governed_by"],
                                                             CASES[i])

    power = [s["drive_rated_power_kw"][0] for s in each]
    j = _first_largest(power)
    assert len(sized.drives) == 1
    assert sized.drives[0].value == power[j] and sized.drives[0].case == CASES[j]
    assert sized.drives[0].governed_by == each[j]["drive_rated_power_governed_by"][0]

    totals = [sum(s["brake_force_kn"]) for s in each]
    k = _first_largest(totals)
    assert sized.brakes_holding.force_kn == tuple(each[k]["brake_force_kn"])
    assert sized.brakes_holding.governed_by == tuple(each[k]["brake_governed_by"])
    assert sized.brakes_holding.case == CASES[k]

    braked = _each(conv, CASES, stop_s=8.0)
    totals = [sum(s["brake_force_kn"]) for s in braked]
    k = _first_largest(totals)
    assert list(sized.brakes_by_stop) == [8.0]
    assert sized.brakes_by_stop[8.0].force_kn == tuple(braked[k]["brake_force_kn"])
    assert sized.brakes_by_stop[8.0].case == CASES[k]
    assert sized.failed_cases == ()


def test_sizes_the_file_gives_are_not_sized():
    given = hand_conveyor_dict(takeup={"type": "gravity", "position": "tail", "mass_kg": 9000})
    given["drives"] = [{**given["drives"][0], "rated_power_kw": 500}]
    sized = size_over_cases(parse_conveyor(given), CASES[:1])
    assert sized.takeup is None and sized.drives == (None,)
    assert sized.brakes_holding is None and sized.brakes_by_stop == {}


def test_a_case_names_its_load_model_the_parameters_it_changes_and_its_temperature():
    assert CASES[0].label() == "full, din, 20 C"
    assert CASES[1].label() == "full, din (f_carry=0.03), 20 C"
    assert DesignCase("din", (("f_carry", 0.02),), -5.0).label() == "full, din, -5 C"
    assert DesignCase("din", load="declines").label() == "declines, din, 20 C"
    assert DesignCase("din", load=0.8).label() == "load 0.8, din, 20 C"
    assert DesignCase("din", load=[1, 0.5]).label() == "load [1, 0.5], din, 20 C"
    # ``at``: the case by what varies among the design's cases, nothing for one case
    assert CASES[2].at(CASES) == "cema, -20 C"
    assert CASES[1].at(CASES[:2]) == "din (f_carry=0.03)"
    assert CASES[0].at(CASES[:1]) == ""
    loads = [DesignCase("din", load=x) for x in ("full", "declines")]
    assert loads[1].at(loads) == "declines"
    assert governed_at("stop_time", "declines") == "stop_time @ declines"
    assert governed_at("stop_time", "") == "stop_time"
    assert governed_at("given", "declines") == "given"


#: A 1 km hand conveyor that rises 25 m over 500 m and falls 80 m over the next 500 m, its
#: head brake (0.5 s delay, 1 s ramp) on the head drive's pulley, a given 40 t take-up (so the
#: brake stays within its pulley's grip and the take-up is not sized).
UNDULATING = hand_conveyor_dict(
    profile=[{"length_m": 500, "lift_m": 25}, {"length_m": 500, "lift_m": -80}],
    brakes=[{"position": "head", "force_kn": "auto", "delay_s": 0.5, "ramp_s": 1.0}],
    takeup={"type": "gravity", "position": "tail", "mass_kg": 40000})


def test_the_brake_of_a_load_envelope_is_the_declines_case_and_says_so():
    """Loaded declines need more brake than the full belt: sized over [full, declines] the
    brake is the declines case's, ``stop_time @ declines``.

    Hand check (engine/design.py, brake_force_auto): a rigid-body stop in t = 10 s after the
    delay d = 0.5 s, the force built over the ramp r = 1 s: M v_1 = Te t_b + F_b (t_b - r/2),
    t_b = t - d, v_1 = v - Te d / M, so F_b = (M v_1 - Te t_b) / (t_b - r/2): the decelerating
    force of the moving mass plus the net gravity pull less the running resistance
    (Te = R + G, G < 0 downhill). Net gravity pull of the load (the belt's own weight cancels
    round the loop): G = m'_L g sum(lift of the loaded sections), m'_L = 50 kg/m:
    full 50 x 9.81 x (25 - 80) = -26 977.5 N, declines 50 x 9.81 x (-80) = -39 240 N. Moving
    mass M = 2 x 1000 m x m'_G 20 kg/m + loaded length x 50 kg/m + 1000 m x (10 + 3) kg/m of
    idler rolls + the pulleys' reduced mass (engine/loop.py rotating_parts, the same for both
    loads); the belt round the pulleys' wraps (about 3 m of the 2 000 m loop) is left out, so
    the hand figure is good to 1e-3. The holding floor 1.2 x |G| (32.4 and 47.1 kN) is below
    both stop forces, so the stop time sets the brake at both loads.
    """
    conv = parse_conveyor(UNDULATING)
    cases = [DesignCase("din", (), 20.0, "auto", load) for load in ("full", "declines")]
    sized = size_over_cases(conv, cases, stop_times=[10.0])
    g, v, t, d, r = 9.81, 4.0, 10.0, 0.5, 1.0
    hand = {}
    for load, loaded_m, lift_m in (("full", 1000.0, 25.0 - 80.0), ("declines", 500.0, -80.0)):
        steady = solve_steady(conv, model="din", load=load)
        resistance = float(steady.resistance_n.sum())  # the din law's, tested in test_statics
        gravity = 50.0 * g * lift_m
        mass = (2 * 1000 * 20.0 + loaded_m * 50.0 + 1000 * (10.0 + 3.0)
                + rotating_parts(conv, steady.loop).total_kg)
        te = resistance + gravity
        assert te == pytest.approx(steady.te_n, rel=1e-9)
        v1 = v - te * d / mass
        t_b = t - d
        hand[load] = (mass * v1 - te * t_b) / (t_b - r / 2) / 1e3
        assert hand[load] > 1.2 * abs(gravity) / 1e3  # the stop time, not holding, sets it
    assert hand["declines"] > 1.1 * hand["full"]
    braked = sized.brakes_by_stop[10.0]
    assert braked.force_kn[0] == pytest.approx(hand["declines"], rel=1e-3)
    assert braked.governed_by == ("stop_time",)
    assert braked.case == cases[1] and braked.at == "declines"
    assert governed_at(braked.governed_by[0], braked.at) == "stop_time @ declines"
    # holding: the declines' larger pull, 1.2 x 39.24 kN
    assert sized.brakes_holding.force_kn[0] == pytest.approx(1.2 * 39.24, rel=1e-9)
    assert sized.brakes_holding.at == "declines"
    # the same design sized at full load alone takes the smaller full-load brake
    alone = size_over_cases(conv, cases[:1], stop_times=[10.0]).brakes_by_stop[10.0]
    assert alone.force_kn[0] == pytest.approx(hand["full"], rel=1e-3) and alone.at == ""
    # ``load=`` puts every case at one load, as before
    full = size_over_cases(conv, cases, load="full", stop_times=[10.0]).brakes_by_stop[10.0]
    assert full.force_kn == alone.force_kn


def test_a_load_that_does_not_fit_the_profile_is_a_sizing_error_naming_the_load():
    conv = parse_conveyor(BRAKED)
    with pytest.raises(SizingError) as info:
        size_over_cases(conv, CASES[:1], load=[0.5, 0.5], design="belt=EP630")
    assert isinstance(info.value, InputError)
    assert info.value.field == "load"
    assert info.value.reason.endswith("(conveyor design belt=EP630)")


def test_a_brake_beyond_its_grip_is_held_at_the_least_grip_over_the_cases():
    """The 10 % incline's 3 s stop needs more than its head pulley passes at every case: the
    design's brake is the least of the cases' grips (a force every case's pulley passes), at
    that case, ``grip``; a 3.5 s stop is within every case's grip and stays the largest
    need (stop_time)."""
    conv = steep_incline()
    sized = size_over_cases(conv, CASES, load="full", stop_times=[3.0, 3.5])
    braked = _each(conv, CASES, stop_s=3.0)
    grips = [s["brake_grip_kn"] for s in braked]
    k = min(range(len(grips)), key=lambda i: grips[i])
    assert all(s["brake_governed_by"] == ["grip"] for s in braked)
    assert sized.brakes_by_stop[3.0].force_kn == pytest.approx((grips[k],), rel=1e-6)
    assert sized.brakes_by_stop[3.0].governed_by == ("grip",)
    assert sized.brakes_by_stop[3.0].case == CASES[k]
    within = _each(conv, CASES, stop_s=3.5)
    totals = [sum(s["brake_force_kn"]) for s in within]
    j = _first_largest(totals)
    assert totals[j] < min(s["brake_grip_kn"] for s in within)
    assert sized.brakes_by_stop[3.5].force_kn == tuple(within[j]["brake_force_kn"])
    assert sized.brakes_by_stop[3.5].governed_by == ("stop_time",)


@pytest.mark.parametrize("stop", [{"mode": "brake", "time_s": 10.0}, {"mode": "coast"}])
def test_a_run_below_the_full_load_keeps_the_motor_and_brake_installed_for_it(stop):
    """The belt and the counterweight are installed once, for the full load; so are the auto
    motors and brakes of a single run. The empty undulating belt has no net gravity pull (the
    belt's own weight cancels round the loop), so sized on its own its brake would be
    nothing but the stop force of an empty belt, and its motor that of the empty belt's
    resistance: an empty run installs the full load's instead (``@ full``), and a full-load
    run is unchanged."""
    from beltstudy.engine.run import run_one

    data = {**UNDULATING, "drives": [{**UNDULATING["drives"][0]}]}
    data["drives"][0].pop("rated_power_kw", None)  # auto
    conv = parse_conveyor(data)
    scn = Scenario(load="full", stop=stop)
    full = run_one(conv, scn, model="din", dynamics=False).summary
    empty = run_one(conv, scn.model_copy(update={"load": "empty"}), model="din",
                    dynamics=False).summary
    on_its_own = auto_sizes(conv, scn.model_copy(update={"load": "empty"}), model="din")
    assert sum(on_its_own["brake_force_kn"]) < 0.5 * full["brake_force_kn"]
    assert empty["brake_force_kn"] == pytest.approx(full["brake_force_kn"], rel=1e-12)
    assert empty["rated_power_kw"] == pytest.approx(full["rated_power_kw"], rel=1e-12)
    assert sum(on_its_own["drive_rated_power_kw"]) < full["rated_power_kw"]
    why = "stop_time" if stop["mode"] == "brake" else "holding"
    assert empty["brake_governed_by"] == f"{why} @ full"
    assert full["brake_governed_by"] == why
    assert empty["rated_power_governed_by"].endswith("@ full")


def test_an_auto_brake_sized_to_nothing_stays_auto_below_the_full_load():
    """A level belt with an auto brake and a coast stop: nothing pulls it at rest (holding 0)
    and no stop time asks for force, so the brake's size over the run's case and the full load
    is 0 kN. A run at half load keeps it auto (a given force_kn must be above 0) and ends as a
    result with a 0 kN brake, as the full-load run does."""
    from beltstudy.engine.run import run_one

    data = hand_conveyor_dict(profile=[{"length_m": 500, "lift_m": 0}],
                              brakes=[{"position": "head", "force_kn": "auto"}])
    conv = parse_conveyor(data)
    scn = Scenario(load=0.5, stop={"mode": "coast"})
    assert sum(auto_sizes(conv, scn, model="din")["brake_force_kn"]) == 0.0
    half = run_one(conv, scn, model="din", dynamics=False).summary
    full = run_one(conv, scn.model_copy(update={"load": "full"}), model="din",
                   dynamics=False).summary
    assert half["brake_force_kn"] == 0.0 == full["brake_force_kn"]
    assert half["status"] != "failed", half["message"]
