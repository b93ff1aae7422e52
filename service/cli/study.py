"""``beltstudy serve | submit | run | status | results | report | compare | demo``: studies.

``submit``, ``status``, ``results``, ``report`` and ``compare`` talk to a running service
(``--url``, default ``BELTSTUDY_URL`` or http://127.0.0.1:8000); ``status``, ``results``,
``report`` and ``compare`` read the local store (``BELTSTUDY_DATA_DIR``) when no service
answers at the default address (an address given by ``--url`` or ``BELTSTUDY_URL`` that does
not answer is an error naming it).
``run`` uses the same executor and store in-process, without HTTP. ``demo`` is ``make run``.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

from beltstudy.service.cli.client import ServiceClient
from beltstudy.service.cli.common import check_output, dumps, writing
from beltstudy.service.cli.console import ProgressBar, format_compare, format_status
from beltstudy.service.cli.demo import run_demo
from beltstudy.service.door.parse import expect_kind, load_mapping
from beltstudy.service.door.studyfile import study_body
from beltstudy.service.errors import Damaged, Invalid, ServiceError, Unavailable
from beltstudy.service.settings import load_settings
from beltstudy.service.store import query
from beltstudy.service.store.parquet import Store
from beltstudy.service.uncertainty import format_text as format_uncertainty

__all__ = ["register"]

DEFAULT_URL = "http://127.0.0.1:8000"


def register(sub) -> None:
    p = sub.add_parser(
        "serve",
        help="run the study service (REST API, Dask executor)",
        description="Run the study service; OpenAPI docs at /docs.",
    )
    p.add_argument(
        "--host", default=None, help="address to listen on (default: BELTSTUDY_HOST, 127.0.0.1)"
    )
    p.add_argument("--port", type=port_number, default=8000,
                   help="port to listen on (1 to 65535; default 8000)")
    p.set_defaults(func=cmd_serve)

    p = sub.add_parser(
        "submit", help="submit a study file to a running service",
        description="Submit a study file (YAML or JSON; its conveyor inlined) to a running "
        "service and print its id; --wait follows its progress to the end. The same study "
        "submitted again is the existing one.")
    p.add_argument("study", help="study file (YAML or JSON)")
    p.add_argument("--wait", action="store_true", help="show progress until the study ends")
    _client_args(p)
    p.set_defaults(func=cmd_submit)

    p = sub.add_parser(
        "run", help="run a study in this process (same executor and store)",
        description="Run a study file in this process, without a service: the same Dask "
        "executor (a LocalCluster) and the same store (BELTSTUDY_DATA_DIR), with a progress "
        "bar.")
    p.add_argument("study", help="study file (YAML or JSON)")
    p.set_defaults(func=cmd_run)

    p = sub.add_parser(
        "status", help="state and progress of one study or of all",
        description="State and progress of one study, or of every study. Asks the service "
        "(--url, BELTSTUDY_URL); when none answers at the default address, reads the local "
        "store (BELTSTUDY_DATA_DIR).")
    p.add_argument("id", nargs="?", help="study id (all studies when omitted)")
    p.add_argument("--json", action="store_true",
                   help="print the answer as JSON: GET /studies/{id}'s document, or "
                   "GET /studies's ({\"studies\": [...]}) for all")
    _client_args(p)
    p.set_defaults(func=cmd_status)

    p = sub.add_parser(
        "results", help="write a study's run rows to a file",
        description="Write a study's run summary rows (SPEC section 4) to a .parquet, .csv or "
        ".json file, from the service or, when none answers at the default address, the "
        "local store.")
    p.add_argument("id", help="study id")
    p.add_argument(
        "-o", "--output", required=True, help="output file: .parquet, .csv or .json (by extension)"
    )
    _client_args(p)
    p.set_defaults(func=cmd_results)

    p = sub.add_parser(
        "report",
        help="write a study's design report: one self-contained HTML page (prints to PDF)",
        description="Write a study's design report: one self-contained HTML page (verdicts, "
        "design basis, figures) that prints to PDF, from the service or the local store.",
    )
    p.add_argument("id", help="study id")
    p.add_argument("-o", "--output", required=True, help="output file (.html)")
    _client_args(p)
    p.set_defaults(func=cmd_report)

    p = sub.add_parser(
        "compare", help="candidate / baseline friction model ratios of a study",
        description="Pair each run of the candidate friction model with the baseline's run "
        "that differs only in the model, and print the ratios of the metrics (of magnitudes), "
        "overall and per axis value. Default: nonlin over cema.")
    p.add_argument("id", help="study id")
    # left out: None, so the answer says "(the default)" of that model only
    p.add_argument("--baseline", default=None,
                   help=f"baseline friction model (default: {query.PAIR_DEFAULTS['baseline']})")
    p.add_argument("--candidate", default=None,
                   help=f"candidate friction model (default: "
                   f"{query.PAIR_DEFAULTS['candidate']})")
    p.add_argument(
        "--metrics", default=None,
        help="comma-separated result columns (default: power_kw and the stop's peak and "
        "lowest tension, t_max_stop_kn and t_min_stop_kn, those a run of the study has)"
    )
    p.add_argument("--json", action="store_true",
                   help="print the whole answer as JSON (GET /studies/{id}/compare's document)")
    _client_args(p)
    p.set_defaults(func=cmd_compare)

    p = sub.add_parser(
        "uncertainty",
        help="a sampled study's distributions, exceedance probabilities and sensitivity "
        "ranking (docs/uncertainty.md)",
        description="A sampled study's distributions of the deciding figures, the probability "
        "that a run is past each design limit, and the sampled inputs ranked by their share "
        "of each figure's variance (docs/uncertainty.md).",
    )
    p.add_argument("id", help="study id")
    p.add_argument("--json", action="store_true", help="print the whole answer as JSON")
    _client_args(p)
    p.set_defaults(func=cmd_uncertainty)

    p = sub.add_parser(
        "demo",
        help="the main job (make run): start the service, submit "
        "studies/paper-comparison.yaml, show progress and the comparison",
        description="The main job (make run): start the service on a free port, submit the "
        "study, follow its progress and print the comparison.",
    )
    p.add_argument("--study", default="studies/paper-comparison.yaml",
                   help="study file (YAML or JSON; default: %(default)s)")
    p.add_argument("--port", type=lambda text: port_number(text, free=True), default=0,
                   help="service port, 0 to 65535 (default 0: a free one)")
    p.set_defaults(func=cmd_demo)


def _client_args(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--url", default=None, help=f"service address (default: BELTSTUDY_URL or {DEFAULT_URL})"
    )
    p.add_argument("--token", default=None, help="bearer token (default: BELTSTUDY_TOKEN)")


def _settings():
    return load_settings()


def port_number(text: str, *, free: bool = False) -> int:
    """argparse type of ``--port``: 1 to 65535 (0 too when ``free``: a free one)."""
    low = 0 if free else 1
    try:
        port = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a port number, got {text!r}") from None
    if not low <= port <= 65535:
        raise argparse.ArgumentTypeError(f"a port is {low} to 65535 (got {port})")
    return port


def _url(args) -> tuple[str, str]:
    """The service address and where it came from (``--url``, ``BELTSTUDY_URL`` or the
    default)."""
    if args.url:
        return args.url, "--url"
    if os.environ.get("BELTSTUDY_URL"):
        return os.environ["BELTSTUDY_URL"], "BELTSTUDY_URL"
    return DEFAULT_URL, ""


def _client(args):
    token = args.token if args.token is not None else _settings().token
    return ServiceClient(_url(args)[0], token)


# ------------------------------------------------------------------------------ commands
#: Longest wait for requests still being answered when the service is stopped [s].
GRACEFUL_SHUTDOWN_S = 5


def _service_log() -> None:
    """The service's own notes (Dask starting and warming, its dashboard, where a surface was
    recomputed) on stderr beside uvicorn's, from INFO up."""
    import logging

    logger = logging.getLogger("beltstudy")
    if not any(getattr(h, "_beltstudy", False) for h in logger.handlers):
        handler = logging.StreamHandler()
        handler.setFormatter(logging.Formatter("%(levelname)s:     %(name)s: %(message)s"))
        handler._beltstudy = True
        logger.addHandler(handler)
    logger.setLevel(logging.INFO)
    logger.propagate = False


def cmd_serve(args) -> int:
    # deferred: uvicorn, FastAPI and Dask load only for the server
    import uvicorn

    from beltstudy.service.api.app import create_app

    settings = _settings()
    host = args.host or settings.host
    # the port is tried before the app starts: uvicorn binds only after the app's startup,
    # which resumes the data directory's unfinished studies (and may start a LocalCluster),
    # and a port in use was then uvicorn's '[Errno 98] ...' and exit status 3
    check_port(host, args.port)
    # the data folder is tried before the app starts too, for a one-line refusal: another
    # process running its studies would run them twice (service.store.claim)
    from beltstudy.service.settings import check_data_dir
    from beltstudy.service.store.claim import DataDirClaim

    probe = DataDirClaim(check_data_dir(settings.data_dir))
    probe.take()
    probe.drop()
    _service_log()
    app = create_app(settings.model_copy(update={"host": host}))
    config = uvicorn.Config(app, host=host, port=args.port, log_level="info",
                            timeout_graceful_shutdown=GRACEFUL_SHUTDOWN_S)
    _stopping_server(uvicorn, config).run()
    return 0


def _stopping_server(uvicorn, config):
    """uvicorn's server that says it is stopping (``SHUTTING_DOWN``) as the signal comes, so
    a request still working (a study in expansion) answers 503 with Retry-After within the
    grace period, not uvicorn's plain-text 500 after it."""
    from beltstudy.service.api.deps import SHUTTING_DOWN

    class StoppingServer(uvicorn.Server):
        def handle_exit(self, sig, frame) -> None:
            SHUTTING_DOWN.set()
            super().handle_exit(sig, frame)

    return StoppingServer(config)


def check_port(host: str, port: int) -> None:
    """Bind ``host:port`` as uvicorn will (every address the name has, as asyncio's
    ``create_server`` does) and let go, or a :class:`ServiceError` naming the address and the
    way out (a port in use, an address this machine lacks)."""
    import errno
    import socket

    try:
        infos = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM,
                                   flags=socket.AI_PASSIVE)
    except socket.gaierror as exc:
        raise ServiceError(
            f"--host {host}: no such address ({exc.strerror}); give an "
            "address such as 127.0.0.1 (--host or BELTSTUDY_HOST)"
        ) from None
    for family, kind, proto, _, sockaddr in dict.fromkeys(infos):
        where = (f"[{sockaddr[0]}]:{port}" if family == socket.AF_INET6
                 else f"{sockaddr[0]}:{port}")
        with socket.socket(family, kind, proto) as sock:
            sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            if family == socket.AF_INET6:
                sock.setsockopt(socket.IPPROTO_IPV6, socket.IPV6_V6ONLY, 1)
            try:
                sock.bind(sockaddr)
            except OSError as exc:
                if exc.errno == errno.EADDRINUSE:
                    raise ServiceError(
                        f"--port {port}: {where} is already in use (another beltstudy "
                        "serve, or another program); stop it, or give another port with "
                        "--port"
                    ) from None
                raise ServiceError(
                    f"--host {host} --port {port}: cannot listen on {where} "
                    f"({exc.strerror}); give another address (--host or BELTSTUDY_HOST) or "
                    "port (--port)"
                ) from None


def cmd_submit(args) -> int:
    body = study_body(args.study)
    with _client(args) as client:
        try:
            st, created = client.submit(body)
        except ServiceError as exc:
            # the conveyor file went inlined, so the service names its fields as conveyor.*;
            # said as `run` says them, with the file the study names
            ref = _conveyor_ref(args.study)
            if ref and exc.status_code == 422 and exc.message.startswith("conveyor."):
                rest = exc.message[len("conveyor."):].replace("; conveyor.", "; ")
                exc.message = f"conveyor: {ref}: {rest}"
                exc.args = (exc.message,)
            raise
        print(
            f"{'submitted' if created else 'already submitted'}: {st['id']} "
            f"({_runs_text(st)}) {client.url}{st['status_url']}"
        )
        if not args.wait:
            return 0
        st = _poll(lambda: client.status(st["id"]), ProgressBar())
        _print_final(st)
    return 0 if st["state"] == "done" else 1


def _conveyor_ref(path) -> str:
    """The conveyor file a study file names ("" for an inline conveyor or an unreadable
    study)."""
    try:
        ref = load_mapping(Path(path)).get("conveyor")
    except (ServiceError, OSError, AttributeError):
        return ""
    return ref if isinstance(ref, str) else ""


def _print_final(st: dict) -> None:
    """The study's status line and, as ``status ID`` prints it, its message: the reason
    of a failed study (no Dask worker, ...) and what to do."""
    print(format_status(st))
    if st.get("message"):
        print(f"  {st['message']}")


def _runs_text(st: dict) -> str:
    """``12 runs`` or ``12 runs; 4 of 16 grid points merged into identical runs``, with the
    axes that change no run named (``brakes.0.delay_s changes no run``)."""
    text = f"{st['total']} runs"
    if st.get("merged"):
        text += f"; {st['merged']} of {st['grid_points']} grid points merged into identical runs"
        inert = st.get("merged_axes") or []
        if inert:
            verb = "changes" if len(inert) == 1 else "change"
            steady = "" if st.get("dynamics", True) else "; the study runs steady only"
            text += (f": {', '.join(inert)} {verb} no run of this study (null in every "
                     f"row{steady})")
    return text


def _poll(get, progress, poll_s: float = 1.0) -> dict:
    while True:
        st = get()
        progress(st)
        if st["state"] not in ("queued", "running"):
            return st
        time.sleep(poll_s)


def cmd_run(args) -> int:
    # deferred: the service's Dask stack loads only for the commands that use it
    from beltstudy.service.studies import StudyService

    settings = _settings()
    service = StudyService(settings.model_copy(update={"warm_start": False}))
    p = Path(args.study)
    data = load_mapping(p)
    expect_kind(data, "study", str(p))
    try:
        st, created = service.submit(data, base_dir=p.parent, confine=False)
        print(
            f"{'study' if created else 'existing study'} {st['id']} ({_runs_text(st)}), "
            f"data in {Store(settings.data_dir).study_dir(st['id'])}",
            file=sys.stderr,
        )
        st = service.wait(st["id"], progress=ProgressBar())
    finally:
        service.close()
    _print_final(st)
    return 0 if st["state"] == "done" else 1


def _local_service():
    """Store-only access when no service answers (no Dask is started)."""
    # deferred: the service's Dask stack loads only for the commands that use it
    from beltstudy.service.studies import StudyService

    return StudyService(_settings().model_copy(update={"warm_start": False}), read_only=True)


def _with_fallback(args, remote, local):
    """``remote(client)``; when the default address does not answer, ``local(service)`` on
    the local store. An address given (``--url`` or ``BELTSTUDY_URL``) that does not answer
    is an error naming it and where it came from."""
    try:
        with _client(args) as client:
            return remote(client)
    except Unavailable as exc:
        source = _url(args)[1]
        if source == "--url":
            raise
        if source:
            raise Unavailable(f"{exc.message} (the address is {source}'s; unset it to read "
                              "the local store instead)") from None
        return local(_local_service())


#: Said under an offline status whose studies the store calls queued or running: no service
#: answers, so nothing runs them until one starts on the data dir (it resumes them).
NOT_RUNNING = ("no service answers: the queued or running studies above are not running now; a "
               "service started on this data dir resumes them where they stopped (beltstudy "
               "serve)")


def cmd_status(args) -> int:
    from beltstudy.service.studies import ACTIVE_STATES

    offline: list[bool] = []

    def local(read):
        def call(service):
            offline.append(True)
            return read(service)
        return call

    if args.id:
        st = _with_fallback(args, lambda c: c.status(args.id),
                            local(lambda s: s.status(args.id)))
        if args.json:
            print(dumps(st))
            return 0
        print(format_status(st))
        if st.get("message"):
            print(f"  {st['message']}")
        if offline and st.get("state") in ACTIVE_STATES:
            print(f"  {NOT_RUNNING}")
        return 0
    studies = _with_fallback(args, lambda c: c.list(), local(lambda s: s.list()))
    if args.json:
        print(dumps({"studies": studies}))
        return 0
    if not studies:
        print("no studies")
    for st in studies:
        print(format_status(st))
        if st.get("state") == "damaged":  # its study.json unreadable: the file and the way out
            print(f"  {st.get('message', '')}")
    if offline and any(st.get("state") in ACTIVE_STATES for st in studies):
        print(NOT_RUNNING)
    return 0


def cmd_results(args) -> int:
    out = Path(args.output)
    fmt = {".parquet": "parquet", ".csv": "csv", ".json": "json"}.get(out.suffix.lower())
    if fmt is None:
        raise Invalid(f"-o {out}: use a .parquet, .csv or .json file name")
    check_output(out, "-o")

    def local(service):
        if fmt == "parquet":
            return query.to_parquet(service.runs(args.id), service.store.runs_schema(args.id))
        if fmt == "csv":
            return query.to_csv(service.runs(args.id)).encode()
        # the document GET /studies/{id}/runs answers (every row, unpaged; the rows of the
        # readable parts, naming any damaged one), as the service writes it: a file made
        # without a service reads as one made with it
        df, bad = service.store.read_runs_readable(args.id)
        try:
            st = service.status(args.id)
        except Damaged:  # the rows are still written, as before the state was added
            st = {}
        doc = {"study_id": args.id, "state": st.get("state"), "done": st.get("done"),
               "study_runs": st.get("total"), "total": int(len(df)), "offset": 0,
               "limit": None,
               "runs": query.rows_to_json(df), **query.unreadable_fields(args.id, bad)}
        return json.dumps(doc, ensure_ascii=False, allow_nan=False,
                          separators=(",", ":")).encode()

    data = _with_fallback(args, lambda c: c.runs(args.id, fmt), local)
    with writing(out):
        out.write_bytes(data)
    print(f"wrote {out} ({len(data)} bytes)")
    if fmt == "json" and b',"unreadable_parts":' in data:  # a key, never inside a string
        print(f"note: runs part files of study {args.id} cannot be read (damaged on disk): "
              f"{out} holds the runs of the other parts; its unreadable_parts and message "
              "name the files and the way out", file=sys.stderr)
    _note_unfinished(args, "the file holds the runs finished so far")
    return 0


def _note_unfinished(args, what: str) -> None:
    """A line on stderr when the study is still queued or running: what was written is not
    the whole study."""
    st = _with_fallback(args, lambda c: c.status(args.id), lambda s: s.status(args.id))
    if st.get("state") in ("queued", "running"):
        print(f"note: study {args.id} is {st['state']} ({st.get('done', 0)} of "
              f"{st.get('total', '?')} runs done): {what}; write it again when "
              "'beltstudy status' says done", file=sys.stderr)


def cmd_report(args) -> int:
    out = Path(args.output)
    if out.suffix.lower() not in (".html", ".htm"):
        raise Invalid(f"-o {out}: the report is HTML; use a .html file name")
    check_output(out, "-o")

    def local(service):
        # deferred: the report's pages load the service's Dask stack
        from beltstudy.service.web.report import build_report

        return build_report(service, args.id)

    text = _with_fallback(args, lambda c: c.report(args.id), local)
    with writing(out):
        out.write_text(text, encoding="utf-8")
    print(f"wrote {out} ({len(text.encode())} bytes): open it in a browser, print to PDF")
    _note_unfinished(args, "the report covers the runs finished so far")
    return 0


def _as_option(message: str, names: tuple[str, ...]) -> str:
    """A service error that starts with one of its parameter ``names`` (``metrics: ...``)
    said with the command line's option (``--metrics: ...``)."""
    for name in names:
        if message.startswith(f"{name}:"):
            return f"--{message}"
    return message


def cmd_compare(args) -> int:
    metrics = [] if args.metrics is None else [m.strip() for m in args.metrics.split(",")]
    if args.metrics is not None and not all(metrics):
        raise Invalid(f"--metrics: an empty name in '{args.metrics}'; give result columns "
                         "comma-separated (e.g. --metrics power_kw,t_max_stop_kn), or leave "
                         "--metrics out for the defaults")
    try:
        result = _with_fallback(
            args,
            lambda c: c.compare(args.id, args.baseline, args.candidate, metrics),
            lambda s: s.compare(args.id, args.baseline, args.candidate, metrics),
        )
    except ServiceError as exc:
        # the service names its parameters (metrics: ...); here they are options
        exc.message = _as_option(exc.message, ("metrics", "baseline", "candidate"))
        raise
    print(dumps(result) if args.json else format_compare(result))
    return 0


def cmd_uncertainty(args) -> int:
    result = _with_fallback(args, lambda c: c.uncertainty(args.id),
                            lambda s: s.uncertainty(args.id))
    print(dumps(result) if args.json else format_uncertainty(result))
    return 0


def cmd_demo(args) -> int:
    return run_demo(args.study, port=args.port)
