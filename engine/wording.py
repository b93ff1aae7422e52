"""Numbers in words: the engine's messages, warnings and notes print a figure to a few
significant figures without an exponent, so 19 740 t reads ``19740``, not ``1.974e+04`` as
``:.4g`` gives it (a leaf module: every engine and service module can import it)."""

from __future__ import annotations

import math

__all__ = ["gnum"]

#: Largest power of ten written out in full; beyond it the exponent stays (3.97e+11 steps
#: is read more easily than 397000000000: a figure of ten million or more is no quantity a
#: conveyor's words give in full).
PLAIN_MAX_EXP = 6


def gnum(value: float, digits: int = 4) -> str:
    """``value`` to ``digits`` significant figures [any unit], as ``f"{value:.{digits}g}"``
    but with the exponent of a large number written out (``gnum(19740.3)`` is ``19740``,
    ``gnum(1210.4, 3)`` is ``1210``); small numbers and non-finite ones as ``:g`` gives them.
    The text parses back with ``float`` to the rounded value."""
    text = f"{value:.{digits}g}"
    if "e+" not in text:
        return text
    rounded = float(text)
    if not math.isfinite(rounded) or abs(rounded) >= 10.0 ** (PLAIN_MAX_EXP + 1):
        return text
    return f"{rounded:.0f}"
