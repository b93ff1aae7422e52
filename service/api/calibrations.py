"""``/calibrations``: fit a friction model to measured steady states (SPEC 7.3)."""

from __future__ import annotations

from functools import partial

from fastapi import APIRouter, Depends
from fastapi.concurrency import run_in_threadpool

from beltstudy.service.api.deps import ERROR_RESPONSES, _error, get_service, require_token
from beltstudy.service.calibration import CalibrationIn, run_calibration
from beltstudy.service.studies import StudyService

__all__ = ["router"]

router = APIRouter(prefix="/calibrations", tags=["calibrations"],
                   dependencies=[Depends(require_token)], responses=ERROR_RESPONSES)


@router.post("", summary="Fit friction model parameters to measured power (SPEC 7.3)",
             responses={400: _error("the body is not JSON")})
async def post_calibration(body: CalibrationIn,
                           service: StudyService = Depends(get_service)) -> dict:
    """Values and standard errors (``fit.<name>.value``, ``.se``), residuals, the names the
    data cannot identify (``not_identifiable``) and a ``models`` block for a study."""
    return await run_in_threadpool(partial(run_calibration, body,
                                           studies_dir=service.settings.studies_dir))
