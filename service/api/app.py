"""The FastAPI application factory.

``create_app(settings)`` builds the app: one :class:`~service.studies.StudyService` on
``app.state.service`` (started and stopped by the lifespan), the routers, the one handler
mapping :class:`~service.errors.ServiceError` to JSON, and the OpenAPI schema of the study
body. Further pages (``service/web/``) are a router module included with one line in
:data:`ROUTERS`.
"""

from __future__ import annotations

import logging
from contextlib import asynccontextmanager

from fastapi import FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse

import engine
from service.errors import ServiceError
from service.settings import Settings, get_settings
from service.studies import StudyService

__all__ = ["create_app", "ROUTERS"]

log = logging.getLogger("beltstudy.api")

#: Router modules, each with a module-level ``router`` (and optionally ``health_router``).
ROUTERS = ("service.api.meta", "service.api.studies", "service.web.routes")


def _error(kind: str, message: str, status: int, headers: dict | None = None) -> JSONResponse:
    return JSONResponse({"error": kind, "message": message}, status_code=status, headers=headers)


def _validation_message(exc: RequestValidationError) -> str:
    lines = []
    for err in exc.errors():
        loc = ".".join(str(p) for p in err.get("loc", ()))
        lines.append(f"{loc}: {err.get('msg', 'invalid')}")
    return "; ".join(dict.fromkeys(lines)) or "invalid request"


def _install_handlers(app: FastAPI) -> None:
    @app.exception_handler(ServiceError)
    async def service_error(request: Request, exc: ServiceError) -> JSONResponse:
        headers = {"WWW-Authenticate": "Bearer"} if exc.status_code == 401 else None
        return _error(exc.kind, exc.message, exc.status_code, headers)

    @app.exception_handler(RequestValidationError)
    async def request_invalid(request: Request, exc: RequestValidationError) -> JSONResponse:
        return _error("invalid", _validation_message(exc), 422)

    @app.exception_handler(Exception)
    async def unexpected(request: Request, exc: Exception) -> JSONResponse:
        log.exception("unhandled error on %s %s", request.method, request.url.path)
        return _error("internal", f"{type(exc).__name__}: {exc}", 500)


def _install_openapi(app: FastAPI) -> None:
    """Add the study body schema (StudyDoc and the conveyor/scenario models) to components."""
    from fastapi.openapi.utils import get_openapi

    from service.study import StudyDoc

    def openapi() -> dict:
        if app.openapi_schema:
            return app.openapi_schema
        schema = get_openapi(
            title=app.title, version=app.version, description=app.description, routes=app.routes
        )
        doc = StudyDoc.model_json_schema(ref_template="#/components/schemas/{model}")
        defs = doc.pop("$defs", {})
        components = schema.setdefault("components", {}).setdefault("schemas", {})
        components.update(defs)
        components["StudyDoc"] = doc
        app.openapi_schema = schema
        return schema

    app.openapi = openapi


def create_app(settings: Settings | None = None, service: StudyService | None = None) -> FastAPI:
    """Build the app; the lifespan starts the service (resume, Dask) and stops it."""
    import importlib

    settings = settings or get_settings()
    service = service or StudyService(settings)

    @asynccontextmanager
    async def lifespan(app: FastAPI):
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
    )
    app.state.service = service
    _install_handlers(app)
    for name in ROUTERS:
        module = importlib.import_module(name)
        for attr in ("health_router", "router"):
            router = getattr(module, attr, None)
            if router is not None:
                app.include_router(router)
    _install_openapi(app)
    return app
