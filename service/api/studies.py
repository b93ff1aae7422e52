"""``/studies`` routes: thin translations of HTTP to :class:`beltstudy.service.studies.StudyService`."""

from __future__ import annotations

import asyncio
import json
from functools import partial
from typing import Literal

from fastapi import APIRouter, Depends, Query, Request, Response
from fastapi.concurrency import run_in_threadpool
from fastapi.responses import StreamingResponse

from beltstudy.service.api.deps import (
    ERROR_RESPONSES,
    SHUTTING_DOWN,
    _error,
    check_query,
    get_service,
    read_data,
    require_token,
)
from beltstudy.service.api.models import (
    AccuracyOut,
    CompareOut,
    Deleted,
    RunDetail,
    RunProfile,
    RunsPage,
    RunSurface,
    StudyList,
    StudyStatus,
)
from beltstudy.service.door.parse import expect_kind
from beltstudy.service.errors import Damaged, DamagedParts, Invalid, Unavailable
from beltstudy.service.store import query
from beltstudy.service.studies import StudyService

__all__ = ["router", "STUDY_BODY_SCHEMA_REF"]

router = APIRouter(
    prefix="/studies",
    tags=["studies"],
    dependencies=[Depends(require_token), Depends(check_query)],
    responses=ERROR_RESPONSES,
)

STUDY_BODY_SCHEMA_REF = {"$ref": "#/components/schemas/StudyDoc"}
PARQUET_TYPE = "application/vnd.apache.parquet"
#: The other media types of a route that answers a table as JSON, CSV or Parquet (OpenAPI).
TABLE_RESPONSES = {200: {"content": {
    "text/csv": {"schema": {"type": "string"}},
    PARQUET_TYPE: {"schema": {"type": "string", "format": "binary"}},
}}}


def _download(df, format: str, name: str, headers: dict | None = None,
              schema=None) -> Response:
    """A table as a CSV or Parquet download named ``<name>.csv`` / ``<name>.parquet``
    (``Content-Disposition: attachment``; the name is built from checked study and run ids;
    ``schema``: the stored table's, whose column types the Parquet keeps)."""
    ext = "csv" if format == "csv" else "parquet"
    headers = {**(headers or {}),
               "Content-Disposition": f'attachment; filename="{name}.{ext}"'}
    if format == "csv":
        return Response(query.to_csv(df), media_type="text/csv; charset=utf-8",
                        headers=headers)
    return Response(query.to_parquet(df, schema), media_type=PARQUET_TYPE, headers=headers)


def _state(service: StudyService, study_id: str) -> dict:
    """The study's status for a table's answer; {} where its document cannot be read (its
    rows are still served, as before the state was added to them)."""
    try:
        return service.status(study_id)
    except Damaged:
        return {}


def _state_header(st: dict) -> dict:
    """``X-Study-State: running; done=2; total=4`` for a download ({} without a state)."""
    if not st:
        return {}
    return {"X-Study-State": f"{st['state']}; done={st['done']}; total={st['total']}"}


def _with_urls(status: dict) -> dict:
    return {
        **status,
        "status_url": f"/studies/{status['id']}",
        "runs_url": f"/studies/{status['id']}/runs",
    }


@router.post(
    "",
    response_model=StudyStatus,
    status_code=202,
    summary="Submit a study (SPEC section 3), JSON or YAML",
    responses={
        200: {"model": StudyStatus, "description": "the same study was already submitted"},
        413: _error("body or grid over the limit"),
        415: _error("Content-Type other than JSON or YAML, a charset other than UTF-8, or a "
                    "compressed body (Content-Encoding)"),
        503: _error("busy expanding other studies (Retry-After says when to send it again)"),
    },
    openapi_extra={
        "requestBody": {
            "required": True,
            "content": {
                "application/json": {"schema": STUDY_BODY_SCHEMA_REF},
                "application/yaml": {"schema": STUDY_BODY_SCHEMA_REF},
            },
        }
    },
)
async def submit_study(
    request: Request, response: Response, service: StudyService = Depends(get_service)
) -> dict:
    data = await read_data(request, service.settings.max_body_bytes, "a study")
    expect_kind(data, "study", "body")
    # resolving runs in a worker thread: the event loop, and so /health, keeps answering
    status, created = await _unless_stopping(run_in_threadpool(
        partial(service.submit, data, strict=True)))
    response.status_code = 202 if created else 200
    response.headers["Location"] = f"/studies/{status['id']}"
    return _with_urls(status)


#: How often a submission in expansion looks whether the service is being stopped [s].
STOPPING_POLL_S = 0.2
#: The Retry-After of a submission the service stopped for [s]: a restart's start-up.
STOPPING_RETRY_S = 10


async def _unless_stopping(work):
    """``await work``, unless the service is being stopped first (``SHUTTING_DOWN``, set on
    SIGTERM or SIGINT by ``beltstudy serve``): then a 503 with ``Retry-After``. A study in
    expansion when the service was stopped outlived its grace period and was answered with
    uvicorn's plain-text '500 Internal Server Error', which the CLI took for another server
    ('check --url'). Its expansion goes on in its thread; sent again after the restart, the
    same study is one study."""
    task = asyncio.ensure_future(work)
    while True:
        done, _ = await asyncio.wait({task}, timeout=STOPPING_POLL_S)
        if done:
            return task.result()
        if SHUTTING_DOWN.is_set():
            task.add_done_callback(lambda t: t.cancelled() or t.exception())
            raise Unavailable(
                "the service is being stopped before the study's expansion finished: send it "
                f"again once the service is back (in {STOPPING_RETRY_S} s or more; the same "
                "study is one study, whether or not this one was stored)",
                headers={"Retry-After": str(STOPPING_RETRY_S)})


@router.get("", response_model=StudyList, summary="All studies, oldest first")
def list_studies(service: StudyService = Depends(get_service)) -> dict:
    return {"studies": [_with_urls(s) for s in service.list()]}


@router.get("/{study_id}", response_model=StudyStatus, summary="State and progress of a study")
def get_study(study_id: str, service: StudyService = Depends(get_service)) -> dict:
    return _with_urls(service.status(study_id))


#: Most ``filter=`` parameters of one request: more than a study has columns (about 400 with
#: six drives and eight curves), each a pass over the rows.
FILTERS_MAX = 500


@router.get(
    "/{study_id}/runs",
    response_model=RunsPage,
    response_model_exclude_unset=True,  # unreadable_parts and message: only when said
    summary="Run summary rows (SPEC section 4) as JSON, CSV or Parquet",
    responses=TABLE_RESPONSES,
)
def get_runs(
    study_id: str,
    request: Request,
    format: Literal["json", "csv", "parquet"] = Query("json", description="output format"),
    status: Literal["ok", "warning", "failed"] | None = Query(None, description="run status"),
    friction_model: str | None = Query(None, description="keep one friction model"),
    filter: list[str] = Query(
        default_factory=list, max_length=FILTERS_MAX,
        description=f"column=value, repeatable (axis or result column), at most {FILTERS_MAX}"
    ),
    sort: str | None = Query(
        None, max_length=200,
        description="order by this column (`-column`: descending); numbers as numbers, text "
        "as text, missing values last, ties in stored order"),
    columns: str | None = Query(
        None, max_length=20_000,
        description="comma-separated columns to return, in that order (default: every "
        "column; JSON rows then hold exactly these, te_<part>_kn unfolded)"),
    limit: int | None = Query(None, ge=1, le=100_000,
                              description="JSON only: rows per page"),
    offset: int = Query(0, ge=0, le=10_000_000, description="JSON only: first row"),
    service: StudyService = Depends(get_service),
):
    if format != "json":
        paged = [n for n in ("limit", "offset") if n in request.query_params]
        if paged:
            raise Invalid(f"query.{paged[0]}: paging is JSON only (format=json); a {format} "
                          "download holds every row the filters keep (narrow it with filter=)")
    wanted = list(filter)
    if status:
        wanted.append(f"status={status}")
    if friction_model:
        wanted.append(f"friction_model={query.model_name(friction_model, 'friction_model')}")
    names = order = None
    if columns is not None or sort is not None:
        known = service.store.runs_columns(study_id)
        names = query.column_list(columns, known) if columns is not None else None
        order = query.sort_key(sort, known) if sort is not None else None
    if names is None:
        df, bad = service.store.read_runs_readable(study_id)
    else:  # only the columns asked and those the filters and the order need
        for column in query.filter_columns(wanted):
            if column and column not in known:
                raise query.no_column("filter", column, known)
        need = names + [c for c in query.filter_columns(wanted) + [order[0] if order else ""]
                        if c and c not in names]
        df, bad = service.store.read_runs_readable(study_id, columns=list(dict.fromkeys(need)))
    if bad and format != "json":  # a file holds no word of the rows it lacks: refused
        raise DamagedParts(study_id, "runs", bad)
    if len(df):
        df = query.apply_filters(df, wanted)
    if order is not None:
        df = query.sort_rows(df, *order)
    if names is not None:
        df = df[names]
    # the study's state beside its rows: while it runs the table is partial (a file says it
    # in X-Study-State, a JSON page in state, done and study_runs)
    st = _state(service, study_id)
    if format != "json":
        schema = service.store.runs_schema(study_id) if format == "parquet" else None
        return _download(df, format, f"{study_id}-runs", schema=schema,
                         headers=_state_header(st))
    page = df.iloc[offset : offset + limit if limit else None]
    head = {"study_id": study_id, "state": st.get("state"), "done": st.get("done"),
            "study_runs": st.get("total"), "total": int(len(df)), "offset": offset,
            "limit": limit, **query.unreadable_fields(study_id, bad)}
    if not len(df) and "message" not in head:  # a filter on an axis's name, not its column
        head.update(query.axis_hint(wanted, st.get("axes") or {}))
    to_json = query.rows_to_json if names is None else query.records_to_json
    if len(page) > STREAM_ROWS:
        return StreamingResponse(_streamed_runs(head, page, to_json),
                                 media_type="application/json")
    return {**head, "runs": to_json(page)}


#: A JSON page of more rows than this is written out as it is encoded, a block of rows at a
#: time: built whole (and checked against the response model) the 19 764 rows of a large
#: study took about 1 GB of the server's memory per request for a 199 MB answer.
STREAM_ROWS = 2_000
STREAM_BLOCK = 500


def _streamed_runs(head: dict, page, to_json):
    """The page's JSON, ``{**head, "runs": [...]}``, in blocks of :data:`STREAM_BLOCK` rows
    (the same document as the whole answer)."""
    yield json.dumps(head, separators=(",", ":"))[:-1].encode() + b',"runs":['
    for i in range(0, len(page), STREAM_BLOCK):
        rows = to_json(page.iloc[i : i + STREAM_BLOCK])
        text = ",".join(json.dumps(r, separators=(",", ":"), allow_nan=False) for r in rows)
        yield (("," if i else "") + text).encode()
    yield b"]}"


@router.get(
    "/{study_id}/runs/{run_id}",
    response_model=RunDetail,
    summary="One run: summary row and key-point time series",
)
def get_run(study_id: str, run_id: str, service: StudyService = Depends(get_service)) -> dict:
    return service.run_detail(study_id, run_id)


@router.get(
    "/{study_id}/runs/{run_id}/surface",
    response_model=RunSurface,
    summary="One run's tension and velocity at every sampled spring and time (SPEC section 5)",
    description="Stored when the study has `surface: true`; otherwise recomputed from the "
    "run's stored inputs on request (runs are deterministic: the same table). JSON, CSV or "
    "Parquet (`run_id, t_s, s_m, tension_kn, velocity_m_s`, float32 values).",
    responses=TABLE_RESPONSES,
)
def get_run_surface(
    study_id: str,
    run_id: str,
    response: Response,
    format: Literal["json", "csv", "parquet"] = Query("json", description="output format"),
    service: StudyService = Depends(get_service),
):
    df, source = service.run_surface(study_id, run_id)
    reason = None if len(df) else service.no_surface_reason(study_id, run_id)
    return _run_table(df, source, "surface", study_id, run_id, format, response, reason)


@router.get(
    "/{study_id}/runs/{run_id}/profile",
    response_model=RunProfile,
    summary="One run's steady tension along the loop (the run page's steady figure)",
    description="Stored with the run by the worker; recomputed from the run's inputs (the "
    "steady solve only) for a run stored before profiles were. JSON, CSV or Parquet "
    "(`run_id, s_m, strand, elevation_m, tension_kn, sag_pct`).",
    responses=TABLE_RESPONSES,
)
def get_run_profile(
    study_id: str,
    run_id: str,
    response: Response,
    format: Literal["json", "csv", "parquet"] = Query("json", description="output format"),
    service: StudyService = Depends(get_service),
):
    df, source = service.run_profile(study_id, run_id)
    return _run_table(df, source, "profile", study_id, run_id, format, response)


def _run_table(df, source: str, what: str, study_id: str, run_id: str, format: str,
               response: Response, reason: str | None = None):
    """One run's table (``what``: surface or profile) as CSV, Parquet or JSON columns, with
    where it came from (stored or recomputed) in ``X-Beltstudy-<What>`` (every format) and
    the JSON; ``reason`` in the JSON says why a surface has no rows."""
    headers = {f"X-Beltstudy-{what.capitalize()}": source}
    response.headers.update(headers)  # the JSON answer's own headers
    if format != "json":
        return _download(df, format, f"{study_id}-{run_id}-{what}", headers)
    return {
        "study_id": study_id,
        "run_id": run_id,
        "source": source,
        "rows": int(len(df)),
        what: query.columns_to_json(df.drop(columns=["run_id"])) if len(df) else None,
        **({"reason": reason} if reason else {}),
    }


@router.get(
    "/{study_id}/accuracy",
    response_model=AccuracyOut,
    summary="Error bars of the study's sampled runs (accuracy: {sample}) and of each column",
    description="The accuracy table (one row per sampled run: `<figure>_err` in the "
    "figure's unit, `<figure>_converged`, the meshes and methods) as JSON, CSV or Parquet; "
    "the JSON also gives the error of each result column over the sample.",
    responses=TABLE_RESPONSES,
)
def get_accuracy(
    study_id: str,
    format: Literal["json", "csv", "parquet"] = Query("json", description="output format"),
    service: StudyService = Depends(get_service),
):
    acc, cols = service.accuracy(study_id)
    st = _state(service, study_id)
    if format != "json":
        return _download(acc, format, f"{study_id}-accuracy", headers=_state_header(st))
    study = service.study_doc(study_id).get("study") or {}
    return {
        "study_id": study_id,
        "state": st.get("state"),
        "sample": study.get("accuracy"),
        "total": int(len(acc)),
        "columns": query.records_to_json(cols),
        "runs": query.records_to_json(acc),
    }


@router.get(
    "/{study_id}/uncertainty",
    summary="A sampled study's distributions, exceedance probabilities and sensitivity "
    "ranking (SPEC 7.4; docs/uncertainty.md)",
)
def get_uncertainty(study_id: str, service: StudyService = Depends(get_service)) -> dict:
    return service.uncertainty(study_id)


@router.get(
    "/{study_id}/compare",
    response_model=CompareOut,
    summary="Runs that differ only in friction model: candidate / baseline ratios",
)
def compare(
    study_id: str,
    request: Request,
    baseline: str = Query(query.PAIR_DEFAULTS["baseline"], description="baseline friction model"),
    candidate: str = Query(query.PAIR_DEFAULTS["candidate"],
                           description="candidate friction model"),
    metrics: str = Query(
        ",".join(query.DEFAULT_METRICS), description="comma-separated numeric columns"
    ),
    service: StudyService = Depends(get_service),
) -> dict:
    names = metrics.split(",") if metrics else []
    if not all(names):  # as columns= and the command line's --metrics say it
        raise Invalid(f"metrics: an empty name in '{metrics}'; give result columns "
                      "comma-separated (metrics=power_kw,t_max_stop_kn), or leave the "
                      "parameter out for the defaults")
    # a model left out is its default, and said so ("(the default)") only then
    given = request.query_params
    return service.compare(study_id, baseline if "baseline" in given else None,
                           candidate if "candidate" in given else None, names)


@router.delete("/{study_id}", response_model=Deleted, summary="Cancel a study and delete its files")
def delete_study(study_id: str, service: StudyService = Depends(get_service)) -> dict:
    return service.delete(study_id)
