"""A drive pulley's slip margin is that of the force it passes (PHYSICS 5.1 and 5.2).

The margin was read from the two springs beside the pulley, ``e^(mu theta) T_lo / T_hi``:
their difference holds the pulley element's own inertia as well as the force the pulley
passes, and at a dol breakaway that spike is resolved higher the shorter the step. A 1.2 km,
8 deg incline on two dol drives with fluid couplings slips its drives in the start; its
lowest margin read 0.99657, 0.98564, 0.96740 and 0.95319 at 1/2 to 1/16 of the step while
the force passed sat at the capstan limit, and a 4 km overland's tail drive read 1.000034
while it slid for 13.2 s. The margin is now ``e^(mu theta) T_slack / (T_slack + |F_belt|)``,
the capstan law's own ratio: 1 at the grip, and a sliding pulley is 1 at most.
"""
from __future__ import annotations

import pytest

from beltstudy.engine.conveyor import Scenario, load_mapping, parse_conveyor
from beltstudy.engine.run import run_one
from tests.conftest import CONVEYORS

DOL = {
    "name": "incline1200-dol", "speed_m_s": 3.5,
    "belt": {"type": "ST3150", "width_m": 1.2, "compound": "standard"},
    "material": {"capacity_t_h": 2200, "density_t_m3": 1.8, "loading_speed_m_s": 0.0},
    "profile": [{"length_m": 1200, "lift_m": 167.0}],
    "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.152, "rolls": 3,
                         "trough_deg": 35, "cema_class": "D"},
               "return": {"spacing_m": 3.0, "roll_diameter_m": 0.152, "rolls": 1,
                          "cema_class": "C"}},
    "drives": [{"position": "head", "wrap_deg": 210, "friction": 0.35, "share": 0.5,
                "pulley_diameter_m": 1.25, "inertia_kg_m2": 900, "control": "dol",
                "coupling": "fluid"}] * 2,
    "takeup": {"type": "gravity", "position": "tail", "mass_kg": "auto", "travel_m": 10},
    "holdback": True,
    "accessories": {"head_kn": 1.5, "tail_kn": 0.5}}


def _run(conv, dt_s=None, **scn):
    extra = {} if dt_s is None else {"dt_s": dt_s}
    return run_one(conv, Scenario(elements=100, stop={"mode": "coast"}, **scn, **extra),
                   model="din")


def test_a_slipping_dol_drives_margin_is_one_at_every_step():
    conv = parse_conveyor(DOL)
    base = _run(conv)
    dt = base.transient.system.model.cycle.dt
    runs = [base, _run(conv, dt / 4.0)]
    for r in runs:
        s = r.summary
        slid = [i for i in (1, 2) if (s[f"drive{i}_slip_s"] or 0.0) > 0.0]
        assert slid, s  # the premise: the breakaway slips the drives
        for i in slid:
            # at the grip the capstan ratio is 1: never below it by more than rounding
            assert s[f"drive{i}_slip_margin_min"] == pytest.approx(1.0, abs=1e-9)
        assert s["slip_margin_min_dyn"] == pytest.approx(1.0, abs=1e-9)
    # the slip itself does not depend on the step either (PHYSICS 5.2): within 2 %
    for i in (1, 2):
        a, b = (r.summary[f"drive{i}_slip_s"] for r in runs)
        assert b == pytest.approx(a, rel=0.02)


def test_a_drive_that_slides_never_reads_a_margin_above_one():
    """overland-4km's coast stop: its tail drive slides for 13.2 s in the start."""
    conv = parse_conveyor(load_mapping(CONVEYORS / "overland-4km.yaml"))
    s = run_one(conv, Scenario(stop={"mode": "coast"}), model="din").summary
    slid = [i for i in range(1, 4) if (s.get(f"drive{i}_slip_s") or 0.0) > 0.0]
    assert slid, s
    for i in slid:
        assert s[f"drive{i}_slip_margin_min"] <= 1.0 + 1e-12
    assert s["slip_margin_min_dyn"] <= 1.0 + 1e-12


def test_a_pulley_sliding_with_its_slack_side_slack_reads_no_grip():
    """downhill-regen on a 3 t take-up: its drive slides with the belt slack over its pulley
    (both sides 0 N, the belt gathering at the head). The capstan grip is then 0: margin 0,
    said as such, not the 1 of a pulley sliding at its grip."""
    conv = parse_conveyor({**load_mapping(CONVEYORS / "downhill-regen.yaml"),
                           "takeup": {**load_mapping(CONVEYORS / "downhill-regen.yaml")["takeup"],
                                      "mass_kg": 3000}})
    res = run_one(conv, Scenario(stop={"mode": "coast"}), model="din")
    s = res.summary
    assert (s["drive1_slip_s"] or 0.0) > 0.0, s
    assert s["drive1_slip_margin_min"] == 0.0
    assert s["slip_margin_min_dyn"] == 0.0
    assert "its slack side went slack while it slipped: no grip, slip margin 0" in s["message"]
