"""Helpers shared by the CLI sub-commands (argument parsing, output)."""

from __future__ import annotations

import json
import math
from typing import Any

from engine.conveyor import InputError


def parse_load(text: str) -> str | float:
    """``full``, ``empty`` or a fraction 0..1 of the design load."""
    if text in ("full", "empty"):
        return text
    try:
        val = float(text)
    except ValueError:
        raise InputError(f"--load: expected full, empty or a fraction 0..1, got {text!r}") from None
    if not 0.0 <= val <= 1.0:
        raise InputError(f"--load: the fraction must be between 0 and 1, got {val}")
    return val


def parse_params(items: list[str] | None, model: str | None = None) -> dict[str, Any]:
    """``NAME=VALUE`` pairs into a dict. With ``model`` given, names may be prefixed
    ``model.NAME``; pairs for other models are dropped. Values are numbers."""
    out: dict[str, Any] = {}
    for item in items or []:
        if "=" not in item:
            raise InputError(f"--param {item!r}: expected NAME=VALUE, e.g. f_carry=0.010")
        name, _, value = item.partition("=")
        name = name.strip()
        if "." in name:
            prefix, _, name = name.partition(".")
            if model is not None and prefix != model:
                continue
        try:
            out[name] = float(value)
        except ValueError:
            raise InputError(f"--param {item!r}: the value must be a number") from None
    return out


def parse_model_params(items: list[str] | None) -> dict[str, dict[str, float]]:
    """``MODEL.NAME=VALUE`` pairs into ``{model: {name: value}}``."""
    out: dict[str, dict[str, float]] = {}
    for item in items or []:
        if "=" not in item or "." not in item.partition("=")[0]:
            raise InputError(f"--param {item!r}: expected MODEL.NAME=VALUE, e.g. din.f_carry=0.010")
        key, _, value = item.partition("=")
        model, _, name = key.partition(".")
        try:
            out.setdefault(model.strip(), {})[name.strip()] = float(value)
        except ValueError:
            raise InputError(f"--param {item!r}: the value must be a number") from None
    return out


def jsonable(obj: Any) -> Any:
    """Make numpy scalars and non-finite floats JSON-safe (NaN/inf become null)."""
    if isinstance(obj, dict):
        return {k: jsonable(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [jsonable(v) for v in obj]
    if hasattr(obj, "item") and not isinstance(obj, str):
        obj = obj.item()
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    return obj


def dumps(obj: Any) -> str:
    return json.dumps(jsonable(obj), indent=2)


def write_table(df, path: str) -> None:
    """Write a DataFrame as CSV or Parquet by the file extension."""
    if path.endswith(".parquet"):
        df.to_parquet(path, index=False)
    elif path.endswith(".csv"):
        df.to_csv(path, index=False)
    else:
        raise InputError(f"{path}: give a .csv or .parquet file name")
