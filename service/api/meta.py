"""``/health``, ``/models`` and ``/catalog/belts``."""

from __future__ import annotations

import dataclasses

from fastapi import APIRouter, Depends, Request

from beltstudy import engine
from beltstudy.engine import ALIASES, MODELS, catalog
from beltstudy.service.api.deps import ERROR_RESPONSES, check_query, get_service, require_token
from beltstudy.service.api.models import BeltsOut, Health, ModelsOut
from beltstudy.service.studies import StudyService

__all__ = ["router", "health_router"]

health_router = APIRouter(tags=["meta"])
router = APIRouter(tags=["meta"], dependencies=[Depends(require_token), Depends(check_query)],
                   responses=ERROR_RESPONSES)


@health_router.get("/health", response_model=Health, summary="Liveness and the Dask executor",
                   responses={422: ERROR_RESPONSES[422]})
async def health(request: Request, service: StudyService = Depends(get_service)) -> dict:
    # on the event loop itself: never queued behind the thread pool's expansions. So the
    # query check is called here, not a dependency (a plain def one runs in that pool): an
    # unknown parameter is a 422 naming it, as on every other route
    check_query(request)
    return {
        "status": "ok",
        "version": engine.__version__,
        "executor": service.executor.info(),
        "studies_running": service.running_count(),
    }


@router.get("/models", response_model=ModelsOut, summary="Friction models and their parameters")
def models() -> dict:
    out = []
    for name, model in MODELS.items():
        table = model.parameter_table()
        for row in table:
            if not isinstance(row["default"], int | float) or isinstance(row["default"], bool):
                row["default"] = None
        out.append(
            {
                "name": name,
                "description": model.description,
                "aliases": [a for a, target in ALIASES.items() if target == name],
                "parameters": table,
            }
        )
    return {"models": out}


@router.get("/catalog/belts", response_model=BeltsOut, summary="The belt catalogue")
def belts() -> dict:
    """Every catalogue belt; ``kind`` in the conveyor file's words (``belt.kind``:
    ``steel_cord`` or ``fabric``, SPEC 7.1), so a row's kind can be pasted into a file."""
    return {"belts": [{**dataclasses.asdict(b), "kind": catalog.FILE_KIND.get(b.kind, b.kind)}
                      for b in catalog.belts().values()]}
