"""The friction-model interface: a parameter dataclass and a law builder."""

from __future__ import annotations

import dataclasses
import difflib
import typing
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from beltstudy.engine.errors import InputError

__all__ = ["FrictionModel", "param"]


@dataclass(frozen=True)
class FrictionModel:
    """A friction model: name, description, parameter class and law builder;
    ``temperature_term`` False for a model whose law does not change with the temperature
    (``din``: one f whatever the ambient; the run's message then says so,
    :func:`beltstudy.engine.friction.temperature_note`)."""

    name: str
    description: str
    params_class: type
    build: Callable[..., Any]
    temperature_term: bool = True
    #: ``(params, temperature_c) -> value``: what the law reads of the ambient temperature
    #: (CEMA: its factor Kt); None: the temperature itself (or nothing, without a
    #: temperature term). See :meth:`temperature_as_read`.
    temperature_read: Callable[[Any, float], Any] | None = None
    #: ``(params, temperature_c) -> str``: a note when the temperature lies beyond the data
    #: the law was read from ("" within it; CEMA's Kt table ends at -40 C).
    range_note: Callable[[Any, float], str] | None = None

    def temperature_as_read(self, params, temperature_c: float):
        """What this model's law reads of ``temperature_c`` [C] with ``params`` (a parameter
        object of :meth:`params`): None for a model without a temperature term, CEMA's Kt for
        the CEMA models (1 at and above 0 C), the temperature itself otherwise. Runs of one
        model whose temperatures read alike build the same law; the study service puts them in
        one task so that the engine can simulate them once
        (:func:`beltstudy.engine.run.run_group`)."""
        if not self.temperature_term:
            return None
        if self.temperature_read is None:
            return float(temperature_c)
        return self.temperature_read(params, float(temperature_c))

    def largest(self, name: str) -> float | None:
        """The largest value parameter ``name`` takes (:func:`param`'s ``hi``; None: no bound
        beyond the model's own check)."""
        return next(f.metadata.get("hi") for f in dataclasses.fields(self.params_class)
                    if f.name == name)

    def accepts(self, name: str, value: float) -> bool:
        """Whether the model takes ``value`` for parameter ``name`` (its own check included)."""
        try:
            self.params({name: value})
        except InputError:
            return False
        return True

    def params(self, overrides: dict[str, Any] | None = None):
        """Default parameters with overrides applied; unknown names raise InputError."""
        overrides = dict(overrides or {})
        fields = {f.name: f for f in dataclasses.fields(self.params_class)}
        clean = {}
        for key, value in overrides.items():
            if key not in fields:
                close = difflib.get_close_matches(key, list(fields), n=1, cutoff=0.5)
                hint = f"; did you mean '{close[0]}'?" if close else ""
                raise InputError(
                    f"unknown parameter of model '{self.name}'{hint}; valid: {', '.join(fields)}",
                    field=f"models.{self.name}.{key}")
            if value is None:
                if type(None) not in typing.get_args(typing.get_type_hints(self.params_class)[key]):
                    raise InputError(
                        "expected a number, got null (only parameters whose default is "
                        "computed may be null)", field=f"models.{self.name}.{key}")
                clean[key] = None
                continue
            try:
                clean[key] = float(value)
            except (TypeError, ValueError):
                raise InputError(f"expected a number, got {value!r}",
                                 field=f"models.{self.name}.{key}") from None
        p = dataclasses.replace(self.params_class(), **clean)
        check = getattr(p, "check", None)
        if check is not None:
            check()  # the model's own bounds first: its words for them
        for key, value in clean.items():
            hi = self.largest(key)
            if hi is not None and value is not None and not value <= hi:
                raise InputError(
                    f"at most {hi:g}, far beyond any published value (got {value:g}); the "
                    "parameters, their defaults and sources: docs/friction.md, GET /models",
                    field=f"models.{self.name}.{key}")
        return p

    def parameter_table(self) -> list[dict[str, Any]]:
        """Name, default and description of every parameter (from the dataclass metadata)."""
        out = []
        for f in dataclasses.fields(self.params_class):
            default = f.default if f.default is not dataclasses.MISSING else None
            out.append({"name": f.name, "default": default, "doc": f.metadata.get("doc", ""),
                        "max": f.metadata.get("hi")})
        return out


def param(default, doc: str, hi: float | None = None):
    """A dataclass field with a documented default (units in the doc string) and, with ``hi``,
    the largest value taken: far beyond any published value (about ten times the top of the
    range the doc string cites), so that only a slip of the pen is refused
    (:meth:`FrictionModel.params`; the study schema's ``maximum``)."""
    return dataclasses.field(default=default, metadata={"doc": doc, "hi": hi})

