"""An axis written as one value: the advice shows an axis that works.

``grid: {temperature_c: null}`` answered "an axis is a list ([null]) or a range ..." and
``"cold"`` "... a list ([cold]) ...": followed, each gave a new error. A value the axis takes is
still wrapped (``temperature_c: 5`` -> ``[5]``, ``friction_model: din`` -> ``[din]``); a bad one
is not, the advice shows valid values of the axis instead, and each advice is checked here by
following it.
"""

from __future__ import annotations

import re

import pytest
import yaml
from fastapi.testclient import TestClient

from beltstudy.service.api.app import create_app
from beltstudy.service.door.studyfile import resolve_study


@pytest.fixture
def client(data_dir, make_settings):
    return TestClient(create_app(make_settings(data_dir)))


def _advice(message: str) -> tuple[str, str | None]:
    """The list and the range the message advises (YAML flow text)."""
    listed = re.search(r"a list[^(]*\((\[[^\]]*\])\)", message)
    ranged = re.search(r"a range \((\{start: [^}]*\})\)", message)
    assert listed, message
    return listed.group(1), ranged.group(1) if ranged else None


@pytest.mark.parametrize(("axis", "value", "wrapped"), [
    ("temperature_c", None, False),
    ("temperature_c", "cold", False),
    ("temperature_c", True, False),
    ("takeup.mass_kg", None, False),
    ("speed_m_s", "fast", False),
    ("models.din.f_carry", "low", False),
    ("load", None, False),
    ("load", "half", False),
    ("belt_type", None, False),
    ("holdback", "x", False),
    ("friction_model", 3, False),
    ("temperature_c", 5, True),
    ("friction_model", "din", True),
])
def test_the_advice_for_one_value_is_an_axis_that_works(client, make_study, axis, value,
                                                        wrapped):
    r = client.post("/studies", json=make_study(grid={axis: value}))
    assert r.status_code == 422, r.text
    message = r.json()["message"]
    assert message.startswith(f"grid.{axis}: "), message
    listed, ranged = _advice(message)
    assert (listed == f"[{yaml.safe_dump(value, default_flow_style=True).split(chr(10))[0]}]"
            ) is wrapped, message
    if not wrapped:
        assert "null" not in listed and "cold" not in listed, message
    # following the advice: the study is taken
    for advice in filter(None, (listed, ranged)):
        resolve_study(make_study(grid={axis: yaml.safe_load(advice)}))
