"""The FastAPI application factory.

``create_app(settings)`` builds the app: one :class:`~beltstudy.service.studies.StudyService` on
``app.state.service`` (started and stopped by the lifespan), the routers, the one handler
mapping :class:`~beltstudy.service.errors.ServiceError` to JSON, and the OpenAPI schema of the study
body. Further pages (``service/web/``) are a router module included with one line in
:data:`ROUTERS`.

Every error is JSON ``{"error", "message"}``: the service's own errors, request validation,
unknown routes and methods (405 with the ``Allow`` header of every method of that path), and,
through :class:`ErrorGuard`, any exception nothing else caught: a logged 500 whose message
gives a reference to the log line and never the exception's text.
"""

from __future__ import annotations

import importlib
import json
import logging
import uuid
from contextlib import asynccontextmanager
from pathlib import Path
from urllib.parse import parse_qsl, unquote

from fastapi import Depends, FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import HTMLResponse, JSONResponse
from pydantic import BaseModel, ValidationError
from starlette.exceptions import HTTPException as StarletteHTTPException
from starlette.requests import ClientDisconnect
from starlette.routing import Match

from beltstudy import engine
from beltstudy.engine import InputError
from beltstudy.engine.conveyor import nearest_word
from beltstudy.engine.errors import shown_text
from beltstudy.service.api.apidoc import API_DOC_CSP, api_reference_html
from beltstudy.service.api.deps import require_token
from beltstudy.service.door.messages import describe
from beltstudy.service.door.openapi import install as install_openapi
from beltstudy.service.errors import ServiceError, bad_study_id
from beltstudy.service.settings import Settings, get_settings
from beltstudy.service.store.parquet import is_study_id
from beltstudy.service.studies import StudyService

__all__ = ["create_app", "ROUTERS"]

log = logging.getLogger("beltstudy.api")

#: Router modules, each with a module-level ``router`` (and optionally ``health_router``).
ROUTERS = ("beltstudy.service.api.meta", "beltstudy.service.api.studies", "beltstudy.service.web.routes",
           "beltstudy.service.api.calibrations")


def _error(kind: str, message: str, status: int, headers: dict | None = None) -> JSONResponse:
    return JSONResponse({"error": kind, "message": shown_text(message)}, status_code=status,
                        headers=headers)


def _body_model(request: Request) -> type[BaseModel] | None:
    """The Pydantic model a route reads its JSON body into (``None``: no such body)."""
    field = getattr(request.scope.get("route"), "body_field", None)
    model = getattr(getattr(field, "field_info", None), "annotation", None)
    return model if isinstance(model, type) and issubclass(model, BaseModel) else None


def _body_message(request: Request, exc: RequestValidationError) -> str | None:
    """A body's problems said as the door says a study's (:func:`describe`): the field's path
    in the body as written (no ``body.`` and no union members such as ``inline``), an
    unknown key with the nearest valid one. ``None`` when the errors are not all the body's
    fields (a body that is no JSON, a query parameter)."""
    model, errors, data = _body_model(request), exc.errors(), getattr(exc, "body", None)
    if model is None or not isinstance(data, dict) or not errors or any(
            tuple(e.get("loc", ()))[:1] != ("body",) or len(e.get("loc", ())) < 2
            for e in errors):
        return None
    details = [{"type": e["type"], "loc": tuple(e["loc"])[1:], "input": e.get("input"),
                **({"ctx": e["ctx"]} if "ctx" in e else {})} for e in errors]
    try:
        return describe(ValidationError.from_exception_data(model.__name__, details), data,
                        model=model)
    except Exception:  # an error pydantic cannot make again: said the plain way below
        log.debug("body errors kept as FastAPI says them", exc_info=True)
        return None


def _validation_message(exc: RequestValidationError) -> str:
    lines = []
    for err in exc.errors():
        loc = ".".join(str(p) for p in err.get("loc", ()))
        msg = err.get("msg", "invalid")
        if err.get("type") == "literal_error":
            # a misspelt choice (format=jsn): the word meant, as a study's door says it
            hint = nearest_word(err.get("input"), msg)
            msg += f": {hint}" if hint else ""
        lines.append(f"{loc}: {msg}")
    return "; ".join(dict.fromkeys(lines)) or "invalid request"


def _install_handlers(app: FastAPI) -> None:
    @app.exception_handler(ServiceError)
    async def service_error(request: Request, exc: ServiceError) -> JSONResponse:
        headers = {"WWW-Authenticate": "Bearer"} if exc.status_code == 401 else exc.headers
        return _error(exc.kind, exc.message, exc.status_code, headers)

    @app.exception_handler(InputError)
    async def input_error(request: Request, exc: InputError) -> JSONResponse:
        # the door turns every user mistake into an Invalid; one that slips past it still
        # names the field (422), never a 500 hiding the message
        log.warning("InputError not turned into Invalid on %s %s: %s", request.method,
                    request.url.path, exc)
        return _error("invalid", str(exc), 422)

    @app.exception_handler(RequestValidationError)
    async def request_invalid(request: Request, exc: RequestValidationError) -> JSONResponse:
        message = _body_message(request, exc) or _validation_message(exc)
        return _error("invalid", message, 422)

    @app.exception_handler(StarletteHTTPException)
    async def http_error(request: Request, exc: StarletteHTTPException) -> JSONResponse:
        path, method = request.url.path, request.method
        if exc.status_code == 404:
            study_id = _unroutable_study_id(request)
            if study_id is not None:  # '/studies/..%2Fx': no route took it, no study has it
                return _error("not_found", bad_study_id(study_id), 404)
            return _error("not_found", f"no route {method} {path}", 404)
        if exc.status_code == 405:
            allowed = _allowed_methods(request)
            return _error(
                "method_not_allowed",
                f"{method} is not allowed on {path}; allowed: {', '.join(allowed)}",
                405,
                {"Allow": ", ".join(allowed)},
            )
        return _error("error", str(exc.detail), exc.status_code, exc.headers)


def _unroutable_study_id(request: Request) -> str | None:
    """The study id of a ``/studies/ID...`` path no route took, when it cannot be a study's
    (``..%2Fx`` decodes to ``../x``: its slash splits the path, so no route matched it);
    None for a path elsewhere or an id of a study's form (an unknown route under it)."""
    raw = request.scope.get("raw_path") or request.url.path.encode()
    parts = raw.split(b"?", 1)[0].split(b"/")
    if len(parts) < 3 or parts[1] != b"studies" or not parts[2]:
        return None
    study_id = unquote(parts[2].decode("latin-1"), errors="replace")
    return None if is_study_id(study_id) else study_id


_METHODS = ("GET", "HEAD", "POST", "PUT", "PATCH", "DELETE")


def _allowed_methods(request: Request) -> list[str]:
    """The methods some route answers on the request's path (for ``Allow``); HEAD wherever
    GET is (:class:`HeadAsGet`)."""
    routes = request.app.router.routes
    allowed = [
        method
        for method in _METHODS
        if any(r.matches({**request.scope, "method": method})[0] == Match.FULL for r in routes)
    ]
    if "GET" in allowed and "HEAD" not in allowed:
        allowed.insert(allowed.index("GET") + 1, "HEAD")
    return allowed


class HeadAsGet:
    """ASGI middleware: ``HEAD`` is answered as ``GET`` would be (status and headers,
    ``Content-Length`` included) without the body, on every route that has GET."""

    def __init__(self, app):
        self.app = app

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http" or scope["method"] != "HEAD":
            await self.app(scope, receive, send)
            return

        async def headers_only(message):
            if message["type"] == "http.response.body":
                if message.get("more_body", False):
                    return
                message = {"type": "http.response.body", "body": b"", "more_body": False}
            await send(message)

        await self.app({**scope, "method": "GET"}, receive, headers_only)


#: Query parameters a route takes more than once (``filter=a=1&filter=b=2``, a list).
REPEATABLE_QUERY = frozenset({"filter"})


class QueryOnce:
    """ASGI middleware: a query parameter given twice (``limit=1&limit=2``) is a 422 naming
    it, where the last value would otherwise win silently; :data:`REPEATABLE_QUERY` are the
    lists a route reads whole."""

    def __init__(self, app):
        self.app = app

    async def __call__(self, scope, receive, send):
        if scope["type"] == "http" and scope.get("query_string"):
            seen: set[str] = set()
            for key, _value in parse_qsl(scope["query_string"].decode("latin-1"),
                                         keep_blank_values=True):
                if key in seen and key not in REPEATABLE_QUERY:
                    body = json.dumps({
                        "error": "invalid",
                        "message": f"query: '{key}' given twice; give each parameter once",
                    }).encode()
                    await send({"type": "http.response.start", "status": 422,
                                "headers": [(b"content-type", b"application/json"),
                                            (b"content-length", str(len(body)).encode())]})
                    await send({"type": "http.response.body", "body": body})
                    return
                seen.add(key)
        await self.app(scope, receive, send)


class ErrorGuard:
    """ASGI middleware: an exception that reaches it becomes a logged 500 ``{error,
    message}`` with a reference to the log line, never the exception's text; the connection
    stays usable. (After the response has started, nothing can be sent: it re-raises.)"""

    def __init__(self, app):
        self.app = app

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        started = False

        async def watch(message):
            nonlocal started
            if message["type"] == "http.response.start":
                started = True
            await send(message)

        try:
            await self.app(scope, receive, watch)
        except ClientDisconnect:
            # the client went away mid-request: nobody to answer, nothing went wrong here
            log.info("client left during %s %s", scope.get("method"), scope.get("path"))
            return
        except Exception:
            ref = uuid.uuid4().hex[:12]
            log.exception("unexpected error %s on %s %s", ref, scope.get("method"),
                          scope.get("path"))
            if started:
                raise
            body = json.dumps({
                "error": "internal",
                "message": f"internal error (reference {ref} in the service log); the request "
                "was not completed",
            }).encode()
            await send({
                "type": "http.response.start",
                "status": 500,
                "headers": [(b"content-type", b"application/json"),
                            (b"content-length", str(len(body)).encode())],
            })
            await send({"type": "http.response.body", "body": body})


def create_app(settings: Settings | None = None, service: StudyService | None = None) -> FastAPI:
    """Build the app; the lifespan starts the service (resume, Dask) and stops it."""

    settings = settings or get_settings()
    service = service or StudyService(settings)

    @asynccontextmanager
    async def lifespan(app: FastAPI):
        if not Path(settings.studies_dir).is_dir():
            log.warning(
                "BELTSTUDY_STUDIES_DIR %s is not a folder (from %s): a POSTed study can give "
                "its conveyor inline only, not as a path; set it to the study files' folder "
                "(the repository's studies/)", settings.studies_dir, Path.cwd())
        service.start()
        try:
            yield
        finally:
            service.close()

    app = FastAPI(
        title="beltstudy",
        version=engine.__version__,
        description="Parameter studies of belt conveyors on Dask: submit a grid, read "
        "every run back as Parquet. Errors are JSON {error, message}.",
        lifespan=lifespan,
        openapi_url=None,  # served below, behind the token like the rest of the API
        docs_url=None,
        redoc_url=None,
    )
    app.state.service = service
    _install_handlers(app)
    app.add_middleware(ErrorGuard)
    app.add_middleware(QueryOnce)
    app.add_middleware(HeadAsGet)
    for name in ROUTERS:
        module = importlib.import_module(name)
        for attr in ("health_router", "router"):
            router = getattr(module, attr, None)
            if router is not None:
                app.include_router(router)
    install_openapi(app, settings.studies_dir)
    _install_docs(app)
    return app


def _install_docs(app: FastAPI) -> None:
    """``/openapi.json`` and ``/docs`` (the routes from it on one page, service/api/apidoc.py),
    both needing the token when one is set."""

    @app.get("/openapi.json", include_in_schema=False, dependencies=[Depends(require_token)])
    def openapi_json() -> JSONResponse:
        return JSONResponse(app.openapi())

    @app.get("/docs", include_in_schema=False, dependencies=[Depends(require_token)])
    def docs() -> HTMLResponse:
        # not FastAPI's Swagger UI: it loads from a CDN, a blank page without internet
        return HTMLResponse(api_reference_html(app.openapi()),
                            headers={"Content-Security-Policy": API_DOC_CSP,
                                     "X-Content-Type-Options": "nosniff"})
