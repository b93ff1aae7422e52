"""The door's messages: a study's one validation error, said the way the door says it.

:func:`describe` turns the :class:`pydantic.ValidationError` of :class:`~beltstudy.service.door.study.StudyIn`
into one line per problem, each naming the field by its path in the study as written:

* a conveyor's or scenario's problem as the engine says it (``conveyor.speed_m_s: ...``,
  :func:`beltstudy.engine.format_validation_error`), the rest of the study likewise;
* a grid value as the expansion says a bad grid point (``grid (belt.width_m=-1):
  conveyor.belt.width_m: ...``): the axis, the value and the field it sets;
* with ``json_types`` (a POSTed body, held to its published schema), a value of the wrong JSON
  type as JSON Schema says it: ``conveyor.speed_m_s: "4.5" is not of type "number"``.

Pydantic's locations carry the members of unions (``str``, ``inline``, ``values``); they are
dropped by walking the location through the data, and a member the value does not have the
shape of (a mapping is no text) is not reported when another member looked inside it.
"""

from __future__ import annotations

import dataclasses
import functools
import json
import math
import re
from collections import defaultdict
from typing import Any

import yaml
from pydantic import BaseModel, TypeAdapter, ValidationError

from beltstudy.engine import (
    ALIASES,
    MODELS,
    Conveyor,
    InputError,
    Scenario,
    format_validation_error,
)
from beltstudy.engine.conveyor import JSON_TYPES, as_json, nearest_word, strict_validate, type_hint
from beltstudy.service.door.study import AXIS_TARGETS, StudyIn, axis_types, unfold_axis

__all__ = ["describe", "MAX_PROBLEMS", "type_fix", "with_type_fixes"]

#: Problems named in one message; the rest are counted.
MAX_PROBLEMS = 5
#: Error types of a union member that does not take the value's shape at all (a mapping for a
#: text): not reported when another member looked inside the value.
SHAPE_TYPES = {"string_type", "float_type", "int_type", "bool_type", "list_type", "dict_type",
               "model_type", "model_attributes_type", "none_required", "literal_error"}
_ROOTS: dict[str, type[BaseModel]] = {"conveyor": Conveyor, "scenario": Scenario}


def _walk(loc: tuple, data: Any, error_type: str) -> tuple:
    """``loc`` without the union members: the keys and indices found in ``data``."""
    out: list = []
    node = data
    for i, part in enumerate(loc):
        if isinstance(node, dict) and isinstance(part, str) and part in node:
            node = node[part]
        elif isinstance(node, list) and isinstance(part, int) and 0 <= part < len(node):
            node = node[part]
        elif not (i == len(loc) - 1 and error_type == "missing"):
            continue  # a union member's label, not in the data (a missing last key is kept)
        out.append(part)
    return tuple(out)


def _located(exc: ValidationError, data: Any) -> list[dict]:
    """The errors with their paths in ``data``, less the union members the value is not."""
    errors = [{**e, "path": _walk(tuple(e["loc"]), data, e["type"])} for e in exc.errors()]
    paths = [e["path"] for e in errors]

    def outshone(e: dict) -> bool:
        return (e["type"] in SHAPE_TYPES and isinstance(e["input"], dict | list)
                and any(p[:len(e["path"])] == e["path"] and len(p) > len(e["path"])
                        for p in paths))

    return [e for e in errors if not outshone(e)]


def _axis_at(path: tuple) -> int | None:
    """Where the axis name is in a path into a grid or zip group (None: not there)."""
    if path[:1] == ("grid",) and len(path) > 1:
        return 1
    if path[:1] == ("zip",) and len(path) > 2:
        return 2
    return None


def _unfolded(path: tuple) -> tuple:
    """A path with an axis into a list as written (``grid.profile.3.lift_m.0``)."""
    at = _axis_at(path)
    if at is None or ".N" not in str(path[at]) or len(path) <= at + 1:
        return path
    return (*path[:at], unfold_axis(path[at], path[at + 1]), *path[at + 2:])


def _dotted(path: tuple) -> str:
    return ".".join(str(p) for p in _unfolded(path)) or "(top level)"


def _as_json_type(errors: list[dict]) -> str:
    """``"4.5" is not of type "number"`` for the errors at one path (the members of a union
    each add what they want)."""
    types = list(dict.fromkeys(JSON_TYPES[e["type"]] for e in errors if e["type"] in JSON_TYPES))
    others = [e["ctx"]["expected"] for e in errors
              if e["type"] == "literal_error" and "ctx" in e]
    text = f'{as_json(errors[0]["input"])} is not of type "{types[0]}"'
    text += "".join(f' or "{t}"' for t in types[1:]) + "".join(f" or {o}" for o in others)
    # what to write (a YAML 1.1 word, a number in quotes): the engine's words (type_hint);
    # else the choice a misspelt word is nearest ("inclnes": did you mean 'inclines'?)
    hint = next((h for e in errors if (h := type_hint(e["input"], e["type"]))), "")
    hint = hint or nearest_word(errors[0]["input"], " ".join(others))
    path = tuple(errors[0]["path"])
    got = errors[0]["input"]
    if not hint and _axis_at(path) == len(path) - 1 and not isinstance(got, dict | list):
        # one value where an axis takes several: the two shapes an axis has
        hint = _axis_advice(str(path[-1]), got)
    elif not hint and path == ("conveyor",) and not isinstance(got, dict | list):
        hint = ("give the path of a conveyor file as text (conveyors/slope-5pct.yaml) or the "
                "conveyor inline")
    elif not hint and len(path) == 3 and path[:2] == ("sample", "axes") \
            and not isinstance(got, dict):
        # a sampled axis written as a value or a list: its distribution (SPEC 7.2)
        number = isinstance(got, int | float) and not isinstance(got, bool)
        mean = as_json(got) if number else "..."
        hint = ("a sampled axis is a distribution, e.g. {dist: uniform, low: ..., high: ...} "
                f"or {{dist: normal, mean: {mean}, sd: ...}}; "
                + ("a list of values is a grid axis (grid:)" if isinstance(got, list) else
                   "a fixed value belongs in the conveyor or the scenario"))
    elif (not hint and path == ("accuracy",) and isinstance(got, int | float)
          and not isinstance(got, bool)):
        # the share of runs written alone: the block that holds it
        hint = f"write the share of runs to check as accuracy: {{sample: {as_json(got)}}}"
    hint = hint or next((f for e in errors if (f := type_fix(e["input"], e["type"], path))), "")
    text += f": {hint}" if hint else ""
    return f"{_dotted(errors[0]['path'])}: {text}"


#: A field's unit by the suffix of its name (the longest first), as a fix writes it.
UNIT_OF_SUFFIX = (("_kg_m2", "kg m2"), ("_t_m3", "t/m3"), ("_m_s2", "m/s2"), ("_m_s", "m/s"),
                  ("_t_h", "t/h"), ("_kn_m", "kN/m"), ("_knm", "kNm"), ("_kg_m", "kg/m"),
                  ("_kg", "kg"), ("_kn", "kN"), ("_kw", "kW"), ("_pct", "%"), ("_deg", "deg"),
                  ("_mm", "mm"), ("_m", "m"), ("_c", "C"), ("_s", "s"))
#: Units written after a number, folded (lower case, no blanks), to the
#: field's unit they convert to and the factor: ``2 km`` in a ``_m`` field is 2000.
_CONVERSIONS = {
    "km": ("m", 1000.0), "cm": ("m", 0.01), "mm": ("m", 0.001),
    "t": ("kg", 1000.0), "g": ("kg", 0.001),
    "m/min": ("m/s", 1 / 60), "km/h": ("m/s", 1 / 3.6),
    "kg/s": ("t/h", 3.6), "mw": ("kW", 1000.0), "w": ("kW", 0.001), "n": ("kN", 0.001),
}
#: Ways of writing a field's own unit after a number (folded as :data:`_CONVERSIONS`).
_SAME_UNIT = {"deg": ("degrees", "°"), "C": ("degc", "°c", "celsius", "°"),
              "%": ("%", "pct", "percent"), "m/s": ("m/s", "mps"), "t/h": ("t/h", "tph")}
#: A number and what follows it: ``4.5 m/s``, ``2km``, ``1.5%``, ``210°``, ``4,5``.
_NUMBER_AND_TEXT = re.compile(r"^([-+]?(?:\d+(?:[.,]\d*)?|[.,]\d+)(?:[eE][-+]?\d+)?)\s*(.*)$")
_DECIMAL_COMMA = re.compile(r"^[-+]?\d+,\d+$")
_NUMBER_TYPES = {"float_type", "float_parsing", "int_type", "int_parsing", "int_from_float"}
_LIST_TYPES = {"list_type", "tuple_type"}
_MAPPING_TYPES = {"dict_type", "model_type", "model_attributes_type"}


def field_unit(path: tuple) -> str:
    """The unit of the field at ``path`` by its name's suffix (``speed_m_s``: ``m/s``), the
    nearest named part that has one (``sag_limit_pct.carry``: ``%``; a grid axis
    ``belt.width_m``: ``m``); "" when none says."""
    for part in reversed(path):
        for name in reversed(str(part).split(".")) if isinstance(part, str) else ():
            unit = next((u for suffix, u in UNIT_OF_SUFFIX if name.lower().endswith(suffix)),
                        "")
            if unit:
                return unit
    return ""


def _figure(value: float) -> str:
    return f"{value:.12g}"


def type_fix(got: Any, error_type: str, path: tuple) -> str:
    """What to write for a value of the wrong type that no other hint covers: a number
    written with its unit or a sign (``4.5 m/s``, ``2 km``, ``1.5%``, ``210°``: the number
    alone, in the field's unit, converted where the unit says how: ``2 km`` -> 2000), a
    decimal comma (``4,5``), an empty value (null), 0 or 1 for a boolean, and a mapping where
    a list goes or a list where a mapping goes. These named the field and the type, not the
    fix ("``drives: {...} is not of type "array"``"); "" for any other value."""
    last = path[-1] if path else None
    if got is None and error_type in JSON_TYPES and error_type != "none_required":
        return f"give a value or remove the {'item' if isinstance(last, int) else 'key'}"
    if (error_type in ("bool_type", "bool_parsing") and isinstance(got, int)
            and not isinstance(got, bool) and got in (0, 1)):
        return "write true or false"
    if error_type in _LIST_TYPES and isinstance(got, dict):
        return "write a list: one `- {...}` item per entry"
    if (error_type in _MAPPING_TYPES and isinstance(got, str) and last == "scenario"
            and got.strip().lower().endswith((".yaml", ".yml", ".json"))):
        # a study's conveyor may be a file, its scenario is written in the study
        return ("a study's scenario is written in the study, not read from a file (the "
                "conveyor is): copy the scenario file's fields under scenario:")
    if error_type in _MAPPING_TYPES and not isinstance(got, dict):  # a list, belt: ST2000
        return "write a mapping `{key: value, ...}`"
    if error_type in ("int_from_float", "int_type") and isinstance(got, float):
        # rolls: 2.5, a count given with a fraction
        return (f"write a whole number ({math.floor(got):g} or {math.ceil(got):g})"
                if math.isfinite(got) else "write a whole number")
    if error_type not in _NUMBER_TYPES or not isinstance(got, str):
        return ""
    text = got.strip()
    if _DECIMAL_COMMA.match(text):
        point = text.replace(",", ".")
        if len(text.partition(",")[2]) == 3:  # 1,200: a thousands separator as likely
            return (f"write {point}: a decimal point, or {text.replace(',', '')} if the comma "
                    "separates thousands")
        return f"write {point}: a decimal point"
    m = _NUMBER_AND_TEXT.match(text)
    if not m:
        # words where a number goes (capacity_t_h: lots): the number, in the field's unit
        unit = field_unit(path)
        return f"write a number{f', in {unit}' if unit else ''}" if text else ""
    if not m.group(2) or m.group(2)[0].isdigit():
        return ""
    number, written = m.group(1).replace(",", "."), m.group(2).strip()
    unit = field_unit(path)
    if not unit:
        return f"write the number alone: {number}"
    folded = written.lower().replace(" ", "")
    if folded == unit.lower() or folded in _SAME_UNIT.get(unit, ()):
        return f"write the number alone, in {unit}: {number}"
    to, factor = _CONVERSIONS.get(folded, (None, 1.0))
    if to == unit:
        return (f"write the number alone, in {unit}: {_figure(float(number) * factor)} "
                f"({number} {written})")
    return f"write the number alone, in {unit} (convert {number} {written} to {unit})"


def with_type_fixes(message: str, data: Any, model: type[BaseModel], prefix: str = "") -> str:
    """``message``, the engine's for ``data`` as ``model`` (:func:`beltstudy.engine.parse_conveyor`
    of a conveyor file, ``parse_scenario`` of a scenario file; its paths after ``prefix``),
    with :func:`type_fix`'s fix after each wrong-type problem that has none: a conveyor file
    is said by the engine's words, and ``speed_m_s: 4.5 m/s`` there got the field and the
    type only, where a study's door gives the fix."""
    if "is not of type" not in message:
        return message
    try:
        strict_validate(model, data)
        return message
    except ValidationError as exc:
        errors = exc.errors()
    except InputError:  # not JSON data: said otherwise
        return message
    for e in errors:
        if e["type"] not in JSON_TYPES or type_hint(e["input"], e["type"]):
            continue
        path = _walk(tuple(e["loc"]), data, e["type"])
        fix = type_fix(e["input"], e["type"], path)
        shown = ".".join(str(p) for p in path) or "(top level)"
        head = f"{prefix}{shown}: {as_json(e['input'])} is not of type "
        at = message.find(head)
        if not fix or at < 0:
            continue
        end = message.find(f"; {prefix}", at + len(head))
        end = len(message) if end < 0 else end
        if ": " in message[at + len(head):end]:  # a fix there already (did you mean ...?)
            continue
        message = f"{message[:end]}: {fix}{message[end:]}"
    return message


@functools.cache
def _axis_items() -> dict[str, tuple[Any, bool, dict | None]]:
    """Axis name (folded) -> (the type of one value, numeric, bounds) (:func:`axis_types`)."""
    return {name: (item, numeric, bounds)
            for name, (_t, item, numeric, bounds) in axis_types().items()}


#: Values an axis's advice may show, tried in order until one the axis takes.
_NUMBER_EXAMPLES = ([0, 10, 20], [1, 2, 3], [0, 0.5, 1], [0.01, 0.02, 0.03])


def _takes(item: Any, bounds: dict | None, values: Any) -> bool:
    """Whether an axis of values of type ``item`` (a model parameter's ``bounds``) takes the
    list ``values``, held to JSON's types as a study is."""
    if not isinstance(values, list) or not values:
        return False
    try:
        TypeAdapter(list[item]).validate_json(json.dumps(values), strict=True)
    except (ValidationError, TypeError, ValueError):
        return False
    low, high = (bounds or {}).get("minimum"), (bounds or {}).get("maximum")
    above = (bounds or {}).get("exclusiveMinimum")
    return all(not isinstance(v, int | float) or isinstance(v, bool) or (
        (low is None or v >= low) and (high is None or v <= high)
        and (above is None or v > above)) for v in values)


def _words(item: Any) -> list[str]:
    """The words an axis's values may be (its schema's enums: load cases, model names)."""
    try:
        schema = TypeAdapter(item).json_schema()
    except Exception:  # noqa: BLE001 - a type without a schema: no words to offer
        return []
    found: list[str] = []
    for option in [schema, *schema.get("anyOf", [])]:
        found += [w for w in option.get("enum", [option.get("const")]) if isinstance(w, str)]
    return found


def _axis_advice(axis: str, got: Any) -> str:
    """What to write for an axis given as the one value ``got``: a list of it (``[5]``,
    ``[din]``) where the axis takes that value, else of values it takes (never the bad value
    wrapped: ``[null]`` fails again); a range of numbers it takes where it is numeric."""
    item, numeric, bounds = _axis_items().get(axis, (None, False, None))
    shown = got if isinstance(got, str) else as_json(got)  # "1,2" -> [1,2]
    try:  # null is no value to vary (where a field takes it, it is its default)
        wrapped = yaml.safe_load(f"[{shown}]") if got is not None else None
    except yaml.YAMLError:
        wrapped = None
    numbers = [v for v in (*_param_examples(axis), *_NUMBER_EXAMPLES)
               if numeric and _takes(item, bounds, v)]
    words = _words(item)[:2] if item is not None else []
    tried = [wrapped, words, *numbers, [True, False]]
    listed = next((v for v in tried if item is None or _takes(item, bounds, v)), None)
    if listed is None:
        return ("an axis is a list of the field's values (one value v: [v]) or, for a "
                "number, a range ({start, stop, step})")
    if listed is wrapped:  # the value itself, in a list
        return f"an axis is a list ([{shown}])" + (" or a range ({start, stop, step})"
                                                    if numeric else "")
    text = _flow(listed)
    if not numbers:
        return f"an axis is a list of values ({text})"
    a, b, c = numbers[0]
    return (f"an axis is a list of values ({text}) or a range "
            f"({{start: {as_json(a)}, stop: {as_json(c)}, step: {as_json(round(b - a, 12))}}})")


def _param_examples(axis: str) -> list[list[float]]:
    """For a model parameter axis (``models.din.f_carry``), its default and twice it, where
    the model has a number for it (a friction factor's scale is not a temperature's)."""
    parts = axis.split(".")
    if len(parts) != 3 or parts[0] != "models":
        return []
    fm = MODELS.get(ALIASES.get(parts[1], parts[1]))
    field = next((f for f in dataclasses.fields(fm.params_class) if f.name == parts[2]),
                 None) if fm is not None else None
    d = getattr(field, "default", None)
    if not isinstance(d, int | float) or isinstance(d, bool) or not d:
        return []
    return [[d, float(f"{2 * d:.12g}"), float(f"{3 * d:.12g}")]]


def _flow(values: list) -> str:
    """A list as a study file writes it: ``[0, 10, 20]``, ``[full, empty]``."""
    return "[" + ", ".join(v if isinstance(v, str) else as_json(v) for v in values) + "]"


def _tag_ctx(e: dict) -> dict:
    """For an unknown key: the union member labels the path walk dropped (a sample axis's
    ``uniform``), so the engine's words list that member's keys, not every member's."""
    if e["type"] != "extra_forbidden":
        return {}
    tags = [p for p in e["loc"][:-1] if isinstance(p, str) and p not in e["path"]]
    return {"ctx": {"tags": tags}} if tags else {}


def _engine_lines(errors: list[dict], model: type[BaseModel], prefix: str, skip: int) -> str:
    """The errors as the engine says them for ``model`` (paths from ``skip`` on)."""
    details = [{"type": e["type"], "loc": _unfolded(e["path"])[skip:], "input": e["input"],
                **({"ctx": e["ctx"]} if "ctx" in e else _tag_ctx(e))} for e in errors]
    exc = ValidationError.from_exception_data(model.__name__, details)
    return format_validation_error(exc, model, prefix)


def _value_key(path: tuple) -> tuple | None:
    """The path of the axis value an error lies in (None: not inside an axis's values)."""
    at = _axis_at(path)
    if at is None:
        return None
    index = at + 2 if ".N" in str(path[at]) else at + 1
    if len(path) <= index or not isinstance(path[index], int):
        return None
    return path[:index + 1]


def _target(path: tuple) -> tuple[type[BaseModel], str, tuple]:
    """The model, prefix and location of the field an axis value sets (``path``: the axis
    value's, as :func:`_value_key` gives it)."""
    at = _axis_at(path)
    folded = path[at]
    target = AXIS_TARGETS[folded]
    if ".N" in folded:
        target = unfold_axis(target, path[at + 1])
    parts = tuple(int(p) if p.isdigit() else p for p in target.split("."))
    if parts[0] in _ROOTS:
        return _ROOTS[parts[0]], f"{parts[0]}.", parts[1:]
    return StudyIn, "", parts


def _grid_value(key: tuple, errors: list[dict], data: dict) -> str:
    """Errors inside one value of one axis, said as a bad grid point is: ``grid (axis=value):
    <the field it sets>: <problem>``."""
    at = _axis_at(key)
    where = "grid" if at == 1 else f"zip.{key[1]}"
    name = _unfolded(key)[at]
    value: Any = data
    for part in key:
        value = value[part]
    model, prefix, lead = _target(key)
    moved = [{**e, "path": lead + e["path"][len(key):]} for e in errors]
    return f"{where} ({name}={value!r}): {_engine_lines(moved, model, prefix, 0)}"


def _part(e: dict) -> str:
    """Which model says an error: ``conveyor`` or ``scenario`` (inside one), else the study."""
    path = e["path"]
    inside = len(path) > 1 or e["type"] == "value_error"
    return path[0] if path and path[0] in _ROOTS and inside else ""


def describe(exc: ValidationError, data: Any, *, json_types: bool = False,
             model: type[BaseModel] = StudyIn) -> str:
    """One line per problem of ``data`` (the study as validated: its axes into lists folded)
    named by its path; ``json_types``: a wrong JSON type said as JSON Schema says it.
    ``model``: the body's model when it is not a study (a calibration request); its
    ``conveyor`` and ``scenario`` are said as the engine says them all the same."""
    errors = _located(exc, data)
    by_path: dict[tuple, list[dict]] = defaultdict(list)
    for e in errors:
        by_path[e["path"]].append(e)
    # a value of a type some member of a union takes, outside that member's range (a load of
    # 2): its range is the problem, not the other members' types
    for path, es in by_path.items():
        valued = [e for e in es if e["type"] not in JSON_TYPES and e["type"] not in SHAPE_TYPES]
        if valued and len(valued) < len(es):
            by_path[path] = valued
    kept = {id(e) for es in by_path.values() for e in es}
    errors = [e for e in errors if id(e) in kept]
    lines: list[str] = []
    typed = [p for p, es in by_path.items()
             if json_types and any(e["type"] in JSON_TYPES for e in es)]
    lines += [_as_json_type(by_path[p]) for p in typed]
    values: dict[tuple, list[dict]] = defaultdict(list)
    parts: dict[str, list[dict]] = defaultdict(list)
    for e in errors:
        if e["path"] in typed:
            continue
        key = _value_key(e["path"])
        if key is not None:
            values[key].append(e)
        else:
            parts[_part(e)].append(e)
    lines += [_grid_value(key, es, data) for key, es in values.items()]
    for part, es in parts.items():
        lines.append(_engine_lines(es, _ROOTS.get(part, model), f"{part}." if part else "",
                                   1 if part else 0))
    more = len(lines) - MAX_PROBLEMS
    return "; ".join(lines[:MAX_PROBLEMS]) + (f"; and {more} more" if more > 0 else "")
