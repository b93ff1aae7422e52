"""A sampled study through the service with a worker killed mid-study (docs/uncertainty.md).

    .venv/bin/python benchmarks/sampled_kill.py benchmarks/slope-uncertainty.yaml OUT_DIR

Starts ``beltstudy serve`` (LocalCluster, two workers) with its data in ``OUT_DIR/data``,
submits the study, SIGKILLs one Dask worker once ``--kill-after`` runs are stored, waits for the
study to finish, and checks that every run the study expands to is stored exactly once. Writes
``OUT_DIR/uncertainty.json``, ``OUT_DIR/uncertainty.txt`` (``beltstudy uncertainty``) and
``OUT_DIR/report.html`` (``beltstudy report``), and prints the check.
"""

from __future__ import annotations

import argparse
import json
import os
import signal
import sys
import time
from pathlib import Path

import pandas as pd

from beltstudy.service.cli.client import ServiceClient
from beltstudy.service.cli.demo import (
    free_port,
    start_server,
    stop_server,
    wait_ready,
    worker_pids,
)
from beltstudy.service.door.studyfile import load_study_file, study_body
from beltstudy.service.uncertainty import format_text

ROOT = Path(__file__).resolve().parents[1]


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("study")
    ap.add_argument("out")
    ap.add_argument("--kill-after", type=int, default=40)
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    expected = {r.run_id for r in load_study_file(args.study).runs}
    port = free_port()
    env = {"BELTSTUDY_DATA_DIR": str(out / "data"), "BELTSTUDY_STUDIES_DIR": str(ROOT / "studies"),
           "BELTSTUDY_WORKERS": "2", "BELTSTUDY_TOKEN": "", "BELTSTUDY_SCHEDULER": ""}
    log = open(out / "service.log", "ab")  # noqa: SIM115
    proc = start_server(port, env=env, log=log)
    client = ServiceClient(f"http://127.0.0.1:{port}", "", timeout=120)
    try:
        wait_ready(client, proc, timeout_s=300)
        t0 = time.monotonic()
        sub, _ = client.submit(study_body(args.study))
        sid = sub["id"]
        killed = None
        while True:
            st = client.status(sid)
            if killed is None and st["done"] >= args.kill_after:
                pids = worker_pids(proc)
                os.kill(pids[0], signal.SIGKILL)
                killed = (st["done"], pids[0])
                print(f"killed worker {pids[0]} with {st['done']} of {st['total']} runs stored",
                      flush=True)
            if st["state"] not in ("queued", "running"):
                break
            time.sleep(2.0)
        wall = time.monotonic() - t0
        runs = pd.read_parquet(out / "data" / "studies" / sid / "runs")
        check = {"study_id": sid, "state": st["state"], "total": st["total"], "done": st["done"],
                 "rows": len(runs), "unique_run_ids": bool(runs["run_id"].is_unique),
                 "lost": len(expected - set(runs["run_id"])),
                 "extra": len(set(runs["run_id"]) - expected),
                 "failed": int((runs["status"] == "failed").sum()),
                 "killed_at_done": killed[0] if killed else None, "wall_s": round(wall, 1)}
        print(json.dumps(check, indent=1))
        unc = client.uncertainty(sid)
        (out / "uncertainty.json").write_text(json.dumps(unc, indent=1))
        (out / "uncertainty.txt").write_text(format_text(unc) + "\n")
        (out / "report.html").write_text(client.report(sid))
        (out / "check.json").write_text(json.dumps(check, indent=1))
        ok = (check["lost"] == 0 and check["extra"] == 0 and check["unique_run_ids"]
              and check["rows"] == len(expected) and killed is not None)
        return 0 if ok else 1
    finally:
        client.close()
        stop_server(proc)
        log.close()


if __name__ == "__main__":
    sys.exit(main())
