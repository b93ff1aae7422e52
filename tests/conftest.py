"""Shared fixtures: paths to the example conveyors, a small hand-calculable conveyor, the
transient fields of a run's summary, and the transient kernel compiled once per session."""

from __future__ import annotations

import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
CONVEYORS = ROOT / "studies" / "conveyors"

#: The transient fields every run with dynamics reports (SPEC section 4).
TRANSIENT_FIELDS = (
    "t_max_dyn_kn", "t_max_dyn_at_m", "t_max_dyn_time_s", "t_min_dyn_kn", "t_min_dyn_at_m",
    "t_min_dyn_time_s", "dyn_factor", "drive_force_max_kn", "drive_power_max_kw",
    "velocity_max_m_s", "velocity_min_m_s", "takeup_travel_m", "start_time_s", "stop_time_s",
    "wave_loop_time_s", "stop_wave_ratio", "sag_max_dyn_pct", "slip_margin_min_dyn",
    "safety_factor_dyn",
)


def hand_conveyor_dict(**over) -> dict:
    """A 1 km conveyor rising 50 m, with round numbers for hand calculations.

    m'_G = 20 kg/m (custom belt, covers 0), m'_L = 720 / (3.6 x 4) = 50 kg/m,
    m'_R carry = 12.5 / 1.25 = 10 kg/m, m'_R return = 7.5 / 2.5 = 3 kg/m.
    """
    d = {
        "name": "hand",
        "speed_m_s": 4.0,
        "belt": {"width_m": 1.0, "rating_kn_m": 1000, "modulus_kn_m": 60000,
                 "carcass_mass_kg_m2": 20.0, "top_cover_mm": 0, "bottom_cover_mm": 0},
        "material": {"capacity_t_h": 720, "density_t_m3": 1.0},
        "profile": [{"length_m": 1000, "lift_m": 50}],
        "idlers": {
            "carry": {"spacing_m": 1.25, "roll_diameter_m": 0.133, "rolls": 3, "trough_deg": 35,
                      "rotating_mass_kg": 12.5, "seal_drag_n": 5.0},
            "return": {"spacing_m": 2.5, "roll_diameter_m": 0.133, "rolls": 1,
                       "rotating_mass_kg": 7.5, "seal_drag_n": 3.0},
        },
        "drives": [{"position": "head", "wrap_deg": 200, "friction": 0.35, "share": 1.0,
                    "pulley_diameter_m": 1.0}],
        "takeup": {"type": "gravity", "position": "tail", "mass_kg": "auto"},
        "sag_limit_pct": {"carry": 3.0, "return": 5.0},
        "accessories": {"head_kn": 1.0, "tail_kn": 0.5},
    }
    for key, val in over.items():
        d[key] = val
    return d


@pytest.fixture
def hand_dict():
    return hand_conveyor_dict()


@pytest.fixture
def hand_conveyor():
    from beltstudy.engine.conveyor import parse_conveyor

    return parse_conveyor(hand_conveyor_dict())


def short30_dict() -> dict:
    """A 30 m level fabric belt at 2 m/s (EP630/4, 0.8 m, 200 t/h), head drive of 15 kW, auto
    take-up at the tail: a conveyor whose automatic step is below 5e-4 s and whose motor is
    about 3 x what it needs."""
    return {
        "name": "short30",
        "speed_m_s": 2.0,
        "belt": {"type": "EP630/4", "width_m": 0.8, "top_cover_mm": 5, "bottom_cover_mm": 2,
                 "compound": "standard"},
        "material": {"capacity_t_h": 200, "density_t_m3": 1.2, "loading_speed_m_s": 0.0},
        "profile": [{"length_m": 30, "lift_m": 0}],
        "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.127, "rolls": 3,
                             "trough_deg": 35, "cema_class": "C"},
                   "return": {"spacing_m": 3.0, "roll_diameter_m": 0.127, "rolls": 1,
                              "cema_class": "C"}},
        "drives": [{"position": "head", "wrap_deg": 200, "friction": 0.35, "share": 1.0,
                    "pulley_diameter_m": 0.5, "inertia_kg_m2": 5, "rated_power_kw": 15,
                    "torque_limit": 1.5}],
        "takeup": {"type": "gravity", "position": "tail", "mass_kg": "auto"},
    }


def incline300_dict(**changes) -> dict:
    """A 300 m, 15 m lift fabric incline at 2 m/s (EP630/4, 0.8 m, 200 t/h), one 75 kW head
    drive (wrap 200 deg, mu 0.35), auto gravity take-up at the tail, no accessories;
    ``changes`` replace top-level fields (a take-up, brakes)."""
    return {
        "name": "incline-300", "speed_m_s": 2.0,
        "belt": {"type": "EP630/4", "width_m": 0.8, "top_cover_mm": 5, "bottom_cover_mm": 2},
        "material": {"capacity_t_h": 200, "density_t_m3": 1.2},
        "profile": [{"length_m": 300, "lift_m": 15}],
        "idlers": {"carry": {"spacing_m": 1.2, "roll_diameter_m": 0.127, "rolls": 3,
                             "trough_deg": 35, "cema_class": "C"},
                   "return": {"spacing_m": 3.0, "roll_diameter_m": 0.127, "rolls": 1,
                              "cema_class": "C"}},
        "drives": [{"position": "head", "wrap_deg": 200, "friction": 0.35, "share": 1.0,
                    "pulley_diameter_m": 0.5, "inertia_kg_m2": 30, "rated_power_kw": 75,
                    "torque_limit": 1.5}],
        "takeup": {"type": "gravity", "position": "tail", "mass_kg": "auto"},
        "accessories": {"head_kn": 0.0, "tail_kn": 0.0},
        **changes,
    }


# --------------------------------------------------------------------------------------------
# The numba kernel, compiled once per session before the first test

#: The warm-up run: the hand conveyor on a dozen elements through a short cycle (a fraction of
#: a second once compiled). Every run's kernel has the same argument types, so this one
#: compile serves them all.
WARM_UP_SCENARIO = {"elements": 12, "start": {"time_s": 2.0}, "run_s": 0.5,
                    "stop": {"mode": "coast"}}

#: What the warm-up did, for the terminal summary.
_warm_up: dict = {}


def _kernel_dispatchers() -> list:
    """The numba functions of the loaded engine modules (each once); their ``stats`` say
    whether they were compiled or loaded from numba's cache."""
    from beltstudy.engine.warmth import kernel_dispatchers

    return kernel_dispatchers()


#: The first test this process runs (:func:`pytest_runtest_setup`).
_first_item: list = []


def _is_live(item) -> bool:
    """A test that starts services, clusters or a browser (marked ``slow`` or ``browser``)."""
    return bool(item.get_closest_marker("slow") or item.get_closest_marker("browser"))


def _leaves_the_compile(config) -> bool:
    """Whether this process leaves a cold kernel's compile to another (pytest-xdist only): the
    worker handed the live group (its first test live, :func:`pytest_collection_modifyitems`)
    compiles at once, since its services' Dask workers need the kernel; another worker whose
    first test is not live runs the tests that never run the kernel meanwhile, and
    waits for the compile at its first test that needs it, instead of idling a core for the
    whole compile (about two minutes of a fresh clone's suite)."""
    if not hasattr(config, "workerinput") or not _first_item or _is_live(_first_item[0]):
        return False
    from beltstudy.engine.warmth import kernel_cold

    return kernel_cold()


@pytest.fixture(scope="session")
def kernel_ran():
    """The warm-up run in this process (for a test of what a process that ran the kernel has;
    a worker that left the compile to another has not run it yet)."""
    from beltstudy.engine.conveyor import Scenario, parse_conveyor
    from beltstudy.engine.run import run_one

    run = run_one(parse_conveyor(hand_conveyor_dict()), Scenario(**WARM_UP_SCENARIO),
                  model="din")
    assert run.summary["status"] != "failed", run.summary["message"]


@pytest.hookimpl(tryfirst=True)
def pytest_runtest_setup(item):
    if not _first_item:
        _first_item.append(item)


@pytest.fixture(scope="session", autouse=True)
def numba_kernel_compiled(request):
    """Compile the transient kernel once, before the first test, so its cost shows as its own
    line (the setup of the first test in ``--durations``, and the terminal summary) instead of
    inside whichever dynamic test comes first. numba's ``cache=True`` keeps the compiled code
    beside the sources: a fresh clone compiles for a minute or more, later sessions load it in
    well under a second. A failure here is reported, not raised: the tests that run the
    kernel fail on their own. Runs in each process (pytest-xdist workers too): on a cold cache
    one of them compiles while the others wait and load what it wrote
    (``beltstudy.engine.dynamics.cache.first_compile``), or run the tests that do not need it
    meanwhile (:func:`_leaves_the_compile`); imports the engine only."""
    t0 = time.perf_counter()
    if _leaves_the_compile(request.config):
        _warm_up["left"] = True
        yield
        return
    try:
        from beltstudy.engine.conveyor import Scenario, parse_conveyor
        from beltstudy.engine.run import run_one

        run = run_one(parse_conveyor(hand_conveyor_dict()), Scenario(**WARM_UP_SCENARIO),
                      model="din")
        if run.summary["status"] == "failed":
            _warm_up["error"] = run.summary["message"]
        _warm_up["compiled"] = any(d.stats.cache_misses for d in _kernel_dispatchers())
    except Exception as exc:  # reported in the summary; the kernel's own tests will fail
        _warm_up["error"] = f"{type(exc).__name__}: {exc}"
    _warm_up["seconds"] = time.perf_counter() - t0
    yield


#: Test files none of whose tests runs the transient kernel, in this process or a child one
#: (``tests/kernel_free.txt``, which says how it was measured).
KERNEL_FREE = frozenset(
    line.strip() for line in (ROOT / "tests" / "kernel_free.txt").read_text().splitlines()
    if line.strip() and not line.startswith("#"))


def _path(item) -> str:
    return item.nodeid.split("::")[0]


def pytest_collection_modifyitems(config, items):
    """With pytest-xdist (``make test``: ``-n 2 --dist loadgroup``), the tests that start
    services, clusters or a browser (``slow``, ``browser``) run one after another on one
    worker, while the other worker takes the rest: two live services at once on a 2-core
    machine would put the tests that time a shutdown or a failure against CPU they do not
    get (with the other live files a group each, beside the timed ones, a fresh clone's suite
    took 876 s against 823 s). Without xdist the mark does nothing.

    The test files that never run the transient kernel (:data:`KERNEL_FREE`) come first, in
    their own order: on a cold cache the worker that does not take the live group runs them
    while the other compiles (:func:`_leaves_the_compile`). pytest-xdist hands out the largest
    group first (the live one, ``loadscopereorder``), then single tests in this order."""
    for item in items:
        if _is_live(item):
            item.add_marker(pytest.mark.xdist_group("live"))
    items.sort(key=lambda item: _path(item) not in KERNEL_FREE)


def pytest_terminal_summary(terminalreporter):
    w = _warm_up
    if w.get("left"):
        terminalreporter.write_sep("-", "numba compile")
        terminalreporter.write_line("transient kernel: cold, left to the process that runs the "
                                    "live tests; the tests that do not run it went first")
        return
    if "seconds" not in w:
        return
    how = ("compiled (numba's cache was cold)" if w.get("compiled")
           else "loaded from numba's on-disk cache")
    line = f"transient kernel warm-up: {w['seconds']:.1f} s, {how}, once before the first test"
    if "error" in w:
        line += f"; the warm-up run failed: {w['error']}"
    terminalreporter.write_sep("-", "numba compile")
    terminalreporter.write_line(line)
