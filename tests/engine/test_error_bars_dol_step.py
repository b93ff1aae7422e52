"""The error bars of a run whose automatic step was shortened to resolve a dol drive train.

The bars rerun the cycle on a mesh half and twice as fine with the step following the mesh
(the run's Courant number), so the finer mesh also takes the finer step. An automatic step
shortened below that by the fastest dol drive train (its light motor behind a fluid coupling)
kept the same step on every mesh: a 1 km 14 deg EP1600/4 incline's drive peak force was
314.7 kN on 102, 202 and 406 elements at 2.08 ms (+- 0.31 kN, the bar's floor), and 302.4 kN at
half the step. The finer mesh now takes the finer step too."""
from __future__ import annotations

import pytest

import beltstudy.engine.accuracy as accuracy
from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.run import run_one

STEEP_DOL = {
    "name": "steep-dol", "speed_m_s": 2.5,
    "belt": {"type": "EP1600/4", "width_m": 1.2},
    "material": {"capacity_t_h": 300, "density_t_m3": 1.5},
    "profile": [{"length_m": 600, "lift_m": 145.2}],
    "idlers": {"carry": {"spacing_m": 1.0, "roll_diameter_m": 0.127, "rolls": 3,
                         "trough_deg": 35, "cema_class": "D"},
               "return": {"spacing_m": 3.0, "roll_diameter_m": 0.127, "rolls": 1,
                          "cema_class": "C"}},
    "drives": [{"position": "head", "wrap_deg": 220, "friction": 0.35, "share": 1.0,
                "pulley_diameter_m": 0.8, "inertia_kg_m2": 80, "rated_power_kw": 500,
                "control": "dol", "coupling": "fluid"}],
    "takeup": {"type": "gravity", "position": "tail", "mass_kg": 3000, "travel_m": 6},
    "holdback": True,
}


def test_the_finer_mesh_of_the_bars_takes_the_finer_step_under_a_dol_drive_train(monkeypatch):
    """The run's step is the drive train's (half the time its 53.3 kg m2 motor, 333 kg at the
    belt line, takes to reach 2.5 m/s at the rated 200 kN: 333 x 2.5 / 200e3 / 2 = 2.08 ms),
    below half the mesh's stability limit. The mesh twice as fine keeps the run's Courant
    number, dt n = const (the stability limit goes as the spring length, dx / c): half the
    step. The coarser mesh's longer step is shortened to the drive train's again."""
    seen: list[tuple[int, float]] = []
    real = accuracy.error_bars

    def spy(scenario, summary, rerun, **kw):
        def recorded(scn):
            s = rerun(scn)
            seen.append((int(s["elements_used"]), float(s["dt_used_s"])))
            return s
        return real(scenario, summary, recorded, **kw)

    monkeypatch.setattr(accuracy, "error_bars", spy)
    conv = parse_conveyor(STEEP_DOL)
    res = run_one(conv, Scenario(elements=60, run_s=5.0), model="din", check=True)
    s = res.summary
    n, dt = int(s["elements_used"]), float(s["dt_used_s"])
    train = 53.333 * (2.0 / 0.8) ** 2 * 2.5 / 200e3 / 2.0
    assert dt == pytest.approx(train, rel=1e-3)
    assert "resolves the fastest dol drive train" in s["message"]
    # (a run that slipped is also run on its own mesh at half its step: accuracy.step_bar)
    assert all(d == pytest.approx(dt / 2, rel=1e-9) for m, d in seen if m == n)
    (n_c, dt_c), (n_f, dt_f) = sorted(x for x in seen if x[0] != n)
    assert n_c < n < n_f
    assert dt_c == pytest.approx(dt, rel=1e-9)  # the coarse mesh: the drive train's step
    assert dt_f * n_f == pytest.approx(dt * n, rel=0.05)  # the fine mesh: half the step
