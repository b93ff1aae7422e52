"""Numbers as an engineer writes them: digits grouped by thousands, a unit, no exponent.

``eng(16886.3, "kg")`` gives ``16 886 kg`` (a narrow no-break space between the groups of three
digits and a no-break space before the unit, as ISO 80000-1 and the SI brochure write them),
never ``1.689e+4``. The design report (:mod:`beltstudy.service.web.report`) formats every
number through :func:`eng`.
"""

from __future__ import annotations

import math
from typing import Any

__all__ = ["eng", "GROUP", "UNIT_SPACE"]

#: Between groups of three digits: U+202F NARROW NO-BREAK SPACE (the SI brochure's thin space,
#: one that never breaks a number across lines).
GROUP = "\u202f"
#: Between a number and its unit: U+00A0 NO-BREAK SPACE.
UNIT_SPACE = "\u00a0"
#: Magnitudes below this are written with a power of ten (``1.2 × 10⁻⁵``).
SMALL = 1e-4

_SUPERSCRIPT = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")


def _group(digits: str) -> str:
    """``'1234567'`` -> ``'1 234 567'`` (narrow no-break spaces)."""
    head = len(digits) % 3 or 3
    parts = [digits[:head]] + [digits[i:i + 3] for i in range(head, len(digits), 3)]
    return GROUP.join(parts)


def eng(value: Any, unit: str = "", digits: int = 4, empty: str = "–",
        strip: bool = True) -> str:
    """``value`` in engineering notation with ``unit``.

    Parameters
    ----------
    value : float, int, bool, None or str
        The number. ``None``, NaN and infinities give ``empty``; text and booleans come back
        as text (``yes`` / ``no`` for booleans).
    unit : str
        Appended after a no-break space (none for ``""`` and ``"-"``).
    digits : int
        Significant digits, but never fewer than the integer part has: 16 886.3 stays
        ``16 886``, 1.23456 gives ``1.235``, 0.012345 gives ``0.01235``, 1e-7 gives
        ``1 × 10⁻⁷``.
    empty : str
        What a missing value shows.
    strip : bool
        Drop trailing zeros of the decimals (``2.000`` -> ``2``, ``6.700`` -> ``6.7``).

    Returns
    -------
    str
        Thousands grouped with :data:`GROUP`; magnitudes below :data:`SMALL` as ``1.2 × 10⁻⁵``.
    """
    if isinstance(value, bool):
        text = "yes" if value else "no"
    elif value is None or (isinstance(value, float) and not math.isfinite(value)):
        return empty
    elif isinstance(value, int | float) or hasattr(value, "__float__") and not isinstance(
            value, str):
        text = _number(float(value), digits, strip)
    else:
        return str(value)
    return text + (UNIT_SPACE + unit if unit and unit != "-" else "")


def _number(x: float, digits: int, strip: bool = True) -> str:
    if not math.isfinite(x):
        return "–"
    if x == 0.0:
        return "0"
    sign = "-" if x < 0 else ""
    a = abs(x)
    if a < SMALL:
        exp = math.floor(math.log10(a))
        mant = f"{a / 10 ** exp:.{max(digits - 1, 0)}f}".rstrip("0").rstrip(".")
        return f"{sign}{mant} × 10{str(exp).translate(_SUPERSCRIPT)}"
    magnitude = math.floor(math.log10(a))  # 0 for 1..9.99, -2 for 0.01..0.099
    decimals = max(digits - 1 - magnitude, 0)
    text = f"{a:.{decimals}f}"
    if "." in text:
        whole, frac = text.split(".")
        frac = frac.rstrip("0") if strip else frac
    else:
        whole, frac = text, ""
    return sign + _group(whole) + ("." + frac if frac else "")
