"""The study schema states each friction model parameter's declared largest value
(``friction.base.param(hi=)``) as its ``maximum``, so generated and hand-written studies see the
bound the model enforces."""

from __future__ import annotations

import dataclasses

from beltstudy.engine.friction import MODELS
from beltstudy.service.door.study import param_bounds


def test_the_study_schema_states_the_largest_value():
    bounded = [(name, f.name, f.metadata["hi"]) for name, fm in MODELS.items()
               for f in dataclasses.fields(fm.params_class) if f.metadata.get("hi") is not None]
    assert len(bounded) > 20
    for model, name, hi in bounded:
        assert param_bounds(MODELS[model], name).get("maximum") == hi, (model, name)
