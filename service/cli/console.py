"""Text output of the CLI: the progress bar, status lines and the comparison table."""

from __future__ import annotations

import math
import sys
import time
from typing import Any, TextIO

from beltstudy.engine.warmth import COMPILE_LINE

__all__ = ["ProgressBar", "format_status", "format_compare", "format_duration"]


def format_duration(seconds: float | None) -> str:
    if seconds is None or not math.isfinite(seconds):
        return "--:--"
    seconds = int(round(seconds))
    h, rest = divmod(seconds, 3600)
    m, s = divmod(rest, 60)
    return f"{h}:{m:02d}:{s:02d}" if h else f"{m:02d}:{s:02d}"


def format_status(st: dict) -> str:
    """One line: id, name, state, runs done/total, failures, elapsed, time left."""
    return (
        f"{st['id']}  {st['name']:<28.28}  {st['state']:<9} {st['done']:>6}/{st['total']:<6} "
        f"failed {st['failed']:<4} elapsed {format_duration(st.get('elapsed_s'))}  "
        f"left {format_duration(st.get('eta_s'))}"
    )


class ProgressBar:
    """``[#####.....] 12/40 runs  1 failed  00:35 left`` on one terminal line.

    Redraws in place on a terminal; elsewhere (a log, CI) prints a line at most every
    ``every_s`` seconds when the progress moved (runs done or failed, the state, the
    message), and otherwise one every ``quiet_s`` seconds to show it is alive: the first
    compile of the engine (minutes at 0 runs) printed the same line every 5 s, some 60 times.
    """

    def __init__(self, stream: TextIO | None = None, width: int = 30, every_s: float = 5.0,
                 quiet_s: float = 60.0):
        self.stream = stream or sys.stderr
        self.width = width
        self.every_s = every_s
        self.quiet_s = quiet_s
        self._last = 0.0
        self._said: tuple | None = None
        self._tty = getattr(self.stream, "isatty", lambda: False)()

    def render(self, st: dict) -> str:
        total = max(int(st["total"]), 1)
        frac = min(int(st["done"]) / total, 1.0)
        filled = int(round(frac * self.width))
        bar = "#" * filled + "." * (self.width - filled)
        line = (
            f"[{bar}] {st['done']}/{st['total']} runs  {st['failed']} failed  "
            f"{format_duration(st.get('eta_s'))} left  ({st['state']})"
        )
        message = st.get("message") or ""
        # what the study waits for: Dask starting or compiling (queued), or a scheduler lost
        # mid-study ('waiting for Dask: ... start workers with ...', running)
        if st["state"] in ("queued", "running") and message:
            line += "  " + (COMPILE_LINE if COMPILE_LINE in message else message)
        return line

    def __call__(self, st: dict) -> None:
        line = self.render(st)
        finished = st["state"] not in ("queued", "running")
        if self._tty:
            self.stream.write("\r" + line + ("\n" if finished else ""))
            self.stream.flush()
            return
        said = (st["done"], st["failed"], st["state"], st.get("message") or "")
        waited = time.monotonic() - self._last
        if finished or waited >= (self.every_s if said != self._said else self.quiet_s):
            self.stream.write(line + "\n")
            self.stream.flush()
            self._last = time.monotonic()
            self._said = said


def _num(value: Any, fmt: str = "{:.3f}") -> str:
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "n/a"
    return fmt.format(value)


def format_compare(result: dict, max_pairs: int = 40) -> str:
    """The comparison as text: ratio statistics per metric and axis, then the pairs."""
    base, cand = result["baseline"], result["candidate"]
    lines = [f"{cand} / {base}: runs that differ only in the friction model (ratios of "
             "magnitudes; 'opposite' marks values of opposite sign)"]
    running = result.get("state") in ("queued", "running")
    if running:
        lines.append(f"study {result['state']}: {result.get('done', 0)} of "
                     f"{result.get('total', '?')} runs done; the ratios are of the pairs "
                     "finished so far")
    same = result.get("same_in_all_pairs") or {}
    if same:
        lines.append("the same in every pair: " + ", ".join(f"{k}={v}" for k, v in same.items()))
    if result.get("failed_pairs"):
        lines.append(f"({result['failed_pairs']} pairs with a failed run have no ratio)")
    for metric in result["metrics"]:
        summary = result["summary"][metric]
        o = summary["overall"]
        lines.append("")
        opposite = o.get("opposite_sign") or 0
        lines.append(
            f"{metric}: ratio mean {_num(o['mean'])}  min {_num(o['min'])}  "
            f"max {_num(o['max'])}  ({o['n']} pairs"
            + (f", {opposite} of opposite sign)" if opposite else ")")
        )
        for axis, groups in summary["by_axis"].items():
            if not groups:
                continue
            cells = "  ".join(f"{value}: {_num(s['mean'])}" for value, s in groups.items())
            lines.append(f"  by {axis:<16} {cells}")
    pairs = result["pairs"]
    if pairs and len(pairs) <= max_pairs:
        metrics = result["metrics"]
        axes = [
            k
            for k in pairs[0]
            if not any(k.startswith(m + "_") for m in metrics)
            and not k.startswith(("run_id", "status"))
        ]
        head = [*axes]
        for m in metrics:
            head += [f"{m} {base}", f"{m} {cand}", "ratio"]
        rows = []
        for p in pairs:
            row = [str(p[a]) for a in axes]
            for m in metrics:
                row += [
                    _num(p.get(f"{m}_baseline"), "{:.1f}"),
                    _num(p.get(f"{m}_candidate"), "{:.1f}"),
                    _num(p.get(f"{m}_ratio"))
                    + (" (opposite)" if p.get(f"{m}_sign") == "opposite" else ""),
                ]
            rows.append(row)
        widths = [max(len(h), *(len(r[i]) for r in rows)) for i, h in enumerate(head)]
        lines.append("")
        lines.append("  ".join(h.rjust(w) for h, w in zip(head, widths, strict=True)))
        for r in rows:
            lines.append("  ".join(c.rjust(w) for c, w in zip(r, widths, strict=True)))
    elif pairs:
        lines.append(f"\n({len(pairs)} pairs; 'beltstudy results ID -o runs.parquet' for all)")
    elif running:
        lines.append("\nno pairs yet: no run of both models with equal other axes has "
                     "finished; compare again when the study is done ('beltstudy status ID')")
    else:
        lines.append("\nno pairs: the study has no runs of both models with equal other axes")
    return "\n".join(lines)
