"""Dependencies shared by the routers: the service object and the bearer token check."""

from __future__ import annotations

import secrets

from fastapi import Depends, Request
from fastapi.security import HTTPAuthorizationCredentials, HTTPBearer

from beltstudy.service.api.models import ErrorOut
from beltstudy.service.errors import Unauthorized
from beltstudy.service.studies import StudyService

__all__ = ["get_service", "require_token", "ERROR_RESPONSES"]

_bearer = HTTPBearer(auto_error=False, description="BELTSTUDY_TOKEN, when the service sets one")


def get_service(request: Request) -> StudyService:
    return request.app.state.service


def require_token(
    request: Request,
    credentials: HTTPAuthorizationCredentials | None = Depends(_bearer),
) -> None:
    """Every route but ``/health`` needs ``Authorization: Bearer <BELTSTUDY_TOKEN>`` if set."""
    token = request.app.state.service.settings.token
    if not token:
        return
    given = credentials.credentials if credentials is not None else ""
    if not secrets.compare_digest(given.encode(), token.encode()):
        raise Unauthorized(
            "missing or wrong bearer token (send Authorization: Bearer <BELTSTUDY_TOKEN>)"
        )


def _error(description: str) -> dict:
    return {"model": ErrorOut, "description": description}


#: Error responses every authenticated route may give (for the OpenAPI schema).
ERROR_RESPONSES = {
    401: _error("missing or wrong bearer token"),
    404: _error("unknown study or run"),
    422: _error("invalid request; the message names the field"),
}
