"""The study file (SPEC sections 3 and 6.3): parsing at the door, expansion and stable ids.

:func:`resolve_study` validates a study mapping once (conveyor by path or inline, scenario,
grid, zip groups, per-model parameters, design case) and returns a :class:`ResolvedStudy`;
everything after it trusts its types. :func:`expand_runs` turns a resolved study into
:class:`RunSpec` objects, each with a ``run_id`` that is a stable hash of its fully resolved
inputs and the engine version.

Expansion: the grid points are the Cartesian product of the grid axes and the zip groups (the
axes of a group vary together). Each point's conveyor and scenario are validated (every point
that makes the conveyor invalid is named), its ``auto`` sizes are replaced by its conveyor
design's (:mod:`service.basis`), and the inputs a run does not use are set to their defaults
(a steady-only run keeps only ``load``, ``temperature_c`` and ``elements`` of the scenario; a
coast stop does not use ``stop.time_s``). Points whose resolved runs are then identical are one
run; an axis whose value differs between the points of one run is null in its row.
"""

from __future__ import annotations

import copy
import dataclasses
import hashlib
import itertools
import json
import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from pydantic import BaseModel, ConfigDict, Field, ValidationError, field_validator

import engine
from engine.conveyor import (
    Conveyor,
    InputError,
    Scenario,
    format_validation_error,
    parse_conveyor,
    parse_scenario,
)
from engine.friction import get_model
from service.axes import Target, axis_column, get_path, resolve_axis, set_path
from service.basis import Case, DesignIn, apply_sizes, design_scenario, has_auto, size_design
from service.errors import Invalid, TooLarge
from service.parse import check_tree, load_mapping

__all__ = [
    "RangeSpec",
    "StudyIn",
    "StudyDoc",
    "Axis",
    "ResolvedStudy",
    "RunSpec",
    "resolve_study",
    "load_study_file",
    "expand_runs",
    "canonical_json",
    "stable_hash",
    "DEFAULT_MODEL",
]

#: Friction model used when the grid has no ``friction_model`` axis and ``model`` is not set.
DEFAULT_MODEL = "din"
#: A study name: letters, digits and `` ._+-`` (no path separators, no ``..``).
NAME_RE = re.compile(r"^[A-Za-z0-9][A-Za-z0-9 ._+\-]{0,119}$")
#: Largest number of values one range axis may produce before the grid limit is checked.
_HASH_LEN = 16


def canonical_json(value: Any) -> str:
    """JSON with sorted keys and no spaces: the text stable ids are hashed from."""
    return json.dumps(value, sort_keys=True, separators=(",", ":"), allow_nan=False)


def stable_hash(value: Any) -> str:
    """First 16 hex digits of the SHA-256 of the canonical JSON of ``value``."""
    return hashlib.sha256(canonical_json(value).encode()).hexdigest()[:_HASH_LEN]


class RangeSpec(BaseModel):
    """An axis given as a range: ``start``, ``start + step``, ... up to and including ``stop``."""

    model_config = ConfigDict(extra="forbid")

    start: float
    stop: float
    step: float = Field(..., description="increment; its sign must lead from start to stop")

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
        return int(math.floor(span + 1e-9)) + 1

    def values(self) -> list[float | int]:
        n = self.count()
        out = [float(f"{self.start + i * self.step:.12g}") for i in range(n)]
        if all(v.is_integer() for v in out) and float(self.step).is_integer():
            return [int(v) for v in out]
        return out


AxisValues = list[Any] | RangeSpec


def _check_name(value: str) -> str:
    if ".." in value or not NAME_RE.match(value):
        raise ValueError(
            "must start with a letter or digit and use only letters, digits, spaces and ._+- "
            "(no path separators or '..'), at most 120 characters"
        )
    return value


class StudyIn(BaseModel):
    """A study as written in a file or POSTed (SPEC section 3); validated at the door."""

    model_config = ConfigDict(extra="forbid")

    name: str = Field(..., description="study name (letters, digits, spaces, ._+-)")
    description: str = Field("", max_length=2000, description="free text")
    conveyor: str | dict[str, Any] = Field(
        ..., description="conveyor file path (relative to the study file) or inline mapping"
    )
    scenario: dict[str, Any] = Field(default_factory=dict, description="SPEC section 2")
    grid: dict[str, AxisValues] = Field(
        default_factory=dict,
        description="axis -> list of values or {start, stop, step}; Cartesian product",
    )
    zip: list[dict[str, AxisValues]] = Field(
        default_factory=list,
        description="groups of axes that vary together (equal lengths), crossed with the grid",
    )
    design: DesignIn | None = Field(
        None,
        description="design case of every auto size, {friction_model, temperature_c, load}; "
        "default: the largest requirement over the study's models and temperatures at full load",
    )
    models: dict[str, dict[str, float | None]] = Field(
        default_factory=dict, description="friction model -> parameter overrides"
    )
    model: str | None = Field(
        None, description="friction model when the grid has no friction_model axis (default din)"
    )
    dynamics: bool = Field(True, description="false = steady tensions only")
    surface: bool = Field(
        False,
        description="store the tension/velocity surface of every dynamic run (SPEC section 5); "
        "false (the default) stores the key-point time series only and recomputes a run's "
        "surface from its inputs when it is asked for",
    )

    @field_validator("name")
    @classmethod
    def _name_is_safe(cls, value: str) -> str:
        return _check_name(value)


def _example() -> dict:
    from service.tasks import TINY_CONVEYOR, TINY_SCENARIO

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


class StudyDoc(StudyIn):
    """The same study with the conveyor and scenario schemas spelled out (OpenAPI only)."""

    model_config = ConfigDict(extra="forbid", json_schema_extra={"examples": [_example()]})

    conveyor: str | Conveyor = Field(  # type: ignore[assignment]
        ..., description="conveyor file path under the service's studies directory, or inline"
    )
    scenario: Scenario = Field(default_factory=Scenario)  # type: ignore[assignment]


@dataclass(frozen=True)
class Axis:
    """One grid axis after validation."""

    name: str
    column: str
    target: Target
    values: tuple[Any, ...]
    group: int | None = None  # zip group index; None for a grid axis

    def to_json(self) -> dict:
        out = {
            "name": self.name,
            "column": self.column,
            "target": self.target.dotted,
            "values": list(self.values),
        }
        if self.group is not None:
            out["group"] = self.group
        return out


@dataclass(frozen=True)
class RunSpec:
    """One run: everything a worker needs, plus the axis values for the row."""

    run_id: str
    axes: dict[str, Any]
    conveyor: dict
    scenario: dict
    model: str
    params: dict
    dynamics: bool
    engine_version: str
    design: dict = field(default_factory=dict)  # *_governed_by of the design's auto sizes
    points: int = 1  # grid points this run stands for


@dataclass
class ResolvedStudy:
    """A validated study: base conveyor and scenario (dumped, defaults filled), axes, models."""

    name: str
    description: str
    conveyor: dict
    scenario: dict
    axes: list[Axis]
    models: dict[str, dict[str, float | None]]
    model: str
    dynamics: bool
    engine_version: str
    conveyor_source: str
    total: int
    id: str = ""
    surface: bool = False
    runs: list[RunSpec] = field(default_factory=list, repr=False)
    design: dict | None = None  # the study's design case as given (None: the default)
    grid_points: int = 0  # points of the grid before identical runs were merged
    designs: list[dict] = field(default_factory=list)  # the design basis per conveyor design

    @property
    def merged(self) -> int:
        """Grid points that were merged into another point's identical run."""
        return max(self.grid_points - self.total, 0)

    def to_json(self) -> dict:
        """The resolved study as stored in ``study.json`` (enough to expand it again)."""
        out = {
            "name": self.name,
            "description": self.description,
            "conveyor": self.conveyor,
            "conveyor_source": self.conveyor_source,
            "scenario": self.scenario,
            "grid": {a.name: list(a.values) for a in self.axes if a.group is None},
            "axes": [a.to_json() for a in self.axes],
            "models": self.models,
            "model": self.model,
            "dynamics": self.dynamics,
            "surface": self.surface,
            "engine_version": self.engine_version,
            "grid_points": self.grid_points,
            "merged": self.merged,
            "designs": self.designs,
        }
        groups = sorted({a.group for a in self.axes if a.group is not None})
        if groups:
            out["zip"] = [{a.name: list(a.values) for a in self.axes if a.group == g}
                          for g in groups]
        if self.design is not None:
            out["design"] = self.design
        return out

    @property
    def columns(self) -> list[str]:
        return [a.column for a in self.axes]


def _err(exc: Exception) -> str:
    return str(exc).strip() or type(exc).__name__


def _resolve_conveyor_path(ref: str, base_dir: Path | None, root: Path | None) -> tuple[dict, str]:
    """Load a conveyor given by path. With ``root`` (the service), stay inside it."""
    if not ref.isprintable():
        raise Invalid(f"conveyor: path {ref!r} contains control characters")
    rel = Path(ref)
    if root is not None:
        if rel.is_absolute() or ".." in rel.parts or "\\" in ref or ref.startswith("~"):
            raise Invalid(
                f"conveyor: path '{ref}' must be relative to the studies directory "
                "without '..' (or give the conveyor inline)"
            )
        root_r = root.resolve()
        path = (root_r / rel).resolve()
        if root_r not in path.parents:
            raise Invalid(f"conveyor: path '{ref}' leaves the studies directory")
        if not path.is_file():
            raise Invalid(f"conveyor: file '{ref}' not found in the studies directory")
    else:
        path = (base_dir or Path.cwd()) / rel
        if not path.is_file():
            raise Invalid(f"conveyor: file '{path}' not found")
    return load_mapping(path, what=f"conveyor: {ref}"), ref


def _axis_values(name: str, spec: AxisValues, max_runs: int, where: str = "grid") -> list[Any]:
    label = f"{where}.{name}"
    if isinstance(spec, RangeSpec):
        try:
            n = spec.count()
        except ValueError as exc:
            raise Invalid(f"{label}: {exc}") from None
        if n > max_runs:
            raise TooLarge(
                f"{label}: the range has {n} values; the study limit is {max_runs} runs"
            )
        values = spec.values()
    else:
        values = list(spec)
    if not values:
        raise Invalid(f"{label}: empty axis; give at least one value")
    seen: set[str] = set()
    for v in values:
        key = canonical_json(v)
        if key in seen:
            raise Invalid(f"{label}: value {v!r} appears twice")
        seen.add(key)
    return values


def _where(axes: list[Axis], indices: list[int], combo: tuple[int, ...]) -> str:
    """``name=value, ...`` of one grid point on the axes ``indices``."""
    return ", ".join(
        f"{axes[i].name}={axes[i].values[j]!r}" for i, j in zip(indices, combo, strict=True)
    )


#: Invalid points named in one error message; the rest are counted.
MAX_NAMED_POINTS = 5


def _refuse_points(kind: str, bad: list[tuple[str, str]], total: int) -> None:
    """Raise :class:`Invalid` naming every grid point in ``bad`` (``(where, message)``)."""
    if not bad:
        return
    if len(bad) == 1:
        where, msg = bad[0]
        raise Invalid(f"grid ({where}): {msg}" if where else msg)
    named = "; ".join(f"({w}): {m}" for w, m in bad[:MAX_NAMED_POINTS])
    more = len(bad) - MAX_NAMED_POINTS
    tail = f"; and {more} more" if more > 0 else ""
    raise Invalid(f"grid: {len(bad)} of {total} {kind} variants are invalid: {named}{tail}")


def _dimensions(axes: list[Axis]) -> list[list[int]]:
    """Axis indices of each dimension of the grid: one per grid axis, one per zip group."""
    dims: list[list[int]] = []
    groups: dict[int, list[int]] = {}
    for i, a in enumerate(axes):
        if a.group is None:
            dims.append([i])
        elif a.group in groups:
            groups[a.group].append(i)
        else:
            groups[a.group] = [i]
            dims.append(groups[a.group])
    return dims


def _points(axes: list[Axis]):
    """Every grid point as a tuple of value indices, one per axis (grid x zip groups)."""
    dims = _dimensions(axes)
    for combo in itertools.product(*[range(len(axes[d[0]].values)) for d in dims]):
        point = [0] * len(axes)
        for dim, j in zip(dims, combo, strict=True):
            for i in dim:
                point[i] = j
        yield tuple(point)


def grid_points(axes: list[Axis]) -> int:
    """Number of grid points (before identical runs are merged)."""
    return math.prod(len(axes[d[0]].values) for d in _dimensions(axes))


def resolve_study(
    data: Any,
    *,
    base_dir: Path | None = None,
    studies_root: Path | None = None,
    max_runs: int = 20_000,
) -> ResolvedStudy:
    """Validate a study mapping; raise :class:`Invalid` / :class:`TooLarge` naming the field.

    ``base_dir`` resolves a conveyor path given in a local study file; ``studies_root`` (set
    by the service) confines such paths to one directory.
    """
    if not isinstance(data, dict):
        raise Invalid("study: expected a mapping with name, conveyor, scenario, grid")
    check_tree(data)  # depth, size, finite numbers, JSON types: before anything is expanded
    try:
        study = StudyIn.model_validate(data)
    except ValidationError as exc:
        raise Invalid(format_validation_error(exc, StudyIn)) from None

    if isinstance(study.conveyor, str):
        conv_data, source = _resolve_conveyor_path(study.conveyor, base_dir, studies_root)
        prefix = "conveyor: "
    else:
        conv_data, source = study.conveyor, "inline"
        prefix = "conveyor."
    try:
        conveyor = parse_conveyor(conv_data, prefix=prefix).model_dump(mode="json", by_alias=True)
        scenario = parse_scenario(study.scenario, prefix="scenario.").model_dump(
            mode="json", by_alias=True
        )
    except InputError as exc:
        raise Invalid(_err(exc)) from None

    models: dict[str, dict[str, float | None]] = {}
    for name, overrides in study.models.items():
        try:
            fm = get_model(name)
            fm.params(overrides)
        except InputError as exc:
            raise Invalid(
                f"models: {_err(exc)}" if "models." not in str(exc) else _err(exc)
            ) from None
        if fm.name in models:
            raise Invalid(f"models.{name}: model '{fm.name}' is given twice")
        models[fm.name] = dict(overrides)

    if not study.grid and not study.zip:
        raise Invalid("grid: empty; give at least one axis, e.g. temperature_c: [-20, 0, 20]")
    specs: list[tuple[str, AxisValues, int | None, str]] = [
        (name, spec, None, "grid") for name, spec in study.grid.items()
    ]
    for g, group in enumerate(study.zip):
        if not group:
            raise Invalid(f"zip.{g}: empty group; give two or more axes of equal length")
        specs += [(name, spec, g, f"zip.{g}") for name, spec in group.items()]
    axes: list[Axis] = []
    for name, spec, group, where in specs:
        values = _axis_values(name, spec, max_runs, where)
        try:
            target = resolve_axis(name, conveyor, scenario)
        except ValueError as exc:
            raise Invalid(_err(exc) if group is None
                          else _err(exc).replace("grid:", f"{where}:", 1)) from None
        for other in axes:
            if other.target.overlaps(target):
                raise Invalid(
                    f"grid: axes '{other.name}' and '{name}' both set {other.target.dotted}"
                    if other.target == target
                    else f"grid: axes '{other.name}' and '{name}' overlap "
                    f"({other.target.dotted} / {target.dotted})"
                )
        if target.root == "model":
            canon = []
            for v in values:
                try:
                    canon.append(get_model(str(v)).name)
                except InputError as exc:
                    raise Invalid(f"{where}.{name}: {_err(exc).split(': ', 1)[-1]}") from None
            if len(set(canon)) != len(canon):
                raise Invalid(f"{where}.{name}: a model is listed twice (aliases count as the "
                              "same)")
            values = canon
        elif target.root == "model_param":
            model, param = target.path
            canon = []
            for v in values:
                try:
                    p = get_model(model).params({**models.get(model, {}), param: v})
                except InputError as exc:
                    raise Invalid(f"{where}.{name}: value {v!r}: {_err(exc)}") from None
                canon.append(getattr(p, param))
            values = canon
        axes.append(Axis(name, axis_column(name), target, tuple(values), group))
    for g in range(len(study.zip)):
        lengths = {a.name: len(a.values) for a in axes if a.group == g}
        if len(set(lengths.values())) > 1:
            raise Invalid(f"zip.{g}: the axes of a zip group vary together and need equal "
                          "lengths; got " + ", ".join(f"{k} {n}" for k, n in lengths.items()))
    columns = [a.column for a in axes]
    if len(set(columns)) != len(columns):
        raise Invalid("grid: two axes map to the same column")
    total = grid_points(axes)
    if total > max_runs:
        raise TooLarge(f"grid: the study has {total} runs; the limit is {max_runs}")

    if any(a.target.root == "model" for a in axes):
        default_model = DEFAULT_MODEL
    else:
        try:
            default_model = get_model(
                study.model or (next(iter(models)) if len(models) == 1 else DEFAULT_MODEL)
            ).name
        except InputError as exc:
            raise Invalid(f"model: {_err(exc).split(': ', 1)[-1]}") from None
    run_models = set(next((a.values for a in axes if a.target.root == "model"),
                          (default_model,)))
    for a in axes:
        if a.target.root == "model_param" and a.target.path[0] not in run_models:
            raise Invalid(f"grid: axis '{a.name}': model '{a.target.path[0]}' is not run by "
                          f"this study (its models: {', '.join(sorted(run_models))})")

    design = None
    if study.design is not None:
        design = study.design.model_dump(exclude_none=True)
        if "friction_model" in design:
            try:
                design["friction_model"] = get_model(design["friction_model"]).name
            except InputError as exc:
                raise Invalid(f"design.friction_model: {_err(exc).split(': ', 1)[-1]}") from None
        if "temperature_c" in design:
            try:
                parse_scenario({"temperature_c": design["temperature_c"]}, prefix="design.")
            except InputError as exc:
                raise Invalid(_err(exc)) from None
        design_scenario(study.design, {})  # the load is a load case

    resolved = ResolvedStudy(
        name=study.name,
        description=study.description,
        conveyor=conveyor,
        scenario=scenario,
        axes=axes,
        models=models,
        model=default_model,
        dynamics=study.dynamics,
        engine_version=engine.__version__,
        conveyor_source=source,
        total=total,
        surface=study.surface,
        design=design,
        grid_points=total,
    )
    resolved.runs, canon, resolved.designs = _expand(resolved)
    resolved.total = len(resolved.runs)
    for i, axis in enumerate(axes):
        keys = [canonical_json(v) for v in canon[i]]
        if len(set(keys)) != len(keys):
            dup = next(v for v, k in zip(canon[i], keys, strict=True) if keys.count(k) > 1)
            where = "grid" if axis.group is None else f"zip.{axis.group}"
            raise Invalid(f"{where}.{axis.name}: value {dup!r} appears twice (after validation)")
        axes[i] = dataclasses.replace(axis, values=tuple(canon[i]))
    resolved.id = study_hash(resolved)
    return resolved


def study_hash(study: ResolvedStudy) -> str:
    """The study id: a stable hash of what decides its runs (and its name)."""
    doc = study.to_json()
    keys = (
        "name",
        "conveyor",
        "scenario",
        "grid",
        "models",
        "model",
        "dynamics",
        "surface",
        "engine_version",
    )
    # zip groups and the design case count only when given, so a study without them keeps
    # the id it had before they existed
    return stable_hash({k: doc[k] for k in (*keys, "zip", "design") if k in doc})


def _parse_conveyor(data: dict) -> Conveyor:
    return parse_conveyor(data, prefix="conveyor.")


def _parse_scenario(data: dict) -> Scenario:
    return parse_scenario(data, prefix="scenario.")


def _params_for(model: str, overrides: dict) -> dict:
    """The model's full parameter set (defaults filled) for the run id."""
    return dataclasses.asdict(get_model(model).params(overrides))


#: Scenario fields a steady-only run uses; the others are set to their defaults.
STEADY_FIELDS = ("load", "temperature_c", "elements")


def run_scenario(scenario: dict, dynamics: bool) -> dict:
    """The scenario as a run uses it: fields it does not read set to their defaults.

    A steady-only run reads ``load``, ``temperature_c`` and ``elements``; a coast stop does
    not read ``stop.time_s`` (the belt stops on its own). Points that differ only there are
    then the same run.
    """
    if not dynamics:
        defaults = Scenario().model_dump(mode="json", by_alias=True)
        return {**defaults, **{k: scenario[k] for k in STEADY_FIELDS}}
    if (scenario.get("stop") or {}).get("mode") == "coast":
        default = Scenario().stop.time_s
        if scenario["stop"].get("time_s") != default:
            return {**scenario, "stop": {**scenario["stop"], "time_s": default}}
    return scenario


def _expand(
    study: ResolvedStudy, designs: list[dict] | None = None
) -> tuple[list[RunSpec], list[list[Any]], list[dict]]:
    """Runs of the study (identical points merged), each axis's validated values, and the
    design basis of each conveyor design. ``designs`` (from ``study.json``) are reused
    instead of sized again when they match."""
    axes = study.axes
    points = list(_points(axes))
    i_conv = [i for i, a in enumerate(axes) if a.target.root == "conveyor"]
    i_scen = [i for i, a in enumerate(axes) if a.target.root == "scenario"]
    i_model = [i for i, a in enumerate(axes) if a.target.root == "model"]
    i_param = [i for i, a in enumerate(axes) if a.target.root == "model_param"]
    canon: list[list[Any]] = [list(a.values) for a in axes]

    def variants(indices, base, parse, kind):
        keys = list(dict.fromkeys(tuple(p[i] for i in indices) for p in points))
        out, models, bad = {}, {}, []
        for key in keys:
            data = copy.deepcopy(base)
            for i, j in zip(indices, key, strict=True):
                set_path(data, axes[i].target.path, copy.deepcopy(axes[i].values[j]))
            try:
                model = parse(data)
            except InputError as exc:
                bad.append((_where(axes, indices, key), _err(exc)))
                continue
            out[key] = model.model_dump(mode="json", by_alias=True)
            models[key] = model
        _refuse_points(kind, bad, len(keys))
        for key, variant in out.items():
            for i, j in zip(indices, key, strict=True):
                canon[i][j] = get_path(variant, axes[i].target.path)
        return out, models

    conveyors, conv_models = variants(i_conv, study.conveyor, _parse_conveyor, "conveyor")
    scenarios, scen_models = variants(i_scen, study.scenario, _parse_scenario, "scenario")

    # every realised pair: a per-section load must match the profile; a dynamic study's
    # scenario must be one the conveyor can do
    from engine.conveyor import section_loads

    pairs = list(dict.fromkeys((tuple(p[i] for i in i_conv), tuple(p[i] for i in i_scen))
                               for p in points))
    bad = []
    for ck, sk in pairs:
        conv, scn = conv_models[ck], scen_models[sk]
        try:
            section_loads(scn.load, conv)
            if study.dynamics:
                from engine.run import check_scenario  # the transient engine loads when needed

                check_scenario(scn, conv)
        except InputError as exc:
            where = ", ".join(w for w in (_where(axes, i_conv, ck), _where(axes, i_scen, sk))
                              if w)
            bad.append((where, _err(exc)))
    if bad:
        where, msg = bad[0]
        raise Invalid(f"{msg} (at grid point {where})" if where else msg)

    # the model and its parameter overrides of each point
    def model_of(p) -> str:
        return axes[i_model[0]].values[p[i_model[0]]] if i_model else study.model

    params: dict[tuple, tuple[dict, str]] = {}

    def params_of(p) -> tuple[dict, str]:
        model = model_of(p)
        key = (model, *(p[i] for i in i_param if axes[i].target.path[0] == model))
        if key not in params:
            overrides = dict(study.models.get(model, {}))
            for i in i_param:
                if axes[i].target.path[0] == model:
                    overrides[axes[i].target.path[1]] = axes[i].values[p[i]]
            params[key] = (overrides, canonical_json(_params_for(model, overrides)))
        return params[key]

    # the design basis: one per conveyor design
    sized = _design_basis(study, points, i_conv, i_scen, conveyors, conv_models, scenarios,
                          model_of, params_of, designs)

    by_id: dict[str, dict] = {}
    run_scenarios: dict[tuple, tuple[dict, str]] = {}
    run_conveyors: dict[tuple, tuple[dict, dict, str]] = {}
    for p in points:
        ck = tuple(p[i] for i in i_conv)
        sk = tuple(p[i] for i in i_scen)
        model = model_of(p)
        overrides, params_json = params_of(p)
        if sk not in run_scenarios:
            scenario = run_scenario(scenarios[sk], study.dynamics)
            run_scenarios[sk] = (scenario, canonical_json(scenario))
        scenario, scenario_json = run_scenarios[sk]
        # the sizes a run gets depend on its conveyor design and, for brakes, its stop
        stop = scenario.get("stop") or {}
        braked = study.dynamics and stop.get("mode") == "brake"
        ckey = (ck, stop.get("time_s") if braked else None)
        if ckey not in run_conveyors:
            entry = sized.get(ck)
            conveyor, governed = apply_sizes(conveyors[ck], entry["sizes"] if entry else None,
                                             scenario, study.dynamics)
            run_conveyors[ckey] = (conveyor, governed, canonical_json(conveyor))
        conveyor, governed, conveyor_json = run_conveyors[ckey]
        key = "\x1f".join(
            [
                conveyor_json,
                scenario_json,
                model,
                params_json,
                str(study.dynamics),
                study.engine_version,
            ]
        )
        run_id = hashlib.sha256(key.encode()).hexdigest()[:_HASH_LEN]
        values = {a.column: canon[i][j] for i, (a, j) in enumerate(zip(axes, p, strict=True))}
        if run_id in by_id:  # an identical run: axes that differ are null in its row
            run = by_id[run_id]
            run["points"] += 1
            for column, value in values.items():
                if canonical_json(run["axes"][column]) != canonical_json(value):
                    run["axes"][column] = None
            continue
        by_id[run_id] = dict(
            run_id=run_id,
            axes=values,
            conveyor=conveyor,
            scenario=scenario,
            model=model,
            params=overrides,
            dynamics=study.dynamics,
            engine_version=study.engine_version,
            design=governed,
            points=1,
        )
    table = [{"axes": entry["axes"], "key": entry["key"], "sizes": entry["sizes"]}
             for entry in sized.values()]
    return [RunSpec(**r) for r in by_id.values()], canon, table


def _design_basis(study, points, i_conv, i_scen, conveyors, conv_models, scenarios, model_of,
                  params_of, stored) -> dict:
    """``{conveyor key: {"axes", "key", "sizes"}}`` for every conveyor design with auto
    sizes (:mod:`service.basis`)."""
    axes = study.axes
    design = study.design or {}
    design_load = design_scenario(DesignIn(**design) if design else None, {}).load
    known = {d["key"]: d["sizes"] for d in stored or []}
    out: dict = {}
    for ck in dict.fromkeys(tuple(p[i] for i in i_conv) for p in points):
        conv = conveyors[ck]
        if not has_auto(conv):
            continue
        key = stable_hash({"conveyor": conv, "design": design, "models": study.models,
                           "scenario": study.scenario})
        mine = [p for p in points if tuple(p[i] for i in i_conv) == ck]
        where = _where(axes, i_conv, ck)
        if key in known:
            sizes = known[key]
        else:
            cases: dict[Case, None] = {}
            stops: set[float] = set()
            for p in mine:
                scn = scenarios[tuple(p[i] for i in i_scen)]
                model = model_of(p)
                overrides = params_of(p)[0]
                if "friction_model" in design and model != design["friction_model"]:
                    model = design["friction_model"]
                    overrides = dict(study.models.get(model, {}))
                temp = float(design.get("temperature_c", scn["temperature_c"]))
                cases[Case(model, tuple(sorted(overrides.items())), temp, scn["elements"])] = None
                if study.dynamics and scn["stop"]["mode"] == "brake":
                    stops.add(float(scn["stop"]["time_s"]))
            sizes = size_design(conv_models[ck], list(cases), design_load, sorted(stops), where)
        out[ck] = {"axes": {axes[i].name: axes[i].values[j]
                            for i, j in zip(i_conv, ck, strict=True)},
                   "key": key, "sizes": sizes}
    return out


def expand_runs(study: ResolvedStudy) -> list[RunSpec]:
    """The study's runs as :class:`RunSpec` objects (validated variants, identical grid points
    merged, the design basis applied)."""
    return _expand(study, study.designs)[0]


def study_from_json(doc: dict, study_id: str) -> ResolvedStudy:
    """Rebuild a resolved study from ``study.json`` (for resuming)."""
    from service.axes import resolve_axis as _resolve

    axes = [
        Axis(
            a["name"],
            a["column"],
            _resolve(a["name"], doc["conveyor"], doc["scenario"]),
            tuple(a["values"]),
            a.get("group"),
        )
        for a in doc["axes"]
    ]
    study = ResolvedStudy(
        name=doc["name"],
        description=doc.get("description", ""),
        conveyor=doc["conveyor"],
        scenario=doc["scenario"],
        axes=axes,
        models=doc.get("models", {}),
        model=doc.get("model", DEFAULT_MODEL),
        dynamics=bool(doc["dynamics"]),
        engine_version=doc["engine_version"],
        conveyor_source=doc.get("conveyor_source", "inline"),
        total=grid_points(axes),
        id=study_id,
        # a study stored before the field existed stored every surface
        surface=bool(doc.get("surface", True)),
        design=doc.get("design"),
        grid_points=grid_points(axes),
        designs=list(doc.get("designs") or []),
    )
    study.runs, _, study.designs = _expand(study, study.designs)
    study.total = len(study.runs)
    return study


def load_study_file(path: str | Path, *, max_runs: int = 20_000) -> ResolvedStudy:
    """Read and resolve a study file (YAML or JSON); the conveyor path is relative to it."""
    p = Path(path)
    return resolve_study(load_mapping(p), base_dir=p.parent, max_runs=max_runs)


def inline_conveyor(data: dict, base_dir: Path) -> dict:
    """A copy of a study mapping with a conveyor path replaced by the file's mapping."""
    out = dict(data)
    ref = out.get("conveyor")
    if isinstance(ref, str):
        conv, _ = _resolve_conveyor_path(ref, base_dir, None)
        out["conveyor"] = conv
    return out
