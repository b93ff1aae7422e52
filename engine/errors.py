"""The engine's one error type for user input (its own module so that every engine module,
the input models and the catalogues alike, can raise it without importing the other)."""

from __future__ import annotations

__all__ = ["InputError"]


class InputError(ValueError):
    """A user input problem: the message names the field and the fix (one line).

    ``InputError(reason, field="models.din.f_carry")`` reads ``models.din.f_carry: reason``;
    ``field`` and ``reason`` stay apart as attributes, so a caller that knows the field by
    another name (a grid axis, the design case) can name it its own way.
    """

    def __init__(self, reason: str, *, field: str | None = None):
        super().__init__(f"{field}: {reason}" if field else reason)
        self.field = field
        self.reason = reason
