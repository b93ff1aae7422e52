"""The door of the study service: a submitted study file or POST body, validated once.

:func:`resolve_study` checks a study mapping (SPEC sections 3 and 6.3: the conveyor by path or
inline, scenario, grid and zip axes, per-model parameters, design case) and raises
:class:`~beltstudy.service.errors.Invalid` / :class:`~beltstudy.service.errors.TooLarge` naming the field; what it
returns, a :class:`~beltstudy.service.grid.expand.ResolvedStudy` expanded by :mod:`beltstudy.service.grid.expand`, is trusted
from then on. A conveyor given as a path is read relative to the study file, or, for a study
the service receives, only from inside its conveyor directory (:func:`conveyor_from_path`:
no absolute paths, no ``..``, no way out through a link).
"""

from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Any

from pydantic import BaseModel, ConfigDict, Field, ValidationError, field_validator

from beltstudy import engine
from beltstudy.engine import (
    Conveyor,
    InputError,
    Scenario,
    format_validation_error,
    get_model,
    parse_conveyor,
    parse_scenario,
)
from beltstudy.service.door.parse import check_tree, load_mapping
from beltstudy.service.errors import Invalid, TooLarge
from beltstudy.service.examples import TINY_CONVEYOR, TINY_SCENARIO
from beltstudy.service.grid.axes import axis_column, resolve_axis
from beltstudy.service.grid.basis import DesignIn, design_scenario
from beltstudy.service.grid.expand import (
    DEFAULT_MODEL,
    Axis,
    ResolvedStudy,
    _err,
    canonical_json,
    finish,
    grid_points,
)

__all__ = [
    "RangeSpec",
    "StudyIn",
    "StudyDoc",
    "resolve_study",
    "load_study_file",
    "study_body",
    "inline_conveyor",
    "conveyor_from_path",
    "NAME_RE",
]

#: A study name: letters, digits and `` ._+-`` (no path separators, no ``..``).
NAME_RE = re.compile(r"^[A-Za-z0-9][A-Za-z0-9 ._+\-]{0,119}$")


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
            "must start with an ASCII letter or digit and use only ASCII letters (a-z, A-Z), "
            "digits, spaces and ._+- "
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


def conveyor_from_path(ref: str, base_dir: Path | None, root: Path | None) -> tuple[dict, str]:
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


def resolve_study(
    data: Any,
    *,
    base_dir: Path | None = None,
    studies_dir: Path | None = None,
    max_runs: int = 20_000,
) -> ResolvedStudy:
    """Validate a study mapping; raise :class:`Invalid` / :class:`TooLarge` naming the field.

    ``base_dir`` resolves a conveyor path given in a local study file; ``studies_dir`` (the
    service's study files directory, ``Settings.studies_dir``) confines such paths to it.
    """
    if not isinstance(data, dict):
        raise Invalid("study: expected a mapping with name, conveyor, scenario, grid")
    check_tree(data)  # depth, size, finite numbers, JSON types: before anything is expanded
    try:
        study = StudyIn.model_validate(data)
    except ValidationError as exc:
        raise Invalid(format_validation_error(exc, StudyIn)) from None

    if isinstance(study.conveyor, str):
        conv_data, source = conveyor_from_path(study.conveyor, base_dir, studies_dir)
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
            raise Invalid(str(exc) if (exc.field or "").startswith("models.")
                          else f"models: {exc}") from None
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
            target = resolve_axis(name, conveyor, scenario, where)
        except InputError as exc:
            raise Invalid(str(exc)) from None
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
                    raise Invalid(f"{where}.{name}: {exc.reason}") from None
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
            raise Invalid(f"model: {exc.reason}") from None
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
                raise Invalid(f"design.friction_model: {exc.reason}") from None
        if "temperature_c" in design:
            try:
                parse_scenario({"temperature_c": design["temperature_c"]}, prefix="design.")
            except InputError as exc:
                raise Invalid(_err(exc)) from None
        design_scenario(study.design, {})  # the load is a load case
    used = run_models | ({design["friction_model"]} if design and "friction_model" in design
                         else set())
    for name, given in zip(models, study.models, strict=True):
        if name not in used:
            raise Invalid(
                f"models.{given}: this study does not run {name} (its models: "
                f"{', '.join(sorted(run_models))}), so these parameters would be ignored; add "
                f"{name} to the friction_model axis or remove models.{given}")

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
    return finish(resolved)


def load_study_file(path: str | Path, *, max_runs: int = 20_000) -> ResolvedStudy:
    """Read and resolve a study file (YAML or JSON); the conveyor path is relative to it."""
    p = Path(path)
    return resolve_study(load_mapping(p), base_dir=p.parent, max_runs=max_runs)


def inline_conveyor(data: dict, base_dir: Path) -> dict:
    """A copy of a study mapping with a conveyor path replaced by the file's mapping."""
    out = dict(data)
    ref = out.get("conveyor")
    if isinstance(ref, str):
        conv, _ = conveyor_from_path(ref, base_dir, None)
        out["conveyor"] = conv
    return out


def study_body(path: str | Path) -> dict:
    """A study file as a POST body: the conveyor file inlined, so the server needs no files."""
    p = Path(path)
    return inline_conveyor(load_mapping(p), p.parent)
