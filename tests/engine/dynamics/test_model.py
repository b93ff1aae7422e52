"""Assembling the transient model (engine/dynamics/model.py): the implicit blocks, Ernst's
chord law, the automatic step, the per-element arrays of a load pattern, and input the model
refuses."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from beltstudy.engine.conveyor import InputError, Scenario, load_conveyor
from beltstudy.engine.dynamics import build_system, simulate
from beltstudy.engine.dynamics.model import chord_strain, implicit_blocks, stability_limit_s
from beltstudy.engine.statics import solve_steady
from tests.conftest import CONVEYORS
from tests.engine.conftest import DIN, hand_conv, hand_drive, two_sections


def test_blocks_cover_the_pulleys_and_wrap_at_the_tail():
    conv = load_conveyor(CONVEYORS / "overland-16km.yaml")
    st = solve_steady(conv, n_elements=40)
    loop = st.loop
    implicit, blocks = implicit_blocks(loop.strand)
    n = loop.n
    # head pulley, head take-up pulley, tail pulley: their springs on both sides are implicit
    for p in (loop.i_head, loop.i_takeup, loop.i_tail):
        assert implicit[p] and implicit[p - 1]
    assert [loop.i_head - 1, loop.i_head, loop.i_takeup, loop.i_takeup + 1] in blocks
    assert [n - 2, n - 1, 0] in blocks
    assert implicit.sum() == 5


def test_ernst_tangent_modulus_is_the_chord_law_derivative():
    """EB_eq(T) = EB / (1 + (w S)^2 EB / (12 T^3)) = dT / d(strain) of the chord law
    strain = T / EB - (w S)^2 / (24 T^2); checked by a finite difference (1e-6)."""
    eb, w_s = 6e7, 9.81 * 20 * 3.0
    a = w_s**2 / 12.0
    t_floor, k_floor = np.array([1.0]), np.array([eb])
    for T in (2e3, 12e3, 1e5):
        h = T * 1e-6
        de = chord_strain(np.array([T + h]), a, eb, t_floor, k_floor) \
            - chord_strain(np.array([T - h]), a, eb, t_floor, k_floor)
        tangent = eb / (1.0 + w_s**2 * eb / (12.0 * T**3))
        assert 2 * h / de[0] == pytest.approx(tangent, rel=1e-6)
    # low tension softens: at T^3 = a EB the modulus halves
    T_half = (a * eb) ** (1.0 / 3.0)
    assert eb / (1.0 + a * eb / T_half**3) == pytest.approx(eb / 2)


def test_step_is_half_the_wave_limit_and_scales_with_dx():
    """For a uniform chain the limit is exactly dx / c; the automatic step is half of it and
    halves with the element length, damping on."""
    n, dx, eb, rho = 50, 10.0, 6e7, 30.0
    lim = stability_limit_s(np.full(n, rho * dx), np.full(n, dx), eb)
    assert lim == pytest.approx(dx / math.sqrt(eb / rho), rel=1e-12)
    conv = load_conveyor(CONVEYORS / "overland-16km.yaml")
    dts = []
    for n_el in (200, 400, 800):
        sys = build_system(conv, Scenario(), solve_steady(conv, n_elements=n_el))
        assert sys.damping == "belt"
        assert sys.dt_s == pytest.approx(0.5 * sys.dt_limit_s)
        dts.append(sys.dt_s)
    assert dts[0] / dts[1] == pytest.approx(2.0, rel=0.1)
    assert dts[1] / dts[2] == pytest.approx(2.0, rel=0.1)


def test_too_much_work_set_by_a_drive_train_names_the_inertia():
    """A motor behind its coupling given no inertia (its mass floored at 1 kg at the rim) on a
    fine mesh: the step the drive train needs makes the run too much work, and the error names
    the drives' inertia as the field to fix, not the step or the mesh."""
    conv = hand_conv(drives=[hand_drive(control="dol", rated_power_kw=240, inertia_kg_m2=2.0,
                                        motor_inertia_kg_m2=0.0, coupling="fluid")],
                     takeup={"type": "gravity", "position": "tail", "mass_kg": 16000})
    st = solve_steady(conv, model="din", n_elements=10000)
    with pytest.raises(InputError, match=r"^drives\[0\]\.inertia_kg_m2: .* too much work .* "
                                         r"fastest dol drive train"):
        build_system(conv, Scenario(elements=10000), st)


@pytest.mark.parametrize("load", ["inclines", "declines", [0.5, 1.0]])
def test_transient_model_runs_on_the_same_per_element_masses(load):
    """The transient model reads the loop's per-element arrays: its gravity and masses are the
    pattern's, and the running phase settles onto the pattern's steady tensions (1 %)."""
    conv = two_sections()
    st = solve_steady(conv, model="din", params=DIN, load=load, n_elements=60)
    scn = Scenario(load=load, elements=60, start={"time_s": 20}, run_s=40)
    sys = build_system(conv, scn, st)
    loop = st.loop
    assert_allclose(sys.model.nodes.gravity, loop.gravity_n, rtol=1e-12)
    assert_allclose(sys.model.nodes.w_mean, loop.mass_kg, rtol=1e-12)
    res = simulate(sys, t_end_s=sys.stop_command_s - sys.dt_s)
    assert res.status != "failed", res.message
    T = res.raw["tension"]
    assert np.max(np.abs(T - st.tension_n) / st.tension_n) < 0.01
