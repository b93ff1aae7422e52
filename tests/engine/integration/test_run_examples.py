"""Every example conveyor runs the whole cycle for every friction model at -30 C and +20 C,
loaded and empty, with every stop mode it can do, and ends ``ok`` or ``warning``: slack, slip
and the other physical limits are warnings that name them, ``failed`` is kept for a diverged
integration, which is never acceptable. 60 elements keep the 200 runs to a few seconds.
"""

from __future__ import annotations

import itertools
import math

import pytest

from beltstudy.engine.conveyor import Scenario, load_conveyor
from beltstudy.engine.friction import MODELS
from beltstudy.engine.run import run_one
from tests.conftest import CONVEYORS, TRANSIENT_FIELDS

EXAMPLES = sorted(p.stem for p in CONVEYORS.glob("*.yaml"))


@pytest.mark.parametrize("model", sorted(MODELS))
@pytest.mark.parametrize("name", EXAMPLES)
def test_example_runs_every_case_without_divergence(name, model):
    conv = load_conveyor(CONVEYORS / f"{name}.yaml")
    stops = ["coast", "controlled"] + (["brake"] if conv.brakes else [])
    for temp, load, stop in itertools.product((-30.0, 20.0), ("full", "empty"), stops):
        scn = Scenario(temperature_c=temp, load=load, elements=60,
                       stop={"mode": stop, "time_s": 30})
        r = run_one(conv, scn, model=model)
        s = r.summary
        where = f"{name} {model} {temp} C {load} {stop}: {s['message']}"
        assert s["status"] in ("ok", "warning"), where
        for key in TRANSIENT_FIELDS:
            assert key in s, key
            val = s[key]
            assert val is None or math.isfinite(val), (key, where)
        if s["start_time_s"] is not None:  # reached design speed (not torque-limited)
            assert s["t_max_dyn_kn"] >= s["t_max_kn"] * 0.999, where
        assert r.timeseries is not None and len(r.timeseries) > 10
        assert r.timeseries["t_s"].iloc[-1] > scn.start.time_s
