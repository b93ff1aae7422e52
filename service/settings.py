"""Service settings: one pydantic-settings object, each field also a ``BELTSTUDY_*`` variable.

| variable | default | meaning |
|---|---|---|
| ``BELTSTUDY_DATA_DIR`` | ``./data`` | root of the Parquet store (empty: ``./data``) |
| ``BELTSTUDY_SCHEDULER`` | empty | ``tcp://host:port`` of a Dask scheduler; empty = LocalCluster |
| ``BELTSTUDY_WORKERS`` | cores | LocalCluster worker processes (one thread each) |
| ``BELTSTUDY_TOKEN`` | empty | bearer token every route but ``/health`` requires when set |
| ``BELTSTUDY_MAX_RUNS`` | 20000 | largest study accepted |
| ``BELTSTUDY_HOST`` | 127.0.0.1 | address ``beltstudy serve`` listens on (``--host``) |
| ``BELTSTUDY_DASHBOARD`` | false | serve the LocalCluster's Dask dashboard on the host |
| ``BELTSTUDY_DASK_TIMEOUT_S`` | 5 | longest wait on the Dask scheduler (connect, cancel, close) |
| ``BELTSTUDY_MAX_EXPANSIONS`` | 1 | studies expanded and validated at once (further: wait, then 503) |
| ``BELTSTUDY_EXPANSION_WAIT_S`` | 30 | longest a submission waits for an expansion slot |

The full table is in the README.
"""

from __future__ import annotations

import os
from functools import lru_cache
from pathlib import Path

from pydantic import Field, ValidationError, field_validator
from pydantic_core import PydanticCustomError
from pydantic_settings import BaseSettings, SettingsConfigDict

from beltstudy.service.errors import Invalid, file_reason, shown_path

__all__ = ["Settings", "get_settings", "load_settings", "check_data_dir", "ENV_PREFIX",
           "unknown_variables", "data_dir_setting", "DEFAULT_DATA_DIR"]

ENV_PREFIX = "BELTSTUDY_"
#: The store's folder when ``BELTSTUDY_DATA_DIR`` is not set or empty.
DEFAULT_DATA_DIR = Path("./data")


class Settings(BaseSettings):
    """Everything the service reads from its environment."""

    model_config = SettingsConfigDict(env_prefix=ENV_PREFIX, extra="ignore")

    data_dir: Path = Field(DEFAULT_DATA_DIR, description="root of the Parquet store (empty: "
                           "the default, ./data)")
    scheduler: str = Field(
        "", description="Dask scheduler address tcp://host:port; empty starts a LocalCluster"
    )
    workers: int | None = Field(
        None, ge=1, le=512, description="LocalCluster worker processes (default: one per core)"
    )
    token: str = Field("", description="bearer token required by every route but /health")
    max_runs: int = Field(20_000, ge=1, description="largest study accepted, in grid points (before identical runs merge)")
    studies_dir: Path = Field(
        Path("./studies"),
        description="the study files directory (the repository's studies/): conveyor paths "
        "given as strings in POST /studies bodies are read from inside it; not the store's "
        "study data, which is under data_dir/studies",
    )
    max_body_bytes: int = Field(1_000_000, ge=1024, description="largest request body [bytes]")
    warm_start: bool = Field(
        True, description="start and warm the Dask workers when the service starts"
    )
    task_seconds: float = Field(1.0, gt=0, description="target work per Dask task [s]")
    host: str = Field(
        "127.0.0.1",
        description="address `beltstudy serve` listens on; the Dask dashboard (when on) binds "
        "to it too",
    )
    dashboard: bool = Field(
        False,
        description="serve the Dask dashboard of the LocalCluster (no token: it shows task "
        "names, worker addresses and logs) on the service's host, port dashboard_port",
    )
    dashboard_port: int = Field(
        8787, ge=0, le=65535, description="dashboard port (0 or a taken port: a free one)"
    )
    dask_timeout_s: float = Field(
        5.0,
        gt=0,
        le=300,
        description="longest the service waits on the Dask scheduler: to connect, and when it "
        "deletes a study or shuts down [s]",
    )

    max_expansions: int = Field(
        1, ge=1, le=64,
        description="studies expanded and validated at once (POST /studies); further ones "
        "wait up to expansion_wait_s, then get 503 with Retry-After. Expansion is Python "
        "work in the service's threads, which share one interpreter lock: a second one at "
        "once finishes no sooner and slows every other answer (measured in "
        "benchmarks/bench_submit.py)",
    )
    expansion_wait_s: float = Field(
        30.0, gt=0, le=600,
        description="longest a submission waits for an expansion slot, or for the same body "
        "being expanded by another request [s]",
    )

    @field_validator("scheduler")
    @classmethod
    def _dask_address(cls, value: str) -> str:
        value = value.strip()
        if value:
            problem = scheduler_problem(value)
            if problem:
                raise PydanticCustomError(
                    "scheduler_address",
                    "must be a Dask scheduler address such as tcp://127.0.0.1:8786: "
                    "{problem}", {"problem": problem})
        return value

    @field_validator("token")
    @classmethod
    def _sendable_token(cls, value: str) -> str:
        # HTTP strips the blanks round a header's value, so a token with a space (a trailing
        # one from a .env or compose file) could never be sent: every client locked out
        if value and not all("!" <= ch <= "~" for ch in value):
            raise PydanticCustomError(
                "token", "a token is printable ASCII (letters, digits and punctuation), "
                "without spaces, line breaks or other characters: no client could send it "
                "in an Authorization header (check for a trailing space)")
        return value

    @field_validator("workers", mode="before")
    @classmethod
    def _empty_is_default(cls, value):
        return None if value in ("", None) else value

    @field_validator("data_dir", mode="before")
    @classmethod
    def _empty_data_dir_is_default(cls, value):
        # empty means not set, as for BELTSTUDY_SCHEDULER and BELTSTUDY_TOKEN: an
        # ``export BELTSTUDY_DATA_DIR=$UNSET`` was read as Path(""), the current folder, and a
        # 'beltstudy run' in a project folder put studies/<id>/ and bodies/ among the
        # user's own study files
        if isinstance(value, str) and not value.strip():
            return DEFAULT_DATA_DIR
        return value

    @property
    def n_local_workers(self) -> int:
        return self.workers or os.cpu_count() or 1


#: The address schemes of Dask's comms (``distributed.comm.registry``; no scheme is tcp).
DASK_SCHEMES = ("tcp", "tls", "ucx", "ws", "wss", "inproc")


def scheduler_problem(address: str) -> str:
    """What keeps Dask from reaching a scheduler at ``address`` whatever runs there ("" for
    none): a scheme Dask has no comm for (``http://``), no host, a port outside 1 to 65535.
    Such an address was retried for ever ('unknown address scheme', 'Timed out trying to
    connect'); the network is not asked here."""
    scheme, sep, rest = address.partition("://")
    if not sep:
        scheme, rest = "tcp", address
    if scheme not in DASK_SCHEMES:
        return f"'{scheme}' is not a Dask scheme ({', '.join(DASK_SCHEMES)})"
    if scheme == "inproc":
        return ""
    if rest.startswith("["):  # [IPv6]:port
        host, _, tail = rest[1:].partition("]")
        port = tail[1:] if tail.startswith(":") else None
    elif rest.count(":") == 1:
        host, port = rest.split(":")
    else:  # a bare host (Dask's default port) or an IPv6 address without brackets
        host, port = rest, None
    if not host.strip("/"):
        return "no host"
    if port is None and scheme in ("tcp", "tls") and not rest.startswith("["):
        # Dask: 'missing port number in address', retried every 5 s for ever
        return "no port (host:port; a Dask scheduler listens on 8786 unless told otherwise)"
    if port is not None and not (port.isdigit() and 1 <= int(port) <= 65535):
        return "a port is 1 to 65535"
    return ""


#: What a setting of each type must be, in words (pydantic's error types).
_MUST_BE = {
    "int_parsing": "must be an integer",
    "int_from_float": "must be an integer",
    "float_parsing": "must be a number",
    "bool_parsing": "must be true or false",
    "finite_number": "must be a finite number",
}


def _setting_problem(err: dict) -> str:
    """``BELTSTUDY_MAX_RUNS: must be an integer (got 'abc')`` for one pydantic error."""
    field = str(err["loc"][0]) if err.get("loc") else ""
    reason = _MUST_BE.get(err["type"]) or err["msg"].replace("Input should be", "must be")
    if field == "token":  # a secret: its length, not its value, goes to the log
        return (f"{ENV_PREFIX}{field.upper()}: {reason} (got {len(str(err.get('input')))} "
                "characters, not shown)")
    return f"{ENV_PREFIX}{field.upper()}: {reason} (got {err.get('input')!r})"


def load_settings(**over) -> Settings:
    """The settings from the environment; a bad value is :class:`Invalid` naming the variable,
    what it must be and what it was (one line: the CLI prints it and exits with status 2)."""
    try:
        return Settings(**over)
    except ValidationError as exc:
        raise Invalid("; ".join(dict.fromkeys(_setting_problem(e) for e in exc.errors()))
                      ) from None


def check_data_dir(path: str | os.PathLike, *, write: bool = True) -> Path:
    """``BELTSTUDY_DATA_DIR`` as a folder the store can use: an existing folder it may write
    in, or a path whose nearest existing part is such a folder (the store creates the rest).
    Anything else is :class:`Invalid` naming the variable, the path and the fix (one line:
    the service refuses to start, exit status 2). ``write=False``: a store only read (a
    command's local read of an archived, read-only store) need not be writable."""
    root = Path(path)
    where = f"{ENV_PREFIX}DATA_DIR: {shown_path(root)}"
    probe = root
    try:
        while not probe.exists():  # the nearest part of the path that exists
            if probe.parent == probe:
                break
            probe = probe.parent
        if probe.exists() and not probe.is_dir():
            what = "is a file" if probe == root else f"is under {shown_path(probe)}, a file"
            raise Invalid(f"{where} {what}, not a folder; give a folder for the store (it is "
                          "created if missing)")
        if write and probe.exists() and not os.access(probe, os.W_OK | os.X_OK):
            raise Invalid(f"{where}: no permission to write in {shown_path(probe)}; give a "
                          "folder the service may write in")
    except OSError as exc:  # a name over the file system's limits, a folder we may not read
        raise Invalid(f"{where}: {file_reason(exc)}") from None
    return root


def data_dir_setting() -> Path:
    """The store's folder the environment names (``BELTSTUDY_DATA_DIR``, empty or unset:
    ``./data``), for a command that writes files the user names and must keep them out of
    the store (:func:`beltstudy.service.cli.common.check_output`). Another setting being bad
    does not stop it: ``beltstudy static`` reads no other, and the commands that do say it."""
    try:
        return load_settings().data_dir
    except Invalid:
        raw = os.environ.get(f"{ENV_PREFIX}DATA_DIR", "")
        return Path(raw) if raw.strip() else DEFAULT_DATA_DIR


@lru_cache(maxsize=1)
def get_settings() -> Settings:
    """The process-wide settings (read once from the environment)."""
    return load_settings()


#: Variables of the prefix that are not settings but are read elsewhere (the CLI's service
#: address).
OTHER_VARIABLES = ("URL",)


def unknown_variables(environ=None) -> list[str]:
    """A line for each ``BELTSTUDY_*`` variable in the environment that no part of beltstudy
    reads (a misspelt setting is otherwise ignored in silence), with the nearest name."""
    import difflib

    environ = os.environ if environ is None else environ
    known = [f"{ENV_PREFIX}{name.upper()}" for name in Settings.model_fields]
    known += [f"{ENV_PREFIX}{name}" for name in OTHER_VARIABLES]
    lines = []
    for name in sorted(environ):
        if not name.upper().startswith(ENV_PREFIX) or name.upper() in known:
            continue
        near = difflib.get_close_matches(name.upper(), known, n=1, cutoff=0.6)
        hint = f"; did you mean {near[0]}?" if near else f"; the settings are {', '.join(known)}"
        lines.append(f"{name}: not a beltstudy setting, ignored{hint}")
    return lines
