"""The study model: what a study file or a POSTed body may say, as Pydantic types.

:class:`StudyIn` is the one definition of a study at the door. A study is validated against
it once (:func:`beltstudy.service.door.studyfile.resolve_study`), and its JSON Schema
(``StudyIn.model_json_schema(schema_generator=StudySchema)``) is the body schema that
``/openapi.json`` serves (:mod:`beltstudy.service.door.openapi`). Its parts come from the
engine:

* ``conveyor`` and ``scenario`` are the engine's :class:`~beltstudy.engine.Conveyor` and
  :class:`~beltstudy.engine.Scenario` (a conveyor may also be a file name);
* ``grid`` and each ``zip`` group are a :data:`Grid`, a model made from those two with one
  field per axis: a list of values of the field the axis sets (the engine field's own type
  and bounds) or, for a number, a :class:`RangeSpec`. An axis into a list (``profile.3.lift_m``)
  is read as the field ``profile.N.lift_m`` holding ``{"3": values}`` (:func:`fold_axes`);
* ``models`` is :data:`FrictionModels`, made from the friction model registry: per model and
  alias, its parameters (types from the parameter dataclass).

What a type cannot say is decided once, after it, by the resolver and the engine, with their
own messages: axis paths (and the nearest valid one), model names and aliases, parameter names
and bounds (each model's ``check``), catalogue ids, the runs a grid makes. For the schema,
those are stated where the value is: the catalogue ids and model names as enums, a parameter's
bounds as its model's check finds them (:func:`param_bounds`), the either-or rules of a belt
and a take-up (:class:`StudySchema`). :data:`NOT_IN_SCHEMA` lists what JSON Schema cannot state.
"""

from __future__ import annotations

import dataclasses
import math
import re
import typing
from collections.abc import Callable, Iterable
from functools import partial
from typing import Annotated, Any, Literal, Union

from pydantic import (
    AfterValidator,
    BaseModel,
    ConfigDict,
    Discriminator,
    Field,
    Tag,
    WithJsonSchema,
    create_model,
    field_validator,
)
from pydantic.json_schema import GenerateJsonSchema
from pydantic_core import core_schema

from beltstudy.engine import ALIASES, MODELS, Conveyor, Scenario, catalog
from beltstudy.engine.conveyor import check_visible
from beltstudy.service.door.sample import SampleIn
from beltstudy.service.examples import TINY_CONVEYOR, TINY_SCENARIO
from beltstudy.service.grid.axes import NAMED_AXES, NOT_READ, field_model
from beltstudy.service.grid.basis import DesignIn

__all__ = [
    "NAME_RE",
    "NAME_PATTERN",
    "NOT_IN_SCHEMA",
    "RangeSpec",
    "Grid",
    "FrictionModels",
    "StudyIn",
    "AccuracyIn",
    "StudySchema",
    "AXIS_TARGETS",
    "fold_axes",
    "unfold_axis",
    "param_bounds",
    "given_models",
    "model_names",
    "OWN_PARTS",
    "fold_name",
    "axis_types",
]

#: A study name: letters, digits and `` ._+-`` (no path separators, no ``..``).
NAME_RE = re.compile(r"^[A-Za-z0-9][A-Za-z0-9 ._+\-]{0,119}$")
#: :data:`NAME_RE` without ``..``, as the schema states it.
NAME_PATTERN = r"^(?!.*\.\.)[A-Za-z0-9][A-Za-z0-9 ._+\-]{0,119}$"
#: Rules of a valid study that JSON Schema cannot state (the resolver checks them).
NOT_IN_SCHEMA = (
    "drive shares sum to 1",
    "a belt's dynamic modulus is at least its static one (the file's, else the catalogue's)",
    "an idler set gives its pitch (spacing_m) or its count, one of them",
    "a profile section's |lift_m| is below its length_m",
    "a range's step leads from start to stop, and its values stay within the study limit",
    "the grid's runs (the product of its axes) stay within BELTSTUDY_MAX_RUNS",
    "no two grid axes set the same field or one inside the other",
    "an axis's values stay distinct once their defaults are filled in ({} and "
    "{head_kn: 0} are one accessories value)",
    "a list index in an axis (profile.3.lift_m) exists in the base conveyor",
    "a friction model appears once counting aliases (din and iso5048 are one)",
    "a design list names each case once (aliases count as one model, full as load 1.0)",
    "a models.<model>.<parameter> axis names a model the study runs (its friction_model "
    "axis, else model, else the one model under models, else din)",
    "a parameter set by a models.<model>.<parameter> axis is not also under models: (its "
    "runs take the axis's value) unless that model is design.friction_model and the study "
    "runs another model, whose runs it sizes",
    "with dynamics, a scenario the conveyor can do (brake stop needs brakes, stop after the "
    "brake delay)",
    "every auto size of a conveyor design is finite (no take-up meets a sag limit near zero)",
    "accuracy (error bars of a sample) only with dynamics",
    "a steady study (dynamics: false) samples no scenario field but load, temperature_c and "
    "elements (the others its runs do not read), nor gives one a grid or zip axis of two or "
    "more values",
    "a sample axis is a numeric axis path, set by no grid or zip axis, and its drawn values "
    "stay within the field's bounds",
    "a sample of method sobol has n = N (D + 2) points, N a power of two, D its axes",
)


# ------------------------------------------------------------------------- names as enums
#: The engine's models inside a conveyor whose schema says more than their types.
Belt = Conveyor.model_fields["belt"].annotation
TakeUp = Conveyor.model_fields["takeup"].annotation
IdlerSet = Conveyor.model_fields["idlers"].annotation.model_fields["carry"].annotation


def model_names() -> list[str]:
    """Every friction model name and alias (the registry's)."""
    return [*MODELS, *ALIASES]


def _belt_ids() -> list[str]:
    return sorted(catalog.belts())


def _idler_classes() -> list[str]:
    return sorted({r.cema_class for r in catalog.idlers()})


def _alias_groups() -> list[list[str]]:
    """Names that mean one friction model (the model and its aliases), groups of two or more."""
    groups = [[name, *[a for a, t in ALIASES.items() if t == name]] for name in MODELS]
    return [g for g in groups if len(g) > 1]


#: A friction model or alias: any text for the registry to resolve (its message names the
#: nearest model); the schema lists the names.
ModelName = Annotated[str, WithJsonSchema({"type": "string", "enum": model_names()})]
#: A belt id of an axis: the catalogue checks it (with a did-you-mean), the schema lists them.
BeltId = Annotated[str | None, WithJsonSchema({"type": "string", "enum": _belt_ids()})]
#: An idler class of an axis, as :data:`BeltId`.
IdlerClass = Annotated[str | None, WithJsonSchema(
    {"anyOf": [{"type": "string", "enum": _idler_classes()}, {"type": "null"}]})]
#: Fields whose values are catalogue ids, the type their axis values take.
_CATALOGUE_AXES: dict[tuple[type[BaseModel], str], Any] = {
    (Belt, "type"): BeltId,
    (IdlerSet, "cema_class"): IdlerClass,
}


class StudySchema(GenerateJsonSchema):
    """The JSON Schema of the study model: Pydantic's, plus what the engine's models check in
    validators and the catalogues rather than in types (ids as enums, the either-or rules of
    a belt and a take-up)."""

    def model_schema(self, schema: core_schema.ModelSchema) -> dict:
        out = super().model_schema(schema)
        refine = _MODEL_RULES.get(schema["cls"])
        if refine is not None:
            refine(out)
        return out


def _belt_rules(schema: dict) -> None:
    props = schema["properties"]
    props["type"] = {"anyOf": [{"type": "string", "enum": _belt_ids()}, {"type": "null"}],
                     "default": None, "description": props["type"].get("description", "")}
    custom = ["rating_kn_m", "modulus_kn_m", "carcass_mass_kg_m2", "top_cover_mm",
              "bottom_cover_mm"]
    printed = [k for k in custom if k != "carcass_mass_kg_m2"] + ["mass_kg_m"]
    schema["anyOf"] = [
        {"required": ["type"], "properties": {"type": {"type": "string"}}},
        {"required": custom, "properties": {k: {"type": "number"} for k in custom}},
        {"required": printed, "properties": {k: {"type": "number"} for k in printed}},
    ]


def _idler_rules(schema: dict) -> None:
    schema["properties"]["cema_class"]["anyOf"] = [
        {"type": "string", "enum": _idler_classes()}, {"type": "null"}]
    # the pitch or the number of sets along the route, one of them
    schema["anyOf"] = [{"required": ["spacing_m"], "properties": {"spacing_m": {"type": "number"}}},
                       {"required": ["count"], "properties": {"count": {"type": "integer"}}}]


def _takeup_rules(schema: dict) -> None:
    schema["anyOf"] = [
        {"properties": {"type": {"const": "gravity"}, "pretension_kn": {"const": "auto"}}},
        {"required": ["type"],
         "properties": {"type": {"const": "fixed"}, "mass_kg": {"const": "auto"}}},
    ]


_MODEL_RULES: dict[type, Callable[[dict], None]] = {
    Belt: _belt_rules, IdlerSet: _idler_rules, TakeUp: _takeup_rules}


# ----------------------------------------------------------------------------- axis values
class RangeSpec(BaseModel):
    """start, start + step, ... up to and including stop"""

    model_config = ConfigDict(extra="forbid")

    start: float
    stop: float
    step: float = Field(..., description="increment; its sign must lead from start to stop",
                        json_schema_extra={"not": {"const": 0}})

    def count(self) -> int:
        if self.step == 0 or not math.isfinite(self.step):
            raise ValueError("step must be a non-zero number")
        span = (self.stop - self.start) / self.step
        if not math.isfinite(span):  # start, stop or step beyond float range
            return 2**63
        if span < -1e-9:
            raise ValueError(
                f"step {self.step:g} does not lead from start {self.start:g} to stop {self.stop:g}"
            )
        n = int(math.floor(span + 1e-9)) + 1
        if span - (n - 1) > 1e-6:  # the stop is not start + a whole number of steps
            last = self.start + (n - 1) * self.step
            raise ValueError(
                f"stop {self.stop:g} is not reached from start {self.start:g} in steps of "
                f"{self.step:g} (the range would end at {last:.12g}); give stop {last:.12g} or "
                f"{last + self.step:.12g}, a step that divides {self.stop - self.start:g}, "
                f"or a list of values")
        return n

    def values(self) -> list[float | int]:
        n = self.count()
        # 12 digits of the range's own scale, not of each value: -0.3 + 3 x 0.1 is 0, as
        # the list [-0.3, ..., 0, ...] gives it (the same inputs, the same run ids). A range
        # of one value is that value: its step and stop, never reached, set no scale (a
        # step of 1e20 from 20 to 20 rounded 20 at 1e20's scale, to 0)
        scale = (max(abs(self.start), abs(self.stop), abs(self.step)) if n > 1
                 else abs(self.start))
        digits = 12 - math.floor(math.log10(scale)) if scale > 0 and math.isfinite(scale) else 12
        out = [float(f"{round(self.start + i * self.step, digits):.12g}") + 0.0
               for i in range(n)]
        if all(v.is_integer() for v in out) and float(self.step).is_integer():
            return [int(v) for v in out]
        return out


def _shape(value: Any) -> str:
    """Which an axis's values are: a range (a mapping) or a list of values."""
    return "range" if isinstance(value, dict | RangeSpec) else "values"


def _numeric(annotation: Any) -> bool:
    """Whether a field takes a number (a range of them makes sense)."""
    if annotation is bool:
        return False
    if annotation in (float, int):
        return True
    if typing.get_origin(annotation) in (list, tuple, Literal):
        return False
    return any(_numeric(a) for a in typing.get_args(annotation))


def _number_branch(schema: dict) -> dict | None:
    for option in schema.get("anyOf", [schema]):
        if option.get("type") in ("number", "integer"):
            return option
    return None


def _axis_schema(schema: dict, bounds: dict | None = None) -> None:
    """An axis's schema as the OpenAPI document states it (Pydantic's: a list of the field's
    values, or a range): the list at least one distinct value long, a range within the bounds
    of the field's number, in steps of its type. ``bounds``: the number's, where its type does
    not say them (a model parameter)."""
    branches = schema.pop("oneOf", None) or [{k: schema.pop(k) for k in list(schema)
                                               if k in ("type", "items")}]
    schema.pop("default", None)
    schema.pop("title", None)
    listed = {**branches[0], "minItems": 1, "uniqueItems": True}
    number = _number_branch(listed["items"])
    if number is not None and bounds:
        number.update(bounds)
    if number is None or len(branches) == 1:
        schema.update(listed)
        return
    bound = {k: v for k, v in number.items() if k in (
        "type", "minimum", "maximum", "exclusiveMinimum", "exclusiveMaximum")}
    ranged = RangeSpec.model_json_schema()
    ranged.pop("title", None)
    props = ranged["properties"]
    props["start"], props["stop"] = dict(bound), dict(bound)
    props["step"] = {"type": number["type"], "not": {"const": 0}}
    schema["anyOf"] = [listed, ranged]


def _axis_type(item: Any, numeric: bool) -> Any:
    """The type of an axis's values: a list of ``item``, or a range when it is a number."""
    listed = list[item]
    if not numeric:
        return listed
    return Annotated[Union[Annotated[listed, Tag("values")],  # noqa: UP007 - tagged members
                           Annotated[RangeSpec, Tag("range")]], Discriminator(_shape)]


def param_bounds(model, name: str) -> dict:
    """A parameter's bounds (``minimum``, ``exclusiveMinimum``, ``maximum``) as the model's own
    ``check`` finds them, asked at 0 and 1."""

    def ok(value: float) -> bool:
        return model.accepts(name, value)

    out: dict[str, float] = {}
    eps = 1e-9
    for edge in (0.0, 1.0):
        if ok(edge) and not ok(edge - eps) and not ok(edge - 1.0):
            out["minimum"] = edge
        elif not ok(edge) and ok(edge + eps) and not ok(edge - 1.0):
            out["exclusiveMinimum"] = edge
        if ok(edge) and not ok(edge + eps) and not ok(edge + 1.0):
            out["maximum"] = edge
    if "minimum" in out and "exclusiveMinimum" in out:
        del out["exclusiveMinimum"]
    hi = model.largest(name)
    if hi is not None and out.get("maximum", math.inf) > hi:
        out["maximum"] = hi  # the parameter's declared largest value (friction.base.param)
    return out


# ---------------------------------------------------------------------------------- axes
def _item(owner: type[BaseModel], name: str, info) -> Any:
    """The type of one value of an axis that sets ``owner.name``: the field's own type with its
    bounds (and its schema's catalogue enum)."""
    if (owner, name) in _CATALOGUE_AXES:
        return _CATALOGUE_AXES[owner, name]
    meta = list(info.metadata)
    if info.json_schema_extra is not None:
        meta.append(Field(json_schema_extra=info.json_schema_extra))
    return Annotated[(info.annotation, *meta)] if meta else info.annotation


def _field_axes(model: type[BaseModel], prefix: str) -> Iterable[tuple[str, Any, bool]]:
    """``(path, item type, numeric)`` of every field of ``model`` and of its sub-models; a
    list of models adds its items' fields under ``<path>.N.``."""
    for name, info in model.model_fields.items():
        key = info.alias or name
        path = f"{prefix}{key}"
        yield path, _item(model, name, info), _numeric(info.annotation)
        inner, is_list = field_model(info.annotation)
        if inner is None:
            continue
        if is_list:
            yield f"{path}.N", inner, False
            yield from _field_axes(inner, f"{path}.N.")
        else:
            yield from _field_axes(inner, f"{path}.")


def _param_axes() -> Iterable[tuple[str, Any, bool, dict]]:
    """``(models.<model>.<parameter>, item type, True, bounds)`` for every model and alias."""
    for name in model_names():
        fm = MODELS[ALIASES.get(name, name)]
        hints = typing.get_type_hints(fm.params_class)
        for f in dataclasses.fields(fm.params_class):
            yield f"models.{name}.{f.name}", hints[f.name], True, param_bounds(fm, f.name)


#: Axis name (folded: ``profile.N.lift_m``) -> the field it sets, dotted from its root
#: (``conveyor.profile.N.lift_m``, ``scenario.temperature_c``, ``model``, ``models.din.c``).
AXIS_TARGETS: dict[str, str] = {}


#: The friction model axis: each model once, counting aliases.
_FRICTION_MODEL_AXIS = {
    "allOf": [{"not": {"allOf": [{"contains": {"const": a}}, {"contains": {"const": b}}]}}
              for group in _alias_groups() for i, a in enumerate(group) for b in group[i + 1:]],
    "description": "friction models, each once counting aliases (din and iso5048 are one)",
}
_INDEX = r"\.(0|[1-9][0-9]*)"


def _axis_field(alias: str, item: Any, numeric: bool, bounds: dict | None) -> tuple:
    """``(type, Field)`` of one axis; an axis into a list holds ``{index: values}``."""
    extra = _FRICTION_MODEL_AXIS if alias == "friction_model" else {}
    unread = NOT_READ.get(tuple(alias.removeprefix("conveyor.").split(".")))
    if unread:
        # a field no run reads (the conveyor's name): set once, never varied (the resolver's
        # words for two values: studyfile._check_read)
        extra = {"maxItems": 1, "description": f"{unread}: no run reads it, so one value "
                 "(the field set once), never an axis of several"}

    def schema(s: dict) -> None:
        if ".N" in alias:
            s = s["additionalProperties"]
        _axis_schema(s, bounds)
        s.update(extra)

    values = _axis_type(item, numeric)
    return (dict[str, values] if ".N" in alias else values,
            Field(None, alias=alias, json_schema_extra=schema))


def axis_types() -> dict[str, tuple[str, Any, bool, dict | None]]:
    """Every axis a grid takes: ``{name: (target, item type, numeric, bounds)}``."""
    axes: dict[str, tuple[str, Any, bool, dict | None]] = {}
    conveyor = {p: (t, n) for p, t, n in _field_axes(Conveyor, "")}
    for path, (item, numeric) in conveyor.items():
        for name in (path, f"conveyor.{path}"):
            axes[name] = (f"conveyor.{path}", item, numeric, None)
    for path, item, numeric in _field_axes(Scenario, ""):
        axes[f"scenario.{path}"] = (f"scenario.{path}", item, numeric, None)
        if path not in conveyor:  # a bare name is a conveyor field first
            axes.setdefault(path, (f"scenario.{path}", item, numeric, None))
    own_types = {"friction_model": ModelName, "belt_type": BeltId}
    for name, path in NAMED_AXES.items():
        target = ".".join(path)
        own = own_types.get(name)
        axes[name] = (target, own, False, None) if own else axes[target]
    for name, item, numeric, bounds in _param_axes():
        axes[name] = (name, item, numeric, bounds)
    return axes


def _grid_fields() -> dict[str, tuple]:
    """The fields of :data:`Grid`, one per axis (named by the axis as an alias)."""
    fields = {}
    for i, (alias, (target, item, numeric, bounds)) in enumerate(axis_types().items()):
        AXIS_TARGETS[alias] = target
        fields[f"axis_{i}"] = _axis_field(alias, item, numeric, bounds)
    return fields


def _grid_schema(schema: dict) -> None:
    """The grid as the OpenAPI document states it: an axis into a list (the field
    ``profile.N.lift_m``) is the property pattern ``^profile\\.(0|[1-9][0-9]*)\\.lift_m$``;
    no other names; at least one axis."""
    props = schema["properties"]
    patterns = {}
    for alias in [a for a in props if ".N" in a]:
        values = props.pop(alias)["additionalProperties"]
        pattern = "^" + re.escape(alias).replace(r"\.N", _INDEX) + "$"
        patterns[pattern] = values
    schema["patternProperties"] = patterns
    schema["additionalProperties"] = False
    schema["minProperties"] = 1
    schema["description"] = (
        "axis -> list of values or {start, stop, step}; Cartesian product. Axes: "
        "friction_model, temperature_c, belt_type, stop_time_s, load, or any dotted conveyor or "
        "scenario field (takeup.mass_kg, profile.0.lift_m, scenario.run_s)")


class _GridBase(BaseModel):
    """The axes of a grid or zip group (fields made by :func:`_grid_fields`); other names are
    kept for the resolver to name the nearest valid one."""

    model_config = ConfigDict(extra="allow", json_schema_extra=_grid_schema)
    __pydantic_extra__: dict[str, list[Any] | RangeSpec]

    def axes(self, written: dict[str, Any]) -> list[tuple[str, list[Any] | RangeSpec]]:
        """``(axis name, values)`` of the axes ``written`` (this grid as given, in its order):
        a range as validated, a list of values as written (the grid sets them into the
        conveyor or scenario, whose model reads them)."""
        fields = {info.alias: name for name, info in type(self).model_fields.items()}
        out = []
        for name, raw in written.items():
            folded, index = fold_name(name)
            value = (getattr(self, fields[folded]) if folded in fields
                     else self.__pydantic_extra__[name])
            if index is not None:
                value = value[index]
            out.append((name, value if isinstance(value, RangeSpec) else raw))
        return out


def fold_name(name: str) -> tuple[str, str | None]:
    """``profile.3.lift_m`` -> (``profile.N.lift_m``, ``"3"``); other names as they are."""
    folded = re.sub(r"\.(0|[1-9][0-9]*)(?=\.|$)", ".N", name)
    if folded == name or folded not in AXIS_TARGETS:
        return name, None
    return folded, ".".join(re.findall(r"\.(0|[1-9][0-9]*)(?=\.|$)", name))


def unfold_axis(folded: str, index: str) -> str:
    """The axis name of ``{folded: {index: ...}}``: the inverse of :func:`fold_name`."""
    parts = iter(index.split("."))
    return re.sub(r"\.N(?=\.|$)", lambda _: f".{next(parts)}", folded)


def fold_axes(grid: Any) -> Any:
    """A grid or zip group with each axis into a list read as its field: ``profile.3.lift_m:
    [..]`` -> ``profile.N.lift_m: {"3": [..]}``."""
    if not isinstance(grid, dict):
        return grid
    out: dict[str, Any] = {}
    for name, values in grid.items():
        folded, index = fold_name(name)
        if index is None:
            out[name] = values
        else:
            out.setdefault(folded, {})[index] = values
    return out


Grid = create_model("Grid", __base__=_GridBase, **_grid_fields())


# ---------------------------------------------------------------------------- parameters
def _bare(extra: dict | None = None, bounds: dict | None = None) -> Callable[[dict], None]:
    """A field's schema without Pydantic's title and default (a field that may be left out is
    not therefore null), with ``bounds`` on its number and ``extra`` keywords."""
    def schema(s: dict) -> None:
        s.pop("default", None)
        s.pop("title", None)
        if bounds:
            _number_branch(s).update(bounds)
        s.update(extra or {})
    return schema


def _params_model(name: str) -> type[BaseModel]:
    """A friction model's parameter overrides: each a number (or null where the default is
    computed); the model checks their names and bounds (the schema states the bounds)."""
    fm = MODELS[name]
    hints = typing.get_type_hints(fm.params_class)
    fields = {
        f.name: (hints[f.name], Field(None, json_schema_extra=_bare(
            {"description": f.metadata.get("doc", "")}, param_bounds(fm, f.name))))
        for f in dataclasses.fields(fm.params_class)
    }
    config = ConfigDict(extra="allow", json_schema_extra={"additionalProperties": False})
    return create_model(fm.params_class.__name__, __config__=config, **fields)


def _not_together(names: list[str]) -> dict:
    """dependentSchemas: no two of ``names`` as keys of one mapping."""
    return {a: {"not": {"anyOf": [{"required": [b]} for b in names if b != a]}} for a in names}


def _friction_models() -> type[BaseModel]:
    """``models``: per friction model and alias, its parameter overrides. Other names are
    kept for the registry to name the nearest model."""
    params = {name: _params_model(name) for name in MODELS}
    dependent: dict = {}
    for group in _alias_groups():
        dependent.update(_not_together(group))

    class Base(BaseModel):
        model_config = ConfigDict(extra="allow", json_schema_extra={
            "additionalProperties": False, "dependentSchemas": dependent,
            "description": "friction model -> parameter overrides (null: the model's "
            "default); a model once, counting its aliases"})
        __pydantic_extra__: dict[str, dict[str, float | None]]

    fields = {f"model_{i}": (params[ALIASES.get(name, name)],
                             Field(None, alias=name, json_schema_extra=_bare()))
              for i, name in enumerate(model_names())}
    return create_model("FrictionModels", __base__=Base, **fields)


FrictionModels = _friction_models()
#: The study's own parts (not the engine's models): the grid, the friction models and their
#: parameters (the OpenAPI document writes them out in the study body).
OWN_PARTS: tuple[type[BaseModel], ...] = (
    Grid, FrictionModels,
    *dict.fromkeys(info.annotation for info in FrictionModels.model_fields.values()))


def given_models(models: BaseModel) -> dict[str, dict[str, Any]]:
    """``{model as written: {parameter: value}}`` of a validated ``models`` mapping (the
    parameters given, unknown ones too: the model names them)."""
    fields = type(models).model_fields
    out = {fields[name].alias: getattr(models, name).model_dump(exclude_unset=True)
           for name in fields if name in models.model_fields_set}
    out.update({name: dict(value) for name, value in (models.__pydantic_extra__ or {}).items()})
    return out


# ----------------------------------------------------------------------------------- study
def _conveyor_kind(value: Any) -> str:
    return "file" if isinstance(value, str) else "inline"


def _check_name(value: str) -> str:
    if ".." in value or not NAME_RE.match(value):
        raise ValueError(
            "must start with an ASCII letter or digit and use only ASCII letters (a-z, A-Z), "
            "digits, spaces and ._+- "
            "(no path separators or '..'), at most 120 characters"
        )
    return value


def _example() -> dict:
    return {
        "name": "example-power-vs-temperature",
        "conveyor": TINY_CONVEYOR,
        "scenario": TINY_SCENARIO,
        "grid": {
            "friction_model": ["din", "cema"],
            "temperature_c": {"start": -20, "stop": 20, "step": 20},
        },
        "dynamics": False,
    }


def _study_schema(schema: dict) -> None:
    schema["anyOf"] = [{"required": ["grid"]},
                       {"required": ["zip"], "properties": {"zip": {"minItems": 1}}},
                       {"required": ["sample"], "properties": {"sample": {"type": "object"}}}]
    schema["description"] = (
        "A study (SPEC section 3). Besides this schema a study must satisfy: "
        + "; ".join(NOT_IN_SCHEMA) + ".")
    schema["examples"] = [_example()]


#: A conveyor: a file under the studies directory (or beside the study file), or inline.
ConveyorRef = Annotated[
    Union[Annotated[str, Tag("file")], Annotated[Conveyor, Tag("inline")]],  # noqa: UP007
    Discriminator(_conveyor_kind)]


class AccuracyIn(BaseModel):
    """Error bars of a sample of the study's runs (SPEC 7.2; beltstudy.engine.accuracy)."""

    model_config = ConfigDict(extra="forbid")

    sample: float = Field(..., gt=0.0, le=1.0, description="fraction of the runs that get "
                          "error bars (at least one run; each costs about 5 runs: a mesh "
                          "half and one twice as fine)")
    seed: int = Field(0, ge=0, description="seed of the sample: the same seed, the same runs")


class StudyIn(BaseModel):
    """A study as written in a file or POSTed (SPEC section 3); validated at the door."""

    model_config = ConfigDict(extra="forbid", title="StudyDoc", json_schema_extra=_study_schema)

    name: str = Field(..., description="study name (letters, digits, spaces, ._+-)",
                      json_schema_extra={"pattern": NAME_PATTERN})
    description: Annotated[str, AfterValidator(partial(check_visible, allow="\n\t"))] = Field(
        "", max_length=2000, description="free text (lines and tabs; no other control or "
        "bidi characters)")
    conveyor: ConveyorRef = Field(
        ..., description="a conveyor file under the service's studies directory, or inline")
    scenario: Scenario = Field(default_factory=Scenario)
    grid: Grid = Field(default_factory=Grid)  # type: ignore[valid-type]
    zip: list[Grid] = Field(  # type: ignore[valid-type]
        default_factory=list,
        description="groups of axes that vary together (equal lengths), crossed with the grid",
    )
    design: DesignIn | None = Field(
        None,
        description="design cases of every auto size, {friction_model, temperature_c, load}, "
        "each one value or a list (every combination is a case, each size the largest over "
        "them); default: the largest requirement over the study's models and temperatures at "
        "full load",
    )
    models: FrictionModels = Field(  # type: ignore[valid-type]
        default_factory=FrictionModels,
        description="friction model -> parameter overrides (null: the model's default); "
        "a model once, counting its aliases")
    model: ModelName | None = Field(
        None, description="friction model when the grid has no friction_model axis (default din)"
    )
    dynamics: bool = Field(True, description="false = steady tensions only")
    surface: bool = Field(
        False,
        description="store the tension/velocity surface of every dynamic run (SPEC section 5); "
        "false (the default) stores the key-point time series only and recomputes a run's "
        "surface from its inputs when it is asked for",
    )
    accuracy: AccuracyIn | None = Field(
        None,
        description="error bars of a seeded sample of the runs ({sample: 0.05}), stored as "
        "the study's accuracy table (dynamic studies only)",
    )
    sample: SampleIn | None = Field(
        None,
        description="uncertain inputs drawn from distributions (SPEC 7.2): n points by "
        "method sobol or lhs with a seed, one more group of axes varying together, crossed "
        "with the grid",
    )

    @field_validator("name")
    @classmethod
    def _name_is_safe(cls, value: str) -> str:
        return _check_name(value)
