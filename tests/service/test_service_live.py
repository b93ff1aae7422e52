"""The service end to end: a real uvicorn server (child process) with a real LocalCluster,
and with an external ``dask scheduler`` plus two ``dask worker`` processes, all on loopback.

Studies are submitted over HTTP, polled to completion, and read back from Parquet with pandas.
"""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd
import pytest
import yaml

pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[2]


def _dynamic_study(make_study, name: str, **over) -> dict:
    """A dynamic study of the 60 m conveyor with few elements (fast runs)."""
    study = make_study(
        name=name,
        dynamics=True,
        grid={"friction_model": ["din", "cema"], "temperature_c": [-10, 20]},
    )
    study.update(over)
    return study


def test_submit_poll_and_read_parquet(live_service, make_study):
    svc = live_service()
    assert svc.health["executor"] == {
        "state": "ready",
        "error": "",
        "scheduler": "local",
        "workers": 2,
        "dashboard": None,
    }
    body = _dynamic_study(
        make_study,
        "live-yaml",
        grid={
            "friction_model": ["din", "cema"],
            "temperature_c": [-10, 20],
            "load": ["full", "empty"],
        },
    )
    r = svc.client._http.post(
        "/studies",
        content=yaml.safe_dump(body).encode(),
        headers={"Content-Type": "application/yaml"},
    )
    assert r.status_code == 202, r.text
    sub = r.json()
    assert sub["total"] == 8 and sub["status_url"] == f"/studies/{sub['id']}"
    st = svc.wait(sub["id"])
    assert st["state"] == "done" and st["done"] == 8 and st["eta_s"] == 0.0
    # resubmitting the same study returns it (200), nothing new is run
    again, created = svc.client.submit(body)
    assert not created and again["id"] == sub["id"] and again["state"] == "done"

    root = svc.data_dir / "studies" / sub["id"]
    runs = pd.read_parquet(root / "runs")
    assert len(runs) == 8 and runs["run_id"].is_unique
    assert set(runs["status"]) <= {"ok", "warning"}, runs[["status", "message"]]
    assert runs["t_max_dyn_kn"].notna().all() and runs["power_kw"].notna().all()
    assert (runs["study_id"] == sub["id"]).all()
    # one installed design: every run has the counterweight the largest requirement over the
    # study's models and temperatures at full load asks for (empty runs included)
    from beltstudy.engine.conveyor import parse_conveyor
    from beltstudy.engine.statics import solve_steady

    conv = parse_conveyor(body["conveyor"])
    need = max(solve_steady(conv, model=m, temperature_c=t, load="full",
                            n_elements=body["scenario"]["elements"]).summary["takeup_mass_kg"]
               for m in ("din", "cema") for t in (-10, 20))
    assert runs["takeup_mass_kg"].nunique() == 1
    assert runs["takeup_mass_kg"].iloc[0] == pytest.approx(need, rel=1e-5)
    assert runs["takeup_governed_by"].notna().all() and runs["fill_pct"].notna().all()
    ts = pd.read_parquet(root / "timeseries")
    assert set(ts["run_id"]) == set(runs["run_id"])
    assert {"t_s", "v_drive_m_s", "t_head_in_kn"} <= set(ts.columns)
    detail = svc.client._http.get(f"/studies/{sub['id']}/runs/{runs['run_id'][0]}").json()
    assert len(detail["timeseries"]["t_s"]) == (ts["run_id"] == runs["run_id"][0]).sum()


def test_surface_is_stored_on_request_and_recomputed_otherwise(live_service, make_study):
    """The same four runs in two studies: with ``surface: true`` the workers store every
    run's surface; without it nothing is stored and the API recomputes each run's surface
    from its stored inputs, equal to the stored one."""
    import io

    svc = live_service()
    plain, _ = svc.client.submit(_dynamic_study(make_study, "surface-off"))
    kept, _ = svc.client.submit(_dynamic_study(make_study, "surface-on", surface=True))
    assert plain["id"] != kept["id"]
    assert svc.wait(plain["id"])["state"] == svc.wait(kept["id"])["state"] == "done"
    root = svc.data_dir / "studies"
    assert not list((root / plain["id"] / "surface").glob("*.parquet"))
    assert list((root / plain["id"] / "timeseries").glob("*.parquet"))
    stored = pd.read_parquet(root / kept["id"] / "surface")
    runs = pd.read_parquet(root / plain["id"] / "runs")
    assert set(runs["run_id"]) == set(stored["run_id"]) and len(runs) == 4
    for run_id in runs["run_id"]:
        want = stored[stored["run_id"] == run_id].reset_index(drop=True)
        assert len(want) > 100
        for sid, source in ((plain["id"], "recomputed"), (kept["id"], "stored")):
            r = svc.client._http.get(f"/studies/{sid}/runs/{run_id}/surface",
                                     params={"format": "parquet"})
            assert r.status_code == 200 and r.headers["x-beltstudy-surface"] == source
            got = pd.read_parquet(io.BytesIO(r.content))
            pd.testing.assert_frame_equal(got, want, check_exact=True)
    body = svc.client._http.get(f"/studies/{plain['id']}/runs/{run_id}/surface").json()
    assert body["source"] == "recomputed" and body["rows"] == len(want)
    assert body["surface"]["s_m"][: 3] == pytest.approx(want["s_m"][:3].tolist())
    assert not list((root / plain["id"] / "surface").glob("*.parquet"))
    # recomputed on the workers (their engine is compiled), not in the service's process
    svc.log.flush()
    log = Path(svc.log.name).read_text(errors="replace")
    assert log.count("recomputed on a Dask worker") == len(runs)
    assert "recomputed in the service" not in log


def test_two_studies_at_once_and_a_failing_run(live_service, make_study, capsys):
    svc = live_service()
    # a fixed step of 5 s is above the stability limit of this conveyor's loop: the engine
    # refuses that run when it runs (the limit needs the loop cut into elements), so those
    # runs become failed rows naming the field.
    a, _ = svc.client.submit(
        _dynamic_study(
            make_study,
            "auto-or-huge-step",
            grid={"friction_model": ["din", "cema"], "scenario.dt_s": ["auto", 5.0]},
        )
    )
    b, _ = svc.client.submit(
        make_study(
            name="steady-at-once", grid={"temperature_c": {"start": -40, "stop": 40, "step": 1}}
        )
    )
    sa, sb = svc.wait(a["id"]), svc.wait(b["id"])
    assert sa["state"] == sb["state"] == "done"
    assert sb["done"] == 81 and sb["failed"] == 0
    assert sa["done"] == 4 and sa["failed"] == 2
    assert sa["message"] == "2 of 4 runs failed"
    runs = pd.read_parquet(svc.data_dir / "studies" / a["id"] / "runs")
    failed = runs[runs["status"] == "failed"]
    assert set(failed["scenario.dt_s"]) == {"5.0"}
    assert failed["message"].str.startswith(
        "scenario.dt_s: 5 s is above the stability limit").all()
    assert failed["power_kw"].isna().all()
    assert (runs[runs["status"] != "failed"]["scenario.dt_s"] == "auto").all()

    # DELETE cancels a running study and removes its files; the service carries on
    long = _dynamic_study(
        make_study, "to-delete", grid={"friction_model": ["nonlin"],  # reads each temperature
                                       "temperature_c": {"start": -40, "stop": 40, "step": 2}}
    )
    long["scenario"] = {**long["scenario"], "elements": 200, "run_s": 30}
    c, _ = svc.client.submit(long)
    st = svc.wait(c["id"], until=lambda st: st["done"] >= 2)
    assert st["state"] == "running"
    # its rows so far come with its state: a partial table says it is one
    page = svc.client._http.get(f"/studies/{c['id']}/runs?columns=run_id").json()
    assert page["state"] in ("running", "done") and page["study_runs"] == 41
    assert page["done"] >= 2 and page["total"] >= 2
    got = svc.client._http.get(f"/studies/{c['id']}/runs?format=csv")
    assert re.fullmatch(r"(running|done); done=\d+; total=41", got.headers["X-Study-State"])
    assert svc.client.delete(c["id"]) == {"id": c["id"], "state": "deleted", "deleted": True,
                                          "cancelled": True, "was": "running"}
    assert not (svc.data_dir / "studies" / c["id"]).exists()
    r = svc.client._http.get(f"/studies/{c['id']}")
    assert r.status_code == 404
    assert {s["id"] for s in svc.client.list()} == {a["id"], b["id"]}

    # a study whose conveyor file has a typo: `submit` names the file as `run` does (the
    # service sees the conveyor inlined and said 'conveyor.belt.widht_m')
    from beltstudy.service.cli import main

    conv = yaml.safe_load((ROOT / "studies" / "conveyors" / "slope-5pct.yaml").read_text())
    conv["belt"]["widht_m"] = conv["belt"].pop("width_m")
    folder = svc.data_dir.parent / "typo"
    folder.mkdir()
    (folder / "typo.yaml").write_text(yaml.safe_dump(conv))
    (folder / "study.yaml").write_text(yaml.safe_dump(
        {"name": "typo", "conveyor": "typo.yaml", "grid": {"temperature_c": [0, 20]}}))
    assert main(["submit", str(folder / "study.yaml"), "--url", svc.url]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: conveyor: typo.yaml: belt.width_m: required field is "
                          "missing; belt.widht_m: unknown key 'widht_m'"), err


def test_killing_a_worker_mid_study_still_completes(live_service, make_study):
    svc = live_service()
    study = _dynamic_study(
        make_study,
        "kill-a-worker",
        grid={
            # models whose laws read every temperature: no two runs are one kernel run
            "friction_model": ["nonlin", "visco"],
            "temperature_c": {"start": -30, "stop": 30, "step": 5},
        },
    )
    study["scenario"] = {**study["scenario"], "elements": 400, "run_s": 30}  # ~0.4 s a run
    sub, _ = svc.client.submit(study)
    st = svc.wait(sub["id"], until=lambda st: st["done"] >= 4)
    assert st["done"] <= 20, "the study is nearly over before the kill; make it longer"
    pids = svc.worker_pids()
    assert len(pids) == 2, pids
    os.kill(pids[0], signal.SIGKILL)
    st = svc.wait(sub["id"])
    assert st["state"] == "done" and st["done"] == st["total"] == 26
    runs = pd.read_parquet(svc.data_dir / "studies" / sub["id"] / "runs")
    assert len(runs) == 26 and runs["run_id"].is_unique


def test_against_an_external_scheduler_and_two_workers(live_service, make_study, tmp_path):
    from beltstudy.service.cli.demo import free_port

    port = free_port()
    dask = os.path.join(os.path.dirname(sys.executable), "dask")
    address = f"tcp://127.0.0.1:{port}"
    log = open(tmp_path / "dask.log", "ab")  # noqa: SIM115
    procs = [
        subprocess.Popen(
            [dask, "scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"],
            stdout=log,
            stderr=log,
        )
    ]
    try:
        time.sleep(1.0)
        for _ in range(2):
            procs.append(
                subprocess.Popen(
                    [
                        dask,
                        "worker",
                        address,
                        "--nthreads",
                        "1",
                        "--nworkers",
                        "1",
                        "--no-dashboard",
                        "--host",
                        "127.0.0.1",
                    ],
                    stdout=log,
                    stderr=log,
                )
            )
        svc = live_service(BELTSTUDY_SCHEDULER=address)
        deadline = time.monotonic() + 60
        while svc.client.health()["executor"]["workers"] < 2 and time.monotonic() < deadline:
            time.sleep(0.5)
        health = svc.client.health()
        assert health["executor"]["scheduler"] == address and health["executor"]["workers"] == 2
        sub, created = svc.client.submit(_dynamic_study(make_study, "external"))
        st = svc.wait(sub["id"])
        assert st["state"] == "done" and st["done"] == 4 and st["failed"] == 0
        runs = pd.read_parquet(svc.data_dir / "studies" / sub["id"] / "runs")
        assert len(runs) == 4 and runs["t_max_dyn_kn"].notna().all()
        svc.stop()
    finally:
        for p in reversed(procs):
            p.send_signal(signal.SIGTERM)
        for p in procs:
            try:
                p.wait(20)
            except subprocess.TimeoutExpired:
                p.kill()
        log.close()
