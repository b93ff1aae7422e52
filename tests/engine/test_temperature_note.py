"""A model without a temperature term (``din``: one friction factor f whatever the ambient,
DIN 22101) says so when it runs at a temperature other than 20 C: its figures are those of
20 C. A note, not a warning: the status stays what the limits make it."""

from __future__ import annotations

import pytest

from beltstudy.engine.conveyor import parse_conveyor
from beltstudy.engine.friction import MODELS
from beltstudy.engine.statics import solve_steady
from tests.conftest import hand_conveyor_dict

NOTE = "note: din has no temperature term; -20 C gives the figures of 20 C"


def test_din_at_minus_20_notes_it_and_gives_the_figures_of_20():
    conv = parse_conveyor(hand_conveyor_dict())
    cold = solve_steady(conv, model="din", temperature_c=-20.0)
    warm = solve_steady(conv, model="din", temperature_c=20.0)
    assert NOTE in cold.message
    assert cold.summary["message"] == cold.message
    # the note does not make a warning, and the figures are those of 20 C
    assert cold.status == warm.status == "ok"
    assert cold.summary["te_kn"] == warm.summary["te_kn"]
    assert "temperature term" not in warm.message


@pytest.mark.parametrize("model", ["nonlin", "cema"])
def test_models_with_a_temperature_term_carry_no_note(model):
    conv = parse_conveyor(hand_conveyor_dict())
    cold = solve_steady(conv, model=model, temperature_c=-20.0)
    warm = solve_steady(conv, model=model, temperature_c=20.0)
    assert "temperature term" not in cold.message
    # they have one: the cold changes their figures
    assert cold.summary["te_kn"] != pytest.approx(warm.summary["te_kn"], rel=1e-3)


def test_only_din_lacks_a_temperature_term():
    assert [m.name for m in MODELS.values() if not m.temperature_term] == ["din"]


def test_din_with_its_factors_given_for_the_temperature_carries_no_note():
    """A study that gives DIN's f for each temperature (``models.din.f_carry`` zipped with
    ``temperature_c``) has brought the temperature in, as the note asks: no note; the
    defaults at -20 C still carry it."""
    conv = parse_conveyor(hand_conveyor_dict())
    given = solve_steady(conv, model="din", temperature_c=-20.0, params={"f_carry": 0.025})
    assert "temperature term" not in given.message
    assert given.summary["te_kn"] > solve_steady(conv, model="din").summary["te_kn"]
    default_f = MODELS["din"].params(None).f_carry
    same = solve_steady(conv, model="din", temperature_c=-20.0, params={"f_carry": default_f})
    assert NOTE in same.message  # the default given by name is still the default


@pytest.mark.parametrize(("model", "name"), [("cema", "kt"), ("cmod", "kt"), ("nonlin", "kta")])
def test_colder_than_cemas_kt_table_is_noted_and_held_at_its_coldest_value(model, name):
    """CEMA's Kt is tabulated from 0 down to -40 C (1.65, CEMA 7th ed.); a colder run uses
    1.65 and says so, naming the parameter that sets Kt. Within the table, or with Kt given,
    no note."""
    conv = parse_conveyor(hand_conveyor_dict())
    colder = solve_steady(conv, model=model, temperature_c=-50.0)
    edge = solve_steady(conv, model=model, temperature_c=-40.0)
    assert f"-50 C uses its value there, 1.65 (models.{model}.{name} sets Kt" in colder.message
    assert "tabulated" not in edge.message
    given = solve_steady(conv, model=model, temperature_c=-50.0, params={name: 1.65})
    assert "tabulated" not in given.message
    if model != "nonlin":  # Non-Lin's rubber reads the temperature itself as well
        assert colder.summary["te_kn"] == pytest.approx(edge.summary["te_kn"], rel=1e-12)
