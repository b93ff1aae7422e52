"""The service's one error hierarchy: each error carries an HTTP status and a one-line message.

Routes raise these; one handler in :mod:`beltstudy.service.api.app` maps them to JSON responses
``{"error": <kind>, "message": <text>}``. The CLI prints ``user_message`` on one line.
"""

from __future__ import annotations

import os
import re

from beltstudy.engine.errors import shown_text
from beltstudy.engine.textfile import file_problem, file_reason, shown_path

__all__ = [
    "file_problem",
    "file_reason",
    "shown_path",
    "shown_id",
    "ServiceError",
    "Invalid",
    "NotFound",
    "Conflict",
    "TooLarge",
    "Unauthorized",
    "Unavailable",
    "UnsupportedMedia",
    "Damaged",
    "DamagedParts",
]


#: Longest id a message repeats whole: study and run ids are 16 hex digits.
SHOWN_ID_MAX = 40


def shown_id(text: str) -> str:
    """An id as a message repeats it: whole up to :data:`SHOWN_ID_MAX` characters, else its
    start and its length (a 100 kB id is not echoed back)."""
    text = str(text)
    if len(text) <= SHOWN_ID_MAX:
        return text
    return f"{text[:16]}... ({len(text)} characters)"


#: What a study id is and where the ids are, for an id that cannot be one (``../x``).
STUDY_ID_FORM = ("a study id is 16 lower-case hexadecimal digits, as POST /studies "
                 "answers it; GET /studies (beltstudy status) lists the studies")


def bad_study_id(study_id: str) -> str:
    """The message of an id that cannot be a study's: the id, its form and the list."""
    return f"study '{shown_id(study_id)}' not found: {STUDY_ID_FORM}"


def unknown_run(study_id: str, run_id: str) -> str:
    """The message of a run id the study has not: the ids, what a run id is when ``run_id``
    cannot be one (``A8D7...``: upper case), and where the study's run ids are listed."""
    run, study = shown_id(run_id), shown_id(study_id)
    where = f"GET /studies/{study}/runs?columns=run_id (beltstudy results {study} -o runs.csv) lists them"
    if re.fullmatch(r"[0-9a-f]{16}", str(run_id)):
        return f"run '{run}' of study '{study}' not found; its run ids: {where}"
    return (f"run '{run}' of study '{study}' not found: a run id is 16 lower-case "
            f"hexadecimal digits; {where}")


class ServiceError(Exception):
    """Base class: ``message`` for people, ``status_code`` for HTTP."""

    status_code = 500
    kind = "error"

    def __init__(self, message: str, status_code: int | None = None,
                 headers: dict[str, str] | None = None):
        message = shown_text(message)  # a 300 kB value given is not echoed whole
        super().__init__(message)
        self.message = message
        self.headers = headers  # extra response headers (Retry-After of a 503)
        if status_code is not None:
            self.status_code = status_code

    @property
    def user_message(self) -> str:
        return self.message


class Invalid(ServiceError):
    """The study or request is invalid (names the field)."""

    status_code = 422
    kind = "invalid"


class NotFound(ServiceError):
    status_code = 404
    kind = "not_found"


class Conflict(ServiceError):
    """The request clashes with what the service is doing (a study being deleted)."""

    status_code = 409
    kind = "conflict"


class TooLarge(ServiceError):
    """A body or a study grid over the configured limit."""

    status_code = 413
    kind = "too_large"


class Unauthorized(ServiceError):
    status_code = 401
    kind = "unauthorized"


class Unavailable(ServiceError):
    """The Dask cluster cannot be reached."""

    status_code = 503
    kind = "unavailable"


class Damaged(ServiceError):
    """A study's stored ``study.json`` cannot be read (edited or truncated outside the
    service, which writes it atomically): a 500 naming the file, with the way out."""

    status_code = 500
    kind = "damaged"

    def __init__(self, study_id: str, path, why: str):
        super().__init__(
            f"study '{shown_id(study_id)}': its stored document {path} cannot be read ({why}); "
            f"nothing else of the study was changed: restore the file from a backup, or "
            f"delete the study (DELETE /studies/{shown_id(study_id)}, which works without it) "
            "and submit it again")


#: Damaged part files a message names one by one; the rest are counted.
SHOWN_PARTS = 3


class DamagedParts(ServiceError):
    """Part files of a study's table (``runs``, ``timeseries``, ...) that Arrow cannot read:
    truncated or overwritten outside the service, which writes each part whole under a
    temporary name and renames it. A 500 naming the study, the files and why, with the ways
    out; ``parts`` holds ``(path, why)`` of each."""

    status_code = 500
    kind = "damaged"

    def __init__(self, study_id: str, table: str, parts: list[tuple[object, str]]):
        self.parts = list(parts)
        super().__init__(damaged_parts_message(study_id, table, self.parts))


def damaged_parts_message(study_id: str, table: str, parts: list[tuple[object, str]]) -> str:
    """What :class:`DamagedParts` says: the study, each damaged file (the first
    :data:`SHOWN_PARTS`) with why it cannot be read, that nothing was changed, and what to
    do: restore the file, or move it out of the folder (the study then reads without the rows
    it held, and submitted again runs them anew), or delete the study and submit it again
    (every run anew)."""
    sid = shown_id(study_id)
    named = "; ".join(f"{path} ({why})" for path, why in parts[:SHOWN_PARTS])
    more = (f"; and {len(parts) - SHOWN_PARTS} more"
            if len(parts) > SHOWN_PARTS else "")
    files = "file" if len(parts) == 1 else "files"
    folder = os.path.dirname(str(parts[0][0])) if parts else table
    return (f"study '{sid}': {len(parts)} {table} part {files} cannot be read: {named}{more}; "
            "the service writes each part whole (a temporary name, then renamed), so it was "
            "damaged on disk afterwards; nothing of the study was changed by the service: "
            f"restore the {files} from a backup, or move {'it' if len(parts) == 1 else 'them'}"
            f" out of {folder} (the study is then read without the rows "
            f"{'it holds' if len(parts) == 1 else 'they hold'}, and the same study submitted "
            "again runs those runs anew), or delete the study "
            f"(DELETE /studies/{sid}) and submit it again to run every run anew")


class UnsupportedMedia(ServiceError):
    """A request body in a media type the route does not read."""

    status_code = 415
    kind = "unsupported_media_type"
