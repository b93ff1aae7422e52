"""A Sobol' ``sample.n`` below the smallest Saltelli design, 2 (D + 2) points, is refused, not
rounded up to it, and docs/uncertainty.md and the schema say so: the docs said every other
``n`` draws the nearest size, so over four axes ``n: 10`` (nearer 12 than 6) was expected to
draw 12, and the docs' own ``n = 9`` refusal over three axes contradicted that rule."""

from __future__ import annotations

import re

import pytest

from beltstudy.service.door.sample import SampleIn, sobol_base
from tests.conftest import ROOT

AXES4 = {name: {"dist": "uniform", "low": 0.0, "high": 1.0}
         for name in ("temperature_c", "models.din.f_carry", "models.din.f_return",
                      "load")}


@pytest.mark.parametrize(("n", "d", "base"), [(12, 4, 2), (17, 4, 2), (18, 4, 2), (19, 4, 4),
                                              (36, 4, 4), (37, 4, 8), (10, 3, 2), (512, 3, 128)])
def test_from_the_smallest_design_up_n_draws_the_nearest_size(n, d, base):
    assert sobol_base(n, d) == base


@pytest.mark.parametrize(("n", "d"), [(10, 4), (11, 4), (9, 3), (3, 1)])
def test_below_the_smallest_design_n_is_refused_with_the_smallest(n, d):
    with pytest.raises(ValueError, match=rf"n = {n}: .*use n >= {2 * (d + 2)}, or method: "
                       "lhs for any n"):
        sobol_base(n, d)


def _flat(text: str) -> str:
    return re.sub(r"\s+", " ", text)


def test_the_docs_and_the_schema_state_the_rule_the_code_keeps():
    docs = _flat((ROOT / "docs" / "uncertainty.md").read_text())
    # the rule: nearest from 2 (D + 2) up, refused below it even where that is the nearest
    assert ("Another `n` of at least the smallest design, 2 (D + 2) points (N = 2), draws the "
            "nearest such size (the smaller on a tie)") in docs
    assert "An `n` below 2 (D + 2) is refused, not rounded up" in docs
    said = re.search(r"over four axes `n: 10` \(nearer 12 than 6\) is refused with `(.*?)`",
                     docs)
    assert said, "the docs' example of n: 10 over four axes"
    with pytest.raises(ValueError) as exc:
        sobol_base(10, 4)
    assert str(exc.value).endswith(said[1])
    # the docs' own refusal (n = 9 over three axes) is the code's and fits the stated rule
    example = re.search(r"sample: n = 9: (method sobol .*?for any n)", docs)
    assert example
    with pytest.raises(ValueError) as exc:
        sobol_base(9, 3)
    assert str(exc.value) == f"n = 9: {example[1]}"
    assert "Below N = 2 it is refused" not in docs  # N = 2 alone was read as "rounded up"
    described = SampleIn.model_json_schema()["properties"]["n"]["description"]
    assert "from 2 (D + 2) up: a smaller n is refused, not rounded up" in described
    with pytest.raises(ValueError, match="use n >= 12"):
        SampleIn.model_validate({"n": 10, "method": "sobol", "axes": AXES4})
