"""The OpenAPI description: the study body's schema is the study model's, and the routes'
parameters say what they take.

:func:`study_schema` is :class:`~beltstudy.service.door.study.StudyIn`'s JSON Schema
(``model_json_schema`` with :class:`~beltstudy.service.door.study.StudySchema`), with one
thing only the service knows added: the conveyor files a POSTed study may name (the valid
conveyors in its studies directory, :func:`conveyor_files`). A POSTed study is validated by
that model, so the schema and the validation are one definition; what JSON Schema cannot
state is checked after the model and named in :data:`NOT_IN_SCHEMA`.

:func:`install` puts the schema into the app's ``/openapi.json`` (as ``StudyDoc``, its
definitions beside FastAPI's) with the patterns of study and run ids, the ``metrics`` list of
``/compare``, the ``filter`` syntax, the friction model names and the plot names.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pyarrow as pa
from fastapi.openapi.utils import get_openapi

from beltstudy.engine import InputError, parse_conveyor
from beltstudy.service.calibration import CalibrationIn
from beltstudy.service.charts import RUN_PLOTS, STUDY_PLOTS
from beltstudy.service.door.parse import load_mapping
from beltstudy.service.door.study import (
    NAME_PATTERN,
    NOT_IN_SCHEMA,
    OWN_PARTS,
    StudyIn,
    StudySchema,
    model_names,
)
from beltstudy.service.errors import ServiceError
from beltstudy.service.store.columns import runs_schema_for_axes
from beltstudy.service.store.query import DEFAULT_METRICS

__all__ = [
    "NOT_IN_SCHEMA",
    "ID_PATTERN",
    "NAME_PATTERN",
    "REF_TEMPLATE",
    "study_schema",
    "conveyor_files",
    "install",
    "metric_names",
]

#: Study and run ids: 16 hex digits.
ID_PATTERN = "^[0-9a-f]{16}$"
#: Where the study model's definitions go in the OpenAPI document.
REF_TEMPLATE = "#/components/schemas/{model}"
_STUDY_FILES = (".yaml", ".yml", ".json")


def conveyor_files(studies_dir: Path) -> list[str]:
    """Conveyor files a POSTed study may name: YAML or JSON under the studies directory that
    read as valid conveyors, as paths relative to it."""

    root = Path(studies_dir)
    if not root.is_dir():
        return []
    out = []
    for path in sorted(root.rglob("*")):
        if path.suffix.lower() not in _STUDY_FILES or not path.is_file():
            continue
        rel = path.relative_to(root)
        if any(part.startswith(".") for part in rel.parts):
            continue
        try:
            parse_conveyor(load_mapping(path))
        except (ServiceError, InputError, ValueError):
            continue
        out.append(rel.as_posix())
    return out


def _inline(node: Any, defs: dict, names: set[str], template: str) -> Any:
    """``node`` with every reference to a definition in ``names`` written out."""
    if isinstance(node, list):
        return [_inline(v, defs, names, template) for v in node]
    if not isinstance(node, dict):
        return node
    ref = node.get("$ref", "")
    name = ref.rpartition("/")[2]
    if name in names and ref == template.format(model=name):
        return _inline({**defs[name], **{k: v for k, v in node.items() if k != "$ref"}},
                       defs, names, template)
    return {k: _inline(v, defs, names, template) for k, v in node.items()}


def study_schema(studies_dir: Path | None = None, ref_template: str = "#/$defs/{model}") -> dict:
    """The JSON Schema (draft 2020-12) of a POSTed study, its definitions in ``$defs``: the
    study model's, with its own parts (grid, friction models) written out in it (only the
    engine's models stay definitions) and a conveyor file one of :func:`conveyor_files`."""

    schema = StudyIn.model_json_schema(ref_template=ref_template, schema_generator=StudySchema)
    defs = schema.pop("$defs")
    own = {model.__name__ for model in OWN_PARTS}
    schema = _inline(schema, defs, own, ref_template)
    schema["$defs"] = {k: _inline(v, defs, own, ref_template) for k, v in defs.items()
                       if k not in own}
    return with_conveyor_files(schema, studies_dir)


def with_conveyor_files(schema: dict, studies_dir: Path | None) -> dict:
    """``schema`` (a study's or a calibration's body) with its ``conveyor`` a file that is one
    of :func:`conveyor_files` (an enum a client and a test generator can read) or inline."""
    files = conveyor_files(studies_dir) if studies_dir is not None else []
    conveyor = schema["properties"]["conveyor"]
    file, inline = conveyor.pop("oneOf")  # text or a mapping: never both
    conveyor.pop("title", None)
    conveyor["anyOf"] = [{**file, "enum": files}, inline] if files else [inline]
    return schema


def _files_key(studies_dir: Path) -> tuple:
    """What the conveyor files of the schema depend on: the study files and their times."""
    root = Path(studies_dir)
    if not root.is_dir():
        return ()
    return tuple(sorted((str(p), p.stat().st_mtime_ns) for p in root.rglob("*")
                        if p.is_file() and p.suffix.lower() in _STUDY_FILES))


# --------------------------------------------------------------------------------- openapi
def metric_names() -> list[str]:
    """Result columns ``/compare`` can take as metrics (the float columns of a run row)."""

    return [f.name for f in runs_schema_for_axes([]) if pa.types.is_floating(f.type)]


def _parameter_schema(path: str, param: dict) -> dict | None:
    """The schema of a route's parameter, where it says more than FastAPI's."""
    where, name = param["in"], param["name"]
    if where == "query" and name in ("baseline", "candidate", "friction_model"):
        # that the candidate is another model than the baseline (an alias is the model) is a
        # rule across the two parameters, which JSON Schema cannot state: said in words
        names = model_names()
        default = param.get("schema", {}).get("default")
        if default in names:  # first: a generator's first pick is then a valid pair (cema,
            names = [default] + [n for n in names if n != default]  # nonlin), not din, din
        out = {"type": "string", "enum": names,
               "description": "a friction model or its alias" + (
                   ", another model than the baseline (by name or alias)"
                   if name == "candidate" else "")}
        if default is not None:
            out["default"] = default
        return out
    if where == "path" and name in ("study_id", "run_id"):
        return {"type": "string", "pattern": ID_PATTERN}
    if where == "path" and name == "name" and "/plots/" in path:
        return {"type": "string", "enum": list(RUN_PLOTS if "/runs/" in path else STUDY_PLOTS)}
    if where == "query" and name == "metrics":
        param["style"], param["explode"] = "form", False
        # at least one: an empty value (metrics=) is refused naming the parameter; the
        # defaults are had by leaving the parameter out
        return {"type": "array", "uniqueItems": True, "minItems": 1,
                "items": {"type": "string", "enum": metric_names()},
                "default": list(DEFAULT_METRICS),
                "description": "result columns, comma-separated, each once; leave the "
                               "parameter out for the defaults"}
    if where == "query" and name == "filter":
        out = {"type": "array", "items": {"type": "string", "pattern": "^[^=]+="},
               "description": param["schema"].get("description", "")}
        if "maxItems" in param["schema"]:  # the route's limit (more is a 422) stays stated
            out["maxItems"] = param["schema"]["maxItems"]
        return out
    return None


def _conflict(description: str) -> dict:
    return {"description": description, "content": {"application/json": {
        "schema": {"$ref": "#/components/schemas/ErrorOut"}}}}


def _patch_operations(schema: dict) -> None:
    for path, ops in schema.get("paths", {}).items():
        for method, op in ops.items():
            for param in op.get("parameters", []):
                better = _parameter_schema(path, param)
                if better is not None:
                    param["schema"] = better
            if path == "/studies" and method == "post":
                op.setdefault("responses", {})["409"] = _conflict(
                    "the same study is being deleted")
            if path == "/studies/{study_id}" and method == "delete":
                op.setdefault("responses", {})["409"] = _conflict(
                    "the study is already being deleted")


def install(app, studies_dir: Path) -> None:
    """``app.openapi()``: FastAPI's description with the study body (``StudyDoc``) and the
    parameters above; made again when the conveyor files change."""

    cache: dict[str, Any] = {}

    def openapi() -> dict:
        key = _files_key(studies_dir)
        if cache.get("key") != key or "schema" not in cache:
            schema = get_openapi(title=app.title, version=app.version,
                                 description=app.description, routes=app.routes)
            body = study_schema(studies_dir, REF_TEMPLATE)
            components = schema.setdefault("components", {}).setdefault("schemas", {})
            # the calibration body, read from the request as a study is (its parts: the
            # study's definitions of the same models win below)
            calibration = with_conveyor_files(
                CalibrationIn.model_json_schema(ref_template=REF_TEMPLATE), studies_dir)
            components.update(calibration.pop("$defs", {}))
            components["CalibrationIn"] = calibration
            components.update(body.pop("$defs"))
            components["StudyDoc"] = body
            _patch_operations(schema)
            cache.update(key=key, schema=schema)
        return cache["schema"]

    app.openapi = openapi
