"""Assembling the transient model (engine/dynamics/model.py): the implicit blocks, Ernst's
chord law, the automatic step, the per-element arrays of a load pattern, and input the model
refuses."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from numpy.testing import assert_allclose

from beltstudy.engine.conveyor import Conveyor, InputError, Scenario, load_conveyor
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
    with pytest.raises(InputError, match=r"^drives.0\.inertia_kg_m2: .* too much work .* "
                                         r"fastest dol drive train"):
        build_system(conv, Scenario(elements=10000), st)


def test_too_much_work_set_by_a_short_element_names_the_point_that_cuts_it():
    """A second feed point 1 mm past the end of overland-16km's first section cuts a 1 mm
    carry element, and the automatic step follows it (1.3e-6 s): the run is too much work,
    and the error names the feed point to move, not the step or the mesh (fewer elements
    leave the 1 mm element as it is)."""
    d = load_conveyor(CONVEYORS / "overland-16km.yaml").model_dump(by_alias=True,
                                                                    exclude_none=True)
    d["material"]["feed"] = [{"at_m": 0.0, "share": 0.6}, {"at_m": 3000.001, "share": 0.4}]
    conv = Conveyor.model_validate(d)
    st = solve_steady(conv, model="din")
    with pytest.raises(InputError, match=r"^material\.feed\.1\.at_m: .* too much work .* "
                                         r"shortest belt element, 0\.001 m long between "
                                         r"material\.feed\.1\.at_m \(3000\.001 m\) and the "
                                         r"end of profile\.0"):
        build_system(conv, Scenario(), st)


def test_a_short_element_that_sets_the_step_is_a_note_naming_the_point():
    """A feed point 1 mm past the end of the hand conveyor's first section cuts a 1 mm
    element whose automatic step is a small fraction of the others': the run is right but
    slow, and its notes say which point to move and how far: a tenth of the median element
    (the carry's 30 elements over 1 000 m, 3.3 m, rounded up to 3.4 m); that far the note is
    gone and the step is many times longer."""
    def system(at_m):
        conv = hand_conv(profile=[{"length_m": 400, "lift_m": 20},
                                  {"length_m": 600, "lift_m": 30}],
                         material={"capacity_t_h": 720, "density_t_m3": 1.0,
                                   "feed": [{"at_m": 0.0, "share": 0.5},
                                            {"at_m": at_m, "share": 0.5}]})
        return build_system(conv, Scenario(elements=60), solve_steady(conv, model="din",
                                                                      n_elements=60))
    near, far = system(400.001), system(403.4)
    note = " ".join(near.notes)
    assert "the automatic step follows the shortest belt element, 0.001 m long" in note
    assert "material.feed.1.at_m (400.001 m)" in note and "the end of profile.0" in note
    assert "3.4 m or more away from it" in note
    assert not any("shortest belt element" in n for n in far.notes)
    assert near.dt_s < 0.05 * far.dt_s


def test_a_short_element_inside_a_curves_arc_is_given_the_radius_that_lengthens_it():
    """A vertical curve whose half arc is under a tenth of the median element cuts a short
    element between the arc's end and its middle (the section's end), and the note said "move
    profile.0.curve_radius_m onto the other point or ... m or more away from it", which a
    radius cannot do. The arc is ``R |delta|``: the note now names the radius that makes each
    half a tenth of the median element. 5 % to 4 % (delta 0.00998 rad) on a 200 m radius: a
    2.0 m arc; 20 elements round the 2 km loop (median about 100 m); the radius named gives
    no note and a step many times longer, 10 % less still gives it."""
    def system(radius):
        conv = hand_conv(profile=[{"length_m": 400, "lift_m": 20, "curve_radius_m": radius},
                                  {"length_m": 600, "lift_m": 24}])
        return build_system(conv, Scenario(elements=20), solve_steady(conv, model="din",
                                                                      n_elements=20))
    note = " ".join(system(200.0).notes)
    said = re.search(r"shortest belt element, [\d.]+ m long between the end of profile\.0 "
                     r"\(400 m\) and an end of the curve after profile\.0 \([\d.]+ m\) from the "
                     r"tail: a radius of (\d+) m or more \(profile\.0\.curve_radius_m, now 200 m\) "
                     r"makes each half of the curve's 2 m arc a tenth of the median element",
                     note)
    assert said, note
    need = float(said.group(1))
    delta = math.atan(20 / 400) - math.atan(24 / 600)
    assert 200.0 * delta == pytest.approx(2.0, rel=0.01)
    assert "onto the other point" not in note
    # the arc's end, 400 - 200 m x delta / 2 = 399.002 m, to a tenth of the 1 m element, not
    # to ten digits (p11's generated conveyors: "(2116.900896 m)")
    assert "and an end of the curve after profile.0 (399 m) from the tail" in note
    ok = system(need)
    assert not any("shortest belt element" in n for n in ok.notes)
    assert any("shortest belt element" in n for n in system(0.9 * need).notes)
    assert system(200.0).dt_s < 0.2 * ok.dt_s  # 0.00036 s against 0.0034 s


@pytest.mark.parametrize("load", ["inclines", "declines", [0.5, 1.0]])
def test_transient_model_runs_on_the_same_per_element_masses(load):
    """The transient model reads the loop's per-element arrays: its gravity and masses are the
    pattern's, and the running phase settles onto the pattern's steady tensions (1 %). (60 s
    of running: the belt's swing as one body against the speed loop's integrator, damped
    by ``Kp / M`` only, takes about 10 s to decay by e on this belt at the default
    bandwidth: 1.1 % off after 40 s, 0.12 % after 60 s.)"""
    conv = two_sections()
    st = solve_steady(conv, model="din", params=DIN, load=load, n_elements=60)
    scn = Scenario(load=load, elements=60, start={"time_s": 20}, run_s=60)
    sys = build_system(conv, scn, st)
    loop = st.loop
    assert_allclose(sys.model.nodes.gravity, loop.gravity_n, rtol=1e-12)
    assert_allclose(sys.model.nodes.w_mean, loop.mass_kg, rtol=1e-12)
    res = simulate(sys, t_end_s=sys.stop_command_s - sys.dt_s)
    assert res.status != "failed", res.message
    T = res.raw["tension"]
    assert np.max(np.abs(T - st.tension_n) / st.tension_n) < 0.01


def test_speed_loop_bandwidth_from_the_drive_the_options_or_the_default():
    """The master's ``speed_loop_rad_s`` sets the loop's bandwidth, the options override it,
    and without either it is the sourced default; the gains are ``2 omega_c M_loop`` and
    ``omega_c^2 M_loop``."""
    from beltstudy.engine.dynamics import DynamicsOptions
    from beltstudy.engine.dynamics.model import DEFAULT_SPEED_LOOP_RAD_S

    scn = Scenario(start={"time_s": 20}, run_s=5, elements=40)
    for drive, opts, want in (({}, None, DEFAULT_SPEED_LOOP_RAD_S),
                              ({"speed_loop_rad_s": 2.0}, None, 2.0),
                              ({"speed_loop_rad_s": 2.0}, DynamicsOptions(
                                  controller_bandwidth_rad_s=0.7), 0.7)):
        conv = hand_conv(drives=[hand_drive(**drive)])
        st = solve_steady(conv, model="din", n_elements=40)
        ctl = build_system(conv, scn, st, opts).model.control
        assert ctl.bandwidth == want
        m_loop = ctl.kp / (2.0 * want)
        assert ctl.ki == pytest.approx(want * want * m_loop, rel=1e-12)


def test_speed_loop_sees_the_shaft_and_the_belt_a_wave_reaches():
    """On a long belt the loop's mass is the master's shaft plus the belt a wave reaches in
    ``1 / omega_c`` on each side, ``(Z_in + Z_out) / omega_c`` with ``Z = rho' c`` (by hand
    from the elements beside the pulley), over the master end's share; on a short stiff one
    it is capped at all moving mass (rigid body); no feedforward by default."""
    from beltstudy.engine.dynamics.model import loop_inertia

    conv = load_conveyor(CONVEYORS / "overland-16km.yaml")
    st = solve_steady(conv, model="din", n_elements=80)
    sysm = build_system(conv, Scenario(start={"time_s": 300}, run_s=5, elements=80), st)
    ctl = sysm.model.control
    loop = st.loop
    j = int(loop.drive_elements[0])  # the head drive is the master (share 0.67) alone there
    z = loop.mass_kg / loop.dx_m * sysm.wave_speed_m_s
    shaft = float(sysm.model.shafts.mass[list(sysm.model.shafts.node).index(j)])
    wc = ctl.bandwidth
    by_hand = (shaft + (z[j - 1] + z[j + 1]) / wc) / 0.67
    assert ctl.kp == pytest.approx(2.0 * wc * by_hand, rel=1e-9)
    total = float(sysm.model.nodes.mass.sum() + sysm.model.shafts.mass.sum())
    assert by_hand < 0.1 * total  # a long belt: far less than the whole belt
    assert ctl.ff == 0.0  # no rigid-body feedforward by default
    index = {int(k): i for i, k in enumerate(sysm.model.shafts.node)}
    assert loop_inertia(conv, loop, sysm.model.shafts, index, sysm.wave_speed_m_s, wc,
                        total) == pytest.approx(by_hand, rel=1e-9)
    assert loop_inertia(conv, loop, sysm.model.shafts, index, sysm.wave_speed_m_s, wc,
                        0.5 * by_hand) == 0.5 * by_hand  # capped at all moving mass


def test_the_breakaway_take_up_keeps_the_rest_state_within_the_grip():
    """The auto take-up's breakaway constraint (slip_breakaway: the drive takes the loaded
    decline's whole gravity pull at standstill) and the rest-state grip check are the same
    Euler-Eytelwein condition on the held pulley: with the auto size the rest state is
    within the grip, and its slack side is at least pull / (e^(mu theta) - 1)."""
    conv = load_conveyor(CONVEYORS / "downhill-regen.yaml")
    st = solve_steady(conv, model="din", n_elements=40)
    assert st.summary["takeup_governed_by"] == "slip_breakaway"
    sys = build_system(conv, Scenario(elements=40), st)
    assert [w for w in sys.warnings if w.startswith("at rest the")] == []


@pytest.mark.parametrize("name, beyond", [("downhill-regen", True), ("slope-5pct", False)])
def test_a_rest_state_beyond_the_held_pulleys_grip_is_said(name, beyond):
    """The pulley holding the belt at rest (the first brake's, else the master drive's)
    passes at most T_slack (e^(mu theta) - 1) (Euler-Eytelwein, static friction). The loaded
    decline's head brake holds the whole downhill pull on a pulley whose slack side the
    take-up keeps low: the system says so, with the grip computed here by hand from the rest
    tensions; the incline's rest state is within its grip and says nothing."""
    conv = load_conveyor(CONVEYORS / f"{name}.yaml")
    if beyond:  # a take-up lighter than the breakaway size (slip_breakaway, 102 t) given
        conv = conv.model_copy(update={"takeup": conv.takeup.model_copy(
            update={"mass_kg": 60000.0})})
    st = solve_steady(conv, model="din", n_elements=40)
    sys = build_system(conv, Scenario(elements=40), st)
    said = [w for w in sys.warnings if w.startswith("at rest the")]
    T = sys.tension_rest_n
    if not beyond:
        assert said == []
        return
    assert len(said) == 1, sys.warnings
    pulley = next(d for d in conv.drives if d.position == "head")
    held = float(re.search(r"passes ([\d.]+) kN", said[0]).group(1))
    grip = float(re.search(r"grip of ([\d.]+) kN", said[0]).group(1))
    slack = float(re.search(r"slack side ([\d.]+) kN", said[0]).group(1))
    assert grip == pytest.approx(slack * math.expm1(pulley.friction
                                                    * math.radians(pulley.wrap_deg)), rel=1e-3)
    assert held > grip
    assert held * 1e3 == pytest.approx(np.max(np.abs(np.diff(T))), rel=1e-3)


def test_a_fixed_step_too_small_for_any_mesh_is_refused_before_the_model_is_built():
    """A fixed dt_s of 1e-9 s was accepted by a study's door and every run then failed when
    its model was built (3.4e11 steps). The scenario alone bounds the work: the cycle is at
    least 2 s of rest + the 60 s start + the 30 s run + the 300 s stop window + 5 s, and a
    fixed step makes (2 + 60 + 30 + 300 + 5) / 1e-9 = 3.97e11 steps, over 5e10 element-steps
    on any mesh: check_scenario (which a dynamic study's door runs on every variant) refuses
    it naming dt_s. 1e-5 s on 100 elements, 4e9 element-steps, passes."""
    from beltstudy.engine.dynamics.model import check_scenario

    conv = hand_conv()
    with pytest.raises(InputError, match=r"^scenario\.dt_s: 1e-09 s makes at least 3\.97e\+11 "
                                         r"steps, too much work for one run \(over 5e10 "
                                         r"element-steps; a cycle of at least 397 s"):
        check_scenario(Scenario(dt_s=1e-9), conv)
    with pytest.raises(InputError, match=r"^scenario\.dt_s: 1e-06 s makes at least 3\.97e\+08 "
                                         r"steps of 200 elements"):
        check_scenario(Scenario(dt_s=1e-6, elements=200), conv)
    check_scenario(Scenario(dt_s=1e-5, elements=100), conv)


def test_a_short_section_that_sets_the_step_is_named_by_its_own_length():
    """A 1 mm profile section between two others is itself the short element: the note named
    the section before it ('move profile.0.length_m onto the other point or ... m or more away
    from it'), which shifts both of the short element's ends alike; it now names the short
    section and the length that lifts it to a tenth of the median element: at that length the
    note is gone, at 0.8 of it the section still sets the step."""
    def system(short_m):
        conv = hand_conv(profile=[{"length_m": 400, "lift_m": 20},
                                  {"length_m": short_m, "lift_m": 0},
                                  {"length_m": 600 - short_m, "lift_m": 30}])
        return build_system(conv, Scenario(elements=60), solve_steady(conv, model="din",
                                                                      n_elements=60))
    note = " ".join(system(0.001).notes)
    said = re.search(r"profile\.1 is 0\.001 m long; give it ([\d.]+) m or more \(a tenth of "
                     r"the median element\) or join it to a neighbouring section", note)
    assert said, note
    assert "move profile.0.length_m" not in note
    need = float(said.group(1))
    assert 3.0 < need < 4.0  # a tenth of about 1 000 m / 30 carry elements
    assert not any("shortest belt element" in n for n in system(need).notes)
    assert any("profile.1 is" in n for n in system(0.8 * need).notes)


def test_a_short_piece_of_a_curves_arc_is_given_the_radius_that_lengthens_it():
    """A curve turning more than a degree each side of its middle is cut in pieces, and a
    piece far shorter than the median element sets the step. The note said "move
    profile.0.curve_radius_m onto the other point or ... away from it": there is no other
    point, and a radius is not moved. Each piece is ``R x its turn``, so the note names the
    radius that makes it a tenth of the median element: +4 % into level on R 208 m is an
    8.3 m arc (0.04 rad), about 2.1 m a piece; the radius named gives no such note."""
    def system(radius):
        conv = hand_conv(profile=[{"length_m": 400, "lift_m": 16, "curve_radius_m": radius},
                                  {"length_m": 600, "lift_m": 0}])
        return build_system(conv, Scenario(elements=20), solve_steady(conv, model="din",
                                                                      n_elements=20))
    note = " ".join(system(208.0).notes)
    said = re.search(r"shortest belt element, ([\d.]+) m long .*?: a radius of (\d+) m or more "
                     r"\(profile\.0\.curve_radius_m, now 208 m\) makes each piece of the "
                     r"curve's arc a tenth of the median element", note)
    assert said, note
    assert "onto the other point" not in note
    piece, need = float(said.group(1)), float(said.group(2))
    assert 208.0 * math.atan(16 / 400) / 4 == pytest.approx(piece, rel=0.02)
    assert "shortest belt element" not in " ".join(system(need).notes)
