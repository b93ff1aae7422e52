"""Below its cover's glass transition a run of a model that reads the rubber (Non-Lin, Visco)
says so: on slope-5pct's standard cover (T_g -50 C) Non-Lin's Te fell from 217.2 kN at -40 C
to 154.9 kN at -60 C with no word, the indentation loss having passed its peak (PHYSICS 3;
the WLF law with T_ref = T_g). The note names the glass transition and the compounds rubbery
there; DIN, which reads no rubber, and a run above T_g carry none."""
from __future__ import annotations

from pathlib import Path

import pytest

from beltstudy.engine import catalog
from beltstudy.engine.conveyor import load_conveyor
from beltstudy.engine.statics import solve_steady

ROOT = Path(__file__).resolve().parents[2]
SLOPE = ROOT / "studies" / "conveyors" / "slope-5pct.yaml"


def _tg(compound: str) -> float:
    return float(catalog.compounds()[compound]["tg_c"])


@pytest.mark.parametrize("model", ["nonlin", "visco"])
def test_a_run_below_the_covers_glass_transition_says_so(model):
    conv = load_conveyor(SLOPE)
    tg = _tg(conv.belt.compound)
    cold = solve_steady(conv, model=model, temperature_c=tg - 10.0, n_elements=100)
    note = f"the {conv.belt.compound} cover is below its glass transition (T_g {tg:g} C"
    assert note in cold.message, cold.message
    colder = [c for c in catalog.compounds() if _tg(c) < tg - 10.0]
    assert colder and all(f"{c} (T_g {_tg(c):g} C)" in cold.message for c in colder)
    warm = solve_steady(conv, model=model, temperature_c=tg + 1.0, n_elements=100)
    assert "glass transition" not in warm.message


def test_the_indentation_loss_falls_below_the_glass_transition_as_the_note_says():
    """The physical claim of the note: at the idler contact's frequency the loss peak lies a
    few kelvin above T_g, so 10 K below T_g the indentation per metre is below its value at
    T_g (the law's own loss curve, not a stored figure)."""
    conv = load_conveyor(SLOPE)
    tg = _tg(conv.belt.compound)
    at = {t: solve_steady(conv, model="nonlin", temperature_c=t, n_elements=100)
          .law.info["indentation_carry_n_m"] for t in (tg - 10.0, tg)}
    assert at[tg - 10.0] < at[tg]


def test_din_reads_no_rubber_and_says_nothing_of_it():
    conv = load_conveyor(SLOPE)
    res = solve_steady(conv, model="din", temperature_c=-60.0, n_elements=100)
    assert "glass transition" not in res.message
