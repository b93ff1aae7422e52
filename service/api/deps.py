"""Dependencies shared by the routers: the service object and the bearer token check."""

from __future__ import annotations

import secrets

from fastapi import Depends, Request
from fastapi.security import HTTPAuthorizationCredentials, HTTPBearer

from beltstudy.service.api.models import ErrorOut
from beltstudy.service.errors import Invalid, Unauthorized
from beltstudy.service.studies import StudyService

__all__ = ["get_service", "require_token", "check_query", "ERROR_RESPONSES"]

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


def _query_names(dependant) -> list[str]:
    """The query parameters of a route and of its dependencies."""
    names = [p.alias for p in dependant.query_params]
    for sub in dependant.dependencies:
        names += [n for n in _query_names(sub) if n not in names]
    return names


def check_query(request: Request) -> None:
    """A query parameter the route does not know, or one given empty, is a 422 naming it
    (an empty ``baseline`` would otherwise fall back to a default without a word)."""
    route = request.scope.get("route")
    dependant = getattr(route, "dependant", None)
    if dependant is None:
        return
    known = _query_names(dependant)
    for name, value in request.query_params.multi_items():
        if name not in known:
            valid = ", ".join(known) if known else "none"
            raise Invalid(f"query.{name}: unknown parameter; this route takes: {valid}")
        if not value.strip():
            raise Invalid(f"query.{name}: empty; give a value or leave the parameter out")


def _error(description: str) -> dict:
    return {"model": ErrorOut, "description": description}


#: Error responses every authenticated route may give (for the OpenAPI schema).
ERROR_RESPONSES = {
    401: _error("missing or wrong bearer token"),
    404: _error("unknown study or run"),
    409: _error("a run of a study that has not finished (the message gives the study's "
                "state), or a study being deleted"),
    422: _error("invalid request; the message names the field"),
}
