"""Calibration (SPEC 7.3) of a name that moves none of the measured values: Non-Lin's seal
drag per roll where the conveyor file gives the idlers' own seal_drag_n (the law reads the
file's), and material flexure on rows all measured with the belt empty (no load to flex)."""

from __future__ import annotations

import pytest

from beltstudy.engine import load_conveyor, solve_steady
from beltstudy.engine.calibration import Measurement, calibrate
from tests.conftest import CONVEYORS

LOADS = (0.2, 0.5, 0.8, 1.0)


@pytest.fixture(scope="module")
def with_seal_drag():
    # the file's carry and return seal drag (per idler set) take the place of
    # Non-Lin's drag_per_roll_n (docs: "used where the conveyor file gives no seal_drag_n")
    conv = load_conveyor(CONVEYORS / "overland-4km.yaml")
    idlers = conv.idlers.model_copy(update={
        "carry": conv.idlers.carry.model_copy(update={"seal_drag_n": 3.9}),
        "return_": conv.idlers.return_.model_copy(update={"seal_drag_n": 1.3})})
    return conv.model_copy(update={"idlers": idlers})


def _rows(conv, params, loads, temperatures=(10.0, 10.0, 10.0, 10.0)):
    """Power the engine makes at ``params``, alternately 0.4 % low and high."""
    return [Measurement(load, t, {"power_kw": solve_steady(
        conv, model="nonlin", params=params, temperature_c=t, load=load
    ).summary["power_kw"] * (1 + 0.004 * (-1) ** (k + 1))})
        for k, (load, t) in enumerate(zip(loads, temperatures, strict=True))]


def test_a_single_name_the_rows_do_not_see_is_held_and_said_so(with_seal_drag):
    # before: the only name held, nothing was fitted and the standard errors' Jacobian of
    # no columns raised "ValueError: need at least one array to concatenate" (a traceback
    # from beltstudy calibrate, 500 from POST /calibrations)
    conv = with_seal_drag
    p1 = solve_steady(conv, model="nonlin", params={"drag_per_roll_n": 1.0}, temperature_c=10.0,
                      load=0.5).summary["power_kw"]
    p3 = solve_steady(conv, model="nonlin", params={"drag_per_roll_n": 3.0}, temperature_c=10.0,
                      load=0.5).summary["power_kw"]
    assert p1 == p3  # the file's seal drag is read, not drag_per_roll_n
    rows = _rows(conv, {}, LOADS)
    cal = calibrate(conv, rows, "nonlin", ["drag_per_roll_n"])
    assert cal.status == "warning"
    assert cal.not_identifiable == ["drag_per_roll_n"]
    assert cal.held == {"drag_per_roll_n": 1.0}
    assert cal.fit["drag_per_roll_n"] == {"value": 1.0, "se": None, "start": 1.0, "ci95": None}
    # four rows, nothing fitted: four degrees of freedom; the model at the defaults gives
    # each row's power P, so a row read P (1 + e) has the residual (P - P (1 + e)) / (P (1 + e))
    # = -e / (1 + e): +0.4016 % for e = -0.4 %, -0.3984 % for e = +0.4 % (the auto take-up,
    # held at one size for every row, moves the third and fourth by under 1e-8)
    assert cal.dof == 4
    assert [r["relative"] for r in cal.residuals] == pytest.approx(
        [0.004 / 0.996, -0.004 / 1.004, 0.004 / 0.996, -0.004 / 1.004], abs=1e-7)
    assert "drag_per_roll_n changes none of the modelled values of these rows" in cal.message
    assert "apart" not in cal.message  # no other name to tell it apart from
    assert cal.notes[0].startswith("drag_per_roll_n: changes none of the modelled values")


def test_material_flexure_on_empty_rows_is_held_beside_a_fitted_name(with_seal_drag):
    # material flexure (p_mf) needs load on the belt; with every row empty mu_b is fitted
    # (the bearing term carries the belt's own mass) and p_mf is held, not grouped with it
    conv = with_seal_drag
    rows = _rows(conv, {"mu_b": 0.002}, ["empty"] * 4, (-10.0, 0.0, 10.0, 25.0))
    cal = calibrate(conv, rows, "nonlin", ["mu_b", "p_mf"])
    assert cal.not_identifiable == ["p_mf"]
    assert cal.held == {"p_mf": 0.4}
    assert cal.fit["mu_b"]["se"] is not None
    assert "p_mf changes none of the modelled values" in cal.message
    assert "cannot tell" not in cal.message


def test_one_row_for_one_name_is_said_in_the_singular(with_seal_drag):
    # one reading fixes one name exactly: "1 measured values for as many fitted names are
    # met" before; mu_b is read here (the bearing term), the seal drag is the file's
    rows = _rows(with_seal_drag, {"mu_b": 0.002}, [0.5], (10.0,))
    cal = calibrate(with_seal_drag, rows, "nonlin", ["mu_b"])
    assert cal.status == "warning" and cal.dof == 0
    assert cal.message.startswith(
        "converged, but 1 measured value for as many fitted names is met exactly")
