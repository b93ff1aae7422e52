"""Feed points along the carry, skirts, belt cleaners and ploughs (SPEC 7.1 ``material.feed``,
issue 28 item 3), against hand calculations on the hand conveyor (tests/conftest.py):
1000 m rising 50 m, v = 4 m/s, m'_G = 20 kg/m, m'_L = 720 / (3.6 x 4) = 50 kg/m (design),
m'_R = 10 kg/m carry and 3 kg/m return, B = 1 m, bulk density 1 t/m3."""

from __future__ import annotations

import math

import numpy as np
import pytest

from beltstudy.engine.conveyor import parse_conveyor
from beltstudy.engine.errors import InputError
from beltstudy.engine.loop import CARRY, G, build_loop
from beltstudy.engine.statics import solve_steady
from tests.conftest import hand_conveyor_dict

MG, ML, MRC, MRR, F = 20.0, 50.0, 10.0, 3.0, 0.020
V = 4.0
L, H = 1000.0, 50.0
#: DIN 22101 with C = 1: main resistances only (no secondary, no feed term)
DIN = {"f_carry": F, "f_return": F, "c": 1.0}


def conv(feed=None, accessories=None, **over):
    material = {"capacity_t_h": 720, "density_t_m3": 1.0}
    if feed is not None:
        material["feed"] = feed
    d = hand_conveyor_dict(material=material,
                           accessories=accessories or {"head_kn": 0.0, "tail_kn": 0.0}, **over)
    return parse_conveyor(d)


def test_skirt_friction_by_the_iso5048_formula():
    # ISO 5048:1989 / DIN 22101 skirt-board friction F_gL = mu_2 I_V^2 rho g l / (v^2 b_1^2)
    # I_V = 720 t/h / 3600 s/h / 1 t/m3 = 0.2 m3/s, rho = 1000 kg/m3, v = 4 m/s,
    # l = 10 m, b_1 = 0.7 m, mu_2 = 0.6:
    # F = 0.6 x 0.04 x 1000 x 9.81 x 10 / (16 x 0.49) = 300.31 N
    hand = 0.6 * 0.2**2 * 1000 * G * 10 / (V**2 * 0.7**2)
    assert hand == pytest.approx(300.306, abs=1e-3)
    c = conv([{"at_m": 0, "share": 1.0, "skirt_length_m": 10, "skirt_width_m": 0.7,
               "skirt_friction": 0.6}])
    res = solve_steady(c, model="din", params=DIN)
    assert res.summary["te_components_kn"]["accessories"] * 1e3 == pytest.approx(hand, rel=1e-9)
    # where the skirts sit: on the carry elements of the first 10 m only
    acc = res.law.parts(V, res.tension_mean_n)["accessories"]
    loop = res.loop
    under = (loop.strand == CARRY) & (loop.s_m < 10.0 - 1e-9)
    assert acc[~under].sum() == 0.0
    # default b_1 = 2/3 B (CEMA) = 0.667 m: F scales with 1 / b_1^2
    c2 = conv([{"at_m": 0, "share": 1.0, "skirt_length_m": 10}])
    r2 = solve_steady(c2, model="din", params=DIN)
    hand2 = 0.6 * 0.2**2 * 1000 * G * 10 / (V**2 * (2.0 / 3.0) ** 2)
    assert r2.summary["te_components_kn"]["accessories"] * 1e3 == pytest.approx(hand2, rel=1e-9)
    # no material, no pressure on the skirts
    r0 = solve_steady(c, model="din", params=DIN, load="empty")
    assert r0.summary["te_components_kn"]["accessories"] == 0.0


def test_skirt_of_a_second_feed_sees_all_the_material_upstream():
    # feed 0.5 at 0 and 0.5 at 300 m, skirts 8 m at the second: I_V there is the whole flow
    # 0.2 m3/s (both feeds), b_1 = 0.6 m: F = 0.6 x 0.04 x 1000 x 9.81 x 8 / (16 x 0.36)
    hand = 0.6 * 0.2**2 * 1000 * G * 8 / (V**2 * 0.6**2)
    c = conv([{"at_m": 0, "share": 0.5},
              {"at_m": 300, "share": 0.5, "skirt_length_m": 8, "skirt_width_m": 0.6}])
    res = solve_steady(c, model="din", params=DIN)
    assert res.summary["te_components_kn"]["accessories"] * 1e3 == pytest.approx(hand, rel=1e-9)


def test_tension_walk_with_a_feed_at_mid_carry():
    # all the material fed at 500 m: no material and no material lift upstream of it.
    # Carry walk (DIN 22101, f per element; the belt's own lift counted on the carry):
    # T_head - T_tail = f g [L m'_R + cos(a) (L m'_G + 500 m'_L)] + g (m'_G H + m'_L H / 2)
    # with sin(a) = 0.05 and no other resistances (C = 1, accessories 0).
    cos = math.sqrt(1 - 0.05**2)
    hand_walk = F * G * (L * MRC + cos * (L * MG + 500 * ML)) + G * (MG * H + ML * H / 2)
    # Te: the carry plus the return, F g [L m'_R,ret + cos L m'_G] - g m'_G H on the return
    hand_te = hand_walk + F * G * (L * MRR + cos * L * MG) - G * MG * H
    c = conv([{"at_m": 500, "share": 1.0}])
    res = solve_steady(c, model="din", params=DIN)
    loop = res.loop
    carry = np.flatnonzero(loop.strand == CARRY)
    T = res.tension_n
    t_tail = T[loop.n - 1]  # the end of the tail pulley: the start of the carry
    t_head = T[carry[-1]]
    assert t_head - t_tail == pytest.approx(hand_walk, rel=1e-9)
    assert res.te_n == pytest.approx(hand_te, rel=1e-9)
    assert res.summary["te_components_kn"]["lift"] * 1e3 == pytest.approx(G * ML * H / 2,
                                                                          rel=1e-9)
    # an element starts at the feed point: the load steps there, not inside an element
    mL = loop.mL_kg_m[carry]
    s = loop.s_m[carry]
    assert np.all(mL[s < 500 - 1e-9] == 0.0)
    assert np.all(mL[s >= 500 - 1e-9] == ML)
    assert np.any(np.isclose(s, 500.0, atol=1e-9))


def test_feed_point_between_element_boundaries_cuts_an_element():
    # 1000 m in 10 carry elements of 100 m: a feed at 250 m cuts the element 200..300
    c = conv([{"at_m": 0, "share": 0.7}, {"at_m": 250, "share": 0.3}])
    loop = build_loop(c, 1.0, n_elements=20)
    carry = loop.strand == CARRY
    s = loop.s_m[carry]
    assert np.any(np.isclose(s, 250.0))
    assert loop.dx_m[carry].sum() == pytest.approx(L, rel=1e-12)
    mL = loop.mL_kg_m[carry]
    assert np.allclose(mL[s < 250 - 1e-9], 0.7 * ML)
    assert np.allclose(mL[s >= 250 - 1e-9], ML)


def test_feed_acceleration_by_share():
    # DIN 22101 / ISO 5048 F_bA = I_m (v - v0), I_m = share x Q: Q = 720 t/h = 200 kg/s.
    # feed 0.6 at 0 (v0 = 0): 120 kg/s x 4 m/s = 480 N on the first carry element;
    # feed 0.4 at 500 m with v0 = 1 m/s: 80 kg/s x (4 - 1) m/s = 240 N on the element at 500 m
    c = conv([{"at_m": 0, "share": 0.6}, {"at_m": 500, "share": 0.4, "loading_speed_m_s": 1.0}])
    res = solve_steady(c, model="cema")
    feed = res.law.parts(V, res.tension_mean_n)["feed"]
    loop = res.loop
    j500 = int(np.flatnonzero(np.isclose(loop.s_m, 500.0) & (loop.strand == CARRY))[0])
    assert feed[0] == pytest.approx(480.0, rel=1e-12)
    assert feed[j500] == pytest.approx(240.0, rel=1e-12)
    assert np.count_nonzero(feed) == 2
    assert res.summary["te_components_kn"]["feed"] == pytest.approx(0.72, rel=1e-12)


def test_one_feed_at_the_tail_is_the_default():
    base = conv()
    one = conv([{"at_m": 0, "share": 1.0}])
    for model in ("din", "cema"):
        a = solve_steady(base, model=model)
        b = solve_steady(one, model=model)
        np.testing.assert_array_equal(a.tension_n, b.tension_n)


def test_scrapers_and_ploughs():
    # ISO 5048: belt cleaner F_r = A p mu_3 = 0.01 m2 x 5e4 N/m2 x 0.6 = 300 N;
    # plough F_a = B k_a = 1 m x 1500 N/m = 1500 N
    acc = {"head_kn": 0.0, "tail_kn": 0.0,
           "scrapers": [{"at": "head", "contact_area_m2": 0.01, "pressure_n_m2": 5e4}],
           "ploughs": [{"at_m": 400}]}
    res = solve_steady(conv(accessories=acc), model="din", params=DIN)
    assert res.summary["te_components_kn"]["accessories"] * 1e3 == pytest.approx(1800.0,
                                                                                 rel=1e-12)
    part = res.law.parts(V, res.tension_mean_n)["accessories"]
    loop = res.loop
    j = int(np.flatnonzero((loop.strand == CARRY) & (loop.s_m <= 400 + 1e-9))[-1])
    assert part[j] == pytest.approx(1500.0)


@pytest.mark.parametrize("feed, field", [
    ([{"at_m": 1000, "share": 1.0}], "material.feed.0.at_m"),
    ([{"at_m": 0, "share": 0.6}, {"at_m": 500, "share": 0.3}], "material.feed.1.share"),
    ([{"at_m": 100, "share": 0.5}, {"at_m": 100, "share": 0.5}], "material.feed.1.at_m"),
    ([{"at_m": 995, "share": 1.0, "skirt_length_m": 10}], "material.feed.0.skirt_length_m"),
    ([{"at_m": 0, "share": 1.0, "skirt_width_m": 0.8}], "material.feed.0.skirt_width_m"),
])
def test_feed_errors_name_the_field(feed, field):
    with pytest.raises(InputError, match=field.replace("[", r"\[").replace("]", r"\]")):
        conv(feed)


def test_the_transient_run_settles_onto_the_steady_tensions_with_feed_points():
    """The transient model reads the same per-element load and resistance law: slope-5pct
    fed 0.6 at the tail and 0.4 at 1230 m (an element is cut there), skirts at both, a belt
    cleaner at the head; after a 30 s start and 120 s of running the tensions are the steady
    ones within 1 % (as tests/engine/integration/test_dynamics_physics.py checks without
    feed points)."""
    from beltstudy.engine.conveyor import load_mapping
    from tests.conftest import CONVEYORS
    from tests.engine.conftest import assert_settles_to_statics

    data = load_mapping(CONVEYORS / "slope-5pct.yaml")
    data["material"]["feed"] = [
        {"at_m": 0, "share": 0.6, "skirt_length_m": 6, "skirt_width_m": 0.8},
        {"at_m": 1230, "share": 0.4, "skirt_length_m": 40}]
    data["accessories"]["scrapers"] = [{"at": "head", "contact_area_m2": 0.012,
                                        "pressure_n_m2": 6e4}]
    c = parse_conveyor(data)
    st = solve_steady(c, model="din", n_elements=80)
    assert np.any(np.isclose(st.loop.s_m, 1230.0))
    assert_settles_to_statics(c, st, start_s=30.0)


def test_skirt_friction_while_accelerating_counts_only_the_flow_fed_there():
    """ISO 5048's F_f = mu_2 rho g l_b A^2 / b_1^2 with A = I_V / ((v + v_0) / 2), the material's
    cross-section in the acceleration zone. Two feeds (0.7 at 100 m, fed at 0.5 m/s; 0.3 at
    600 m, fed at rest), 10 m skirts each, b_1 0.7 m, mu_2 0.6, mu_1 0.6, on the hand conveyor
    (I_V = 0.2 m3/s in all, v 4 m/s, rho 1000 kg/m3). At the second feed the 0.7 fed upstream
    already runs at v: A = 0.14 / 4 + 0.06 / 2 = 0.065 m2, not 0.2 / 2 = 0.1 m2 (the whole
    flow at the mean speed, 2.4 x the force). By hand, from the force the skirts add to DIN's
    secondary resistance with their F_gL taken out."""
    from beltstudy.engine.friction.din import acceleration_skirt_forces

    feed = [{"at_m": 100, "share": 0.7, "loading_speed_m_s": 0.5, "skirt_length_m": 10,
             "skirt_width_m": 0.7, "skirt_friction": 0.6},
            {"at_m": 600, "share": 0.3, "loading_speed_m_s": 0.0, "skirt_length_m": 10,
             "skirt_width_m": 0.7, "skirt_friction": 0.6}]
    c = conv(feed=feed)
    forces = acceleration_skirt_forces(build_loop(c), c, mu1=0.6)
    rho, b1, mu2 = 1000.0, 0.7, 0.6

    def f_f(area, v0):
        lb = (V * V - v0 * v0) / (2 * G * 0.6)
        return mu2 * rho * G * lb * area * area / (b1 * b1)
    first = f_f(0.14 / ((V + 0.5) / 2), 0.5)
    second = f_f(0.14 / V + 0.06 / (V / 2), 0.0)
    assert sorted(forces[forces > 0]) == pytest.approx(sorted([first, second]), rel=1e-9)
    assert second == pytest.approx(mu2 * rho * G * (16 / (2 * G * 0.6)) * 0.065**2 / 0.49)
