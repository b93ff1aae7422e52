"""The service's one error hierarchy: each error carries an HTTP status and a one-line message.

Routes raise these; one handler in :mod:`beltstudy.service.api.app` maps them to JSON responses
``{"error": <kind>, "message": <text>}``. The CLI prints ``user_message`` on one line.
"""

from __future__ import annotations

import errno
import os

__all__ = [
    "file_problem",
    "file_reason",
    "shown_path",
    "ServiceError",
    "Invalid",
    "NotFound",
    "Conflict",
    "TooLarge",
    "Unauthorized",
    "Unavailable",
    "UnsupportedMedia",
]


class ServiceError(Exception):
    """Base class: ``message`` for people, ``status_code`` for HTTP."""

    status_code = 500
    kind = "error"

    def __init__(self, message: str, status_code: int | None = None,
                 headers: dict[str, str] | None = None):
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


class UnsupportedMedia(ServiceError):
    """A request body in a media type the route does not read."""

    status_code = 415
    kind = "unsupported_media_type"


# ------------------------------------------------------------------ a user's file names
#: A file or folder name, and a whole path, at most this many bytes (Linux; the OS is asked
#: where it answers).
NAME_MAX, PATH_MAX = 255, 4096

#: Longest path shown whole in a message; a longer one is shortened in the middle.
SHOWN_MAX = 120


def shown_path(path: str | os.PathLike) -> str:
    """``path`` for a one-line message: whole up to :data:`SHOWN_MAX` characters, else its
    start and end with its length (``aaaa...aaa.yaml (5005 characters)``)."""
    text = os.fsdecode(path)
    if len(text) <= SHOWN_MAX:
        return text
    return f"{text[:60]}...{text[-50:]} ({len(text)} characters)"


def _limit(path: str, name: str, default: int) -> int:
    """The OS's limit ``name`` (``PC_NAME_MAX``) at the nearest folder of ``path`` that
    exists; ``default`` where it does not say."""
    folder = os.path.dirname(os.path.abspath(path)) or "/"
    while True:
        try:
            return os.pathconf(folder, name)
        except (OSError, ValueError):
            parent = os.path.dirname(folder)
            if parent == folder:
                return default
            folder = parent


def file_problem(exc: OSError, path: str | os.PathLike | None = None) -> str:
    """One line for an ``OSError`` on a file the user named: ``PATH: what is wrong; the
    fix`` (a name over the file system's limit, a missing folder, no permission, ...).
    ``path`` (what the user gave) is shown; default: the file the error names."""
    raw = path if path is not None else exc.filename
    text = os.fsdecode(raw) if raw is not None else ""
    return f"{shown_path(text)}: {file_reason(exc)}" if text else file_reason(exc)


def file_reason(exc: OSError) -> str:
    """What is wrong with the file of ``exc`` and the fix, without its name (lengths are
    measured on the path the error names)."""
    actual = os.fsdecode(exc.filename) if exc.filename is not None else ""
    if exc.errno == errno.ENAMETOOLONG and actual:
        name_max = _limit(actual, "PC_NAME_MAX", NAME_MAX)
        longest = max(actual.split(os.sep), key=lambda part: len(os.fsencode(part)))
        size = len(os.fsencode(longest))
        if size > name_max:
            return (f"file name too long: a name of {size} bytes, at most {name_max} per "
                    "file or folder name; give a shorter name")
        path_max = _limit(actual, "PC_PATH_MAX", PATH_MAX)
        return (f"path too long: {len(os.fsencode(actual))} bytes, at most {path_max}; give "
                "a shorter path")
    reasons = {
        errno.ENAMETOOLONG: "name too long; give a shorter name",
        errno.ENOENT: "no such file or folder; check the name",
        errno.ENOTDIR: "a part of the path is a file, not a folder; check the path",
        errno.EISDIR: "it is a folder; give a file name",
        errno.EACCES: "no permission; choose a file you may use",
        errno.EPERM: "no permission; choose a file you may use",
        errno.ELOOP: "too many symbolic links; check the path",
        errno.ENOSPC: "no space left on the device",
        errno.EROFS: "the file system is read-only; choose another folder",
    }
    return reasons.get(exc.errno) or exc.strerror or type(exc).__name__
