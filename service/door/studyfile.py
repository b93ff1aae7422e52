"""The door of the study service: a submitted study file or POST body, validated once.

:func:`resolve_study` holds a study mapping to the study model
(:class:`~beltstudy.service.door.study.StudyIn`, SPEC sections 3 and 6.3: the conveyor by path
or inline, scenario, grid and zip axes, per-model parameters, design case), then checks what
the types leave open (axis paths, model names and parameters, grid sizes) and expands it. It
raises :class:`~beltstudy.service.errors.Invalid` / :class:`~beltstudy.service.errors.TooLarge`
naming the field; what it returns, a :class:`~beltstudy.service.grid.expand.ResolvedStudy`
expanded by :mod:`beltstudy.service.grid.expand`, is trusted from then on. A conveyor given as a
path is read relative to the study file, or, for a study the service receives, only from
inside its conveyor directory (:func:`conveyor_from_path`: no absolute paths, no ``..``, no
way out through a link).
"""

from __future__ import annotations

import difflib
import functools
import itertools
import json
import math
import typing
from pathlib import Path
from typing import Any

from pydantic import ValidationError

from beltstudy import engine
from beltstudy.engine import Conveyor, InputError, get_model, parse_conveyor
from beltstudy.engine.conveyor import json_numbers
from beltstudy.engine.reads import STEADY_FIELDS
from beltstudy.engine.wording import gnum
from beltstudy.service.door.messages import describe, with_type_fixes
from beltstudy.service.door.parse import check_tree, expect_kind, load_mapping
from beltstudy.service.door.sample import (
    SampleIn,
    bounds_problem,
    draw,
    sobol_n_within,
    value_bounds,
)
from beltstudy.service.door.study import (
    NAME_RE,
    RangeSpec,
    StudyIn,
    axis_types,
    fold_axes,
    fold_name,
    given_models,
)
from beltstudy.service.errors import Invalid, TooLarge, file_problem, shown_path
from beltstudy.service.grid.axes import NOT_READ, axis_column, resolve_axis
from beltstudy.service.grid.basis import (
    check_design_once,
    design_loads,
    design_models,
    design_temperatures,
)
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
    "read_study",
    "resolve_study",
    "load_study_file",
    "study_body",
    "inline_conveyor",
    "conveyor_from_path",
    "NAME_RE",
]


def read_study(data: Any, *, strict: bool = True) -> StudyIn:
    """``data`` as a :class:`StudyIn`: the one validation of a study's types, names and
    bounds; :class:`Invalid` naming each problem's field.

    One strict path for study files, JSON and YAML bodies and mappings built in Python: every
    value held to its JSON type, as the published schema does (``"1"`` is no number,
    ``"true"`` no boolean, ``true`` no number), integers by value whatever their notation
    (``12.0``, YAML's ``0x0c``). ``strict`` is kept for callers that pass it; a lax path no
    longer exists. Axes into lists are read as their fields
    (:func:`~beltstudy.service.door.study.fold_axes`).
    """
    if not isinstance(data, dict):
        raise Invalid("study: expected a mapping with name, conveyor, scenario, grid")
    check_tree(data)  # depth, size, finite numbers, JSON types: before anything is expanded
    folded = {**data}
    if "grid" in data:
        folded["grid"] = fold_axes(data["grid"])
    if isinstance(data.get("zip"), list):
        folded["zip"] = [fold_axes(g) for g in data["zip"]]
    try:
        # Pydantic's strict mode takes JSON's types exactly on JSON text (on Python data it
        # would also refuse a list for a pair, a motor curve's point): the tree checked
        # above goes to it as JSON
        return StudyIn.model_validate_json(json.dumps(_integers(folded)), strict=True)
    except ValidationError as exc:
        raise Invalid(describe(exc, folded, json_types=True)) from None


def _integers(data: dict) -> dict:
    """A study with its integral numbers written as integers
    (:func:`beltstudy.engine.conveyor.json_numbers`). The design case stays as written: it is
    stored as given."""
    return {k: v if k == "design" else json_numbers(v) for k, v in data.items()}


#: Files looked at for the nearest name of a conveyor path that is not there (a bound: a
#: studies directory is a handful of files, a working directory may be anything).
_NEAREST_SCAN = 2000


def _nearest_file(ref: str, folder: Path, recursive: bool) -> str:
    """The file meant by a conveyor path that is not there: a YAML or JSON file under
    ``folder`` (its path relative to it) of the same name in another folder, with the other
    extension (``.yml``) or a near spelling; "" when none is near."""
    try:
        found = folder.rglob("*") if recursive else folder.glob("*")
        names = []
        for path in itertools.islice(found, _NEAREST_SCAN):
            rel = path.relative_to(folder)
            if (path.suffix.lower() in (".yaml", ".yml", ".json") and path.is_file()
                    and not any(part.startswith(".") for part in rel.parts)):
                names.append(rel.as_posix())
    except OSError:
        return ""
    # by the file's own name (a shared folder makes every path look near)
    stems = sorted({Path(n).stem for n in names})
    close = difflib.get_close_matches(Path(ref).stem, stems, n=1, cutoff=0.75)
    if not close:
        return ""
    meant = [n for n in sorted(names) if Path(n).stem == close[0]]
    same_folder = [n for n in meant if Path(n).parent == Path(ref).parent]
    return (same_folder or meant)[0]


def _did_you_mean(name: str) -> str:
    return f"; did you mean '{name}'?" if name else ""


def conveyor_from_path(ref: str, base_dir: Path | None, root: Path | None) -> tuple[dict, str]:
    """Load a conveyor given by path. With ``root`` (the service), stay inside it."""
    if not ref.strip():
        raise Invalid("conveyor: empty; give the path of a conveyor file (e.g. "
                      "conveyors/slope-5pct.yaml) or the conveyor inline")
    if not ref.isprintable():
        raise Invalid(f"conveyor: path {ref!r} contains control characters")
    rel = Path(ref)
    try:
        if root is not None:
            if rel.is_absolute() or ".." in rel.parts or "\\" in ref or ref.startswith("~"):
                raise Invalid(
                    f"conveyor: path '{shown_path(ref)}' must be relative to the studies "
                    "directory without '..' (or give the conveyor inline)"
                )
            root_r = root.resolve()
            path = (root_r / rel).resolve()
            if root_r not in path.parents:
                raise Invalid(f"conveyor: path '{shown_path(ref)}' leaves the studies directory")
            if path.is_dir():
                raise Invalid(f"conveyor: '{shown_path(ref)}' is a folder in the studies "
                              "directory, not a file; give a conveyor file in it")
            if not path.is_file() and not root_r.is_dir():
                # a service started outside the repository (./studies is relative to where
                # it starts): say so, without the service's own folders
                raise Invalid(f"conveyor: file '{shown_path(ref)}' not found: the service "
                              "has no studies directory to read it from (its "
                              "BELTSTUDY_STUDIES_DIR is not a folder); give the conveyor "
                              "inline (beltstudy submit inlines it), or ask its operator to "
                              "set BELTSTUDY_STUDIES_DIR to the study files' folder")
            if not path.is_file():
                raise Invalid(f"conveyor: file '{shown_path(ref)}' not found in the studies "
                              "directory (paths are relative to it)"
                              + _did_you_mean(_nearest_file(ref, root_r, recursive=True)))
        else:
            path = (base_dir or Path.cwd()) / rel
            if path.is_dir():
                raise Invalid(f"conveyor: '{shown_path(path)}' is a folder, not a file; give a "
                              "conveyor file")
            if not path.is_file():
                # a near name in the folder the path names (slope-5pct.yml for .yaml)
                near = (_nearest_file(path.name, path.parent, recursive=False)
                        if path.parent.is_dir() else "")
                if near:
                    raise Invalid(f"conveyor: file '{shown_path(path)}' not found"
                                  + _did_you_mean(shown_path(path.parent / near)))
                # a study file copied out of studies/ keeps its 'conveyors/...' path: say
                # where a conveyor path is read from
                folder = shown_path((base_dir or Path.cwd()).absolute())
                raise Invalid(f"conveyor: file '{shown_path(path)}' not found (a conveyor "
                              f"path is read from the study file's folder, {folder}); give "
                              "the path from there, or the conveyor inline")
        data = load_mapping(path, what=f"conveyor: {shown_path(ref)}")
        expect_kind(data, "conveyor", f"conveyor: {shown_path(ref)}")
        return data, ref
    except OSError as exc:  # a name over the file system's limits, a folder we may not read
        # the path as given: a service's own folders stay out of the answer
        raise Invalid(f"conveyor: cannot read the file: {file_problem(exc, ref)}") from None


def _range_fix(spec: RangeSpec, max_runs: int) -> str:
    """What brings a range within the run limit: the smallest step that does on its own
    (rounded up at three digits), or a shorter range."""
    span = abs(float(spec.stop) - float(spec.start))
    if max_runs < 2 or not math.isfinite(span) or span == 0:
        return "a larger step or a shorter range"
    least = span / (max_runs - 1)
    # a round step (1, 2, 2.5 or 5 x a power of ten) that reaches the stop: 'at least
    # 0.00701' over -60 to 80 was refused next for not reaching 80 (0.01 does, 14 001 values)
    for exp in range(math.floor(math.log10(least)), math.floor(math.log10(least)) + 3):
        for m in (1.0, 2.0, 2.5, 5.0):
            step = m * 10.0 ** exp
            k = span / step
            if step >= least and abs(k - round(k)) <= 1e-9 * k:
                return (f"a step of {step:g} ({round(k) + 1} values from {spec.start:g} to "
                        f"{spec.stop:g}: this axis alone within the limit; the other axes "
                        "multiply it), or a shorter range")
    scale = 10.0 ** (math.floor(math.log10(least)) - 2)
    least = math.ceil(least / scale * (1 - 1e-12)) * scale
    return (f"a step of at least {gnum(least, 3)} (that keeps this axis alone within the limit), "
            "or a shorter range")


def _axis_values(name: str, spec: list | RangeSpec, max_runs: int, where: str) -> list[Any]:
    label = f"{where}.{name}"
    if isinstance(spec, RangeSpec):
        try:
            n = spec.count()
        except ValueError as exc:
            raise Invalid(f"{label}: {exc}") from None
        if n > max_runs:
            # a count past 10^15 (a step near float's smallest, or a range past float's
            # largest, counted as 2^63) said as its order, not as a 19- to 300-digit number
            count = (str(n) if n < HUGE_COUNT else
                     f"more than 10^{round(math.log10(HUGE_COUNT))} (from {spec.start:g} to "
                     f"{spec.stop:g} in steps of {spec.step:g})")
            raise TooLarge(
                f"{label}: the range has {count} values; the study limit is {max_runs} runs: "
                + _range_fix(spec, max_runs)
            )
        values = spec.values()
    else:
        values = list(spec)
    written = values
    values = [_positive_zero(v) for v in values]
    if not values:
        raise Invalid(f"{label}: empty axis; give at least one value")
    seen: dict[str, Any] = {}
    for v, as_written in zip(values, written, strict=True):
        same = _load_fraction(v) if name in ("load", "scenario.load") else v
        key = canonical_json(float(same) if isinstance(same, int | float)
                             and not isinstance(same, bool) else same)
        if key in seen:
            first = seen[key]
            if first == v:
                zero = "" if canonical_json(as_written) == canonical_json(v) else " (-0.0 is 0.0)"
                raise Invalid(f"{label}: value {v!r} appears twice{zero}")
            named = v if isinstance(v, str | list) else first
            where = " on every section" if isinstance(named, list) else ""
            raise Invalid(f"{label}: {first!r} and {v!r} are the same load ({named!r} is "
                          f"{float(_load_fraction(named)):g} x the design load{where}); "
                          "give one")
        seen[key] = v
    return values


def _load_fraction(load: Any) -> Any:
    """A load case as the one fraction of the design load it is everywhere, where it is one:
    ``full`` 1 and ``empty`` 0 (engine.conveyor.section_loads), a list of one fraction per
    carry section that are all equal that fraction; any other case itself."""
    if isinstance(load, str):
        return LOAD_NAMES.get(load, load)
    if (isinstance(load, list) and load
            and all(isinstance(x, int | float) and not isinstance(x, bool) for x in load)
            and len({float(x) for x in load}) == 1):
        return float(load[0])
    return load


def _positive_zero(value: Any) -> Any:
    """``value`` with every ``-0.0`` in it read as ``0.0``: the same number, so the same
    duplicate key and the same run id (JSON writes ``-0.0`` apart from ``0.0``)."""
    if isinstance(value, float):
        return 0.0 if value == 0.0 else value
    if isinstance(value, list):
        return [_positive_zero(v) for v in value]
    if isinstance(value, dict):
        return {k: _positive_zero(v) for k, v in value.items()}
    return value


#: Load cases by name that are one fraction of the design load everywhere.
#: A range counted at or past this many values is said by its order (:func:`_axis_values`).
HUGE_COUNT = 10**15
LOAD_NAMES = {"full": 1.0, "empty": 0.0}


def _conveyor(study: StudyIn, base_dir: Path | None, studies_dir: Path | None
              ) -> tuple[dict, str]:
    """The study's conveyor, dumped, and where it came from (a path, or ``inline``)."""
    try:
        if isinstance(study.conveyor, str):
            conv_data, source = conveyor_from_path(study.conveyor, base_dir, studies_dir)
            where = f"conveyor: {shown_path(source)}: "
            try:
                conveyor = parse_conveyor(conv_data, prefix=where)
            except InputError as exc:  # a wrong type with its fix, as an inline one gets
                raise InputError(with_type_fixes(str(exc), conv_data, Conveyor, where)) from None
        else:
            # the same checks as a file's (catalogue, fill): the Pydantic model alone lets an
            # over-filled belt through to the grid, which would fail there on every variant
            conveyor = parse_conveyor(study.conveyor.model_dump(mode="json", by_alias=True),
                                      prefix="conveyor.", strict=False)
            source = "inline"
    except InputError as exc:
        raise Invalid(_err(exc)) from None
    return conveyor.model_dump(mode="json", by_alias=True), source


def _models(study: StudyIn) -> tuple[dict[str, dict[str, float | None]], dict[str, str]]:
    """``{model: parameter overrides}`` (each checked by its model) and the name each model
    was given by."""
    models: dict[str, dict[str, float | None]] = {}
    given: dict[str, str] = {}
    for name, overrides in given_models(study.models).items():
        try:
            fm = get_model(name)
        except InputError as exc:  # the key under models: is the field, not friction_model
            raise Invalid(f"models.{name}: {exc.reason}") from None
        try:
            fm.params(overrides)
        except InputError as exc:
            raise Invalid(str(exc) if str(exc).startswith("models.")  # names its field
                          else f"models.{name}: {exc}") from None
        if fm.name in models:
            raise Invalid(f"models.{name}: model '{fm.name}' is given twice")
        models[fm.name] = dict(overrides)
        given[fm.name] = name
    return models, given


def _axis(name: str, spec, group: int | None, where: str, bases: tuple[dict, dict],
          models: dict, max_runs: int) -> Axis:
    """One axis: its values (a range counted out), the field it sets, its values canonical
    (model names, model parameters)."""
    values = _axis_values(name, spec, max_runs, where)
    problem = _study_field_axis(name, values, where)
    if problem:
        raise Invalid(problem)
    try:
        target = resolve_axis(name, *bases, where)
    except InputError as exc:
        raise Invalid(str(exc)) from None
    if target.root == "model":
        canon = []
        for v in values:
            try:
                canon.append(get_model(str(v)).name)
            except InputError as exc:
                raise Invalid(f"{where}.{name}: {exc.reason}") from None
        if len(set(canon)) != len(canon):
            raise Invalid(f"{where}.{name}: a model is listed twice (aliases count as the same)")
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
    return Axis(name, axis_column(name), target, tuple(values), group)


#: Fields of the study itself that an axis name may be mistaken for (``name`` is the
#: conveyor's, ``models`` the start of a model parameter axis: both are axis paths).
_STUDY_FIELDS = frozenset(StudyIn.model_fields) - {"name", "models"}


def _study_field_axis(name: str, values: list, where: str) -> str:
    """The refusal of an axis named as a field of the study (``dynamics``, ``model``): one
    value for all its runs, not a conveyor or scenario field; "" for any other name."""
    if name not in _STUDY_FIELDS:
        return ""
    label = f"{where}.{name}: '{name}' is a field of the study, not an axis"
    if name == "model":
        shown = ", ".join(str(v) for v in values)
        return (f"{label} (the one friction model of a study without a friction_model axis); "
                f"to run several models give the friction_model axis ({where}: "
                f"{{friction_model: [{shown}]}})")
    example = json.dumps(values[0]) if values and not isinstance(values[0], dict | list) \
        else "..."
    return (f"{label}: it holds for every run of the study; give it once at the top level "
            f"({name}: {example}), and submit one study per value to compare them")


def _axes(study: StudyIn, data: dict, bases: tuple[dict, dict], models: dict,
          max_runs: int) -> list[Axis]:
    """The grid's and the zip groups' axes, in the order written; no two set one field."""
    groups = [(None, "grid", study.grid, data.get("grid") or {})]
    groups += [(g, f"zip.{g}", grid, data["zip"][g]) for g, grid in enumerate(study.zip)]
    if len(groups) == 1 and not groups[0][3] and study.sample is None:
        raise Invalid("grid: empty; give at least one axis, e.g. temperature_c: [-20, 0, 20]")
    axes: list[Axis] = []
    for group, where, grid, written in groups:
        if group is not None and not written:
            raise Invalid(f"{where}: empty group; give one or more axes (the axes of a group "
                          "vary together, so each has the same number of values), e.g. "
                          "{temperature_c: [0, 20], load: [full, empty]}")
        for name, spec in grid.axes(written):
            _add_axis(axes, _axis(name, spec, group, where, bases, models, max_runs))
    for axis in _sample_axes(study, bases, models):
        _add_axis(axes, axis)
    _check_zip_lengths(axes, len(study.zip))
    return axes


def _check_read(study: StudyIn, axes: list[Axis]) -> None:
    """A grid or zip axis of two or more values of a field no run reads would make runs that
    differ in nothing a run reads: refused. A steady study's runs read no scenario field but
    :data:`STEADY_FIELDS` (the stop time, the start: every point one run, its column null, as
    a sample axis would be, refused in :func:`_sample_axes`); no run reads the conveyor's
    :data:`~beltstudy.service.grid.axes.NOT_READ` fields (its name: as many runs, with the
    same results). One value is the field set once."""
    for axis in axes:
        t = axis.target
        if axis.sample or len(axis.values) < 2:
            continue
        where = f"zip.{axis.group}" if axis.group is not None else "grid"
        n = len(axis.values)
        if t.root == "conveyor" and t.path in NOT_READ:
            raise Invalid(f"{where}.{axis.name}: no run reads {NOT_READ[t.path]} (free text, "
                          f"the same physics under any name), so its {n} values would be {n} "
                          "runs with the same results; drop the axis (name the conveyor in "
                          "the conveyor, the study in its own name:)")
        if (not study.dynamics and t.root == "scenario" and t.path
                and t.path[0] not in STEADY_FIELDS):
            raise Invalid(f"{where}.{axis.name}: a steady study (dynamics: false) does not "
                          f"read scenario.{'.'.join(t.path)}, so its {n} values would be one "
                          "run; vary it in a study with dynamics: true, or drop the axis")


def _add_axis(axes: list[Axis], axis: Axis) -> None:
    """Append ``axis``; no two axes set one field or one inside the other."""
    def place(a: Axis) -> str:
        """Where the axis was given: ``grid.x``, ``zip[k].x`` or ``sample.axes.x``."""
        if a.sample:
            return f"sample.axes.{a.name}"
        return f"zip.{a.group}.{a.name}" if a.group is not None else f"grid.{a.name}"

    for other in axes:
        if other.target.overlaps(axis.target):
            raise Invalid(
                f"{place(other)} and {place(axis)} both set {other.target.shown}: give it "
                "in one of them"
                if other.target == axis.target
                else f"{place(other)} and {place(axis)} overlap ({other.target.shown} / "
                f"{axis.target.shown}): give one of them"
            )
    axes.append(axis)


@functools.cache
def _numeric_axes() -> dict[str, bool]:
    """Axis name (folded) -> whether it takes a number."""
    return {name: numeric for name, (_t, _item, numeric, _b) in axis_types().items()}


def _whole_numbers_only(annotation: Any) -> bool:
    """Whether a field's numbers are integers only (``int``, ``int | None``, ``'auto' | int``:
    a count such as ``scenario.elements`` or ``idlers.carry.count``), no ``float``."""
    kinds: set[type] = set()

    def leaves(a: Any) -> None:
        if a in (int, float):
            kinds.add(a)
        elif typing.get_origin(a) is typing.Annotated:
            leaves(typing.get_args(a)[0])
        elif typing.get_origin(a) not in (list, tuple, typing.Literal):
            for arg in typing.get_args(a):
                leaves(arg)

    leaves(annotation)
    return kinds == {int}


@functools.cache
def _axis_bounds(folded: str) -> dict[str, float]:
    """An axis's numeric bounds (:func:`~beltstudy.service.door.sample.value_bounds`)."""
    found = axis_types().get(folded)
    return value_bounds(found[1], found[3]) if found else {}


def _too_many_runs(axes: list[Axis], total: int, max_runs: int,
                   sample: SampleIn | None = None) -> str:
    """The refusal of a study over ``max_runs``: the count, the factors it is the product of
    (each grid axis, zip group and the sample), and what brings it under the limit. Named
    ``sample.n`` when the grid alone fits and the sample takes it over (``sample.method``
    when only a Latin hypercube fits), else ``grid``. A Sobol' design's factor is the size it
    draws for the ``sample.n`` written (6144 points for ``n: 6000`` over one axis), and the
    fix is the largest ``n`` whose design fits (:func:`_smaller_sample`)."""
    factors: dict[str, int] = {}
    for a in axes:
        label = ("sample.n" if a.sample else a.name if a.group is None
                 else f"zip.{a.group}")
        factors.setdefault(label, len(a.values))
    drawn = factors.get("sample.n")

    def factor(label: str, n: int) -> str:
        if label == "sample.n" and sample is not None and n != sample.n:
            return f"the {sample.method} design's {n} points for sample.n {sample.n}"
        return f"{label} {n}"

    shown = " x ".join(factor(k, n) for k, n in factors.items())
    grid_alone = total // drawn if drawn else total
    points = max_runs // max(grid_alone, 1)  # sample points the grid leaves room for
    field, fix = (_smaller_sample(sample, sum(a.sample for a in axes), points, grid_alone)
                  if drawn else ("grid", ""))
    # the limit is checked before the grid is expanded (expansion is the costly part), so it
    # counts grid points: identical runs are merged only then (a stop time over coast stops),
    # and a study of 90 points that are 3 runs was told it 'has 90 runs'
    return (f"{field}: the study has {total} grid points (runs before identical ones are "
            f"merged); the limit is {max_runs} ({shown}): give "
            f"{fix or 'fewer values on an axis'}, or split the study into several")


def _smaller_sample(sample: SampleIn | None, d: int, points: int, grid_alone: int
                    ) -> tuple[str, str]:
    """The field and the fix of a sample of ``d`` axes that takes a study of ``grid_alone``
    runs per point over the limit, which leaves room for ``points`` points: ``("grid", "")``
    when not even two fit. A Latin hypercube draws ``n`` points: at most ``points``. A Sobol'
    design draws N (d + 2) for the nearest N a power of two
    (:func:`~beltstudy.service.door.sample.sobol_n_within`): the largest ``n`` whose design
    fits (4608 over one axis within 5000 points, not 5000, which draws 6144), or a Latin
    hypercube when not even N = 2 fits."""
    if points < 2:
        return "grid", ""
    if sample is None or sample.method != "sobol":
        return "sample.n", f"a smaller sample.n (at most {points} points with this grid)"
    within = sobol_n_within(d, points)
    if within is None:
        return "sample.method", (
            f"method: lhs with sample.n at most {points} (method sobol's smallest design, "
            f"N = 2, has 2 (D + 2) = {2 * (d + 2)} points for D = {d} axes, "
            f"{2 * (d + 2) * grid_alone} runs with this grid)")
    n, size = within
    runs = f", {size * grid_alone} runs with this grid" if grid_alone > 1 else ""
    return "sample.n", (
        f"sample.n at most {n} (method sobol draws N (D + 2) points, N a power of two, the "
        f"nearest to n: {n} draws {size}{runs}), or method: lhs with sample.n at most "
        f"{points}")


def _sample_axes(study: StudyIn, bases: tuple[dict, dict], models: dict) -> list[Axis]:
    """The ``sample:`` axes (:mod:`beltstudy.service.door.sample`): one more group of axes
    varying together (the last), their values drawn; each path a numeric axis."""
    if study.sample is None:
        return []
    group = len(study.zip)
    out = []
    targets = {}
    for name, dist in study.sample.axes.items():  # before drawing: names, types, ends
        where = f"sample.axes.{name}"
        try:
            targets[name] = resolve_axis(name, *bases, "sample.axes")
        except InputError as exc:
            raise Invalid(str(exc)) from None
        t = targets[name]
        if not study.dynamics and t.root == "scenario" and t.path[0] not in STEADY_FIELDS:
            raise Invalid(f"{where}: a steady study (dynamics: false) does not read "
                          f"scenario.{'.'.join(t.path)}, so every draw would be one run; "
                          "sample it in a study with dynamics: true, or drop it")
        if not _numeric_axes().get(fold_name(name)[0], False):
            raise Invalid(f"{where}: '{name}' does not take a number; a sample axis is a "
                          "numeric field (temperature_c, takeup.mass_kg, "
                          "models.nonlin.mu_b, ...)")
        if _whole_numbers_only(axis_types()[fold_name(name)[0]][1]):
            raise Invalid(f"{where}: '{name}' takes a whole number (a count) and a sample "
                          "draws real values, which it would refuse; give its values as a "
                          f"grid axis instead (grid: {{{name}: [...]}})")
        problem = bounds_problem(name, dist, None, _axis_bounds(fold_name(name)[0]))
        if problem:
            raise Invalid(f"{where}: {problem}")
    for name, values in draw(study.sample).items():
        where = f"sample.axes.{name}"
        target = targets[name]
        problem = bounds_problem(name, study.sample.axes[name], values,
                                 _axis_bounds(fold_name(name)[0]))
        if problem:
            raise Invalid(f"{where}: {problem}")
        if target.root == "model_param":
            model, param = target.path
            for v in values:
                try:
                    get_model(model).params({**models.get(model, {}), param: v})
                except InputError as exc:
                    raise Invalid(f"{where}: drawn value {v:g}: {exc.reason} (a distribution "
                                  "within the parameter's bounds, e.g. lognormal for a "
                                  "positive one)") from None
        out.append(Axis(name, axis_column(name), target,
                        tuple(_positive_zero(v) for v in values), group, True))
    return out


def _check_zip_lengths(axes: list[Axis], groups: int) -> None:
    for g in range(groups):
        lengths = {a.name: len(a.values) for a in axes if a.group == g}
        if len(set(lengths.values())) > 1:
            raise Invalid(f"zip.{g}: the axes of a zip group vary together and need equal "
                          "lengths; got " + ", ".join(f"{k} {n}" for k, n in lengths.items()))
    columns = [a.column for a in axes]
    if len(set(columns)) != len(columns):
        raise Invalid("grid: two axes map to the same column")


def _run_models(study: StudyIn, axes: list[Axis], models: dict) -> tuple[str, set[str]]:
    """The default model (no friction_model axis) and the models the study runs; a model
    parameter axis of a model it does not run is refused."""
    model_axis = next((a for a in axes if a.target.root == "model"), None)
    if model_axis is not None:
        if study.model is not None:
            where = (f"zip.{model_axis.group}.{model_axis.name}" if model_axis.group is not None
                     else f"grid.{model_axis.name}")
            raise Invalid(f"model: '{study.model}' is for a study without a friction_model "
                          f"axis; this one runs {where} ({', '.join(model_axis.values)}), so "
                          "model: would be ignored: leave it out, or list the model in the axis")
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
            # named where the axis is written: a sample's and a zip group's are no grid axes
            where = ("sample.axes" if a.sample else
                     f"zip.{a.group}" if a.group is not None else "grid")
            m = a.target.path[0]
            raise Invalid(f"{where}: axis '{a.name}': model '{m}' is not run by this study "
                          f"(its models: {', '.join(sorted(run_models))}); add {m} to the "
                          f"friction_model axis to vary it in runs, or, for a design model, "
                          f"give one value in models: {m}: (the design basis takes one)")
    return default_model, run_models


def _design(study: StudyIn) -> dict | None:
    """The design cases as given, their models canonical; every temperature and load checked
    (a list names its bad entry: ``design.load[1]``)."""
    if study.design is None:
        return None
    design = study.design.model_dump(exclude_none=True)
    models = design_models(study.design)
    if models is not None:
        design["friction_model"] = (models if isinstance(design["friction_model"], list)
                                    else models[0])
    design_temperatures(study.design)
    design_loads(study.design)  # each load is a load case
    check_design_once(study.design)
    return design


def _check_models_used(given: dict[str, str], run_models: set[str], design: dict | None
                       ) -> None:
    """Parameters of a model the study neither runs nor designs with would be ignored."""
    used = run_models | set(design_models(design) or [])
    for name, as_given in given.items():
        if name not in used:
            raise Invalid(
                f"models.{as_given}: this study does not run {name} (its models: "
                f"{', '.join(sorted(run_models))}), so these parameters would be ignored; add "
                f"{name} to the friction_model axis or remove models.{as_given}")


def _check_models_on_axes(axes: list[Axis], models: dict, given: dict[str, str],
                          run_models: set[str], design: dict | None) -> None:
    """A parameter under ``models:`` that an axis also sets: every run of that model takes the
    axis's value, so the fixed one would be ignored (refused naming both, as the same field
    in the grid and a zip group is), unless a design case reads it (the model is a
    ``design.friction_model`` and the study runs another model, whose runs it sizes)."""
    designs = set(design_models(design) or [])
    for axis in axes:
        if axis.target.root != "model_param":
            continue
        model, param = axis.target.path
        if param not in models.get(model, {}) or (model in designs and run_models - {model}):
            continue
        place = (f"sample.axes.{axis.name}" if axis.sample else
                 f"zip.{axis.group}.{axis.name}" if axis.group is not None else
                 f"grid.{axis.name}")
        value = json.dumps(models[model][param])
        raise Invalid(f"models.{given[model]}.{param} and {place} both set "
                      f"models.{model}.{param}: give it in one of them (every {model} run takes "
                      f"the axis's value, so {param}: {value} under models: would be ignored)")


def resolve_study(
    data: Any,
    *,
    base_dir: Path | None = None,
    studies_dir: Path | None = None,
    max_runs: int = 20_000,
    strict: bool = False,
) -> ResolvedStudy:
    """Validate a study mapping and expand it; raise :class:`Invalid` / :class:`TooLarge`
    naming the field.

    ``base_dir`` resolves a conveyor path given in a local study file; ``studies_dir`` (the
    service's study files directory, ``Settings.studies_dir``) confines such paths to it.
    ``strict``: a POSTed body, held to JSON's types (:func:`read_study`).
    """
    study = read_study(data, strict=strict)
    # -0.0 is 0.0 wherever it is written (conveyor, scenario, models, design, sample; the
    # axes read it so in _axis_values): the same inputs, so the same run and study ids (JSON
    # writes -0.0 apart from 0.0)
    conveyor, source = _conveyor(study, base_dir, studies_dir)
    conveyor = _positive_zero(conveyor)
    scenario = _positive_zero(study.scenario.model_dump(mode="json", by_alias=True))
    models, given = _models(study)
    models = _positive_zero(models)
    axes = _axes(study, data, (conveyor, scenario), models, max_runs)
    total = grid_points(axes)
    if total > max_runs:
        raise TooLarge(_too_many_runs(axes, total, max_runs, study.sample))
    _check_read(study, axes)
    default_model, run_models = _run_models(study, axes, models)
    design = _positive_zero(_design(study))
    _check_models_used(given, run_models, design)
    _check_models_on_axes(axes, models, given, run_models, design)
    if study.accuracy is not None and not study.dynamics:
        raise Invalid("accuracy: error bars are those of the transient runs; this study has "
                      "dynamics: false (set dynamics: true or remove accuracy)")
    if study.surface and not study.dynamics:
        raise Invalid("surface: the tension and velocity surface is that of the transient "
                      "runs; this study has dynamics: false, whose runs have none (set "
                      "dynamics: true or remove surface)")
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
        accuracy=(study.accuracy.model_dump() if study.accuracy is not None else None),
        sample=(_positive_zero(study.sample.model_dump(mode="json")) if study.sample is not None
                else None),
    )
    return finish(resolved)


def load_study_file(path: str | Path, *, max_runs: int = 20_000) -> ResolvedStudy:
    """Read and resolve a study file (YAML or JSON); the conveyor path is relative to it."""
    p = Path(path)
    data = load_mapping(p)
    expect_kind(data, "study", str(p))
    return resolve_study(data, base_dir=p.parent, max_runs=max_runs)


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
    data = load_mapping(p)
    expect_kind(data, "study", str(p))
    return inline_conveyor(data, p.parent)
