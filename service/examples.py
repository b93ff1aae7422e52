"""The tiny example conveyor and scenario: the example study of the OpenAPI schema, the
workers' warm-up run and the tests' smallest study."""

from __future__ import annotations

from typing import Any

__all__ = ["TINY_CONVEYOR", "TINY_SCENARIO"]

#: A 60 m conveyor with a handful of elements: compiles every code path in well under a second
#: once numba's cache is warm.
TINY_CONVEYOR: dict[str, Any] = {
    "name": "warm-up",
    "speed_m_s": 2.0,
    "belt": {"type": "EP630/4", "width_m": 0.8},
    "material": {"capacity_t_h": 200, "density_t_m3": 1.0},
    "profile": [{"length_m": 60, "lift_m": 3}],
    "idlers": {
        "carry": {"spacing_m": 1.2, "trough_deg": 30},
        "return": {"spacing_m": 3.0, "rolls": 1},
    },
    "drives": [{"position": "head", "pulley_diameter_m": 0.6, "inertia_kg_m2": 20}],
}
TINY_SCENARIO: dict[str, Any] = {
    "elements": 12,
    "start": {"time_s": 2.0},
    "run_s": 1.0,
    "stop": {"mode": "coast", "time_s": 2.0},
    "record_dt_s": 0.5,
}
