"""Friction models behind one registry (STYLE: choose a model by name in one place).

Each model is a :class:`FrictionModel`: a frozen parameter dataclass with documented
defaults and a ``build(loop, conveyor, temperature_c, params) -> ResistanceLaw`` function.
``get_model(name)`` accepts the canonical names and aliases; an unknown name raises
:class:`~beltstudy.engine.conveyor.InputError` listing the valid ones.
"""

from __future__ import annotations

import difflib

from beltstudy.engine.errors import InputError
from beltstudy.engine.friction import cema, cmod, din, nonlin, visco
from beltstudy.engine.friction.base import FrictionModel, param

__all__ = ["FrictionModel", "MODELS", "ALIASES", "canonical_name", "get_model", "param",
           "temperature_note", "REFERENCE_TEMPERATURE_C"]


ALIASES = {"iso5048": "din", "din22101": "din", "viscoah": "visco", "non-lin": "nonlin"}

#: canonical model name -> model, in the order models are listed
MODELS: dict[str, FrictionModel] = {m.name: m for m in (din.MODEL, cema.MODEL, cmod.MODEL,
                                                         visco.MODEL, nonlin.MODEL)}


def canonical_name(name: str) -> str:
    """A model name as the models are keyed: lower case, an alias replaced by its model
    (``ISO5048`` is ``din``); an unknown name comes back lower-cased, not refused."""
    key = str(name).lower()
    return ALIASES.get(key, key)


def get_model(name: str) -> FrictionModel:
    key = canonical_name(name)
    if key not in MODELS:
        valid = list(MODELS) + [f"{a} (= {t})" for a, t in ALIASES.items()]
        close = difflib.get_close_matches(str(name), list(MODELS) + list(ALIASES), n=1)
        hint = f" (did you mean '{close[0]}'?)" if close else ""
        raise InputError(f"unknown model '{name}'{hint}; valid: {', '.join(valid)}",
                         field="friction_model")
    return MODELS[key]


#: The temperature a model without a temperature term stands for [C]: the scenario's default
#: ambient (``Scenario.temperature_c``).
REFERENCE_TEMPERATURE_C = 20.0


def temperature_note(model: FrictionModel, temperature_c: float,
                     params_given: bool = False) -> str:
    """The note a run of ``model`` at ``temperature_c`` [C] carries when the model has no
    temperature term (``FrictionModel.temperature_term``) and the temperature is not
    :data:`REFERENCE_TEMPERATURE_C`: its figures are those of 20 C, and what would bring the
    temperature in. "" otherwise, and "" when the run gives the model's parameters
    (``params_given``: friction factors for that temperature, the way the note asks for)."""
    if (model.temperature_term or params_given
            or abs(float(temperature_c) - REFERENCE_TEMPERATURE_C) < 1e-9):
        return ""
    others = ", ".join(m.name for m in MODELS.values() if m.temperature_term)
    return (f"note: {model.name} has no temperature term; {float(temperature_c):g} C gives the "
            f"figures of {REFERENCE_TEMPERATURE_C:g} C (friction factors for that temperature "
            f"as models.{model.name} parameters, or a model with one: {others})")
