"""``belt: {type: auto}``: the belt the study chose is in ``GET /studies/{id}``.

The choice (the belt, its margins, the next lighter, the note or, when no catalogue belt
passes, the warning) is a design value the expansion writes into the study's ``study.json``
(``study.designs[i].sizes.belt``, :func:`beltstudy.service.grid.basis.design_belt`), and the
report showed it, but the REST status had no word of it: a client had to read the report or
the runs' ``belt_type_used``. ``belt_choices`` now carries it, one per conveyor design,
as stored; null when the conveyor gives its belt.
"""

from __future__ import annotations

import json

from fastapi.testclient import TestClient

from beltstudy.service.api.app import create_app


def _auto_belt_study(make_study, make_conveyor, name: str, **conveyor) -> dict:
    conv = make_conveyor(belt={"type": "auto", "kind": "fabric", "width_m": 0.8}, **conveyor)
    return make_study(name, conveyor=conv, grid={"friction_model": ["din"],
                                                  "temperature_c": [5]})


def _stored_choices(data_dir, sid: str) -> list[dict]:
    doc = json.loads((data_dir / "studies" / sid / "study.json").read_text())
    return [{"axes": d["axes"], **d["sizes"]["belt"]} for d in doc["study"]["designs"]]


def test_the_study_status_holds_the_belt_it_chose(
    data_dir, make_study, make_conveyor, make_settings, finished_study
):
    sid = finished_study(data_dir, _auto_belt_study(make_study, make_conveyor, "auto"))
    given = finished_study(data_dir, make_study("given"))
    client = TestClient(create_app(make_settings(data_dir)))

    st = client.get(f"/studies/{sid}").json()
    (choice,) = st["belt_choices"]
    assert [choice] == _stored_choices(data_dir, sid)  # as study.json holds it
    assert choice["axes"] == {} and choice["kind"] == "fabric" and choice["passed"] is True
    assert choice["note"].startswith(f"belt.type auto (fabric): {choice['type']} (")
    assert {"safety_factor", "safety_factor_start", "mass_kg_m", "case",
            "next_lighter"} <= set(choice)
    # the belt the runs ran on
    runs = client.get(f"/studies/{sid}/runs", params={"columns": "belt_type_used"}).json()
    assert {r["belt_type_used"] for r in runs["runs"]} == {choice["type"]}
    # a given belt: null; the list says the same as the study's own status
    assert client.get(f"/studies/{given}").json()["belt_choices"] is None
    listed = {s["id"]: s for s in client.get("/studies").json()["studies"]}
    assert listed[sid]["belt_choices"] == st["belt_choices"]
    assert listed[given]["belt_choices"] is None
    # and the schema says it
    schema = client.get("/openapi.json").json()["components"]["schemas"]["StudyStatus"]
    assert "belt_choices" in schema["properties"]


def test_no_belt_passes_is_said_in_the_study_status(
    data_dir, make_study, make_conveyor, make_settings, finished_study
):
    """A 600 m fabric belt lifting 1000 t/h 150 m: no catalogue fabric belt passes at 0.8 m;
    the heaviest is used, ``passed`` is false and the note is the warning with its remedy."""
    sid = finished_study(data_dir, _auto_belt_study(
        make_study, make_conveyor, "none-passes",
        material={"capacity_t_h": 1000, "density_t_m3": 1.0},
        profile=[{"length_m": 600, "lift_m": 150}]))
    st = TestClient(create_app(make_settings(data_dir))).get(f"/studies/{sid}").json()
    (choice,) = st["belt_choices"]
    assert [choice] == _stored_choices(data_dir, sid)
    assert choice["passed"] is False and choice["safety_factor"] < 10.0
    assert choice["note"].startswith("belt.type auto (fabric): no catalogue belt passes the "
                                     f"safety factors; the heaviest, {choice['type']} (")
    assert "would avoid it" in choice["note"]
    assert choice["next_lighter"]["mass_kg_m"] < choice["mass_kg_m"]
