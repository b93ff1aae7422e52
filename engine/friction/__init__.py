"""Friction models behind one registry (STYLE: choose a model by name in one place).

Each model is a :class:`FrictionModel`: a frozen parameter dataclass with documented
defaults and a ``build(loop, conveyor, temperature_c, params) -> ResistanceLaw`` function.
``get_model(name)`` accepts the canonical names and aliases; an unknown name raises
:class:`~engine.conveyor.InputError` listing the valid ones.
"""

from __future__ import annotations

import difflib
import importlib

from engine.conveyor import InputError
from engine.friction.base import FrictionModel, param

__all__ = ["FrictionModel", "MODELS", "ALIASES", "get_model", "model_names", "param"]


#: canonical model name -> module in engine.friction
_MODULES = {
    "din": "din",
    "cema": "cema",
    "cmod": "cmod",
    "visco": "visco",
    "nonlin": "nonlin",
}
ALIASES = {"iso5048": "din", "din22101": "din", "viscoah": "visco", "non-lin": "nonlin"}


def _load() -> dict[str, FrictionModel]:
    out = {}
    for name, mod in _MODULES.items():
        try:
            module = importlib.import_module(f"engine.friction.{mod}")
        except ModuleNotFoundError as exc:
            if exc.name == f"engine.friction.{mod}":
                continue
            raise
        out[name] = module.MODEL
    return out


MODELS: dict[str, FrictionModel] = _load()


def model_names() -> list[str]:
    return list(MODELS)


def get_model(name: str) -> FrictionModel:
    key = ALIASES.get(str(name).lower(), str(name).lower())
    if key not in MODELS:
        valid = list(MODELS) + [f"{a} (= {t})" for a, t in ALIASES.items() if t in MODELS]
        close = difflib.get_close_matches(str(name), list(MODELS) + list(ALIASES), n=1)
        hint = f"; did you mean '{close[0]}'?" if close else ""
        raise InputError(f"friction_model: unknown model '{name}'{hint} valid: {', '.join(valid)}")
    return MODELS[key]
