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

__all__ = ["FrictionModel", "MODELS", "ALIASES", "canonical_name", "get_model", "param"]


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
