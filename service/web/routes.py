"""Pages (``/``, ``/ui/...``), their static files and data, and the plot routes.

Pages are shells with no study data in them, served without the token so the login field
can be shown; ``static/app.js`` fetches everything else with ``Authorization: Bearer``.
Study and run ids are checked before they reach a page; every value placed in a page is
escaped. The plot routes and ``/ui/data`` need the token like the rest of the API.
"""

from __future__ import annotations

import html
import re
from importlib import resources
from string import Template
from typing import Literal

from fastapi import APIRouter, Depends, Query, Response
from fastapi.responses import HTMLResponse

from beltstudy.service.api.deps import ERROR_RESPONSES, check_query, get_service, require_token
from beltstudy.service.errors import NotFound
from beltstudy.service.studies import StudyService, study_models
from beltstudy.service.web import figures
from beltstudy.service.web.report import REPORT_CSP, build_report

__all__ = ["router", "pages", "api"]

_ID_RE = re.compile(r"^[0-9a-f]{16}$")
#: Content security policy of the pages: nothing from elsewhere, no inline script.
CSP = (
    "default-src 'self'; img-src 'self' blob: data:; script-src 'self'; style-src 'self'; "
    "object-src 'none'; base-uri 'none'; frame-ancestors 'none'; form-action 'self'"
)
STATIC = {
    "app.js": "text/javascript; charset=utf-8",
    "style.css": "text/css; charset=utf-8",
}
_PLOT_RESPONSES = {
    200: {
        "content": {t: {"schema": {"type": "string", "format": "binary"}}
                    for t in figures.FORMATS.values()},
        "description": "the figure",
    }
}

pages = APIRouter(include_in_schema=False)
api = APIRouter(dependencies=[Depends(require_token), Depends(check_query)],
                responses=ERROR_RESPONSES, tags=["plots"])


def _resource(*parts: str) -> str:
    return resources.files("beltstudy.service.web").joinpath(*parts).read_text(encoding="utf-8")


def _page(page: str, title: str, study_id: str = "", run_id: str = "") -> HTMLResponse:
    values = {k: html.escape(v, quote=True) for k, v in
              {"page": page, "title": title, "study_id": study_id, "run_id": run_id}.items()}
    body = Template(_resource("templates", f"{page}.html")).safe_substitute(values)
    text = Template(_resource("templates", "layout.html")).safe_substitute(values, body=body)
    return HTMLResponse(text, headers={"Content-Security-Policy": CSP,
                                       "X-Content-Type-Options": "nosniff",
                                       "Referrer-Policy": "no-referrer"})


def _check_id(value: str, what: str) -> str:
    if not _ID_RE.match(value):
        raise NotFound(f"{what} '{value}' not found")
    return value


# ------------------------------------------------------------------------------------ pages
@pages.get("/", response_class=HTMLResponse)
def index_page() -> HTMLResponse:
    return _page("index", "studies")


@pages.get("/ui/studies/{study_id}", response_class=HTMLResponse)
def study_page(study_id: str) -> HTMLResponse:
    return _page("study", "study", _check_id(study_id, "study"))


@pages.get("/ui/studies/{study_id}/runs/{run_id}", response_class=HTMLResponse)
def run_page(study_id: str, run_id: str) -> HTMLResponse:
    return _page("run", "run", _check_id(study_id, "study"), _check_id(run_id, "run"))


@pages.get("/ui/static/{name}")
def static_file(name: str) -> Response:
    if name not in STATIC:
        raise NotFound(f"static file '{name}' not found")
    return Response(_resource("static", name), media_type=STATIC[name],
                    headers={"Cache-Control": "no-cache", "X-Content-Type-Options": "nosniff"})


# ------------------------------------------------------------------------------------ data
@api.get("/ui/data/studies/{study_id}", summary="What the study page shows besides the runs")
def study_data(study_id: str, service: StudyService = Depends(get_service)) -> dict:
    doc = service.store.read(study_id)
    study = doc.get("study", {})
    conveyor = study.get("conveyor") or {}
    return {
        "id": study_id,
        "name": doc.get("name", ""),
        "description": study.get("description", ""),
        "conveyor_name": conveyor.get("name", "") if isinstance(conveyor, dict) else "",
        "conveyor_source": study.get("conveyor_source", ""),
        "dynamics": bool(study.get("dynamics", False)),
        "model": study.get("model"),
        "axes": [{"name": a["name"], "column": a["column"], "values": a["values"],
                  "group": a.get("group")}
                 for a in study.get("axes", [])],
        "grid_points": study.get("grid_points"),
        "merged": study.get("merged", 0),
        "merged_axes": study.get("merged_axes", []),
        "design": study.get("design"),
        "designs": study.get("designs") or [],
        "models": study_models(doc),
        "columns": service.store.runs_columns(study_id),
        "study_plots": figures.STUDY_PLOTS,
        "run_plots": figures.RUN_PLOTS,
    }


@api.get(
    "/studies/{study_id}/plots/{name}",
    summary="A figure of a study as PNG or SVG",
    response_class=Response,
    responses=_PLOT_RESPONSES,
    description="Names: " + "; ".join(f"`{k}`: {v}" for k, v in figures.STUDY_PLOTS.items()),
)
def study_plot(
    study_id: str,
    name: str,
    format: Literal["png", "svg"] = Query("png", description="png or svg"),
    baseline: str | None = Query(None, description="ratio: baseline model (default cema)"),
    candidate: str | None = Query(None, description="ratio: candidate model (default nonlin)"),
    service: StudyService = Depends(get_service),
) -> Response:
    make = figures.study_figure(service, study_id, name, baseline, candidate)
    return Response(figures.render(make, format), media_type=figures.FORMATS[format],
                    headers={"Cache-Control": "no-store"})


@api.get(
    "/studies/{study_id}/runs/{run_id}/plots/{name}",
    summary="A figure of one run as PNG or SVG",
    response_class=Response,
    responses=_PLOT_RESPONSES,
    description="Names: " + "; ".join(f"`{k}`: {v}" for k, v in figures.RUN_PLOTS.items()),
)
def run_plot(
    study_id: str,
    run_id: str,
    name: str,
    format: Literal["png", "svg"] = Query("png", description="png or svg"),
    service: StudyService = Depends(get_service),
) -> Response:
    make = figures.run_figure(service, study_id, run_id, name)
    return Response(figures.render(make, format), media_type=figures.FORMATS[format],
                    headers={"Cache-Control": "no-store"})


@api.get(
    "/studies/{study_id}/report",
    summary="The design report of a study: one self-contained HTML page (prints to PDF)",
    response_class=Response,
    responses={200: {"content": {"text/html": {"schema": {"type": "string"}}},
                     "description": "the report"}},
)
def study_report(study_id: str, service: StudyService = Depends(get_service)) -> Response:
    return HTMLResponse(build_report(service, study_id), headers={
        "Content-Security-Policy": REPORT_CSP, "X-Content-Type-Options": "nosniff",
        "Referrer-Policy": "no-referrer", "Cache-Control": "no-store",
        "Content-Disposition": f'inline; filename="report-{study_id}.html"'})


#: The router the app factory includes (pages, static files, page data, plots).
router = APIRouter()
router.include_router(pages)
router.include_router(api)
