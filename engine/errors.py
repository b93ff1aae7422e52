"""The engine's one error type for user input (its own module so that every engine module,
the input models and the catalogues alike, can raise it without importing the other), and
:func:`shown_text`, which keeps a message that repeats the user's input to a readable length."""

from __future__ import annotations

import re

__all__ = ["InputError", "shown_text", "ECHO_MAX", "MESSAGE_MAX"]

#: Longest run of characters without a space (a value, a key, a JSON echo) a message repeats
#: whole; a longer one keeps its start and end and says its length.
ECHO_MAX = 300
#: Longest message said whole; a longer one keeps its start and end and says its length.
MESSAGE_MAX = 5000
_LONG_RUN = re.compile(rf"\S{{{ECHO_MAX + 1},}}")
#: A long run's quotes and brackets before it and its quotes, brackets and colon after it:
#: kept whole, so the length said is the value's own.
_WRAP = re.compile(r"^([\"'(\[{]*)(.*?)([\"')\]}:;,.]*)$", re.S)


def _cut(text: str, head: int, tail: int) -> str:
    return f"{text[:head]}...{text[-tail:]} ({len(text)} characters)"


def _cut_run(run: str) -> str:
    before, core, after = _WRAP.match(run).groups()
    return f"{before}{_cut(core, 60, 40)}{after}" if len(core) > ECHO_MAX else run


def shown_text(message: str) -> str:
    """``message`` as an error says it: every run of more than :data:`ECHO_MAX` characters
    without a space (its quotes, brackets and trailing colon apart) shortened to its first 60
    and last 40 characters and its length, and the whole cut to :data:`MESSAGE_MAX`
    characters the same way. A 300 000-character name or key was echoed whole (a 300 kB, or
    600 kB, one-line message)."""
    text = _LONG_RUN.sub(lambda m: _cut_run(m.group(0)), str(message))
    return text if len(text) <= MESSAGE_MAX else _cut(text, 3000, 1000)


class InputError(ValueError):
    """A user input problem: the message names the field and the fix (one line).

    ``InputError(reason, field="models.din.f_carry")`` reads ``models.din.f_carry: reason``;
    ``field`` and ``reason`` stay apart as attributes, so a caller that knows the field by
    another name (a grid axis, the design case) can name it its own way. The message repeats
    no input whole past :func:`shown_text`'s lengths.
    """

    def __init__(self, reason: str, *, field: str | None = None):
        reason = shown_text(reason)
        field = None if field is None else shown_text(field)
        super().__init__(shown_text(f"{field}: {reason}" if field else reason))
        self.field = field
        self.reason = reason
