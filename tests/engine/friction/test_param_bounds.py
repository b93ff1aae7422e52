"""Every friction model parameter with a declared largest value (``friction.base.param(hi=)``):
the value itself is taken, anything above it is an InputError naming the parameter (the study
schema's maximum: tests/service/test_param_schema.py)."""

from __future__ import annotations

import dataclasses

import pytest

from beltstudy.engine.errors import InputError
from beltstudy.engine.friction import MODELS

BOUNDED = [(name, f.name, f.metadata["hi"]) for name, fm in MODELS.items()
           for f in dataclasses.fields(fm.params_class) if f.metadata.get("hi") is not None]


def test_the_slips_of_the_pen_a_tester_found_are_bounded():
    names = {(m, p) for m, p, _ in BOUNDED}
    assert {("cema", "ky"), ("cema", "kt"), ("cema", "ai_n"), ("din", "c"), ("nonlin", "mu_b"),
            ("nonlin", "bearing_diameter_m"), ("visco", "kappa_ir"),
            ("visco", "frequency_hz")} <= names


@pytest.mark.parametrize("model, name, hi", BOUNDED, ids=[f"{m}.{p}" for m, p, _ in BOUNDED])
def test_a_parameter_above_its_largest_value_is_refused_naming_it(model, name, hi):
    fm = MODELS[model]
    default = getattr(fm.params_class(), name)
    assert default is None or default <= hi / 5.0  # the bound lies far beyond the default
    with pytest.raises(InputError) as ei:
        fm.params({name: hi * 1.001})
    # in the model's own words where its check bounds it already (DIN's f: "a friction factor
    # between 0 and 1"), else "at most <hi>"
    assert str(ei.value).startswith(f"models.{model}.{name}: ")
    assert f"at most {hi:g}" in str(ei.value) or "between 0 and 1" in str(ei.value)
    try:  # the bound itself passes the bound (the model's own checks may still refuse it)
        fm.params({name: hi})
    except InputError as exc:
        assert "at most" not in str(exc)

