"""Reading a user's text file (conveyor, scenario, study, measurement CSV): the one place
that decides which encodings are taken.

Taken: UTF-8 with or without a byte order mark (Excel's "CSV UTF-8" writes one), and UTF-16
with its byte order mark (Windows Notepad's "Unicode"). Anything else, such as a Latin-1
comment (``# Förderband 30° Neigung``), is an :class:`~beltstudy.engine.errors.InputError`
naming the file, the first byte that is not UTF-8 and where it is, with the fix.
"""

from __future__ import annotations

import codecs
import errno
import os
from pathlib import Path

from beltstudy.engine.errors import InputError

__all__ = ["read_text", "decode_text", "file_problem", "file_reason", "shown_path"]

_UTF16_BOMS = (codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE)


def _where(data: bytes, start: int) -> tuple[int, int]:
    """Line and column (1-based, the column in characters) of byte ``start`` of ``data``."""
    line = data.count(b"\n", 0, start) + 1
    begin = data.rfind(b"\n", 0, start) + 1
    column = len(data[begin:start].decode("utf-8", errors="replace")) + 1
    return line, column


def decode_text(data: bytes, what: str) -> str:
    """``data`` as text: UTF-8 (a leading byte order mark dropped) or UTF-16 with its byte
    order mark; :class:`InputError` ``WHAT: not UTF-8 text (...): save it as UTF-8``
    otherwise. Line ends are kept as they are. UTF-32 (its byte order mark, read before
    UTF-16's, whose mark begins it) and text with NUL bytes (UTF-16 or UTF-32 without a mark,
    which decodes as UTF-8 with a NUL between letters: the user was told of an unknown column
    ``'l\\0o\\0a\\0d\\0'``) are refused naming the encoding."""
    if data.startswith((codecs.BOM_UTF32_LE, codecs.BOM_UTF32_BE)):
        raise InputError(f"{what}: UTF-32 text (it starts with a UTF-32 byte order mark): "
                         "save it as UTF-8")
    if data.startswith(_UTF16_BOMS):
        try:
            return data.decode("utf-16")
        except UnicodeDecodeError as exc:
            raise InputError(
                f"{what}: not valid UTF-16 text (it starts with a UTF-16 byte order mark, but "
                f"byte {exc.start} does not decode): save it as UTF-8"
            ) from None
    nul = data.find(b"\x00")
    if nul >= 0:
        line, column = _where(data, nul)
        wide = ("UTF-16 or UTF-32 without a byte order mark, by the NUL bytes between its "
                "letters" if data[1::2].count(0) > len(data) // 4 or data[::2].count(0)
                > len(data) // 4 else "binary data, not text")
        raise InputError(f"{what}: a NUL byte at line {line}, column {column}: {wide}; "
                         "save it as UTF-8")
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        bom = len(codecs.BOM_UTF8) if data.startswith(codecs.BOM_UTF8) else 0
        start = exc.start + bom
        line, column = _where(data, start)
        raise InputError(
            f"{what}: not UTF-8 text (byte 0x{data[start]:02x} at line {line}, column "
            f"{column}): save it as UTF-8"
        ) from None


def read_text(path: str | Path, what: str | None = None) -> str:
    """The text of the file at ``path`` (encodings: :func:`decode_text`); errors start with
    ``what`` (default: the path)."""
    p = Path(path)
    what = what or str(p)
    try:
        if p.is_dir():
            raise InputError(f"{what}: is a folder, not a file; give a file in it")
        if p.exists() and not p.is_file():
            raise InputError(f"{what}: not a regular file (a device or a pipe); give a file")
        if not p.is_file():
            raise InputError(f"{what}: file not found")
        data = p.read_bytes()
    except OSError as exc:
        raise InputError(f"{what}: cannot read it: {file_reason(exc)}") from None
    return decode_text(data, what)


# ------------------------------------------------------------------ a user's file names
# (here, where the engine reads them; the service's errors re-export them)
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
