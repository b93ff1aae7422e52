"""docker/: the compose file parses and names the settings the service reads."""

from __future__ import annotations

from pathlib import Path

import yaml

from beltstudy.service.settings import ENV_PREFIX, Settings

ROOT = Path(__file__).resolve().parents[2]


def _env_names(service: dict) -> set[str]:
    env = service.get("environment", {})
    if isinstance(env, list):
        return {item.split("=", 1)[0] for item in env}
    return set(env)


def test_compose_runs_service_scheduler_and_two_workers_on_one_volume():
    compose = yaml.safe_load((ROOT / "docker" / "compose.yaml").read_text())
    services = compose["services"]
    assert {"service", "scheduler", "worker"} <= set(services)
    assert services["worker"]["deploy"]["replicas"] == 2
    assert "--nthreads" in services["worker"]["command"]
    assert "data" in compose["volumes"]
    for name in ("service", "worker"):
        assert any(v.startswith("data:") for v in services[name]["volumes"]), name

    env = _env_names(services["service"])
    fields = {f"{ENV_PREFIX}{name.upper()}" for name in Settings.model_fields}
    beltstudy_vars = {n for n in env if n.startswith(ENV_PREFIX)}
    assert beltstudy_vars <= fields, beltstudy_vars - fields
    assert {
        "BELTSTUDY_DATA_DIR",
        "BELTSTUDY_SCHEDULER",
        "BELTSTUDY_TOKEN",
        "BELTSTUDY_MAX_RUNS",
    } <= beltstudy_vars
    scheduler = services["service"]["environment"]["BELTSTUDY_SCHEDULER"]
    assert scheduler == "tcp://scheduler:8786" and "8786" in " ".join(
        services["scheduler"]["command"]
    )


def test_settings_table_in_the_docs_matches_the_settings():
    text = (ROOT / "README.md").read_text()
    for name in ("DATA_DIR", "SCHEDULER", "WORKERS", "TOKEN", "MAX_RUNS"):
        assert f"BELTSTUDY_{name}" in text
        assert name.lower() in Settings.model_fields


def test_dockerfile_installs_the_package_and_serves():
    text = (ROOT / "docker" / "Dockerfile").read_text()
    assert "pip install ." in text and '"beltstudy", "serve"' in text
