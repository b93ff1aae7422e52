"""Fixtures of the web tests: an app with the pages mounted, a finished study without Dask."""

from __future__ import annotations

import time
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from beltstudy.service.api.app import create_app
from beltstudy.service.dask.jobs import study_schema
from beltstudy.service.dask.tasks import run_batch
from beltstudy.service.door.studyfile import resolve_study
from beltstudy.service.settings import Settings
from beltstudy.service.store.columns import rows_to_table
from beltstudy.service.store.parquet import PART_TABLES, Store

ROOT = Path(__file__).resolve().parents[2]
XSS = "<script>alert(1)</script><b>x</b>"


def tiny_conveyor(name: str = "tiny") -> dict:
    """A 300 m conveyor, solved in milliseconds."""
    return {
        "name": name,
        "speed_m_s": 2.5,
        "belt": {"type": "EP630/4", "width_m": 0.8},
        "material": {"capacity_t_h": 300, "density_t_m3": 1.0},
        "profile": [{"length_m": 150, "lift_m": 4}, {"length_m": 150, "lift_m": 8}],
        "idlers": {
            "carry": {"spacing_m": 1.2, "trough_deg": 30},
            "return": {"spacing_m": 3.0, "rolls": 1},
        },
        "drives": [{"position": "head", "pulley_diameter_m": 0.6, "inertia_kg_m2": 20}],
    }


def tiny_study(name: str = "tiny-study", conveyor_name: str = "tiny", **over) -> dict:
    """2 models x 2 temperatures, steady only: four runs."""
    study = {
        "name": name,
        "conveyor": tiny_conveyor(conveyor_name),
        "grid": {"friction_model": ["din", "cema"], "temperature_c": [-20, 20]},
        "dynamics": False,
    }
    study.update(over)
    return study


def app_with_pages(data_dir: Path, **settings):
    """The service app with the web router (included here if the factory does not yet)."""
    s = Settings(data_dir=data_dir, warm_start=False, studies_dir=ROOT / "studies", **settings)
    app = create_app(s)
    if not any(getattr(r, "path", "") == "/ui/static/{name}" for r in app.routes):
        from beltstudy.service.web.routes import router

        app.include_router(router)
    return app


def client(data_dir: Path, **settings) -> TestClient:
    """A TestClient without the lifespan (no Dask is started)."""
    return TestClient(app_with_pages(data_dir, **settings))


def finished_study(data_dir: Path, data: dict, name: str | None = None) -> str:
    """Run ``data`` in this process and store it as a done study; return its id.

    ``name`` overrides the stored name (to store names the validator would refuse).
    """
    study = resolve_study(data, studies_dir=ROOT / "studies")
    store = Store(data_dir)
    now = time.time()
    store.create(study.id, {
        "id": study.id, "name": name or study.name, "state": "done", "total": study.total,
        "done": study.total, "failed": 0, "elapsed_s": 0.5, "message": "",
        "created_at": now, "updated_at": now, "started_at": now, "finished_at": now,
        "engine_version": study.engine_version, "study": study.to_json(),
    })
    out = run_batch(study.id, study.runs, study.surface)
    for table in PART_TABLES:
        if out[table] is not None:
            store.write_part(study.id, table, "0", out[table])
    store.write_part(study.id, "runs", "0", rows_to_table(out["rows"], study_schema(study)))
    failed = sum(1 for r in out["rows"] if r["status"] == "failed")
    store.update(study.id, failed=failed)
    return study.id


class Web:
    """What the web tests need, as one fixture."""

    XSS = XSS
    ROOT = ROOT
    tiny_conveyor = staticmethod(tiny_conveyor)
    tiny_study = staticmethod(tiny_study)
    app_with_pages = staticmethod(app_with_pages)
    client = staticmethod(client)
    finished_study = staticmethod(finished_study)


@pytest.fixture
def web() -> type[Web]:
    return Web
