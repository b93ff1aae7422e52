"""Schemathesis over the live service (uvicorn, LocalCluster, the token set), every check:
no 5xx, every response as its schema says, every request the schema calls valid accepted and
every one it calls invalid refused. Bounded: a few examples per operation and a fixed seed.

This runs the same command as the longer run by hand (see BENCHMARKS.md):

    SCHEMATHESIS_HOOKS=tests.service.schemathesis_hooks schemathesis run URL/openapi.json \\
        -H "Authorization: Bearer TOKEN" --checks all --phases examples,fuzzing,stateful

The rules of a valid study that JSON Schema cannot state are held by the hooks in
``schemathesis_hooks`` (generated valid studies that break one are skipped).
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from tests.service import schemathesis_hooks
from tests.service.conftest import LiveService

pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[2]
TOKEN = "schemathesis-token"


def run_schemathesis(url: str, token: str, max_examples: int, seed: int, log: Path) -> str:
    """The schemathesis command line over ``url``; its output (also written to ``log``)."""
    exe = Path(sys.executable).parent / "schemathesis"
    cmd = [
        str(exe), "--config-file", str(Path(__file__).with_name("schemathesis.toml")),
        "run", f"{url}/openapi.json",
        "-H", f"Authorization: Bearer {token}",
        "--checks", "all",
        "--phases", "examples,fuzzing,stateful",
        "--max-examples", str(max_examples),
        "--seed", str(seed),
        "--no-color",
        # the hooks skip generated studies and calibrations that break a rule JSON Schema
        # cannot state (a calibration: fitted names of the body's model, a row's power and
        # force agreeing as P = Te v, readings the belt can carry), so generation is slower
        # than Hypothesis expects and most random calibrations are skipped; whether the
        # health check trips then rides on the seed's draw (it passed or failed as the
        # operation's description text changed), which is not a finding about the API.
        # POST /calibrations' valid bodies are tested in tests/service/test_calibrate.py
        "--suppress-health-check=too_slow,filter_too_much",
    ]
    env = {**os.environ, "SCHEMATHESIS_HOOKS": "tests.service.schemathesis_hooks",
           "PYTHONPATH": str(ROOT)}
    out = subprocess.run(cmd, cwd=log.parent, env=env, capture_output=True, text=True,
                         timeout=900)
    text = out.stdout + out.stderr
    log.write_text(text)
    return text


def test_every_check_holds_over_the_live_service(tmp_path):
    service = LiveService(
        tmp_path / "data",
        tmp_path / "beltstudy.service.log",
        BELTSTUDY_TOKEN=TOKEN,
        BELTSTUDY_MAX_RUNS=str(schemathesis_hooks.MAX_RUNS),
    )
    try:
        text = run_schemathesis(service.url, TOKEN, 8, 14, tmp_path / "schemathesis.log")
    finally:
        service.stop()
    summary = text[text.rfind("SUMMARY"):]
    cases = re.search(r"(\d+) generated", summary)
    assert cases and int(cases.group(1)) > 100, summary
    assert "Failures:" not in summary and "Errors:" not in summary, text[-6000:]
    assert re.search(r"\d+ passed", summary.splitlines()[-1]) or "passed" in summary, summary
