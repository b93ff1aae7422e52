"""A POSTed study with a very long value or key is refused with a message of readable length:
a 300 000-character study name, conveyor name, belt type, grid axis, friction model or
unknown key was echoed whole (a 300 kB to 600 kB 422 body); now each keeps its first 60 and
last 40 characters and says its length, the field still named and nothing stored.

In-process (TestClient without the lifespan): nothing valid is submitted."""

from __future__ import annotations

import pytest
from fastapi.testclient import TestClient

from beltstudy.service.api.app import create_app
from tests.service.conftest import tiny_conveyor, tiny_study

LONG = "x" * 300_000


@pytest.fixture
def client(data_dir, make_settings):
    return TestClient(create_app(make_settings(data_dir)))


@pytest.mark.parametrize(("body", "start"), [
    (tiny_study(name=LONG), "name: "),
    (tiny_study(conveyor=tiny_conveyor(name=LONG)), "conveyor.name: "),
    (tiny_study(conveyor=tiny_conveyor(belt={"type": LONG, "width_m": 0.8})),
     "conveyor.belt.type: unknown belt type 'xxx"),
    (tiny_study(grid={LONG: [1]}), "grid: unknown axis 'xxx"),
    (tiny_study(grid={"friction_model": [LONG]}), "grid.friction_model: unknown model 'xxx"),
    (tiny_study(**{LONG: 1}), "xxx"),
    (tiny_study(scenario={"load": LONG}), "scenario.load: "),
])
def test_a_long_value_is_not_echoed_whole(client, data_dir, body, start):
    answer = client.post("/studies", json=body)
    assert answer.status_code == 422, answer.text[:300]
    message = answer.json()["message"]
    assert message.startswith(start), message[:200]
    assert "(300000 characters)" in message
    assert len(answer.content) < 3000, len(answer.content)
    root = data_dir / "studies"
    assert not root.exists() or not any(root.iterdir())
