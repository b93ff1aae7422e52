"""The study grid: axes, grid points, expansion into runs and stable ids (SPEC 3 and 6.3).

Everything here trusts its input: a :class:`ResolvedStudy` comes from the door
(:func:`beltstudy.service.door.studyfile.resolve_study`) or from a stored ``study.json``
(:func:`study_from_json`). :func:`expand_runs` turns it into :class:`RunSpec` objects, each
with a ``run_id`` that is a stable hash of its fully resolved inputs and the engine version.

Expansion: the grid points are the Cartesian product of the grid axes and the zip groups (the
axes of a group vary together). Each point's conveyor and scenario are validated (every point
that makes the conveyor invalid is named), its ``auto`` sizes are replaced by its conveyor
design's (:mod:`beltstudy.service.grid.basis`), and the scenario fields the run does not read
are set to their defaults (the engine says which: :func:`beltstudy.engine.scenario_as_read`).
Points whose resolved runs are then identical are one run; an axis whose value differs between
the points of one run is null in its row.
"""

from __future__ import annotations

import dataclasses
import functools
import hashlib
import itertools
import json
import math
from dataclasses import dataclass, field
from functools import partial
from typing import Any

from beltstudy.engine import (
    Conveyor,
    DesignCase,
    InputError,
    Scenario,
    brake_sizing_stop_time,
    conveyor_as_read,
    conveyor_variant,
    get_model,
    parse_conveyor,
    parse_scenario,
    scenario_as_read,
    section_loads,
)
from beltstudy.service.errors import Invalid
from beltstudy.service.grid.axes import Target, get_path, resolve_axis, with_paths
from beltstudy.service.grid.basis import (
    apply_sizes,
    check_design_loads,
    design_loads,
    design_models,
    design_temperatures,
    has_auto,
    size_design,
)

__all__ = [
    "Axis",
    "ResolvedStudy",
    "RunSpec",
    "expand_runs",
    "finish",
    "grid_points",
    "study_from_json",
    "study_hash",
    "accuracy_sample",
    "mark_accuracy_sample",
    "canonical_json",
    "stable_hash",
    "DEFAULT_MODEL",
]

#: Friction model used when the grid has no ``friction_model`` axis and ``model`` is not set.
DEFAULT_MODEL = "din"
#: Hex digits of a run or study id.
_HASH_LEN = 16


def canonical_json(value: Any) -> str:
    """JSON with sorted keys and no spaces: the text stable ids are hashed from."""
    return json.dumps(value, sort_keys=True, separators=(",", ":"), allow_nan=False)


@functools.lru_cache(maxsize=4096)
def _key_text(key: str) -> str:
    return json.dumps(key)


def canonical_mapping(value: dict, memo: dict[int, tuple[Any, str]]) -> str:
    """:func:`canonical_json` of a mapping, each top-level value serialised once: ``memo``
    keeps the text of values met before (by identity), so the many variants of one conveyor,
    which share every part a grid point does not change, are serialised once per part."""
    parts = []
    for key in sorted(value):
        item = value[key]
        hit = memo.get(id(item))
        if hit is None or hit[0] is not item:
            hit = memo[id(item)] = (item, canonical_json(item))
        parts.append(f"{_key_text(key)}:{hit[1]}")
    return "{" + ",".join(parts) + "}"


#: A uniform load case that the engine reads as one of the named ones
#: (:func:`beltstudy.engine.conveyor.load_fraction`: full is 1, empty 0 of the design load).
_LOAD_NAMES_BY_FRACTION = {1.0: "full", 0.0: "empty"}
_LOAD_TARGET = ("scenario", ("load",))


def load_key(load: Any) -> Any:
    """A load case as the run and study ids hash it: a number equal to a named uniform case
    is that name (``1.0`` -> ``full``, ``0`` -> ``empty``; the scenario's default is
    ``full``, so its ids stay put), anything else itself. The engine runs both forms alike;
    the rows keep the value as written."""
    if isinstance(load, int | float) and not isinstance(load, bool):
        return _LOAD_NAMES_BY_FRACTION.get(float(load), load)
    return load


def _scenario_key(scenario: dict) -> dict:
    """``scenario`` with its load as :func:`load_key` hashes it (``scenario`` itself when
    that is its load already)."""
    load = scenario.get("load")
    key = load_key(load)
    return scenario if key is load else {**scenario, "load": key}


def _design_key(design: dict) -> dict:
    """A design basis with its load cases as :func:`load_key` hashes them: one case, or a
    list of cases (a list of numbers alone is one load per profile section, kept)."""
    load = design.get("load")
    if isinstance(load, list):
        if not any(isinstance(x, str | list) for x in load):
            return design
        return {**design, "load": [load_key(x) for x in load]}
    return {**design, "load": load_key(load)} if "load" in design else design


def stable_hash(value: Any) -> str:
    """First 16 hex digits of the SHA-256 of the canonical JSON of ``value``."""
    return hashlib.sha256(canonical_json(value).encode()).hexdigest()[:_HASH_LEN]


@dataclass(frozen=True)
class Axis:
    """One grid axis after validation."""

    name: str
    column: str
    target: Target
    values: tuple[Any, ...]
    group: int | None = None  # zip group index; None for a grid axis
    sample: bool = False  # drawn from a distribution (``sample:``; its group is the last)

    def to_json(self) -> dict:
        out = {
            "name": self.name,
            "column": self.column,
            "target": self.target.dotted,
            "values": list(self.values),
        }
        if self.group is not None:
            out["group"] = self.group
        if self.sample:
            out["sample"] = True
        return out


@dataclass(frozen=True, slots=True)
class RunSpec:
    """One run: everything a worker needs, plus the axis values for the row.

    The grid makes it (:func:`expand_runs`) and the worker reads it
    (:func:`beltstudy.service.dask.tasks.run_batch`): it travels to Dask as itself, pickled once
    with its task. ``conveyor`` and ``scenario`` are the run's validated, dumped mappings
    (hashed into ``run_id``); the worker turns them into the engine's models.
    """

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
    check: bool = False  # in the study's accuracy sample: error bars (beltstudy.engine.accuracy)


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
    accuracy: dict | None = None  # {sample, seed}: the runs that get error bars
    sample: dict | None = None  # ``sample:`` as validated (n, method, seed, axes)

    @property
    def merged(self) -> int:
        """Grid points that were merged into another point's identical run."""
        return max(self.grid_points - self.total, 0)

    @property
    def merged_axes(self) -> list[str]:
        """Axes of two or more values that change no run of the study: their column is null
        in every row (a brake's delay in steady runs), so every point that differs only in
        them was merged (SPEC 6.3)."""
        if not self.runs:
            return []
        return [a.name for a in self.axes
                if len(a.values) > 1 and all(r.axes.get(a.column) is None for r in self.runs)]

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
            "merged_axes": self.merged_axes,
            "designs": self.designs,
        }
        groups = sorted({a.group for a in self.axes if a.group is not None and not a.sample})
        if groups:
            out["zip"] = [{a.name: list(a.values) for a in self.axes if a.group == g}
                          for g in groups]
        if self.design is not None:
            out["design"] = self.design
        if self.accuracy is not None:
            out["accuracy"] = self.accuracy
        if self.sample is not None:
            out["sample"] = self.sample
        return out

    @property
    def columns(self) -> list[str]:
        return [a.column for a in self.axes]


def _err(exc: Exception) -> str:
    return str(exc).strip() or type(exc).__name__


def _where(axes: list[Axis], indices: list[int], combo: tuple[int, ...]) -> str:
    """``name=value, ...`` of one grid point on the axes ``indices``."""
    return ", ".join(
        f"{axes[i].name}={axes[i].values[j]!r}" for i, j in zip(indices, combo, strict=True)
    )


#: Invalid points named in one error message; the rest are counted.
MAX_NAMED_POINTS = 5


def _origin(axes: list[Axis], indices: list[int]) -> str:
    """Where the axes ``indices`` were given, as an error names it: ``grid`` (grid and zip
    axes, crossed into grid points), ``sample.axes`` (drawn values), or both."""
    drawn = {axes[i].sample for i in indices}
    if drawn == {True}:
        return "sample.axes"
    return "grid and sample.axes" if True in drawn else "grid"


#: What to do when drawn values make an invalid conveyor or scenario.
_DRAWN_FIX = ("; give each sample axis a distribution whose draws the field takes (a narrower "
              "one, or uniform or triangular with low and high within it)")


#: What to do when an axis sets one of two exclusive fields and the file gives the other
#: (``idlers.carry.count`` on a file with ``spacing_m``: 'not both').
_BOTH_FIX = ("; where an axis sets one of two fields the conveyor file gives the other of, an "
             "axis of that other field with the value null (grid: {idlers.carry.spacing_m: "
             "[null]} beside idlers.carry.count) clears the file's")


def _refuse_points(kind: str, bad: list[tuple[str, str]], total: int,
                   origin: str = "grid") -> None:
    """Raise :class:`Invalid` naming every grid point in ``bad`` (``(where, message)``);
    ``origin``: where the axes were given (:func:`_origin`)."""
    if not bad:
        return
    fix = _DRAWN_FIX if "sample" in origin else ""
    if any(", not both" in m for _w, m in bad):
        fix += _BOTH_FIX
    if len(bad) == 1:
        where, msg = bad[0]
        raise Invalid(f"{origin} ({where}): {msg}{fix}" if where else msg)
    named = "; ".join(f"({w}): {m}" for w, m in bad[:MAX_NAMED_POINTS])
    more = len(bad) - MAX_NAMED_POINTS
    tail = f"; and {more} more" if more > 0 else ""
    raise Invalid(f"{origin}: {len(bad)} of {total} {kind} variants are invalid: "
                  f"{named}{tail}{fix}")


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


def _refuse_unread_axes(study: ResolvedStudy, canon: list[list]) -> None:
    """A sample axis that no run of the study reads: every draw that differs only in it was
    merged into one run, so its column is null in every row (a stop time drawn over coast
    stops only, which do not read it) and the sample's statistics describe nothing it drew;
    :class:`Invalid` naming it and what would read it. A grid axis is merged as SPEC 6.3 says
    (points whose runs are identical are one run, the column null), and a sample axis some
    runs read stays."""
    for i, axis in enumerate(study.axes):
        if not axis.sample or len({canonical_json(v) for v in canon[i]}) < 2:
            continue
        if any(run.axes.get(axis.column) is not None for run in study.runs):
            continue
        where = "sample.axes"
        path = ".".join((axis.target.root, *axis.target.path))
        hint = ""
        if path == "scenario.stop.time_s":
            hint = (" (a coast stop does not read its stop time, nor a brake stop on brakes "
                    "whose forces are all given: vary it over controlled stops or auto brakes)")
        raise Invalid(f"{where}.{axis.name}: no run of this study reads {path}{hint}, so its "
                      f"{len(canon[i])} draws are one run and the sample varies nothing there; "
                      "sample a field the runs read, or drop the axis")


def finish(study: ResolvedStudy) -> ResolvedStudy:
    """Expand a study built at the door: its runs (identical points merged), the design
    basis, each axis's values as validated, and the study id. Returns ``study``."""
    study.runs, canon, study.designs = _expand(study)
    axes = study.axes
    study.total = len(study.runs)
    _refuse_unread_axes(study, canon)
    for i, axis in enumerate(axes):
        keys = [canonical_json(v) for v in canon[i]]
        if not axis.sample and len(set(keys)) != len(keys):
            dup = next(v for v, k in zip(canon[i], keys, strict=True) if keys.count(k) > 1)
            where = "grid" if axis.group is None else f"zip.{axis.group}"
            # None is how 'auto' and null are both held (an auto size): said as written
            shown = "auto (or null, the same)" if dup is None else repr(dup)
            raise Invalid(f"{where}.{axis.name}: value {shown} appears twice (after validation)")
        axes[i] = dataclasses.replace(axis, values=tuple(canon[i]))
    study.id = study_hash(study)
    mark_accuracy_sample(study)
    return study


def accuracy_sample(run_ids: list[str], sample: float, seed: int = 0) -> set[str]:
    """The runs that get error bars: ``ceil(sample x runs)`` of them (at least one), those
    whose hash of ``(seed, run_id)`` is smallest. Deterministic and seeded; it depends on the
    runs alone, not on their order or on how they are batched."""
    if not run_ids:
        return set()
    k = min(len(run_ids), max(1, math.ceil(sample * len(run_ids) - 1e-9)))
    return set(sorted(run_ids, key=lambda r: stable_hash([int(seed), r]))[:k])


def mark_accuracy_sample(study: ResolvedStudy) -> None:
    """Mark the runs of a dynamic study's accuracy sample (``RunSpec.check``)."""
    if not study.accuracy or not study.dynamics:
        return
    chosen = accuracy_sample([r.run_id for r in study.runs], float(study.accuracy["sample"]),
                             int(study.accuracy.get("seed", 0)))
    study.runs = [dataclasses.replace(r, check=True) if r.run_id in chosen else r
                  for r in study.runs]




def study_hash(study: ResolvedStudy) -> str:
    """The study id: a stable hash of what decides its runs (and its name)."""
    doc = study.to_json()
    # a load written as its fraction (1.0) is the named case (full): the same runs, one id
    doc["scenario"] = _scenario_key(doc["scenario"])
    groups = sorted({a.group for a in study.axes if a.group is not None and not a.sample})
    for a in study.axes:
        if (a.target.root, a.target.path) != _LOAD_TARGET or a.sample:
            continue
        values = [load_key(v) for v in a.values]
        if a.group is None:
            doc["grid"][a.name] = values
        else:
            doc["zip"][groups.index(a.group)][a.name] = values
    if doc.get("design") is not None:
        # a design field left empty is its default (the study's models and temperatures, full
        # load): `design: {}` and `design: {load: full}` are the study without one, one id
        design = {k: v for k, v in _design_key(doc["design"]).items()
                  if v is not None and not (k == "load" and v == "full")}
        if design:
            doc["design"] = design
        else:
            del doc["design"]
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
    return stable_hash({k: doc[k] for k in (*keys, "zip", "design", "accuracy", "sample")
                        if k in doc})


def _parse_conveyor(data: dict) -> Conveyor:
    return parse_conveyor(data, prefix="conveyor.")


def _parse_scenario(data: dict) -> Scenario:
    return parse_scenario(data, prefix="scenario.")


def _variant_parser(base: dict, parse_whole, variant=None):
    """``sets -> (model, dumped)`` for the variants of ``base`` (a dumped conveyor or
    scenario whose values the door held to their JSON types): with ``variant`` (conveyors:
    :func:`beltstudy.engine.conveyor.conveyor_variant`) only the top-level parts a grid point
    changes are validated again; without, the whole mapping, without the JSON round trip."""
    if variant is None:
        def whole(sets):
            model = parse_whole(with_paths(base, sets), strict=False)
            return model, model.model_dump(mode="json", by_alias=True)
        return whole
    base_model = parse_whole(base, strict=False)

    def parts(sets):
        data = with_paths(base, sets)  # copies on write: the changed parts are new objects
        changed = {k: v for k, v in data.items() if k not in base or v is not base[k]}
        return variant(base_model, base, changed, "conveyor.")
    return parts


def _params_for(model: str, overrides: dict) -> dict:
    """The model's full parameter set (defaults filled) for the run id."""
    return dataclasses.asdict(get_model(model).params(overrides))


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
            sets = [(axes[i].target.path, axes[i].values[j])
                    for i, j in zip(indices, key, strict=True)]
            try:
                models[key], out[key] = parse(sets)
            except InputError as exc:
                bad.append((_where(axes, indices, key), _err(exc)))
                continue
        _refuse_points(kind, bad, len(keys), _origin(axes, indices))
        for key, variant in out.items():
            for i, j in zip(indices, key, strict=True):
                canon[i][j] = get_path(variant, axes[i].target.path)
        return out, models

    conveyors, conv_models = variants(
        i_conv, study.conveyor,
        _variant_parser(study.conveyor, partial(parse_conveyor, prefix="conveyor."),
                        conveyor_variant), "conveyor")
    scenarios, scen_models = variants(
        i_scen, study.scenario,
        _variant_parser(study.scenario, partial(parse_scenario, prefix="scenario.")),
        "scenario")

    # every realised pair: a per-section load must match the profile; a dynamic study's
    # scenario must be one the conveyor can do

    pairs = list(dict.fromkeys((tuple(p[i] for i in i_conv), tuple(p[i] for i in i_scen))
                               for p in points))
    bad = []
    for ck, sk in pairs:
        conv, scn = conv_models[ck], scen_models[sk]
        try:
            section_loads(scn.load, conv)
            if study.dynamics:
                # deferred: the transient engine (numba) loads only for a dynamic study
                from beltstudy.engine.run import check_scenario

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
    memo: dict[int, tuple[Any, str]] = {}  # canonical text of shared conveyor parts
    run_scenarios: dict[tuple, tuple[dict, str]] = {}
    run_conveyors: dict[tuple, tuple[dict, dict]] = {}
    read_conveyors: dict[tuple, str] = {}  # canonical conveyor as read, per stop kind
    for p in points:
        ck = tuple(p[i] for i in i_conv)
        sk = tuple(p[i] for i in i_scen)
        model = model_of(p)
        overrides, params_json = params_of(p)
        # a brake stop on brakes whose forces are all given does not read its stop time
        given = all(b.force_kn != "auto" for b in conv_models[ck].brakes)
        if (sk, given) not in run_scenarios:
            # what the engine reads of the scenario: points that differ only in fields the
            # run does not read are one run
            scenario = scenario_as_read(scenarios[sk], dynamics=study.dynamics,
                                        brakes_given=given)
            run_scenarios[sk, given] = (scenario, canonical_json(_scenario_key(scenario)))
        scenario, scenario_json = run_scenarios[sk, given]
        # the sizes a run gets depend on its conveyor design and, for brakes, its stop
        ckey = (ck, brake_sizing_stop_time(scenario, dynamics=study.dynamics))
        if ckey not in run_conveyors:
            entry = sized.get(ck)
            conveyor, governed = apply_sizes(conveyors[ck], entry["sizes"] if entry else None,
                                             scenario, study.dynamics)
            run_conveyors[ckey] = (conveyor, governed)
        conveyor, governed = run_conveyors[ckey]
        # keyed on what the run reads of it: a brake that never acts does not make a new run
        rkey = (ckey, (scenario.get("stop") or {}).get("mode") == "brake")
        if rkey not in read_conveyors:
            read_conveyors[rkey] = canonical_mapping(
                conveyor_as_read(conveyor, scenario, dynamics=study.dynamics), memo)
        conveyor_json = read_conveyors[rkey]
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
    table = list({entry["key"]: {"axes": entry["axes"], "key": entry["key"],
                                 "sizes": entry["sizes"]} for entry in sized.values()}.values())
    return [RunSpec(**r) for r in by_id.values()], canon, table


def _design_basis(study, points, i_conv, i_scen, conveyors, conv_models, scenarios, model_of,
                  params_of, stored) -> dict:
    """``{conveyor key: {"axes", "key", "sizes"}}`` for every conveyor design with auto
    sizes (:mod:`beltstudy.service.grid.basis`): its design cases are every listed load x
    model x temperature of ``design:``, a model or temperature it does not name being the
    study's own of each run."""
    axes = study.axes
    if any(a.sample for a in axes):
        return _nominal_basis(study, points, i_conv, i_scen, model_of, stored)
    design = study.design or {}
    loads = [load for _where, load in design_loads(design)]
    models = design_models(design)
    temps = design_temperatures(design)
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
            check_design_loads(conv_models[ck], design, where)
            cases: dict[DesignCase, None] = {}
            stops: set[float] = set()
            for p in mine:
                _add_cases(cases, stops, study, scenarios[tuple(p[i] for i in i_scen)],
                           model_of(p), params_of(p)[0], (loads, models, temps))
            sizes = size_design(conv_models[ck], list(cases), sorted(stops), where)
        out[ck] = {"axes": {axes[i].name: axes[i].values[j]
                            for i, j in zip(i_conv, ck, strict=True)},
                   "key": key, "sizes": sizes}
    return out


def _nominal_basis(study, points, i_conv, i_scen, model_of, stored) -> dict:
    """The design basis of a sampled study: a design is sized once, at its nominal inputs
    (the study's conveyor, scenario and model parameters with the grid's values and none of
    the sample's), and held for every sample point: the sample then tests that design
    against the uncertain inputs (a motor sized to each point's own friction would never be
    overloaded). ``{full conveyor key: entry}`` as :func:`_design_basis` gives it."""
    axes = study.axes
    grid_conv = [i for i in i_conv if not axes[i].sample]
    grid_scen = [i for i in i_scen if not axes[i].sample]
    grid_param = [i for i, a in enumerate(axes) if a.target.root == "model_param"
                  and not a.sample]
    design = study.design or {}
    loads = [load for _where, load in design_loads(design)]
    models = design_models(design)
    temps = design_temperatures(design)
    known = {d["key"]: d["sizes"] for d in stored or []}
    by_grid: dict[tuple, dict | None] = {}
    out: dict = {}
    for p in points:
        gk = tuple(p[i] for i in grid_conv)
        if gk not in by_grid:
            conv_data = with_paths(study.conveyor, [(axes[i].target.path, axes[i].values[p[i]])
                                                    for i in grid_conv])
            conv_model = _parse_conveyor(conv_data)
            conv = conv_model.model_dump(mode="json", by_alias=True)
            by_grid[gk] = None
            if has_auto(conv):
                key = stable_hash({"conveyor": conv, "design": design, "models": study.models,
                                   "scenario": study.scenario, "sample": "nominal"})
                where = _where(axes, grid_conv, gk)
                sizes = known.get(key)
                if sizes is None:
                    check_design_loads(conv_model, design, where)
                    sizes = _size_nominal(study, [q for q in points if tuple(
                        q[i] for i in grid_conv) == gk], conv_model, grid_scen, grid_param,
                        model_of, (loads, models, temps), where)
                by_grid[gk] = {"axes": {axes[i].name: axes[i].values[j]
                                        for i, j in zip(grid_conv, gk, strict=True)},
                               "key": key, "sizes": sizes}
        if by_grid[gk] is not None:
            out[tuple(p[i] for i in i_conv)] = by_grid[gk]
    return out


def _size_nominal(study, mine, conv_model, grid_scen, grid_param, model_of, cases_of,
                  where) -> dict:
    """The sizes of one design of a sampled study over its grid points' nominal cases."""
    axes = study.axes
    cases: dict[DesignCase, None] = {}
    stops: set[float] = set()
    for p in mine:
        scn = parse_scenario(with_paths(study.scenario, [
            (axes[i].target.path, axes[i].values[p[i]]) for i in grid_scen]),
            prefix="scenario.").model_dump(mode="json", by_alias=True)
        run_model = model_of(p)
        overrides = dict(study.models.get(run_model, {}))
        for i in grid_param:
            if axes[i].target.path[0] == run_model:
                overrides[axes[i].target.path[1]] = axes[i].values[p[i]]
        _add_cases(cases, stops, study, scn, run_model, overrides, cases_of)
    return size_design(conv_model, list(cases), sorted(stops), where)


def _add_cases(cases: dict, stops: set, study, scn: dict, run_model: str, overrides: dict,
               cases_of: tuple) -> None:
    """Add one grid point's design cases (every listed load x model x temperature, a model
    or temperature ``design:`` does not name being the point's own) and its brake sizing
    stop time."""
    loads, models, temps = cases_of
    pinned = [(run_model, overrides)] if models is None else [
        (m, overrides if m == run_model else dict(study.models.get(m, {}))) for m in models]
    for model, over in pinned:
        for temp in temps if temps is not None else [scn["temperature_c"]]:
            for load in loads:
                cases[DesignCase(model, tuple(sorted(over.items())), float(temp),
                                 scn["elements"], load, name_model=models is not None)] = None
    stop_s = brake_sizing_stop_time(scn, dynamics=study.dynamics)
    if stop_s is not None:
        stops.add(stop_s)


def expand_runs(study: ResolvedStudy) -> list[RunSpec]:
    """The study's runs as :class:`RunSpec` objects (validated variants, identical grid points
    merged, the design basis applied)."""
    return _expand(study, study.designs)[0]


def study_from_json(doc: dict, study_id: str) -> ResolvedStudy:
    """Rebuild a resolved study from ``study.json`` (for resuming)."""
    axes = [
        Axis(
            a["name"],
            a["column"],
            resolve_axis(a["name"], doc["conveyor"], doc["scenario"]),
            tuple(a["values"]),
            a.get("group"),
            bool(a.get("sample", False)),
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
        accuracy=doc.get("accuracy"),
        sample=doc.get("sample"),
    )
    study.runs, _, study.designs = _expand(study, study.designs)
    study.total = len(study.runs)
    mark_accuracy_sample(study)
    return study
