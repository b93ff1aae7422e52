"""``/calibrations``: fit a friction model to measured steady states (SPEC 7.3)."""

from __future__ import annotations

from functools import partial

from fastapi import APIRouter, Depends, Request
from fastapi.concurrency import run_in_threadpool

from beltstudy.service.api.deps import (
    CALIBRATION_BODY_FIX,
    ERROR_RESPONSES,
    _error,
    get_service,
    read_data,
    require_token,
)
from beltstudy.service.calibration import read_calibration, run_calibration
from beltstudy.service.studies import StudyService

__all__ = ["router", "CALIBRATION_BODY_SCHEMA_REF"]

router = APIRouter(prefix="/calibrations", tags=["calibrations"],
                   dependencies=[Depends(require_token)], responses=ERROR_RESPONSES)

#: The body's schema (``CalibrationIn``, put into the OpenAPI components by
#: :func:`beltstudy.service.door.openapi.install`).
CALIBRATION_BODY_SCHEMA_REF = {"$ref": "#/components/schemas/CalibrationIn"}


@router.post(
    "",
    summary="Fit friction model parameters to measured power (SPEC 7.3), JSON or YAML",
    responses={413: _error("body over the limit, or more measured rows than a calibration "
                           "takes (200)"),
               415: _error("Content-Type other than JSON or YAML, a charset other than "
                           "UTF-8, or a compressed body (Content-Encoding)")},
    openapi_extra={"requestBody": {"required": True, "content": {
        "application/json": {"schema": CALIBRATION_BODY_SCHEMA_REF},
        "application/yaml": {"schema": CALIBRATION_BODY_SCHEMA_REF},
    }}},
)
async def post_calibration(request: Request,
                           service: StudyService = Depends(get_service)) -> dict:
    """Values, standard errors and 95 % intervals (``fit.<name>.value``, ``.se``, ``.ci95``),
    residuals, the names the data cannot identify (``not_identifiable``) and a ``models``
    block for a study. The body is read as ``POST /studies`` reads a study: JSON or YAML."""
    data = await read_data(request, service.settings.max_body_bytes, "a calibration",
                           CALIBRATION_BODY_FIX)
    body = await run_in_threadpool(read_calibration, data)
    return await run_in_threadpool(partial(run_calibration, body,
                                           studies_dir=service.settings.studies_dir))
