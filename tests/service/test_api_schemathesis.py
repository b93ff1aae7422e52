"""Schemathesis over the service's own OpenAPI schema: no 5xx, no response that breaks it.

In-process (ASGI) against an app whose Dask executor is closed, so generated studies that
happen to be valid are stored and queued but never computed. Bounded in examples and time.
"""

from __future__ import annotations

import shutil
import tempfile

import pytest
import schemathesis
from hypothesis import HealthCheck, settings
from schemathesis.checks import not_a_server_error
from schemathesis.specs.openapi.checks import (
    content_type_conformance,
    response_schema_conformance,
    status_code_conformance,
)

from service.api.app import create_app
from service.settings import Settings
from service.studies import StudyService

CHECKS = [
    not_a_server_error,
    status_code_conformance,
    content_type_conformance,
    response_schema_conformance,
]


def _app(tmp_dir: str):
    s = Settings(data_dir=tmp_dir, warm_start=False, max_runs=50)
    service = StudyService(s)
    service.executor.close()  # no computing here: submissions stay queued
    return create_app(s, service=service)


_DATA = tempfile.mkdtemp(prefix="beltstudy-schemathesis-")
APP = _app(_DATA)
schema = schemathesis.openapi.from_asgi("/openapi.json", APP)


@pytest.fixture(scope="module", autouse=True)
def _cleanup():
    yield
    APP.state.service.close()
    shutil.rmtree(_DATA, ignore_errors=True)


@schema.parametrize()
@settings(max_examples=15, deadline=None, suppress_health_check=list(HealthCheck), derandomize=True)
def test_no_server_errors_and_responses_match_the_schema(case):
    case.call_and_validate(checks=CHECKS)
