"""The study file (SPEC section 3): parsing at the door, grid expansion and stable ids.

:func:`resolve_study` validates a study mapping once (conveyor by path or inline, scenario,
grid, per-model parameters) and returns a :class:`ResolvedStudy`; everything after it trusts
its types. :func:`expand_runs` turns a resolved study into :class:`RunSpec` objects, each with
a ``run_id`` that is a stable hash of its fully resolved inputs and the engine version.
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
        ..., description="axis -> list of values or {start, stop, step}; Cartesian product"
    )
    models: dict[str, dict[str, float | None]] = Field(
        default_factory=dict, description="friction model -> parameter overrides"
    )
    model: str | None = Field(
        None, description="friction model when the grid has no friction_model axis (default din)"
    )
    dynamics: bool = Field(True, description="false = steady tensions only")
    surface: bool = Field(
        True,
        description="store the tension/velocity surface of every dynamic run (SPEC section 5); "
        "false keeps the key-point time series only",
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

    def to_json(self) -> dict:
        return {
            "name": self.name,
            "column": self.column,
            "target": self.target.dotted,
            "values": list(self.values),
        }


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
    surface: bool = True
    runs: list[RunSpec] = field(default_factory=list, repr=False)

    def to_json(self) -> dict:
        """The resolved study as stored in ``study.json`` (enough to expand it again)."""
        return {
            "name": self.name,
            "description": self.description,
            "conveyor": self.conveyor,
            "conveyor_source": self.conveyor_source,
            "scenario": self.scenario,
            "grid": {a.name: list(a.values) for a in self.axes},
            "axes": [a.to_json() for a in self.axes],
            "models": self.models,
            "model": self.model,
            "dynamics": self.dynamics,
            "surface": self.surface,
            "engine_version": self.engine_version,
        }

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


def _axis_values(name: str, spec: AxisValues, max_runs: int) -> list[Any]:
    if isinstance(spec, RangeSpec):
        try:
            n = spec.count()
        except ValueError as exc:
            raise Invalid(f"grid.{name}: {exc}") from None
        if n > max_runs:
            raise TooLarge(
                f"grid.{name}: the range has {n} values; the study limit is {max_runs} runs"
            )
        values = spec.values()
    else:
        values = list(spec)
    if not values:
        raise Invalid(f"grid.{name}: empty axis; give at least one value")
    seen: set[str] = set()
    for v in values:
        key = canonical_json(v)
        if key in seen:
            raise Invalid(f"grid.{name}: value {v!r} appears twice")
        seen.add(key)
    return values


def _where(axes: list[Axis], indices: list[int], combo: tuple[int, ...]) -> str:
    """``name=value, ...`` of one grid point on the axes ``indices``."""
    return ", ".join(
        f"{axes[i].name}={axes[i].values[j]!r}" for i, j in zip(indices, combo, strict=True)
    )


def _validate_variants(
    axes: list[Axis], base: dict, parse, root: str, parsed: dict | None = None
) -> dict[tuple[int, ...], dict]:
    """Apply every combination of the axes on ``root`` to ``base`` and validate each result
    (the validated models also go into ``parsed`` when given)."""
    mine = [i for i, a in enumerate(axes) if a.target.root == root]
    out: dict[tuple[int, ...], dict] = {}
    for combo in itertools.product(*[range(len(axes[i].values)) for i in mine]):
        data = copy.deepcopy(base)
        for i, j in zip(mine, combo, strict=True):
            set_path(data, axes[i].target.path, copy.deepcopy(axes[i].values[j]))
        try:
            model = parse(data)
        except InputError as exc:
            raise Invalid(f"grid ({_where(axes, mine, combo)}): {_err(exc)}") from None
        out[combo] = model.model_dump(mode="json", by_alias=True)
        if parsed is not None:
            parsed[combo] = model
    return out


def _check_scenarios(axes: list[Axis], conveyors: dict, scenarios: dict) -> None:
    """Every conveyor variant with every scenario variant: a scenario the conveyor cannot do
    (a brake stop without brakes, a stop shorter than the brake delay) is refused at the door,
    naming the grid point, before any run is computed."""
    from engine.run import check_scenario  # the transient engine loads only when needed

    i_conv = [i for i, a in enumerate(axes) if a.target.root == "conveyor"]
    i_scen = [i for i, a in enumerate(axes) if a.target.root == "scenario"]
    for ck, conv in conveyors.items():
        for sk, scn in scenarios.items():
            try:
                check_scenario(scn, conv)
            except InputError as exc:
                where = ", ".join(
                    w for w in (_where(axes, i_conv, ck), _where(axes, i_scen, sk)) if w
                )
                raise Invalid(f"{_err(exc)} (at grid point {where})" if where
                              else _err(exc)) from None


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

    if not study.grid:
        raise Invalid("grid: empty; give at least one axis, e.g. temperature_c: [-20, 0, 20]")
    axes: list[Axis] = []
    total = 1
    for name, spec in study.grid.items():
        values = _axis_values(name, spec, max_runs)
        try:
            target = resolve_axis(name, conveyor, scenario)
        except ValueError as exc:
            raise Invalid(_err(exc)) from None
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
                    raise Invalid(f"grid.{name}: {_err(exc).split(': ', 1)[-1]}") from None
            if len(set(canon)) != len(canon):
                raise Invalid(f"grid.{name}: a model is listed twice (aliases count as the same)")
            values = canon
        axes.append(Axis(name, axis_column(name), target, tuple(values)))
        total *= len(values)
    columns = [a.column for a in axes]
    if len(set(columns)) != len(columns):
        raise Invalid("grid: two axes map to the same column")
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
    )
    resolved.runs, canon = _expand(resolved)
    for i, axis in enumerate(axes):
        keys = [canonical_json(v) for v in canon[i]]
        if len(set(keys)) != len(keys):
            dup = next(v for v, k in zip(canon[i], keys, strict=True) if keys.count(k) > 1)
            raise Invalid(f"grid.{axis.name}: value {dup!r} appears twice (after validation)")
        axes[i] = dataclasses.replace(axis, values=tuple(canon[i]))
    ids = {r.run_id for r in resolved.runs}
    if len(ids) != len(resolved.runs):
        raise Invalid(
            "grid: two grid points give identical runs (values equal after validation, "
            "e.g. 20 and 20.0); remove the duplicate"
        )
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
    return stable_hash({k: doc[k] for k in keys})


def _parse_conveyor(data: dict) -> Conveyor:
    return parse_conveyor(data, prefix="conveyor.")


def _parse_scenario(data: dict) -> Scenario:
    return parse_scenario(data, prefix="scenario.")


def _params_for(model: str, overrides: dict) -> dict:
    """The model's full parameter set (defaults filled) for the run id."""
    return dataclasses.asdict(get_model(model).params(overrides))


def _expand(study: ResolvedStudy) -> tuple[list[RunSpec], list[list[Any]]]:
    """Runs of the Cartesian product, and each axis's values as validated (canonical)."""
    axes = study.axes
    conv_models: dict = {}
    scen_models: dict = {}
    conveyors = _validate_variants(axes, study.conveyor, _parse_conveyor, "conveyor", conv_models)
    scenarios = _validate_variants(axes, study.scenario, _parse_scenario, "scenario", scen_models)
    if study.dynamics:
        _check_scenarios(axes, conv_models, scen_models)
    conv_json = {k: canonical_json(v) for k, v in conveyors.items()}
    scen_json = {k: canonical_json(v) for k, v in scenarios.items()}
    i_conv = [i for i, a in enumerate(axes) if a.target.root == "conveyor"]
    i_scen = [i for i, a in enumerate(axes) if a.target.root == "scenario"]
    i_model = [i for i, a in enumerate(axes) if a.target.root == "model"]
    canon: list[list[Any]] = [list(a.values) for a in axes]
    for indices, variants in ((i_conv, conveyors), (i_scen, scenarios)):
        for combo, variant in variants.items():
            for i, j in zip(indices, combo, strict=True):
                canon[i][j] = get_path(variant, axes[i].target.path)
    params: dict[str, tuple[dict, str]] = {}
    runs = []
    for combo in itertools.product(*[range(len(a.values)) for a in axes]):
        ck = tuple(combo[i] for i in i_conv)
        sk = tuple(combo[i] for i in i_scen)
        model = axes[i_model[0]].values[combo[i_model[0]]] if i_model else study.model
        if model not in params:
            overrides = study.models.get(model, {})
            params[model] = (overrides, canonical_json(_params_for(model, overrides)))
        overrides, params_json = params[model]
        key = "\x1f".join(
            [
                conv_json[ck],
                scen_json[sk],
                model,
                params_json,
                str(study.dynamics),
                study.engine_version,
            ]
        )
        runs.append(
            RunSpec(
                run_id=hashlib.sha256(key.encode()).hexdigest()[:_HASH_LEN],
                axes={
                    a.column: canon[i][j] for i, (a, j) in enumerate(zip(axes, combo, strict=True))
                },
                conveyor=conveyors[ck],
                scenario=scenarios[sk],
                model=model,
                params=overrides,
                dynamics=study.dynamics,
                engine_version=study.engine_version,
            )
        )
    return runs, canon


def expand_runs(study: ResolvedStudy) -> list[RunSpec]:
    """The Cartesian product of the axes as :class:`RunSpec` objects (validated variants)."""
    return _expand(study)[0]


def study_from_json(doc: dict, study_id: str) -> ResolvedStudy:
    """Rebuild a resolved study from ``study.json`` (for resuming)."""
    from service.axes import resolve_axis as _resolve

    axes = [
        Axis(
            a["name"],
            a["column"],
            _resolve(a["name"], doc["conveyor"], doc["scenario"]),
            tuple(a["values"]),
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
        total=math.prod(len(a.values) for a in axes),
        id=study_id,
        surface=bool(doc.get("surface", True)),
    )
    study.runs = expand_runs(study)
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
