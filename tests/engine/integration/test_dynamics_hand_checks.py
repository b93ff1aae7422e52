"""Hand checks of a whole cycle on a short level belt where the figures are clean (300 m,
loaded carry 60 kg/m, return 30 kg/m, EB 10 000 kN, E_dyn B 15 000 kN, DIN, s-curve start
60 s, coast stop), each against a law with its tolerance:

* a power failure is a tension step Z dv at the drive pulley: the drive force F vanishes,
  the pulley and the belt beside it lose dv = F / (Z_c + Z_r), the carry entering the
  pulley drops by Z_c dv and the return leaving it rises by Z_r dv (2 %), Z = sqrt(E_dyn B
  rho'); read 5 shaft time constants m_p / (Z_c + Z_r) after the trip (27 ms here);
* the take-up carriage, running, takes in half the belt's running stretch, 1/2 int (T_run -
  T_rest) / EB (2 %), and at the s-curve's peak acceleration a the acceleration's stretch
  beside it, (m'_c - m'_r) a L^2 / (4 EB) (the carry's tension gains m'_c a s from the
  take-up at the tail, the return's loses m'_r a (L - x)) (3 %);
* the coast stop is the rigid body's: stop time to 1 % of speed 0.99 M v / Te and the
  stopping distance M v^2 / (2 Te), the kinetic energy spent on the work of the resistances
  Te d (1 %; DIN's resistance is constant while the belt moves).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.run import run_one

L, V = 300.0, 2.0
RHO_C, RHO_R = 60.0, 30.0  # belt 20 + load 30 + idlers 10; belt 20 + idlers 10 [kg/m]
EB, EB_DYN = 10000e3, 15000e3


def linear_conveyor():
    return parse_conveyor({
        "name": "linear-300m",
        "speed_m_s": V,
        "belt": {"width_m": 1.0, "rating_kn_m": 1000, "modulus_kn_m": EB / 1e3,
                 "dynamic_modulus_kn_m": EB_DYN / 1e3, "carcass_mass_kg_m2": 20.0,
                 "top_cover_mm": 0, "bottom_cover_mm": 0},
        "material": {"capacity_t_h": 216, "density_t_m3": 1.0, "loading_speed_m_s": 0.0},
        "profile": [{"length_m": L, "lift_m": 0.0}],
        "idlers": {"carry": {"spacing_m": 1.25, "rotating_mass_kg": 12.5, "seal_drag_n": 5.0},
                   "return": {"spacing_m": 2.5, "rotating_mass_kg": 25.0, "seal_drag_n": 3.0}},
        "drives": [{"position": "head", "wrap_deg": 200, "friction": 0.35,
                    "pulley_diameter_m": 1.0, "inertia_kg_m2": 0.0}],
        "takeup": {"type": "gravity", "position": "tail", "mass_kg": 8000},
    })


@pytest.fixture(scope="module")
def run():
    return run_one(linear_conveyor(), Scenario(start={"control": "s-curve", "time_s": 60},
                                               run_s=30, stop={"mode": "coast"},
                                               record_dt_s=0.002),
                   model="din", check=False, remedy=False)


def test_the_moving_masses_are_the_hand_ones(run):
    s = run.summary
    assert s["belt_mass_kg_m"] + s["load_mass_kg_m"] + s["idler_mass_carry_kg_m"] == \
        pytest.approx(RHO_C, rel=1e-9)
    assert s["belt_mass_kg_m"] + s["idler_mass_return_kg_m"] == pytest.approx(RHO_R, rel=1e-9)
    assert s["belt_modulus_dyn_kn"] * 1e3 == pytest.approx(EB_DYN, rel=1e-12)


def test_a_power_failure_is_a_tension_step_z_dv_at_the_drive(run):
    sy, ts = run.transient.system, run.timeseries
    t = ts["t_s"].to_numpy()
    i0 = int(np.searchsorted(t, sy.stop_command_s)) - 1  # last record before the trip
    f = ts["f_drive_kn"].iloc[i0] * 1e3
    assert f == pytest.approx(sy.te_n, rel=0.01)  # running: the drive gives Te
    zc, zr = math.sqrt(EB_DYN * RHO_C), math.sqrt(EB_DYN * RHO_R)
    dv = f / (zc + zr)
    tau = float(sy.model.shafts.mass[0]) / (zc + zr)
    j = int(np.searchsorted(t, sy.stop_command_s + 5 * tau))
    assert ts["v_drive_m_s"].iloc[i0] - ts["v_drive_m_s"].iloc[j] == pytest.approx(dv, rel=0.02)
    assert (ts["t_head_in_kn"].iloc[i0] - ts["t_head_in_kn"].iloc[j]) * 1e3 == \
        pytest.approx(zc * dv, rel=0.02)
    assert (ts["t_head_out_kn"].iloc[j] - ts["t_head_out_kn"].iloc[i0]) * 1e3 == \
        pytest.approx(zr * dv, rel=0.02)


def test_the_carriage_takes_in_the_running_and_the_acceleration_stretch(run):
    sy, ts = run.transient.system, run.timeseries
    t, x = ts["t_s"].to_numpy(), ts["x_takeup_m"].to_numpy()
    sp = sy.model.springs
    x_run = 0.5 * float(np.sum(sp.len_m * (sy.steady_tension_n - sy.tension_rest_n))) / EB
    i0 = int(np.searchsorted(t, sy.stop_command_s)) - 1
    assert x[i0] == pytest.approx(x_run, rel=0.02)
    a = np.gradient(ts["v_ref_m_s"].to_numpy(), t)
    k = int(np.argmax(a))
    assert a[k] == pytest.approx(2 * V / 60.0, rel=0.01)  # the s-curve's peak, 2 v / t
    x_acc = (RHO_C - RHO_R) * a[k] * L ** 2 / (4 * EB)
    assert x[k] == pytest.approx(x_run + x_acc, rel=0.03)
    assert x_acc > 0.2 * x_run  # the check sees the acceleration's part


def test_a_coast_stop_is_the_rigid_body_s_and_spends_its_kinetic_energy_on_the_resistances(run):
    sy, s = run.transient.system, run.summary
    m = float(sy.model.nodes.mass.sum() + sy.model.shafts.mass.sum())
    assert m == pytest.approx(L * (RHO_C + RHO_R), rel=0.08)  # plus the pulleys' estimate
    te = sy.te_n
    assert s["stop_time_s"] == pytest.approx(0.99 * m * V / te, rel=0.01)
    assert s["stop_distance_m"] == pytest.approx(m * V ** 2 / (2 * te), rel=0.01)
    assert te * s["stop_distance_m"] == pytest.approx(0.5 * m * V ** 2, rel=0.01)
