"""Studies that compare one installed design: the design basis, zip groups, model parameters
as axes, identical runs merged, points that break the conveyor named, load patterns.

Runs are computed in this process (beltstudy.service.dask.tasks.run_batch, the workers' code) and read back
from Parquet with pandas; the live test in test_service_live.py does the same on Dask.
"""

from __future__ import annotations

import pandas as pd
import pytest

from beltstudy.engine.conveyor import Scenario, parse_conveyor
from beltstudy.engine.design import auto_sizes
from beltstudy.engine.statics import solve_steady
from beltstudy.service.cli.study import _runs_text
from beltstudy.service.door.studyfile import resolve_study
from beltstudy.service.errors import Invalid
from beltstudy.service.grid.basis import round_up
from beltstudy.service.store.parquet import Store
from tests.service.conftest import ROOT, tiny_conveyor


def _runs(data_dir, sid) -> pd.DataFrame:
    return pd.read_parquet(data_dir / "studies" / sid / "runs")


def _belt(belt_type: str):
    return parse_conveyor(tiny_conveyor(belt={"type": belt_type, "width_m": 0.8}))


def test_one_takeup_per_belt_type_the_largest_over_models_and_temperatures(
        make_study, finished_study, data_dir):
    """Every row of one belt type has the same counterweight, the largest any model and
    temperature of the study needs at full load (rounded up to six digits); empty runs keep
    it. The same holds for the motors' rated power."""
    grid = {"belt_type": ["EP630/4", "EP1000/5"], "friction_model": ["din", "cema", "nonlin"],
            "temperature_c": [-30, 20], "load": ["full", "empty"]}
    sid = finished_study(data_dir, make_study(name="basis", grid=grid))
    runs = _runs(data_dir, sid)
    assert len(runs) == 2 * 3 * 2 * 2
    assert set(runs["status"]) <= {"ok", "warning"}, runs["message"].tolist()
    for belt, rows in runs.groupby("belt_type"):
        conv = _belt(belt)
        need = {(m, t): solve_steady(conv, model=m, temperature_c=t, load="full",
                                     n_elements=12).summary  # the study's scenario mesh
                for m in grid["friction_model"] for t in grid["temperature_c"]}
        (model, temp), largest = max(need.items(), key=lambda kv: kv[1]["takeup_mass_kg"])
        assert rows["takeup_mass_kg"].nunique() == 1
        assert rows["takeup_mass_kg"].iloc[0] == pytest.approx(largest["takeup_mass_kg"],
                                                               rel=1e-5)
        assert rows["takeup_mass_kg"].iloc[0] >= largest["takeup_mass_kg"]
        # the constraint and the case by what varies (model, temperature) and is the same
        # among the cases that need the largest (a take-up held at rest feels no friction
        # model nor temperature: then the constraint alone)
        tied = [k for k, s in need.items()
                if s["takeup_mass_kg"] == pytest.approx(largest["takeup_mass_kg"], rel=1e-9)]
        at = ", ".join(([model] if len({m for m, _t in tied}) == 1 else [])
                       + ([f"{temp:g} C"] if len({t for _m, t in tied}) == 1 else []))
        gov = largest["takeup_governed_by"]
        assert set(rows["takeup_governed_by"]) == {f"{gov} @ {at}" if at else gov}
        assert rows["rated_power_kw"].nunique() == 1
        # the motor power through the default drive train's 0.95, x 1.25
        (model, temp), rated = max(((k, 1.25 * s["power_kw"] / 0.95)
                                    for k, s in need.items()),
                                   key=lambda kv: kv[1])
        assert rows["rated_power_kw"].iloc[0] == pytest.approx(rated, rel=1e-5)
        assert set(rows["rated_power_governed_by"]) == {
            f"peripheral_force @ {model}, {temp:g} C"}
    assert runs.groupby("belt_type")["takeup_mass_kg"].first().nunique() == 2


def test_a_given_design_case_sizes_every_run(make_study, finished_study, data_dir):
    design = {"friction_model": "din", "temperature_c": -20, "load": "full"}
    grid = {"friction_model": ["cema", "nonlin"], "temperature_c": [-30, 0, 20]}
    study = resolve_study(make_study(grid=grid, design=design))
    conv = parse_conveyor(tiny_conveyor())
    case = solve_steady(conv, model="din", temperature_c=-20, load="full",
                        n_elements=12).summary
    masses = {r.conveyor["takeup"]["mass_kg"] for r in study.runs}
    assert masses == {round_up(case["takeup_mass_kg"])}
    runs = _runs(data_dir, finished_study(data_dir, make_study(grid=grid, design=design)))
    assert len(runs) == 6 and runs["takeup_mass_kg"].nunique() == 1
    assert runs["takeup_mass_kg"].iloc[0] == pytest.approx(case["takeup_mass_kg"], rel=1e-5)
    (entry,) = study.designs
    assert entry["sizes"]["takeup"]["case"] == "full, din, -20 C"
    # one design case, but its model is not the runs' own: the model is named, so a reader of
    # the cema and nonlin rows sees that din sized their take-up (the column said
    # 'slip_start @ -20 C' where design.friction_model pinned visco with a temperature axis)
    assert entry["sizes"]["takeup"]["at"] == "din"
    assert all(r.design["takeup_governed_by"] == f"{case['takeup_governed_by']} @ din"
               for r in study.runs)
    assert set(runs["takeup_governed_by"]) == {f"{case['takeup_governed_by']} @ din"}
    with pytest.raises(Invalid, match=r"design.friction_model: unknown model 'dinn'"):
        resolve_study(make_study(grid=grid, design={"friction_model": "dinn"}))
    with pytest.raises(Invalid, match=r"design.temperature: unknown key 'temperature'; did you mean "
                                      r"'temperature_c'"):
        resolve_study(make_study(grid=grid, design={"temperature": -20}))
    with pytest.raises(Invalid, match=r"design.temperature_c: .*greater than or equal to -60"):
        resolve_study(make_study(grid=grid, design={"temperature_c": -70}))


def test_zip_lets_din_f_follow_the_temperature(make_study, finished_study, data_dir):
    zipped = [{"temperature_c": [-30, 0, 20], "models.din.f_carry": [0.025, 0.020, 0.017]}]
    study = resolve_study(make_study(grid={"load": ["full", "empty"]}, zip=zipped,
                                     model="din"))
    assert study.total == study.grid_points == 2 * 3
    pairs = {(r.axes["temperature_c"], r.params["f_carry"]) for r in study.runs}
    assert pairs == {(-30.0, 0.025), (0.0, 0.020), (20.0, 0.017)}
    sid = finished_study(data_dir, make_study(grid={"load": ["full"]}, zip=zipped,
                                              model="din"))
    runs = _runs(data_dir, sid).sort_values("temperature_c")
    assert list(runs["models.din.f_carry"]) == [0.025, 0.020, 0.017]
    conv = parse_conveyor(tiny_conveyor())
    for _, row in runs.iterrows():
        s = solve_steady(conv, model="din", params={"f_carry": row["models.din.f_carry"]},
                         temperature_c=row["temperature_c"], n_elements=12).summary
        assert row["power_kw"] == pytest.approx(s["power_kw"], rel=1e-9)
    # a stop time that varies with a brake force
    braked = tiny_conveyor(brakes=[{"position": "head", "force_kn": 5.0, "delay_s": 0.5}])
    study = resolve_study(make_study(
        conveyor=braked, dynamics=True, scenario={"stop": {"mode": "brake"}},
        grid={"temperature_c": [20]},
        zip=[{"stop_time_s": [5, 10], "brakes.0.force_kn": [8.0, 4.0]}]))
    # given brake forces size nothing by the stop time (engine.reads): the two points stay
    # two runs by their forces, each with the stop time the run reads, the default
    from beltstudy.engine import Scenario
    default = Scenario().stop.time_s
    assert {(r.scenario["stop"]["time_s"], r.conveyor["brakes"][0]["force_kn"])
            for r in study.runs} == {(default, 8.0), (default, 4.0)}


@pytest.mark.parametrize("zipped, message", [
    ([{"temperature_c": [0, 10], "models.din.f_carry": [0.02]}], r"zip.0: .*equal lengths"),
    ([{}], r"zip.0: empty group"),
    ([{"temprature_c": [0]}], r"zip.0: unknown axis 'temprature_c'"),
])
def test_bad_zip_groups_are_refused(make_study, zipped, message):
    with pytest.raises(Invalid, match=message):
        resolve_study(make_study(grid={"load": ["full"]}, zip=zipped))


def test_model_parameters_as_axes_and_identical_runs_merged(make_study, finished_study,
                                                            data_dir):
    """``models.din.f_carry`` does not change a cema run: the two cema points are one run,
    whose row has the axis null; the study says it merged one point."""
    grid = {"friction_model": ["din", "cema"], "models.din.f_carry": [0.010, 0.016]}
    study = resolve_study(make_study(grid=grid))
    assert study.grid_points == 4 and study.total == 3 and study.merged == 1
    # some runs read f_carry: it is no axis that changes no run
    assert study.merged_axes == []
    sid = finished_study(data_dir, make_study(grid=grid))
    runs = _runs(data_dir, sid)
    assert len(runs) == 3 and runs["run_id"].is_unique
    cema = runs[runs["friction_model"] == "cema"]
    assert len(cema) == 1 and cema["models.din.f_carry"].isna().all()
    din = runs[runs["friction_model"] == "din"].sort_values("models.din.f_carry")
    assert list(din["models.din.f_carry"]) == [0.010, 0.016]
    assert din["power_kw"].iloc[1] > din["power_kw"].iloc[0]
    with pytest.raises(Invalid, match=r"unknown parameter of model 'din'; did you mean "
                                      r"'models.din.f_carry'"):
        resolve_study(make_study(grid={"models.din.f_cary": [0.01]}))
    # and how to vary it or give it to the design basis (it named no fix)
    with pytest.raises(Invalid, match=r"model 'nonlin' is not run by this study .*; add nonlin "
                                      r"to the friction_model axis to vary it in runs, or, for "
                                      r"a design model, give one value in models: nonlin:"):
        resolve_study(make_study(grid={"models.nonlin.p_mf": [1.0]}))
    with pytest.raises(Invalid, match=r"models.din.f_carry: value -1.*between 0 and 1"):
        resolve_study(make_study(grid={"models.din.f_carry": [-1]}))


def test_an_axis_that_changes_no_run_is_named(make_study, finished_study, data_dir):
    """A brake's delay acts only in a transient: in a steady study its two values merged into
    one run each, said only as '2 of 4 grid points merged'. The axis is named in the study
    (``merged_axes``), its status and the command line's words."""
    braked = tiny_conveyor(brakes=[{"position": "head", "force_kn": 5.0, "delay_s": 0.5}])
    body = make_study(conveyor=braked, grid={"brakes.0.delay_s": [0.5, 2.0],
                                             "temperature_c": [0, 20]})
    study = resolve_study(body)
    assert study.grid_points == 4 and study.total == 2
    assert study.merged_axes == ["brakes.0.delay_s"]
    sid = finished_study(data_dir, body)
    assert _runs(data_dir, sid)["brakes.0.delay_s"].isna().all()
    stored = Store(data_dir).read(sid)["study"]
    assert stored["merged_axes"] == ["brakes.0.delay_s"]
    status = {"total": 2, "merged": stored["merged"], "grid_points": stored["grid_points"],
              "merged_axes": stored["merged_axes"], "dynamics": stored["dynamics"]}
    assert _runs_text(status) == (
        "2 runs; 2 of 4 grid points merged into identical runs: brakes.0.delay_s changes no "
        "run of this study (null in every row; the study runs steady only)")
    # a study whose axes all change runs says nothing more
    assert resolve_study(make_study(grid={"temperature_c": [0, 20]})).merged_axes == []


def test_a_coast_crossed_with_four_stop_times_stores_one_coast_run(make_study, finished_study,
                                                                   data_dir, make_settings):
    """The stop time is no input of a coast stop: a coast crossed with four stop times stores
    one coast run (one per temperature with a temperature axis). The auto brake is sized per
    stop time and held over the temperatures (the largest of them)."""
    braked = tiny_conveyor(brakes=[{"position": "head", "force_kn": "auto", "delay_s": 0.5}])
    stops = {"scenario.stop.mode": ["coast", "brake"], "stop_time_s": [20, 30, 40, 60]}
    sid = finished_study(data_dir, make_study(name="coast-x-4", conveyor=braked, dynamics=True,
                                              grid=stops))
    runs = _runs(data_dir, sid)
    assert len(runs) == 5
    coast = runs[runs["scenario.stop.mode"] == "coast"]
    assert len(coast) == 1 and coast["stop_time_target_s"].isna().all()
    # the axis stop_time_s is the column stop_time_target_s; the column stop_time_s is each
    # run's achieved stop: a filter on the axis's name that matches nothing says so
    from fastapi.testclient import TestClient

    from beltstudy.service.api.app import create_app

    client = TestClient(create_app(make_settings(data_dir)))
    page = client.get(f"/studies/{sid}/runs", params={"filter": "stop_time_s=20"}).json()
    assert page["total"] == 0
    assert page["message"].startswith("filter stop_time_s=20 matched no row: the study's axis "
                                      "stop_time_s is the column stop_time_target_s "
                                      "(filter=stop_time_target_s=20)"), page
    page = client.get(f"/studies/{sid}/runs", params={"filter": "stop_time_target_s=20"}).json()
    assert page["total"] == 1 and page.get("message") is None

    grid = {**stops, "temperature_c": [-20, 20]}
    body = make_study(conveyor=braked, dynamics=True, grid=grid)
    study = resolve_study(body)
    assert study.grid_points == 16 and study.total == 2 + 8 and study.merged == 6
    sid = finished_study(data_dir, body)
    runs = _runs(data_dir, sid)
    assert len(runs) == 10
    coast = runs[runs["scenario.stop.mode"] == "coast"]
    assert len(coast) == 2 and coast["stop_time_target_s"].isna().all()
    assert set(coast["brake_governed_by"]) == {"holding"}
    brake = runs[runs["scenario.stop.mode"] == "brake"]
    conv = parse_conveyor(braked)
    for stop, rows in brake.groupby("stop_time_target_s"):
        assert rows["brake_force_kn"].nunique() == 1
        scn = {t: Scenario(temperature_c=t, elements=12, stop={"mode": "brake",
                                                                "time_s": stop})
               for t in (-20, 20)}
        need = max(auto_sizes(conv, s, model="din")["brake_force_kn"][0] for s in scn.values())
        assert rows["brake_force_kn"].iloc[0] == pytest.approx(need, rel=1e-5)
    assert brake.groupby("stop_time_target_s")["brake_force_kn"].first().is_monotonic_decreasing


def test_a_conveyor_axis_that_breaks_the_conveyor_is_refused_naming_the_points(make_study):
    grid = {"profile.0.lift_m": [3, 70, 80], "temperature_c": [0, 20]}
    with pytest.raises(Invalid) as err:
        resolve_study(make_study(grid=grid))
    text = str(err.value)
    assert "2 of 3 conveyor variants are invalid" in text
    assert "profile.0.lift_m=70" in text and "profile.0.lift_m=80" in text
    assert "profile.0.lift_m=3" not in text
    assert "lift_m (70" in text and "\n" not in text
    grid = {"drives.0.share": [1.0, 0.5]}
    with pytest.raises(Invalid, match=r"grid \(drives.0.share=0.5\): .*shares sum to 0.5"):
        resolve_study(make_study(grid=grid))


def test_the_refusal_is_a_422_and_exit_2(make_study, make_settings, data_dir, capsys,
                                         tmp_path, monkeypatch):
    from fastapi.testclient import TestClient

    from beltstudy.service.api.app import create_app
    from beltstudy.service.cli import main

    body = make_study(grid={"profile.0.lift_m": [3, 70, 80]})
    app = create_app(make_settings(data_dir))
    r = TestClient(app).post("/studies", json=body)
    assert r.status_code == 422 and "profile.0.lift_m=70" in r.json()["message"]
    import yaml

    path = tmp_path / "study.yaml"
    path.write_text(yaml.safe_dump(body))
    monkeypatch.setenv("BELTSTUDY_DATA_DIR", str(data_dir))
    assert main(["run", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "profile.0.lift_m=80" in err


def test_load_patterns_and_surge_in_a_study(make_study, finished_study, data_dir):
    conveyor = tiny_conveyor(profile=[{"length_m": 30, "lift_m": 2},
                                      {"length_m": 30, "lift_m": -1}])
    grid = {"load": ["full", "inclines", "declines", [1.0, 0.5], 1.2]}
    sid = finished_study(data_dir, make_study(conveyor=conveyor, grid=grid))
    runs = _runs(data_dir, sid)
    assert len(runs) == 5
    by_load = {row["load"]: row for _, row in runs.iterrows()}
    assert set(by_load) == {"full", "inclines", "declines", "[1.0, 0.5]", "1.2"}
    assert by_load["1.2"]["status"] == "warning" and "surge" in by_load["1.2"]["message"]
    assert by_load["inclines"]["te_lift_kn"] > 0 > by_load["declines"]["te_lift_kn"]
    assert runs["takeup_mass_kg"].nunique() == 1  # one installed counterweight
    with pytest.raises(Invalid, match=r"scenario.load: 3 fractions for 2 profile sections.*"
                                      r"grid point load=\[1, 1, 1\]"):
        resolve_study(make_study(conveyor=conveyor, grid={"load": [[1, 1, 1]]}))


def test_design_basis_survives_the_round_trip_through_study_json(make_study):
    from beltstudy.service.grid.expand import study_from_json

    study = resolve_study(make_study(zip=[{"temperature_c": [-20, 20],
                                           "models.din.f_carry": [0.03, 0.02]}],
                                     grid={"belt_type": ["EP630/4", "EP800/4"]}))
    doc = study.to_json()
    assert len(doc["designs"]) == 2 and doc["zip"]
    again = study_from_json(doc, study.id)
    assert [r.run_id for r in again.runs] == [r.run_id for r in study.runs]
    assert again.designs == study.designs


def test_example_design_study_resolves():
    from beltstudy.service.door.studyfile import load_study_file

    for path in sorted((ROOT / "studies").glob("*.yaml")):
        load_study_file(path)


def test_a_drive_speed_loop_is_a_grid_axis_checked_like_the_file(make_study):
    """``drives.0.speed_loop_rad_s`` varies like any drive field: each run's conveyor carries
    its value; a value outside 0.1-50 rad/s is refused naming the grid point and the range."""
    from beltstudy.service.grid.expand import expand_runs

    runs = expand_runs(resolve_study(make_study(grid={"drives.0.speed_loop_rad_s": [2.0, 8.0]})))
    assert sorted({r.conveyor["drives"][0]["speed_loop_rad_s"] for r in runs}) == [2.0, 8.0]
    with pytest.raises(Invalid, match=r"drives.0.speed_loop_rad_s=90.*outside 0.1 to 50 rad/s"):
        resolve_study(make_study(grid={"drives.0.speed_loop_rad_s": [2.0, 90.0]}))


#: The 60 m warm-up conveyor rising 1 m over 30 m and falling 6 m over the next 30 m, an auto
#: head brake and a given take-up: loaded declines need more brake than the full belt.
UNDULATING = tiny_conveyor(
    profile=[{"length_m": 30, "lift_m": 1.0}, {"length_m": 30, "lift_m": -6.0}],
    brakes=[{"position": "head", "force_kn": "auto", "delay_s": 0.5}],
    takeup={"type": "gravity", "position": "tail", "mass_kg": 3000})


def _braked_study(make_study, **over):
    from tests.service.conftest import TINY_SCENARIO

    return make_study(conveyor=UNDULATING, dynamics=True,
                      scenario={**TINY_SCENARIO, "stop": {"mode": "brake", "time_s": 4.0}},
                      grid={"load": ["full", "declines", "empty"]}, **over)


def test_a_design_over_full_and_declines_sizes_the_brake_from_the_declines_and_says_so(
        make_study, finished_study, data_dir):
    """``design: {load: [full, declines]}`` (SPEC 7.2): the brake of every run is the larger
    of the two loads' needs (the declines': their net downhill pull is larger and the stop
    time sets both, engine/design.py), and every run's ``brake_governed_by`` says so:
    ``stop_time @ declines``. The design table names the case in full."""
    conv = parse_conveyor(UNDULATING)
    need = {}
    for load in ("full", "declines"):
        scn = Scenario(load=load, elements=12, stop={"mode": "brake", "time_s": 4.0})
        sizes = auto_sizes(conv, scn, model="din")
        assert sizes["brake_governed_by"] == ["stop_time"]
        need[load] = sizes["brake_force_kn"][0]
    assert need["declines"] > 1.05 * need["full"]

    body = _braked_study(make_study, design={"load": ["full", "declines"]})
    study = resolve_study(body)
    assert {r.conveyor["brakes"][0]["force_kn"] for r in study.runs} == {
        round_up(need["declines"])}
    (entry,) = study.designs
    stop = entry["sizes"]["brakes"]["stop_time_s"]["4"]
    assert (stop["case"], stop["at"]) == ("declines, din, 20 C", "declines")
    runs = _runs(data_dir, finished_study(data_dir, body))
    assert len(runs) == 3
    assert set(runs["brake_governed_by"]) == {"stop_time @ declines"}
    assert runs["brake_force_kn"].iloc[0] == pytest.approx(need["declines"], rel=1e-5)
    # the rated power: the full belt's running resistance (the declines regenerate)
    assert set(runs["rated_power_governed_by"]) == {"running_resistance @ full"}

    # a scalar design load still sizes at that one load: the full belt's smaller brake
    one = resolve_study(_braked_study(make_study, design={"load": "full"}))
    assert {r.conveyor["brakes"][0]["force_kn"] for r in one.runs} == {round_up(need["full"])}
    assert {r.design["brake_governed_by"] for r in one.runs} == {"stop_time"}


@pytest.mark.parametrize("design, message", [
    ({"load": ["full", "downhill"]},
     r"^design.load\[1\]: \"downhill\" is not of type \"number\" or \"array\" or 'full', "
     r"'empty', 'inclines' or 'declines'$"),
    ({"load": ["full", [1.0, 0.5, 0.2]]},
     r"^design.load\[1\]: 3 fractions for 2 profile sections"),
    ({"load": [1.0, 0.5, 0.2]},
     r"^design.load: 3 fractions for 2 profile sections.*a list of load cases names at "
     r"least one"),
    ({"load": []}, r"^design.load: an empty list"),
    ({"temperature_c": [-20, -70]}, r"^design.temperature_c\[1\]: .*greater than or equal"),
    ({"friction_model": ["din", "dinn"]}, r"^design.friction_model\[1\]: unknown model"),
])
def test_a_bad_design_list_entry_is_refused_naming_it(make_study, design, message):
    with pytest.raises(Invalid, match=message):
        resolve_study(_braked_study(make_study, design=design))


@pytest.mark.parametrize("design, message", [
    ({"load": ["full", "full"]},
     r"^design.load\[1\]: 'full' is design.load\[0\] again; give each design case once$"),
    ({"load": ["full", "declines", 1.0]},
     r"^design.load\[2\]: 1.0 is design.load\[0\] \('full'\) again; give each design "
     r"case once$"),
    ({"temperature_c": [-20, 30, -20.0]},
     r"^design.temperature_c\[2\]: -20.0 is design.temperature_c\[0\] again; give each "
     r"design case once$"),
    ({"friction_model": ["din", "iso5048"]},
     r"^design.friction_model\[1\]: 'iso5048' is design.friction_model\[0\] \('din'\) "
     r"again \(aliases count as the same\); give each design case once$"),
])
def test_a_design_case_listed_twice_is_refused_naming_both(make_study, design, message):
    """A design list names each case once, as a grid axis lists each value once: a repeat
    (an alias, 1.0 for full, -20.0 for -20) is most likely a typo for another case."""
    with pytest.raises(Invalid, match=message):
        resolve_study(_braked_study(make_study, design=design))


def test_a_bad_design_load_is_a_422_naming_the_entry(make_study, make_settings, data_dir):
    from fastapi.testclient import TestClient

    from beltstudy.service.api.app import create_app

    app = create_app(make_settings(data_dir))
    body = _braked_study(make_study, design={"load": ["full", "downhill"]})
    r = TestClient(app).post("/studies", json=body)
    assert r.status_code == 422 and r.json()["message"].startswith("design.load[1]: ")
    # every list at once is accepted: 2 loads x 2 temperatures x 2 models
    study = resolve_study(_braked_study(make_study, design={
        "load": ["full", "declines"], "temperature_c": [-20, 30],
        "friction_model": ["din", "cema"]}), strict=True)
    assert study.design["friction_model"] == ["din", "cema"]


def test_a_design_over_models_and_temperatures_names_the_governing_one():
    """Models and temperatures listed in ``design:`` are design cases like loads: the take-up
    of a study run at one model and temperature is the largest over the listed ones."""
    from tests.service.conftest import tiny_study

    body = tiny_study(grid={"temperature_c": [20]}, model="din",
                      design={"friction_model": ["din", "cema"], "temperature_c": [-30, 20]})
    study = resolve_study(body)
    conv = parse_conveyor(tiny_conveyor())
    need = {(m, t): auto_sizes(conv, Scenario(temperature_c=t, elements=12), model=m)
            for m in ("din", "cema") for t in (-30.0, 20.0)}
    (model, temp), largest = max(need.items(), key=lambda kv: kv[1]["drive_rated_power_kw"][0])
    (entry,) = study.designs
    drive = entry["sizes"]["drives"][0]
    assert drive["rated_power_kw"] == round_up(largest["drive_rated_power_kw"][0])
    assert drive["case"] == f"full, {model}, {temp:g} C"
    gov = largest["drive_rated_power_governed_by"][0]
    assert {r.design["rated_power_governed_by"] for r in study.runs} == {
        f"{gov} @ {model}, {temp:g} C"}


def test_a_design_take_up_beyond_any_counterweight_is_a_warning_that_says_why(
        make_study, finished_study, data_dir, make_conveyor):
    """A drive pulley that barely grips (friction 1e-5: e^(mu theta) - 1 = 3.7e-5) needs a
    counterweight of thousands of tonnes to pass Te, beyond the 2 000 t a file may give. The
    study's runs are not failed on the size they were never given: each sizes its own take-up
    and says what sets it and what would avoid it (more friction, more wrap)."""
    conv = make_conveyor(drives=[{"position": "head", "pulley_diameter_m": 0.6,
                                  "inertia_kg_m2": 20, "friction": 1e-5}])
    sid = finished_study(data_dir, make_study(name="slippery", conveyor=conv,
                                              grid={"temperature_c": [0, 20]}))
    runs = _runs(data_dir, sid)
    assert set(runs["status"]) == {"warning"}, runs["message"].tolist()
    assert (runs["takeup_mass_kg"] > 2.0e6).all()
    for msg in runs["message"]:
        assert "is beyond any counterweight" in msg and "more friction" in msg


def test_every_part_of_a_design_load_message_names_its_place_in_the_study(make_study):
    """design.load: [2.0] (one fraction per profile section, 2 above the surge limit 1.3):
    each part of the message names the study's field; the per-section entry was named
    'load.0', the scenario's path, not design.load.0."""
    with pytest.raises(Invalid) as err:
        resolve_study(_braked_study(make_study, design={"load": [2.0]}))
    msg = err.value.message
    assert msg.startswith("design.load: ") and "; design.load.0: Input should be less than or " \
        "equal to 1.3 (got 2)" in msg, msg
    assert "; load" not in msg
