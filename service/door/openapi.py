"""The OpenAPI description says what the validation accepts, and the study body is checked
against it.

:func:`study_schema` builds the JSON Schema of a study body (``StudyDoc``) from the same
sources the validation uses: the Pydantic models of the study, conveyor and scenario, the
catalogues (belt types, compounds, idler classes), the friction model registry (names, aliases,
parameters, and each parameter's bounds as the model's own ``check`` finds them), the grid
axes (every conveyor and scenario field, each axis's values valid for its field), and the
conveyor files in the studies directory. :func:`check_body` holds a POSTed study to that
schema, so nothing the schema refuses is accepted (``"true"`` for a boolean, ``"1"`` for a
number). What JSON Schema cannot state is checked after it, at the door as before, and named
in :data:`NOT_IN_SCHEMA`.

:func:`install` puts the schema into the app's ``/openapi.json`` with the patterns of study
and run ids, the ``metrics`` list of ``/compare``, the ``filter`` syntax and the plot names.
"""

from __future__ import annotations

import copy
import dataclasses
import json
import math
import re
import typing
from pathlib import Path
from typing import Any

import jsonschema_rs
import pyarrow as pa
from fastapi.openapi.utils import get_openapi
from pydantic import BaseModel

from beltstudy.engine import (
    ALIASES,
    MODELS,
    Conveyor,
    InputError,
    Scenario,
    catalog,
    parse_conveyor,
)
from beltstudy.service.door.parse import load_mapping
from beltstudy.service.door.studyfile import StudyIn
from beltstudy.service.errors import Invalid, ServiceError
from beltstudy.service.examples import TINY_CONVEYOR, TINY_SCENARIO
from beltstudy.service.grid.axes import _field_model
from beltstudy.service.store.columns import runs_schema_for_axes
from beltstudy.service.store.query import DEFAULT_METRICS
from beltstudy.service.web import figures

__all__ = [
    "NOT_IN_SCHEMA",
    "ID_PATTERN",
    "NAME_PATTERN",
    "study_schema",
    "conveyor_files",
    "check_body",
    "install",
    "metric_names",
]

#: Study and run ids: 16 hex digits.
ID_PATTERN = "^[0-9a-f]{16}$"
#: A study name (``beltstudy.service.door.studyfile.NAME_RE`` without ``..``).
NAME_PATTERN = r"^(?!.*\.\.)[A-Za-z0-9][A-Za-z0-9 ._+\-]{0,119}$"
#: Rules of a valid study that JSON Schema cannot state (checked after the schema).
NOT_IN_SCHEMA = (
    "drive shares sum to 1",
    "a profile section's |lift_m| is below its length_m",
    "a range's step leads from start to stop, and its values stay within the study limit",
    "the grid's runs (the product of its axes) stay within BELTSTUDY_MAX_RUNS",
    "no two grid axes set the same field or one inside the other",
    "an axis's values stay distinct once their defaults are filled in ({} and "
    "{head_kn: 0} are one accessories value)",
    "a list index in an axis (profile.3.lift_m) exists in the base conveyor",
    "a friction model appears once counting aliases (din and iso5048 are one)",
    "a models.<model>.<parameter> axis names a model the study runs (its friction_model "
    "axis, else model, else the one model under models, else din)",
    "with dynamics, a scenario the conveyor can do (brake stop needs brakes, stop after the "
    "brake delay)",
    "every auto size of a conveyor design is finite (no take-up meets a sag limit near zero)",
)


def _model_names() -> tuple[list[str], list[str]]:
    return list(MODELS), list(ALIASES)


def _bounds(model, name: str, optional: bool) -> dict:
    """A parameter's schema, its bounds found by asking the model's ``check``."""

    def ok(value: float) -> bool:
        try:
            model.params({name: value})
        except InputError:
            return False
        return True

    out: dict[str, Any] = {"type": "number"}
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
    assert all(math.isfinite(v) for k, v in out.items() if k != "type")
    return {"anyOf": [out, {"type": "null"}]} if optional else out


def _alias_groups() -> list[list[str]]:
    """Names that mean one friction model (the model and its aliases), groups of two or more."""

    groups = [[name, *[a for a, t in ALIASES.items() if t == name]] for name in MODELS]
    return [g for g in groups if len(g) > 1]


def _not_together(names: list[str]) -> dict:
    """dependentSchemas: no two of ``names`` as keys of one mapping."""
    return {
        a: {"not": {"anyOf": [{"required": [b]} for b in names if b != a]}} for a in names
    }


def _models_schema() -> dict:
    props = {}
    for name, model in {**MODELS, **{a: MODELS[t] for a, t in ALIASES.items()}}.items():
        hints = typing.get_type_hints(model.params_class)
        params = {}
        for f in dataclasses.fields(model.params_class):
            optional = type(None) in typing.get_args(hints[f.name])
            params[f.name] = {**_bounds(model, f.name, optional),
                              "description": f.metadata.get("doc", "")}
        props[name] = {"type": "object", "additionalProperties": False, "properties": params}
    dependent = {}
    for group in _alias_groups():
        dependent.update(_not_together(group))
    return {
        "type": "object",
        "additionalProperties": False,
        "properties": props,
        "dependentSchemas": dependent,
        "description": "friction model -> parameter overrides (null: the model's default); "
        "a model once, counting its aliases",
    }


def conveyor_files(studies_dir: Path) -> list[str]:
    """Conveyor files a POSTed study may name: YAML or JSON under the studies directory that
    read as valid conveyors, as paths relative to it."""

    root = Path(studies_dir)
    if not root.is_dir():
        return []
    out = []
    for path in sorted(root.rglob("*")):
        if path.suffix.lower() not in (".yaml", ".yml", ".json") or not path.is_file():
            continue
        rel = path.relative_to(root).as_posix()
        if any(part.startswith(".") for part in path.relative_to(root).parts):
            continue
        try:
            parse_conveyor(load_mapping(path))
        except (ServiceError, InputError, ValueError):
            continue
        out.append(rel)
    return out


# ------------------------------------------------------------------------------------ axes
def _numeric(schema: dict) -> dict | None:
    """The number (or integer) branch of a field schema, if it has one."""
    options = schema.get("anyOf", [schema])
    for option in options:
        if option.get("type") in ("number", "integer"):
            return option
    return None


def _axis_values(field: dict) -> dict:
    """Schema of an axis's values for a field: a list of valid values, or a range within the
    field's bounds (numbers only)."""
    field = {k: v for k, v in field.items() if k not in ("default", "title")}
    listed = {"type": "array", "minItems": 1, "uniqueItems": True, "items": field}
    num = _numeric(field)
    if num is None:
        return listed
    bound = {k: v for k, v in num.items() if k in (
        "type", "minimum", "maximum", "exclusiveMinimum", "exclusiveMaximum")}
    step = {"type": num["type"], "not": {"const": 0}}
    ranged = {
        "type": "object",
        "additionalProperties": False,
        "required": ["start", "stop", "step"],
        "properties": {"start": bound, "stop": bound, "step": step},
        "description": "start, start + step, ... up to and including stop",
    }
    return {"anyOf": [listed, ranged]}


def _walk_axes(model: type[BaseModel], prefix: str, out: dict, patterns: dict,
               pattern_prefix: str | None) -> None:
    """Every field (and sub-model) of ``model`` as an axis name -> values schema."""
    props = model.model_json_schema(ref_template="#/$defs/{model}")["properties"]
    for name, f in model.model_fields.items():
        key = f.alias or name
        schema = props[key]
        inner, is_list = _sub_model(f.annotation)
        path = f"{prefix}{key}"
        if pattern_prefix is None:
            out[path] = _axis_values(schema)
        else:
            patterns[f"{pattern_prefix}{_re(key)}$"] = _axis_values(schema)
        if inner is None:
            continue
        if is_list:
            item = copy.deepcopy(schema["items"])
            index = r"\.(0|[1-9][0-9]*)"
            pat = f"{pattern_prefix or '^' + _re(prefix)}{_re(key)}{index}"
            patterns[pat + "$"] = _axis_values(item)
            _walk_axes(inner, "", out, patterns, pat + r"\.")
        else:
            _walk_axes(inner, f"{path}.", out, patterns,
                       None if pattern_prefix is None else f"{pattern_prefix}{_re(key)}\\.")


def _re(text: str) -> str:
    return text.replace(".", r"\.")


def _sub_model(annotation: Any) -> tuple[type[BaseModel] | None, bool]:
    return _field_model(annotation)


def _grid_schema() -> dict:
    props: dict[str, dict] = {}
    patterns: dict[str, dict] = {}
    conv_axes: dict[str, dict] = {}
    conv_patterns: dict[str, dict] = {}
    _walk_axes(Conveyor, "", conv_axes, conv_patterns, None)
    scen_axes: dict[str, dict] = {}
    _walk_axes(Scenario, "", scen_axes, {}, None)
    for path, schema in conv_axes.items():
        props[path] = schema
        props[f"conveyor.{path}"] = schema
    for pat, schema in conv_patterns.items():
        patterns[pat] = schema
        patterns["^conveyor\\." + pat[1:]] = schema
    for path, schema in scen_axes.items():
        props[f"scenario.{path}"] = schema
        if path not in conv_axes:  # a bare name is a conveyor field first
            props.setdefault(path, schema)
    belt_ids = sorted(catalog.belts())
    types = {"type": "array", "minItems": 1, "uniqueItems": True,
             "items": {"type": "string", "enum": belt_ids}}
    for name in ("belt.type", "conveyor.belt.type", "belt_type"):
        props[name] = types
    names, aliases = _model_names()
    props["friction_model"] = {
        "type": "array", "minItems": 1, "uniqueItems": True,
        "items": {"type": "string", "enum": names + aliases},
        "allOf": [
            {"not": {"allOf": [{"contains": {"const": a}}, {"contains": {"const": b}}]}}
            for group in _alias_groups() for i, a in enumerate(group) for b in group[i + 1:]
        ],
        "description": "friction models, each once counting aliases (din and iso5048 are one)",
    }
    props["temperature_c"] = props["scenario.temperature_c"]
    props["stop_time_s"] = props["scenario.stop.time_s"]
    props["load"] = props["scenario.load"]
    # a friction model's parameter as an axis: models.<model>.<parameter> (numbers, or null
    # for a parameter whose default is computed)

    for name, model in {**MODELS, **{a: MODELS[t] for a, t in ALIASES.items()}}.items():
        hints = typing.get_type_hints(model.params_class)
        for f in dataclasses.fields(model.params_class):
            optional = type(None) in typing.get_args(hints[f.name])
            props[f"models.{name}.{f.name}"] = _axis_values(_bounds(model, f.name, optional))
    return {
        "type": "object",
        "minProperties": 1,
        "additionalProperties": False,
        "properties": props,
        "patternProperties": patterns,
        "description": "axis -> list of values or {start, stop, step}; Cartesian product. "
        "Axes: friction_model, temperature_c, belt_type, stop_time_s, load, or any dotted "
        "conveyor or scenario field (takeup.mass_kg, profile.0.lift_m, scenario.run_s)",
    }


# ---------------------------------------------------------------------------------- study
def _refine_conveyor(defs: dict) -> None:
    """Catalogue ids and the either-or rules of belt and take-up."""

    belt = defs["Belt"]
    ids = sorted(catalog.belts())
    belt["properties"]["type"] = {
        "anyOf": [{"type": "string", "enum": ids}, {"type": "null"}],
        "default": None, "description": belt["properties"]["type"].get("description", ""),
    }
    belt["properties"]["compound"]["enum"] = sorted(catalog.compounds())
    custom = ["rating_kn_m", "modulus_kn_m", "carcass_mass_kg_m2", "top_cover_mm",
              "bottom_cover_mm"]
    belt["anyOf"] = [
        {"required": ["type"], "properties": {"type": {"type": "string"}}},
        {"required": custom, "properties": {k: {"type": "number"} for k in custom}},
    ]
    classes = sorted({r.cema_class for r in catalog.idlers()})
    idler = defs["IdlerSet"]["properties"]["cema_class"]
    idler["anyOf"] = [{"type": "string", "enum": classes}, {"type": "null"}]
    defs["TakeUp"]["anyOf"] = [
        {"properties": {"type": {"const": "gravity"}, "pretension_kn": {"const": "auto"}}},
        {"required": ["type"],
         "properties": {"type": {"const": "fixed"}, "mass_kg": {"const": "auto"}}},
    ]


def study_schema(studies_dir: Path | None = None) -> dict:
    """The JSON Schema (draft 2020-12) of a POSTed study, with its definitions in ``$defs``."""

    conv = Conveyor.model_json_schema(ref_template="#/$defs/{model}")
    defs = conv.pop("$defs")
    scen = Scenario.model_json_schema(ref_template="#/$defs/{model}")
    defs.update(scen.pop("$defs"))
    _refine_conveyor(defs)
    defs["Conveyor"], defs["Scenario"] = conv, scen
    study = StudyIn.model_json_schema(ref_template="#/$defs/{model}")
    defs.update(study.pop("$defs", {}))
    props = study["properties"]
    files = conveyor_files(studies_dir) if studies_dir is not None else []
    conveyor_ref = {"$ref": "#/$defs/Conveyor"}
    props["conveyor"] = {
        "anyOf": [{"type": "string", "enum": files}, conveyor_ref] if files else [conveyor_ref],
        "description": "a conveyor file under the service's studies directory, or inline",
    }
    props["scenario"] = {"$ref": "#/$defs/Scenario"}
    props["name"]["pattern"] = NAME_PATTERN
    grid = _grid_schema()
    props["grid"] = grid
    props["zip"] = {"type": "array", "items": {**grid, "description": "axes that vary "
                    "together (lists of one length), crossed with the grid"}}
    study["anyOf"] = [{"required": ["grid"]},
                      {"required": ["zip"], "properties": {"zip": {"minItems": 1}}}]
    props["models"] = _models_schema()
    names, aliases = _model_names()
    props["model"] = {"anyOf": [{"type": "string", "enum": names + aliases}, {"type": "null"}],
                      "default": None, "description": props["model"].get("description", "")}
    study["$defs"] = defs
    study["title"] = "StudyDoc"
    study["description"] = (
        "A study (SPEC section 3). Besides this schema a study must satisfy: "
        + "; ".join(NOT_IN_SCHEMA) + "."
    )
    study["examples"] = [{
        "name": "example-power-vs-temperature",
        "conveyor": TINY_CONVEYOR,
        "scenario": TINY_SCENARIO,
        "grid": {"friction_model": ["din", "cema"],
                 "temperature_c": {"start": -20, "stop": 20, "step": 20}},
        "dynamics": False,
    }]
    return study


# ---------------------------------------------------------------------------------- check
class BodyChecker:
    """Holds POSTed studies to :func:`study_schema` (rebuilt when the conveyor files change)."""

    def __init__(self, studies_dir: Path):
        self.studies_dir = Path(studies_dir)
        self._key: tuple | None = None
        self._schema: dict | None = None
        self._validator = None

    def _files_key(self) -> tuple:
        root = self.studies_dir
        if not root.is_dir():
            return ()
        return tuple(sorted((str(p), p.stat().st_mtime_ns) for p in root.rglob("*")
                            if p.is_file() and p.suffix.lower() in (".yaml", ".yml", ".json")))

    def schema(self) -> dict:
        key = self._files_key()
        if self._schema is None or key != self._key:
            self._schema = study_schema(self.studies_dir)
            self._validator = jsonschema_rs.Draft202012Validator(self._schema)
            self._key = key
        return self._schema

    def errors(self, data: Any) -> list[str]:
        """``path: problem`` for each way ``data`` breaks the schema (empty: it fits)."""
        self.schema()
        out = []
        for err in self._validator.iter_errors(data):
            for path, message in _explain(err):
                out.append(f"{'.'.join(str(p) for p in path) or '(top level)'}: "
                           f"{_short(message)}")
            if len(out) >= 3:
                break
        return out[:3]


def _explain(err) -> list[tuple[list, str]]:
    """``(path, message)`` of the errors that say what is wrong: for an ``anyOf`` (a value
    that may take several forms: a number or a range, a file name or a conveyor) the errors
    of the form the value was meant to have, the one whose errors lie deepest inside it (a
    mapping with a bad field is meant to be a mapping), instead of "is not valid under any of
    the schemas"; when every form fails at the value itself, what each form wants."""
    kind = err.kind
    if type(kind).__name__ != "AnyOf" or not getattr(kind, "context", None):
        return [(list(err.instance_path), err.message)]
    here = len(err.instance_path)
    branches = [b for b in kind.context if b]
    if not branches:
        return [(list(err.instance_path), err.message)]
    deep = [b for b in branches if min(len(e.instance_path) for e in b) > here]
    if deep:
        best = max(deep, key=lambda b: (min(len(e.instance_path) for e in b), -len(b)))
        return [x for e in best for x in _explain(e)]
    # every form fails at the value itself: say what each wants ("is not of type ..."),
    # the value named once
    value = err.message.split(" is not valid under any", 1)[0]
    wants = []
    for b in branches:
        for e in b:
            m = e.message
            if m.startswith(value + " "):
                m = m[len(value) + 1:]
            if m not in wants:
                wants.append(m)
    return [(list(err.instance_path), f"{value} " + "; and ".join(wants))]


def _short(message: str, limit: int = 300) -> str:
    return message if len(message) <= limit else message[: limit - 3] + "..."


def check_body(checker: BodyChecker, data: Any, resolve) -> None:
    """Refuse a study the schema refuses. The message is the study validation's own when it
    finds the problem (it names the field and the fix), else the schema's."""

    problems = checker.errors(data)
    if not problems:
        return
    if any(re.fullmatch(r'[^(][^:]*: .* is not of type "(number|integer|boolean)"', p)
           and "; and " not in p for p in problems):
        # a value of the wrong JSON type: the schema names it exactly, where the study
        # validation may first have turned it into something else ("nan" into a number)
        raise Invalid("; ".join(problems))
    try:
        resolve(data)  # raises with its message when it sees the problem too
    except ServiceError:
        raise
    except Exception:  # noqa: BLE001 - outside the schema anything may break: its message
        pass
    raise Invalid("; ".join(problems))


# --------------------------------------------------------------------------------- openapi
def metric_names() -> list[str]:
    """Result columns ``/compare`` can take as metrics (the float columns of a run row)."""

    return [f.name for f in runs_schema_for_axes([]) if pa.types.is_floating(f.type)]


def _patch_operations(schema: dict) -> None:
    for path, ops in schema.get("paths", {}).items():
        for method, op in ops.items():
            for param in op.get("parameters", []):
                if param["in"] == "query" and param["name"] in ("baseline", "candidate",
                                                                 "friction_model"):
                    names, aliases = _model_names()
                    old = param.get("schema", {})
                    param["schema"] = {"type": "string", "enum": names + aliases,
                                       "description": "a friction model or its alias"}
                    if "default" in old:
                        param["schema"]["default"] = old["default"]
                if param["in"] == "path" and param["name"] in ("study_id", "run_id"):
                    param["schema"] = {"type": "string", "pattern": ID_PATTERN}
                if param["in"] == "path" and param["name"] == "name" and "/plots/" in path:
                    names = figures.RUN_PLOTS if "/runs/" in path else figures.STUDY_PLOTS
                    param["schema"] = {"type": "string", "enum": list(names)}
                if param["in"] == "query" and param["name"] == "metrics":
                    param["style"], param["explode"] = "form", False
                    param["schema"] = {
                        "type": "array",
                        "uniqueItems": True,
                        "items": {"type": "string", "enum": metric_names()},
                        "default": list(DEFAULT_METRICS),
                        "description": "result columns, comma-separated; none: the defaults",
                    }
                if param["in"] == "query" and param["name"] == "filter":
                    param["schema"] = {
                        "type": "array",
                        "items": {"type": "string", "pattern": "^[^=]+="},
                        "description": param["schema"].get("description", ""),
                    }
            if path == "/studies" and method == "post":
                op.setdefault("responses", {})["409"] = {
                    "description": "the same study is being deleted",
                    "content": {"application/json": {
                        "schema": {"$ref": "#/components/schemas/ErrorOut"}}},
                }
            if path == "/studies/{study_id}" and method == "delete":
                op.setdefault("responses", {})["409"] = {
                    "description": "the study is already being deleted",
                    "content": {"application/json": {
                        "schema": {"$ref": "#/components/schemas/ErrorOut"}}},
                }


def install(app, checker: BodyChecker) -> None:
    """``app.openapi()``: FastAPI's description with the study body and the patches above."""

    cache: dict[str, Any] = {}

    def openapi() -> dict:
        body = checker.schema()
        if cache.get("body") is not body:
            schema = get_openapi(title=app.title, version=app.version,
                                 description=app.description, routes=app.routes)
            doc = json.loads(json.dumps(body).replace('"#/$defs/', '"#/components/schemas/'))
            defs = doc.pop("$defs")
            components = schema.setdefault("components", {}).setdefault("schemas", {})
            components.update(defs)
            components["StudyDoc"] = doc
            _patch_operations(schema)
            cache.update(body=body, schema=schema)
        return cache["schema"]

    app.openapi = openapi
