"""Reading a user's text file (conveyor, scenario, study, measurement CSV): the one place
that decides which encodings are taken.

Taken: UTF-8 with or without a byte order mark (Excel's "CSV UTF-8" writes one), and UTF-16
with its byte order mark (Windows Notepad's "Unicode"). Anything else, such as a Latin-1
comment (``# Förderband 30° Neigung``), is an :class:`~beltstudy.engine.errors.InputError`
naming the file, the first byte that is not UTF-8 and where it is, with the fix.
"""

from __future__ import annotations

import codecs
from pathlib import Path

from beltstudy.engine.errors import InputError

__all__ = ["read_text", "decode_text"]

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
    otherwise. Line ends are kept as they are."""
    if data.startswith(_UTF16_BOMS):
        try:
            return data.decode("utf-16")
        except UnicodeDecodeError as exc:
            raise InputError(
                f"{what}: not valid UTF-16 text (it starts with a UTF-16 byte order mark, but "
                f"byte {exc.start} does not decode): save it as UTF-8"
            ) from None
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
        if not p.is_file():
            raise InputError(f"{what}: file not found")
        data = p.read_bytes()
    except OSError as exc:
        raise InputError(f"{what}: cannot read it ({exc.strerror or type(exc).__name__})") \
            from None
    return decode_text(data, what)
