"""Dependencies shared by the routers: the service object and the bearer token check."""

from __future__ import annotations

import difflib
import secrets
import threading
from typing import Any

from fastapi import Depends, Request
from fastapi.concurrency import run_in_threadpool
from fastapi.security import HTTPAuthorizationCredentials, HTTPBearer

from beltstudy.service.api.models import ErrorOut
from beltstudy.service.calibration import MAX_ROWS
from beltstudy.service.door.parse import YAML_TYPES, parse_body
from beltstudy.service.errors import Invalid, TooLarge, Unauthorized, UnsupportedMedia
from beltstudy.service.studies import StudyService

__all__ = ["get_service", "require_token", "check_query", "read_data", "ERROR_RESPONSES",
           "SHUTTING_DOWN"]

#: Set when ``beltstudy serve`` is told to stop (SIGTERM, SIGINT), before uvicorn's grace
#: period: a request still working (a study in expansion) answers 503 with Retry-After
#: instead of being cut off with a plain-text 500 when the grace period ends.
SHUTTING_DOWN = threading.Event()

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
            close = difflib.get_close_matches(name, known, n=1, cutoff=0.6)
            meant = f" (did you mean '{close[0]}'?)" if close else ""
            raise Invalid(f"query.{name}: unknown parameter{meant}; this route takes: {valid}")
        if not value.strip():
            raise Invalid(f"query.{name}: empty; give a value or leave the parameter out")


#: What brings a body within the limit (the 413's fix): a conveyor written inline is most of
#: a study's bytes, and the limit is the service's setting.
BODY_FIX = ("; give the conveyor as a path in the service's studies folder "
            "(BELTSTUDY_STUDIES_DIR) rather than inline, shorten the description, or raise "
            "the service's BELTSTUDY_MAX_BODY_BYTES")
#: The 413's fix for a calibration: its bytes are its ``measured`` rows (it has no
#: description, and its conveyor is most often a path already). It was told the study's fix,
#: which cannot bring 60 000 measured rows within the limit.
CALIBRATION_BODY_FIX = (f"; send fewer measured rows (a calibration takes at most {MAX_ROWS}), "
                        "or averages of repeated readings at the same load and temperature, "
                        "or raise the service's BELTSTUDY_MAX_BODY_BYTES")


async def _read_body(request: Request, limit: int, fix: str = BODY_FIX) -> bytes:
    declared = request.headers.get("content-length")
    if declared and declared.isdigit() and int(declared) > limit:
        raise TooLarge(f"body: {declared} bytes; the limit is {limit} "
                       f"(BELTSTUDY_MAX_BODY_BYTES){fix}")
    chunks, size = [], 0
    async for chunk in request.stream():
        size += len(chunk)
        if size > limit:
            raise TooLarge(f"body: more than {limit} bytes, the limit "
                           f"(BELTSTUDY_MAX_BODY_BYTES){fix}")
        chunks.append(chunk)
    return b"".join(chunks)


def _check_media_type(content_type: str, what: str) -> None:
    """A body route reads JSON or YAML only: any other ``Content-Type`` (or none) is a 415
    naming the types it takes (text/plain is not parsed as JSON)."""
    media = content_type.split(";", 1)[0].strip().lower()
    if media != "application/json" and media not in YAML_TYPES:
        given = f"'{media}'" if media else "none"
        raise UnsupportedMedia(
            f"Content-Type: {given} is not read here; send {what} as application/json or "
            f"YAML ({', '.join(YAML_TYPES)})"
        )


def _check_encoding(content_type: str, content_encoding: str, what: str) -> None:
    """The body is read as it arrives, as UTF-8 text: a compressed body (``Content-Encoding:
    gzip``) or another declared charset (``charset=utf-16``) is a 415 saying so, where it
    was a 422 'body: not UTF-8 text' that named neither header."""
    coding = content_encoding.strip().lower()
    if coding and coding != "identity":
        raise UnsupportedMedia(
            f"Content-Encoding: '{coding}' is not read here; send {what} uncompressed "
            "(no Content-Encoding header)")
    for param in content_type.split(";")[1:]:
        key, _, value = param.partition("=")
        charset = value.strip().strip('"').lower()
        if key.strip().lower() == "charset" and charset not in ("utf-8", "utf8", "us-ascii"):
            raise UnsupportedMedia(
                f"Content-Type: charset '{charset}' is not read here; send {what} as UTF-8 "
                "(charset=utf-8, or no charset)")


async def read_data(request: Request, limit: int, what: str, fix: str = BODY_FIX) -> Any:
    """The request's body as data, one way for every route that takes a document (``what``:
    ``a study``, ``a calibration``): JSON or YAML by ``Content-Type`` (415 for any other), at
    most ``limit`` bytes (413, ``fix`` saying how that document gets smaller), syntax errors
    with their line and column (422). Parsing runs in a worker thread: the event loop, and so
    /health, keeps answering meanwhile."""
    content_type = request.headers.get("content-type", "")
    _check_media_type(content_type, what)
    _check_encoding(content_type, request.headers.get("content-encoding", ""), what)
    body = await _read_body(request, limit, fix)
    return await run_in_threadpool(parse_body, body, content_type, what)


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
