"""Calibration (SPEC 7.3): whether a fitted name ended at its bound depends on the data, not on
where the fit started."""

from __future__ import annotations

import numpy as np
import pytest

from beltstudy.engine import load_conveyor
from beltstudy.engine.calibration import _at_bound, calibrate, measurements_from_rows
from tests.conftest import CONVEYORS

#: Ten steady powers [kW] of the 5 % slope made by Non-Lin with 2 % noise (a tester's file):
#: load, ambient [C], power at the drive pulleys [kW].
ROWS = [(0.0, -20, 144.3370801346383), (0.3, 18, 261.99855280232424),
        (0.5, 12, 417.8529823190316), (0.7, 6, 551.9241631631025),
        (0.9, 15, 676.6985568497333), (1.0, 22, 740.4368890560282),
        (0.6, 2, 476.3517651973111), (0.8, -10, 668.1051934060217),
        (0.2, -25, 295.72486438697024), (1.0, 30, 785.176565929346)]


@pytest.fixture(scope="module")
def slope():
    """slope-5pct with the plant's counterweight, 18 t (not sized by the fit)."""
    conv = load_conveyor(CONVEYORS / "slope-5pct.yaml")
    tu = conv.takeup.model_copy(update={"mass_kg": 18000.0})
    return conv.model_copy(update={"takeup": tu})


def test_a_fit_at_the_bound_is_said_so_whatever_its_start(slope):
    """drag_per_roll_n and m_star fitted to these rows end with m_star at about 0 (3.7e-7 from
    the default start 0.0035, 2.8e-7 from 0.007; standard error 0.012 either way). The verdict
    counted a value below 1e-4 x its start as at the bound: 'ok', exit 0, from 0.0035 (3.7e-7
    is 1.05e-4 of it), 'warning ... ends at the bound 0' with m_star not identifiable from
    0.007 (3.9e-5 of it), on the same values, standard errors and residuals. The data would
    take m_star to -5.8e-5 (the Gauss-Newton step from the fit): at the bound from every
    start."""
    rows = measurements_from_rows([{"load": ld, "temperature_c": t, "power_kw": p}
                                   for ld, t, p in ROWS])
    fits = [calibrate(slope, rows, "nonlin", ["drag_per_roll_n", "m_star"],
                      starts={"m_star": s}) for s in (0.0035, 0.007, 0.02)]
    for cal in fits:
        assert cal.status == "warning" and cal.not_identifiable == ["m_star"]
        assert cal.message.startswith("m_star ends at the bound 0 (the data would take it "
                                      "below")
        assert cal.fit["m_star"]["value"] < 1e-6 and cal.fit["m_star"]["ci95"] is None
        assert cal.fit["drag_per_roll_n"]["value"] == pytest.approx(1.671, abs=1e-3)
        assert cal.fit["m_star"]["se"] == pytest.approx(0.01197, rel=1e-3)
    assert len({cal.message for cal in fits}) == 1


def test_the_bound_is_judged_by_where_the_data_would_take_the_value():
    """By hand, one name with J = (1, 1): residuals (0.1, 0.1) at x = 1e-7 give the step
    d = -(J^T J)^-1 J^T r = -0.2 / 2 = -0.1, below 0: at the bound. Residuals (0.1, -0.1) give
    J^T r = 0, d = 0: a fit that converged there, not at the bound, even at x = 1e-12."""
    jac = np.array([[1.0], [1.0]])
    assert _at_bound(["k"], np.array([1e-7]), [0.0], jac, np.array([0.1, 0.1])) == ["k"]
    assert _at_bound(["k"], np.array([1e-12]), [0.0], jac, np.array([0.1, -0.1])) == []
    # a bound of the model's own (DIN's C >= 1): 1.05 - 0.1 = 0.95 is below it, 1.2 - 0.1 is not
    assert _at_bound(["c"], np.array([1.05]), [1.0], jac, np.array([0.1, 0.1])) == ["c"]
    assert _at_bound(["c"], np.array([1.2]), [1.0], jac, np.array([0.1, 0.1])) == []
