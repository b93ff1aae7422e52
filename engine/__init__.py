"""beltstudy engine: conveyor models, friction models, statics and transient dynamics.

The engine's public API, the one the study service reaches it through:

* input models: ``Conveyor``, ``Scenario``, ``parse_conveyor``, ``parse_scenario``,
  ``load_conveyor``, ``load_mapping``, ``section_loads``, ``format_validation_error``,
  ``InputError``;
* friction registry: ``MODELS``, ``ALIASES``, ``get_model``, ``canonical_name``;
* catalogues (``catalog``: belts, idlers, compounds) and ``resolve_belt``;
* one run: ``run_one`` -> ``RunResult``, ``check_scenario``, ``DynamicsOptions``;
* what a run reads: ``scenario_as_read``, ``unread_fields``, ``brake_sizing_stop_time``;
* sizing: ``auto_sizes`` (one case), ``size_over_cases`` (a design over its cases);
* steady state: ``solve_steady`` -> ``SteadyResult``; ``build_loop`` (``Loop.where``),
  ``capacity``; the safety factor limits;
* results: ``results`` (every result field by group), ``check_summary``;
* calibration: ``calibrate``, ``measurements_from_rows`` (SPEC 7.3).

``run_one``, ``RunResult``, ``check_scenario`` and ``DynamicsOptions`` load the transient
engine (numba) on first use, not when ``beltstudy.engine`` is imported.
"""

from importlib import import_module
from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("beltstudy")
except PackageNotFoundError:  # pragma: no cover - running from a source tree without install
    __version__ = "0.6.32"

from beltstudy.engine import catalog, results  # noqa: E402
from beltstudy.engine.beltselect import (  # noqa: E402
    BeltChoice,
    SteadyCase,
    design_cases,
    resolve_auto_belt,
    run_cases,
    run_message,
    select_belt,
    with_belt,
)
from beltstudy.engine.capacity import Capacity, capacity  # noqa: E402
from beltstudy.engine.catalog import AUTO as BELT_AUTO  # noqa: E402
from beltstudy.engine.catalog import resolve_belt  # noqa: E402
from beltstudy.engine.conveyor import (  # noqa: E402
    LOAD_MAX,
    TEMPERATURE_MAX_C,
    TEMPERATURE_MIN_C,
    Conveyor,
    Scenario,
    conveyor_variant,
    format_validation_error,
    load_conveyor,
    load_mapping,
    parse_conveyor,
    parse_scenario,
    section_loads,
)
from beltstudy.engine.design import GIVEN, auto_sizes, summary_fields  # noqa: E402
from beltstudy.engine.drives import OVERLOAD_S_MAX  # noqa: E402
from beltstudy.engine.errors import InputError  # noqa: E402
from beltstudy.engine.friction import ALIASES, MODELS, canonical_name, get_model  # noqa: E402
from beltstudy.engine.loop import Loop, build_loop  # noqa: E402
from beltstudy.engine.reads import (  # noqa: E402
    STEADY_FIELDS,
    brake_sizing_stop_time,
    conveyor_as_read,
    scenario_as_read,
    unread_brakes,
    unread_fields,
)
from beltstudy.engine.results import MAX_DRIVES, check_summary  # noqa: E402
from beltstudy.engine.sizing import (  # noqa: E402
    BrakeSizes,
    DesignCase,
    DesignSizes,
    Largest,
    SizingError,
    governed_at,
    installed_at_full_load,
    load_label,
    size_over_cases,
)
from beltstudy.engine.statics import (  # noqa: E402
    SAFETY_FACTOR_MIN,
    STARTUP_FACTOR,
    TRANSIENT_SAFETY_RATIO,
    SteadyResult,
    solve_steady,
)

#: Names that load the transient engine (numba): imported on first use.
_DEFERRED = {
    "run_one": "beltstudy.engine.run",
    "RunResult": "beltstudy.engine.run",
    "check_scenario": "beltstudy.engine.run",
    "DynamicsOptions": "beltstudy.engine.dynamics",
    "calibrate": "beltstudy.engine.calibration",
    "measurements_from_rows": "beltstudy.engine.calibration",
}

__all__ = [
    "__version__",
    "InputError",
    "Conveyor", "Scenario", "parse_conveyor", "parse_scenario", "load_conveyor",
    "conveyor_variant",
    "load_mapping", "section_loads", "format_validation_error", "LOAD_MAX", "TEMPERATURE_MIN_C", "TEMPERATURE_MAX_C",
    "MODELS", "ALIASES", "get_model", "canonical_name",
    "catalog", "resolve_belt",
    "run_one", "RunResult", "check_scenario", "DynamicsOptions",
    "STEADY_FIELDS", "unread_fields", "scenario_as_read", "brake_sizing_stop_time",
    "conveyor_as_read", "unread_brakes",
    "auto_sizes", "summary_fields", "GIVEN",
    "DesignCase", "DesignSizes", "Largest", "BrakeSizes", "SizingError", "size_over_cases", "installed_at_full_load",
    "governed_at", "load_label",
    "solve_steady", "SteadyResult", "SAFETY_FACTOR_MIN", "TRANSIENT_SAFETY_RATIO",
    "build_loop", "Loop", "capacity", "Capacity",
    "results", "check_summary", "MAX_DRIVES", "OVERLOAD_S_MAX",
]

# belt selection (belt.type: auto)
__all__ += ["BeltChoice", "SteadyCase", "design_cases", "resolve_auto_belt", "run_cases", "run_message",
            "select_belt", "with_belt", "BELT_AUTO", "STARTUP_FACTOR"]


# calibration against measured steady power (SPEC 7.3; scipy loads on first use)
__all__ += ["calibrate", "measurements_from_rows"]


def __getattr__(name: str):
    """The transient engine's names, imported when first asked for (PEP 562)."""
    if name not in _DEFERRED:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(import_module(_DEFERRED[name]), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *_DEFERRED})
