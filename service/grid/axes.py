"""Grid axes: which input field an axis name sets, and the Parquet column it becomes.

An axis is one of the five named axes of the design card (``friction_model``,
``temperature_c``, ``belt_type``, ``stop_time_s``, ``load``), any dotted field of the
conveyor (``takeup.mass_kg``, ``belt.width_m``, ``profile.0.lift_m``) or of the scenario
(``scenario.run_s``, or bare ``run_s``), or a friction model parameter
(``models.din.f_carry``: root ``model_param``, path ``(model, parameter)``). A ``conveyor.``
prefix is accepted too. Unknown paths are rejected with the nearest valid path.
"""

from __future__ import annotations

import dataclasses
import difflib
import typing
from dataclasses import dataclass
from typing import Any

from pydantic import BaseModel

from beltstudy.engine import MODELS, Conveyor, InputError, Scenario, get_model, results
from beltstudy.engine.conveyor import unit_twin

__all__ = [
    "NAMED_AXES",
    "NOT_READ",
    "RESULT_COLUMNS_TAKEN",
    "Target",
    "resolve_axis",
    "axis_column",
    "with_paths",
    "get_path",
    "valid_paths",
    "field_model",
]

#: The design card's named axes -> (root, path) they set.
NAMED_AXES: dict[str, tuple[str, ...]] = {
    "friction_model": ("model",),
    "temperature_c": ("scenario", "temperature_c"),
    "belt_type": ("conveyor", "belt", "type"),
    "stop_time_s": ("scenario", "stop", "time_s"),
    "load": ("scenario", "load"),
}

#: Conveyor fields no run reads (free text: the conveyor's ``name`` is a label, the physics is
#: the same under any name) -> how a message says them. An axis of two or more of their values
#: would be runs that differ in nothing a run reads, with the same results: the door refuses it
#: (:func:`beltstudy.service.door.studyfile.resolve_study`), and no suggestion points at one.
NOT_READ: dict[tuple[str, ...], str] = {("name",): "the conveyor's name"}

#: Result columns an axis column must not shadow (every column of :mod:`beltstudy.engine.results`;
#: SPEC section 4 names the achieved stop time ``stop_time_s``); such an axis is stored as
#: ``<stem>_target_<unit>``.
RESULT_COLUMNS_TAKEN = frozenset(results.columns())


@dataclass(frozen=True)
class Target:
    """Where an axis value goes: ``root`` is conveyor, scenario or model."""

    root: str
    path: tuple[str | int, ...]

    @property
    def dotted(self) -> str:
        return ".".join([self.root, *map(str, self.path)])

    @property
    def shown(self) -> str:
        """The field as a study file writes it (``models.din.f_carry``; ``dotted`` keeps the
        stored root name ``model_param``)."""
        root = "models" if self.root == "model_param" else self.root
        return ".".join([root, *map(str, self.path)])

    def overlaps(self, other: Target) -> bool:
        if self.root != other.root:
            return False
        n = min(len(self.path), len(other.path))
        return self.path[:n] == other.path[:n]


def field_model(annotation: Any) -> tuple[type[BaseModel] | None, bool]:
    """The model inside a field annotation and whether it is a list of that model."""
    origin = typing.get_origin(annotation)
    if origin is list:
        inner, _ = field_model(typing.get_args(annotation)[0])
        return inner, True
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return annotation, False
    for arg in typing.get_args(annotation):
        found, is_list = field_model(arg)
        if found is not None:
            return found, is_list
    return None, False


def _lookup(model: type[BaseModel], key: str) -> str | None:
    """The key as it appears in the dumped mapping (alias when there is one)."""
    for name, f in model.model_fields.items():
        if key in (name, f.alias):
            return f.alias or name
    return None


def _walk(model: type[BaseModel], parts: list[str], data: Any) -> tuple[str | int, ...] | str:
    """Check ``parts`` against the model tree; return the normalised path or an error."""
    out: list[str | int] = []
    current: type[BaseModel] | None = model
    is_list = False
    for part in parts:
        if is_list:
            if not (part.isascii() and part.isdigit()):
                # str.isdigit takes any script's digits and superscripts ('²', Arabic-Indic
                # '١'), which int() reads as another number or not at all
                at = ".".join(map(str, out))
                odd = next((c for c in part if not c.isascii()), None)
                if odd is not None and any(c.isnumeric() for c in part):
                    return (f"the index '{part}' into '{at}' must be a plain number 0-9 (ASCII "
                            f"digits only; U+{ord(odd):04X} '{odd}' is not one)")
                return f"expected an index into '{at}', got '{part}'"
            index = int(part)
            size = len(data) if isinstance(data, list) else 0
            if index >= size:
                return (
                    f"'{'.'.join(map(str, out))}' has {size} "
                    f"{'entry' if size == 1 else 'entries'}; index {index} is out of range"
                )
            out.append(index)
            data = data[index]
            is_list = False
            continue
        if current is None:
            return f"'{'.'.join(map(str, out))}' has no sub-fields"
        key = _lookup(current, part)
        if key is None:
            return "unknown"
        field = next(f for n, f in current.model_fields.items() if key in (n, f.alias))
        out.append(key)
        data = data.get(key) if isinstance(data, dict) else None
        current, is_list = field_model(field.annotation)
    return tuple(out)


def _paths(model: type[BaseModel], prefix: str, data: Any) -> list[str]:
    out = []
    for name, f in model.model_fields.items():
        key = f.alias or name
        path = f"{prefix}{key}"
        out.append(path)
        inner, is_list = field_model(f.annotation)
        if inner is None:
            continue
        sub = data.get(key) if isinstance(data, dict) else None
        if is_list:
            items = sub if isinstance(sub, list) and sub else [None]
            for i, item in enumerate(items):
                out.append(f"{path}.{i}")
                out.extend(_paths(inner, f"{path}.{i}.", item))
        else:
            out.extend(_paths(inner, f"{path}.", sub))
    return out


def valid_paths(conveyor: dict, scenario: dict) -> list[str]:
    """Every axis name accepted for this conveyor and scenario (for suggestions), less the
    fields no run reads (:data:`NOT_READ`)."""

    models = [f"models.{m}.{f.name}" for m, fm in MODELS.items()
              for f in dataclasses.fields(fm.params_class)]
    unread = {".".join(path) for path in NOT_READ}
    return (
        list(NAMED_AXES) + [p for p in _paths(Conveyor, "", conveyor) if p not in unread]
        + _paths(Scenario, "scenario.", scenario) + models
    )


def resolve_axis(name: str, conveyor: dict, scenario: dict, where: str = "grid") -> Target:
    """Map an axis name to the field it sets; raise :class:`InputError` naming the nearest
    path, with ``where`` (``grid`` or ``zip.<n>``) as its field.

    ``conveyor`` and ``scenario`` are the resolved (dumped) base mappings, used for list
    lengths (``profile.3.lift_m`` needs four sections).
    """
    if name in NAMED_AXES:
        root, *path = NAMED_AXES[name]
        return Target(root, tuple(path))
    parts = name.split(".")
    if any(p == "" for p in parts):
        raise InputError(f"axis '{name}' is not a dotted field path", field=where)
    if parts[0] == "models":
        return _model_param(name, parts, where)
    candidates: list[tuple[str, type[BaseModel], list[str], dict]] = []
    if parts[0] == "scenario":
        candidates.append(("scenario", Scenario, parts[1:], scenario))
    elif parts[0] == "conveyor":
        candidates.append(("conveyor", Conveyor, parts[1:], conveyor))
    else:
        candidates.append(("conveyor", Conveyor, parts, conveyor))
        candidates.append(("scenario", Scenario, parts, scenario))
    problems = []
    for root, model, rest, data in candidates:
        if not rest:
            continue
        found = _walk(model, rest, data)
        if isinstance(found, tuple):
            return Target(root, found)
        if found != "unknown":
            problems.append(found)
    if problems:
        raise InputError(f"axis '{name}': {problems[0]}", field=where)
    paths = valid_paths(conveyor, scenario)
    close = difflib.get_close_matches(name, paths, n=1, cutoff=0.5)
    hint = f"; did you mean '{close[0]}'?" if close else ""
    # a field with its unit written in another one (belt.width_ft): the field and the
    # conversion, as the conveyor file says it (renamed alone, the values stay in feet)
    parent, _, last = name.rpartition(".")
    twin = unit_twin(last, [p.rpartition(".")[2] for p in paths if p.rpartition(".")[0] == parent])
    if twin:
        hint = "; " + twin.replace("did you mean '", f"did you mean '{parent}." if parent else
                                   "did you mean '", 1)
    raise InputError(
        f"unknown axis '{name}'{hint} (axes are {', '.join(NAMED_AXES)} or a dotted "
        "conveyor or scenario field such as takeup.mass_kg or scenario.run_s, or a model "
        "parameter such as models.din.f_carry)", field=where)


def _model_param(name: str, parts: list[str], where: str) -> Target:
    """``models.<model>.<parameter>``: a friction model parameter as an axis."""

    if len(parts) != 3:
        raise InputError(f"axis '{name}': a model parameter axis is "
                         "models.<model>.<parameter>, e.g. models.din.f_carry", field=where)
    try:
        fm = get_model(parts[1])
    except InputError as exc:
        raise InputError(f"axis '{name}': {exc.reason}", field=where) from None
    fields = [f.name for f in dataclasses.fields(fm.params_class)]
    if parts[2] not in fields:
        close = difflib.get_close_matches(parts[2], fields, n=1, cutoff=0.5)
        hint = f"; did you mean 'models.{fm.name}.{close[0]}'?" if close else ""
        raise InputError(f"axis '{name}': unknown parameter of model '{fm.name}'{hint}; "
                         f"valid: {', '.join(fields)}", field=where)
    return Target("model_param", (fm.name, parts[2]))


def axis_column(name: str) -> str:
    """The Parquet column of an axis: its name, unless a result column has that name."""
    if name not in RESULT_COLUMNS_TAKEN:
        return name
    stem, _, unit = name.rpartition("_")
    return f"{stem}_target_{unit}"


def get_path(data: Any, path: tuple[str | int, ...]) -> Any:
    """``data[path]`` (None where the path is missing)."""
    node = data
    for key in path:
        try:
            node = node[key]
        except (KeyError, IndexError, TypeError):
            return None
    return node


def with_paths(base: dict, sets: list[tuple[tuple[str | int, ...], Any]]) -> dict:
    """``base`` with ``data[path] = value`` for each of ``sets``, ``base`` untouched: the
    mappings and lists on each path are copied (missing mappings created), everything else is
    shared with ``base``, so the result must only be read (parsing never changes its input; a
    20 000-run study need not copy its whole conveyor 20 000 times)."""
    data = dict(base)
    for path, value in sets:
        node: Any = data
        for key in path[:-1]:
            child = node[key] if isinstance(key, int) else node.get(key)
            if child is None:
                child = {}
            elif isinstance(child, dict):
                child = dict(child)
            elif isinstance(child, list):
                child = list(child)
            node[key] = child
            node = child
        node[path[-1]] = value
    return data
