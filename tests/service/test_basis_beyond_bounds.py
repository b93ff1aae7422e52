"""A study's design basis keeps an auto size beyond its field's bound auto in its runs, as it
did the take-up's: a motor over 30 000 kW or a brake over 17 280 kN written into a run's
conveyor failed that run on a field the file leaves out (tests/engine/test_auto_beyond_bounds.py
has the warnings the runs then give)."""
from __future__ import annotations

from beltstudy.engine.conveyor import FORCE_MAX_KN, POWER_MAX_KW
from beltstudy.service.grid.basis import apply_sizes


def test_a_study_keeps_a_size_beyond_the_bound_auto():
    conv = {"takeup": {"type": "gravity", "mass_kg": "auto"},
            "drives": [{"rated_power_kw": None}, {"rated_power_kw": None}],
            "brakes": [{"force_kn": "auto"}], "belt": {"type": "ST2000"}}
    sizes = {"drives": [{"rated_power_kw": 2 * POWER_MAX_KW, "governed_by": "peripheral_force"},
                        {"rated_power_kw": 500.0, "governed_by": "peripheral_force"}],
             "brakes": {"holding": {"force_kn": [2 * FORCE_MAX_KN],
                                    "governed_by": ["holding"]}, "stop_time_s": {}}}
    out, governed = apply_sizes(conv, sizes, {}, dynamics=False)
    assert out["drives"][0]["rated_power_kw"] is None  # beyond: the run sizes its own
    assert out["drives"][1]["rated_power_kw"] == 500.0
    assert out["brakes"][0]["force_kn"] == "auto"
    # what set a size kept auto is the run's own to say, not the design's
    assert "rated_power_governed_by" not in governed
    assert "brake_governed_by" not in governed
