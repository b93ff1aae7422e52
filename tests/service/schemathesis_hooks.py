"""Schemathesis hooks: keep generated *valid* studies to the rules JSON Schema cannot state.

The study schema (``beltstudy.service.door.openapi.study_schema``) states everything JSON Schema can; the
few rules it cannot (``beltstudy.service.door.openapi.NOT_IN_SCHEMA``: sums, comparisons between fields,
products over the grid) are written out here, independently of the service's code, and
generated positive bodies that break one are skipped (negative ones are left alone: they are
refused anyway). Used by ``tests/service/test_api_schemathesis.py`` and by hand with
``SCHEMATHESIS_HOOKS=tests.service.schemathesis_hooks``.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import schemathesis

#: The studies directory the live service is given (conveyor files named by path).
STUDIES = Path(__file__).resolve().parents[2] / "studies"
#: The service's BELTSTUDY_MAX_RUNS in the schemathesis runs.
MAX_RUNS = 50

_NAMED = {
    "friction_model": "model",
    "temperature_c": "scenario.temperature_c",
    "belt_type": "conveyor.belt.type",
    "stop_time_s": "scenario.stop.time_s",
    "load": "scenario.load",
}
_CONVEYOR_TOP = {
    "name", "speed_m_s", "belt", "material", "profile", "idlers", "drives", "takeup",
    "brakes", "holdback", "sag_limit_pct", "accessories", "safety_factor_min",
}
_ALIASES = {"iso5048": "din", "din22101": "din", "viscoah": "visco", "non-lin": "nonlin"}


def _target(axis: str) -> str:
    if axis in _NAMED:
        return _NAMED[axis]
    if axis.startswith("models."):
        _, model, param = axis.split(".")
        return f"models.{_ALIASES.get(model, model)}.{param}"
    if axis.startswith(("conveyor.", "scenario.")):
        return axis
    head = axis.split(".")[0]
    return f"conveyor.{axis}" if head in _CONVEYOR_TOP else f"scenario.{axis}"


def _range_values(spec: dict) -> list[float] | None:
    start, stop, step = spec["start"], spec["stop"], spec["step"]
    span = (stop - start) / step
    if not math.isfinite(span) or span < -1e-9 or span > MAX_RUNS:
        return None
    n = int(math.floor(span + 1e-9)) + 1
    values = [float(f"{start + i * step:.12g}") for i in range(n)]
    return values if len(set(values)) == len(values) else None


def _conveyor_ok(conv: Any) -> bool:
    if not isinstance(conv, dict):
        return True  # a file from the studies directory: valid as shipped
    drives = conv.get("drives", [])
    if abs(sum(d.get("share", 1.0) for d in drives) - 1.0) > 1e-6:
        return False
    limits = (conv.get("sag_limit_pct") or {}).values()
    if any(isinstance(v, int | float) and v < 1e-100 for v in limits):
        return False  # no finite auto take-up meets a sag limit this close to zero
    if not _dynamic_modulus_ok(conv.get("belt")):
        return False
    idlers = conv.get("idlers")
    route_m = sum(p["length_m"] for p in conv.get("profile", []))
    for strand in (idlers.values() if isinstance(idlers, dict) else ()):
        if isinstance(strand, dict) and (strand.get("spacing_m") is None) == (
                strand.get("count") is None):
            return False  # an idler set gives its pitch or its count, one of them
        if isinstance(strand, dict) and strand.get("count") is not None and \
                not 0.1 <= route_m / strand["count"] <= 20.0:
            return False  # sets counted along the route: a pitch of 0.1 to 20 m (Conveyor)
    if not all(abs(p.get("lift_m", 0.0)) < p["length_m"] for p in conv.get("profile", [])):
        return False
    return _whole_checks_pass(conv)


def _whole_checks_pass(conv: dict) -> bool:
    """The conveyor's registered checks of the whole (``WHOLE_CHECKS``: the cross-section's
    fill against the capacity and speed, the middle roll), rules across fields no schema
    states: a conveyor they refuse is skipped. A conveyor whose own model refuses it is still
    sent (whether the schema says so is what the run checks)."""
    import beltstudy.engine.capacity  # noqa: F401 - registers the fill and the middle roll
    from beltstudy.engine.conveyor import WHOLE_CHECKS, Conveyor, InputError

    try:
        model = Conveyor.model_validate(conv)
    except ValueError:
        return True
    try:
        for check in WHOLE_CHECKS:
            check(model, "")
    except InputError:
        return False
    return True


def _catalogue_moduli() -> dict[str, float]:
    """Static modulus [kN/m] of each catalogue belt, from the catalogue file itself."""
    import csv

    path = Path(__file__).resolve().parents[2] / "engine" / "data" / "belts.csv"
    rows = csv.DictReader(line for line in path.read_text().splitlines()
                          if not line.startswith("#"))
    return {r["id"]: float(r["modulus_kn_m"]) for r in rows}


def _dynamic_modulus_ok(belt: Any) -> bool:
    """A given dynamic modulus is at least the static one (the file's, else the catalogue's)."""
    if not isinstance(belt, dict) or belt.get("dynamic_modulus_kn_m") is None:
        return True
    static = belt.get("modulus_kn_m")
    if static is None:
        static = _catalogue_moduli().get(belt.get("type"))
    return static is None or belt["dynamic_modulus_kn_m"] >= static


def _list_len(conv: Any, name: str) -> int | None:
    if not isinstance(conv, dict):
        return None
    return len(conv.get(name, []))


def _study_ok(body: dict) -> bool:
    conv = body.get("conveyor")
    if not _conveyor_ok(conv):
        return False
    grid = body.get("grid", {})
    groups = [dict(grid)] + [dict(g) for g in body.get("zip", [])]
    axes: dict = {}
    total = 1
    for g, group in enumerate(groups):
        lengths = set()
        for axis, values in group.items():
            if axis in axes:
                return False  # one axis in two places
            if isinstance(values, dict):
                values = _range_values(values)
                if values is None:
                    return False
            axes[axis] = values
            lengths.add(len(values))
            if g == 0:
                total *= len(values)
        if g > 0:
            if len(lengths) != 1:
                return False  # a zip group's axes vary together: one length
            total *= lengths.pop()
        if total > MAX_RUNS:
            return False
    targets = []
    for axis, values in axes.items():
        target = _target(axis)
        parts = target.split(".")
        if len(parts) > 2 and parts[0] == "conveyor" and parts[2].isdigit():
            size = _list_len(conv, parts[1])
            if size is None or int(parts[2]) >= size:
                return False  # the index must exist in an inline base conveyor
        base = _base_conveyor(conv)
        if parts[0] == "conveyor" and isinstance(base, dict) and \
                not _indices_exist(base, parts[1:]):
            return False  # an index into a list the base conveyor (inline or file) lacks
        if parts[0] == "conveyor" and len(parts) > 1 and isinstance(base, dict):
            # a conveyor axis changes the conveyor: each variant must stay valid
            for value in values:
                variant = _with(base, parts[1:], value)
                if variant is None or not _conveyor_ok(variant) or \
                        _variant_refused(base, variant):
                    return False
        if any(isinstance(v, (dict, list)) for v in values) and not _distinct(conv, parts,
                                                                             values):
            return False  # two values that are one once defaults are filled in
        targets.append(target)
        if axis in ("friction_model",):
            canon = [_ALIASES.get(v, v) for v in values]
            if len(set(canon)) != len(canon):
                return False
    if total > MAX_RUNS:
        return False
    for i, a in enumerate(targets):
        for b in targets[i + 1:]:
            if a == b or a.startswith(b + ".") or b.startswith(a + "."):
                return False
    models = [_ALIASES.get(m, m) for m in body.get("models", {})]
    if len(set(models)) != len(models):
        return False
    if "friction_model" in axes:
        run = {_ALIASES.get(m, m) for m in axes["friction_model"]}
    else:
        one = body.get("model") or (models[0] if len(models) == 1 else "din")
        run = {_ALIASES.get(one, one)}
    for target in targets:
        if target.startswith("models.") and target.split(".")[1] not in run:
            return False  # a parameter of a model the study does not run
    design = body.get("design") if isinstance(body.get("design"), dict) else {}
    listed = design.get("friction_model")
    designed = {_ALIASES.get(m, m) for m in (listed if isinstance(listed, list) else [listed])
                if isinstance(m, str)}
    fixed = {f"models.{_ALIASES.get(m, m)}.{p}" for m, given in body.get("models", {}).items()
             if isinstance(given, dict) for p in given}
    for target in targets:
        model = target.split(".")[1] if target.startswith("models.") else None
        if target in fixed and not (model in designed and run - {model}):
            return False  # under models: and on an axis: the fixed value would be ignored
    for name in ("friction_model", "temperature_c", "load"):
        listed = design.get(name)
        if isinstance(listed, list):
            canon = [json.dumps(_design_case(v), default=str) for v in listed]
            if len(set(canon)) != len(canon):
                return False  # a design case listed twice
    used = run | {_ALIASES.get(design.get("friction_model"), design.get("friction_model"))}
    if any(m not in used for m in models):
        return False  # parameters of a model the study neither runs nor designs with
    if body.get("dynamics", True) and not _scenario_fits(body, axes):
        return False
    if body.get("accuracy") is not None and body.get("dynamics") is False:
        return False  # error bars are those of the transient
    if body.get("surface") is True and body.get("dynamics") is False:
        return False  # the surface is that of the transient
    if body.get("dynamics") is False:
        for axis, values in axes.items():
            parts = _target(axis).split(".")
            if parts[0] == "scenario" and len(parts) > 1 and len(values) > 1 and \
                    parts[1] not in ("load", "temperature_c", "elements"):
                return False  # a steady study does not read it: its values would be one run
    return _section_loads_fit(body, axes)


def _design_case(value: Any) -> Any:
    """A design list's entry as the service compares them: a model by its name, full and
    empty as 1 and 0, every number a float."""
    if isinstance(value, str):
        return {"full": 1.0, "empty": 0.0}.get(value, _ALIASES.get(value, value))
    if isinstance(value, list):
        return [_design_case(v) for v in value]
    if isinstance(value, int | float) and not isinstance(value, bool):
        return float(value)
    return value


def _section_loads_fit(body: dict, axes: dict) -> bool:
    """A load given as a list has one fraction per carry profile section of the conveyor."""
    base = _base_conveyor(body.get("conveyor"))
    profiles = [base.get("profile")] if isinstance(base, dict) else []
    for axis, values in axes.items():
        if _target(axis) == "conveyor.profile":
            profiles = list(values)
    counts = {len(p) for p in profiles if isinstance(p, list)}
    loads = [v for axis, values in axes.items() if _target(axis) == "scenario.load"
             for v in values]
    scenario = body.get("scenario")
    if not loads and isinstance(scenario, dict) and "load" in scenario:
        loads = [scenario["load"]]
    return all(not isinstance(v, list) or {len(v)} == counts or not counts for v in loads)


def _base_conveyor(conv: Any) -> Any:
    """The study's base conveyor as a mapping: inline, or the shipped file it names."""
    if isinstance(conv, str):  # read as the service reads it (YAML 1.2: 6.0e4 is a number)
        from beltstudy.engine.conveyor import load_mapping

        return load_mapping(STUDIES / conv)
    return conv


def _variant_refused(base: dict, variant: dict) -> bool:
    """Whether the conveyor refuses a variant of a base it accepts: an axis value is held to
    its field's schema alone, and what it breaks together with the base's other fields (a
    take-up moved to the tail that keeps the base's ``at_m`` along the return) is a rule
    across fields no schema states. A base the conveyor refuses is not judged here."""
    from beltstudy.engine.conveyor import InputError, parse_conveyor

    try:
        parse_conveyor(base)
    except (InputError, ValueError):
        return False
    try:
        parse_conveyor(variant)
    except (InputError, ValueError):
        return True
    return False


def _indices_exist(base: dict, path: list[str]) -> bool:
    """Whether every list index on a conveyor axis's path names an entry of the base
    conveyor (``accessories.ploughs.0`` on a conveyor without ploughs is refused: the index
    is out of range). A field the base does not give is fine unless an index lies below it."""
    node: Any = base
    for i, key in enumerate(path):
        if isinstance(node, list):
            if not key.isdigit() or int(key) >= len(node):
                return False
            node = node[int(key)]
        elif isinstance(node, dict) and key in node:
            node = node[key]
        else:
            return not any(k.isdigit() for k in path[i:])
    return True


def _distinct(conv: Any, parts: list[str], values: list) -> bool:
    """Whether the object values of a conveyor or scenario axis stay distinct once validated
    (``{}`` and ``{"head_kn": 0}`` are one accessories value); the engine's own models fill
    the defaults."""
    from beltstudy.engine.conveyor import InputError, Scenario, parse_conveyor

    if parts[0] == "conveyor":
        conv = _base_conveyor(conv)
        if not isinstance(conv, dict):
            return True
    else:
        conv = {}
    keys = set()
    for value in values:
        variant = _with(conv, parts[1:], value)
        if variant is None:
            return True
        try:
            model = (parse_conveyor(variant) if parts[0] == "conveyor" else
                     Scenario.model_validate(variant))
        except (InputError, ValueError):
            return True  # an invalid value: refused anyway
        node: Any = model.model_dump(mode="json", by_alias=True)
        for key in parts[1:]:
            node = node[int(key)] if isinstance(node, list) else node.get(key)
        keys.add(json.dumps(node, sort_keys=True))
    return len(keys) == len(values)


def _with(conv: dict, path: list[str], value: Any) -> dict | None:
    import copy

    out = copy.deepcopy(conv)
    node: Any = out
    for key in path[:-1]:
        if isinstance(node, list):
            if not key.isdigit() or int(key) >= len(node):
                return None
            node = node[int(key)]
        else:
            node = node.setdefault(key, {})
    if isinstance(node, list):
        return None
    node[path[-1]] = value
    return out


def _scenario_fits(body: dict, grid: dict) -> bool:
    """With dynamics: a brake stop needs brakes and must be longer than the delay of every
    auto-sized brake; a torque start needs the relative formulation. (Grids with an axis that
    could change one of these are skipped: too many cases to follow here.)"""
    touchy = ("scenario.stop", "scenario.start", "scenario.formulation", "conveyor.brakes")
    if any(_target(a).startswith(touchy) or _target(a) == "scenario" for a in grid):
        return False
    scenario = body.get("scenario") or {}
    if scenario.get("formulation") == "support" and \
            (scenario.get("start") or {}).get("control") == "torque":
        return False
    conv = body.get("conveyor")
    stop = scenario.get("stop") or {}
    if stop.get("mode", "coast") != "brake":
        return True
    if not isinstance(conv, dict):
        return False
    brakes = conv.get("brakes", [])
    delays = [b.get("delay_s", 0.5) for b in brakes if b.get("force_kn", "auto") == "auto"]
    return bool(brakes) and (not delays or stop.get("time_s", 30.0) > max(delays))


#: Ambient temperatures a run takes [C] (the scenario's bounds).
TEMPERATURE_C = (-60.0, 60.0)


def _sample_ok(body: dict) -> bool:
    """A ``sample:`` keeps the rules outside its schema: method sobol's n is N (D + 2) with N
    a power of two; every axis a numeric field whose drawn values stay within its bounds
    (here: only bounded temperature distributions, the one axis these hooks can vouch for);
    n x the grid within MAX_RUNS (checked by :func:`_study_ok` with the sample as one more
    group of n distinct temperatures)."""
    sample = body["sample"]
    axes = sample["axes"]
    n, d = int(sample["n"]), len(axes)  # 512.0 is an integer to JSON Schema
    if sample.get("method", "sobol") == "sobol":
        base = n // (d + 2)
        if n % (d + 2) or base < 2 or base & (base - 1):
            return False
    lo, hi = TEMPERATURE_C
    for name, dist in axes.items():
        if name not in ("temperature_c", "scenario.temperature_c"):
            return False
        if dist["dist"] not in ("uniform", "triangular") or dist["low"] < lo or dist["high"] > hi:
            return False
    if n > MAX_RUNS:
        return False
    zips = list(body.get("zip", []))
    zips.append({"temperature_c": [round(lo + 1 + i * 0.01, 2) for i in range(n)]})
    return _study_ok({**body, "zip": zips})


@schemathesis.hook
def filter_body(ctx, body):
    """Skip generated valid studies that break a rule outside the schema."""
    if isinstance(body, dict) and "name" in body and body.get("sample") is not None:
        try:
            return _sample_ok(body)
        except (TypeError, KeyError, AttributeError, ZeroDivisionError, ValueError, OSError):
            return True
    if not isinstance(body, dict) or "name" not in body or \
            ("grid" not in body and "zip" not in body):
        return True
    try:
        return _study_ok(body)
    except (TypeError, KeyError, AttributeError, ZeroDivisionError, ValueError, OSError):
        return True  # not a well-formed study: it is a negative case, refused anyway


def _calibration_ok(body: dict) -> bool:
    """A calibration body keeps the rules outside its schema (SPEC 7.3): a conveyor file that
    exists, every row with a measured power_kw or te_kn, fitted names the model's parameters
    (fixed ones too), a name not both fitted and fixed, a load case the profile takes."""
    from beltstudy.engine import get_model

    conv = body["conveyor"]
    if isinstance(conv, str) and not (STUDIES / conv).is_file():
        return False
    if not _conveyor_ok(conv):
        return False
    if any("power_kw" not in r and "te_kn" not in r for r in body["measured"]):
        return False
    if any(r["load"] not in ("full", "empty", "inclines", "declines")
           and not (isinstance(r["load"], int | float) and 0 <= r["load"] <= 1.3)
           for r in body["measured"]):
        return False
    valid = {f["name"] for f in get_model(body["model"]).parameter_table()}
    names = [str(f).partition("=")[0] for f in body["fit"]]
    params = body.get("params") or {}
    return (set(names) <= valid and len(set(names)) == len(names) and set(params) <= valid
            and not set(names) & set(params) and len(body["measured"]) <= 8)


@schemathesis.hook("filter_body")
def filter_calibration(ctx, body):
    """Skip generated valid calibrations that break a rule outside the schema."""
    if not isinstance(body, dict) or "measured" not in body or "fit" not in body:
        return True
    try:
        return _calibration_ok(body)
    except (TypeError, KeyError, AttributeError, ValueError, OSError):
        return True


#: The models ``GET /studies/{id}/compare`` pairs when a parameter is left out (README).
_PAIR_DEFAULTS = {"baseline": "cema", "candidate": "nonlin"}


def _pair_ok(path: str, query: dict) -> bool:
    """A comparison names two models: the candidate (given or its default, nonlin) is not
    the baseline (given or its default, cema), an alias being its model. Across two
    parameters, so outside JSON Schema; the handler refuses it with a 422 naming
    ``candidate``. Positive compare requests broke it in 353 of 525 generated (seed 5): both
    parameters drawn as the enum's first value, ``din``."""
    if not path.endswith("/compare"):
        return True
    pair = {}
    for label, default in _PAIR_DEFAULTS.items():
        value = query.get(label, default)
        if not isinstance(value, str):
            return True  # a negative case: refused anyway
        pair[label] = _ALIASES.get(value, value)
    return pair["baseline"] != pair["candidate"]


@schemathesis.hook("filter_query")
def filter_model_pair(ctx, query):
    """Skip generated comparisons whose candidate is the baseline (a rule across fields)."""
    operation = getattr(ctx, "operation", None)
    if operation is None or not isinstance(query, dict):
        return True
    return _pair_ok(operation.path, query)
