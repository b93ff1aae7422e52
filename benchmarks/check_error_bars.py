"""Do the error bars hold? (issue 26 acceptance; beltstudy.engine.accuracy)

For each conveyor (the examples in studies/conveyors and those of benchmarks/conveyors: a
short steep incline, a long flat overland, a regenerative decline, and the published
summaries rebuilt from their inputs) and each stop (coast, controlled, brake where the
conveyor has a brake), at the defaults (automatic mesh ``n`` and step), the run's error bars are computed as ``beltstudy simulate`` computes them (meshes
``n/2, n, 2n``) and compared with the value at ``4n`` elements (the automatic step follows
the mesh: a quarter of the step; where it does not, on a route whose curves' arc elements set
it, the 2n and 4n runs are given half and a quarter of the run's step, as the run's bars are). It prints, per figure, whether the bar contains that value,
the misses, and the fraction of figures whose bar holds it (target: at least 95 %).

Every run's summary is cached in ``--cache`` (one JSON file per conveyor text, scenario,
mesh, engine version and engine source), so an interrupted check resumes where it stopped
and a rerun after a change to the engine's sources recomputes only what the change touched.

    .venv/bin/python benchmarks/check_error_bars.py                       # everything
    .venv/bin/python benchmarks/check_error_bars.py --quick               # 5 s running
    .venv/bin/python benchmarks/check_error_bars.py --conveyors slope-5pct,steep-incline \\
        --stops coast,brake

The full check runs every conveyor on four meshes up to 4 x the automatic one (a 4n run
costs about 16 base runs): 84 runs, about 20 s on one core once the kernel is compiled
(engine 0.4.1); a cached rerun takes a few seconds.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import math
import os
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "studies" / "conveyors"
OWN = ROOT / "benchmarks" / "conveyors"
STOPS = ("coast", "controlled", "brake")
#: A bar holds a value to this relative slack (rounding of the stored figures).
REL_SLACK = 1e-9


def _engine_hash() -> str:
    """Hash of the engine's sources that make a run (the error bars' own module aside: the
    bars are computed from the cached runs each time): a change to them invalidates the
    cache."""
    h = hashlib.sha256()
    for p in sorted((ROOT / "engine").rglob("*.py")):
        if p.name == "accuracy.py":
            continue
        h.update(p.relative_to(ROOT).as_posix().encode())
        h.update(p.read_bytes())
    return h.hexdigest()[:16]


def _conveyors(names: str | None) -> list[Path]:
    paths = sorted(EXAMPLES.glob("*.yaml")) + sorted(OWN.glob("*.yaml"))
    if not names:
        return paths
    out = []
    for name in names.split(","):
        name = name.strip()
        p = Path(name)
        if p.suffix in (".yaml", ".yml", ".json") and p.exists():
            out.append(p)
            continue
        hit = [q for q in paths if q.stem == name]
        if not hit:
            sys.exit(f"error: no conveyor {name!r} (known: {', '.join(q.stem for q in paths)})")
        out += hit
    return out


class Cache:
    """Run summaries on disk, one JSON per key."""

    def __init__(self, root: Path, engine_key: str):
        self.root = root
        self.engine_key = engine_key
        root.mkdir(parents=True, exist_ok=True)

    def path(self, conveyor_text: str, scenario: dict, elements) -> Path:
        key = json.dumps([conveyor_text, scenario, elements, self.engine_key], sort_keys=True)
        return self.root / (hashlib.sha256(key.encode()).hexdigest()[:24] + ".json")

    def get(self, *key):
        p = self.path(*key)
        if p.exists():
            try:
                return json.loads(p.read_text())
            except ValueError:
                p.unlink()
        return None

    def put(self, summary: dict, *key) -> None:
        p = self.path(*key)
        tmp = p.with_suffix(".tmp")
        tmp.write_text(json.dumps(summary, default=float))
        os.replace(tmp, p)


def _summary(res) -> dict:
    s = dict(res.summary)
    s.pop("te_components_kn", None)
    return {k: v for k, v in s.items() if v is None or isinstance(v, int | float | str)}


def run_case(path: Path, stop: str, args, cache: Cache, log) -> list[dict] | None:
    """The figures of one conveyor and stop: per figure its bar and the 4n value."""
    from beltstudy.engine import load_conveyor, parse_scenario
    from beltstudy.engine.accuracy import ELEMENTS_MIN, RATIO, STEP_FOLLOWS, bars
    from beltstudy.engine.dynamics import DynamicsOptions
    from beltstudy.engine.run import run_one

    text = path.read_text()
    conv = load_conveyor(path)
    if stop == "brake" and not conv.brakes:
        return None
    scn_data = {"stop": {"mode": stop}}
    if args.quick:
        scn_data["run_s"] = 5.0
    scn = parse_scenario(scn_data)

    def summary(elements, dt_s=None):
        key = dict(scn_data, dt_s=dt_s) if dt_s is not None else scn_data
        hit = cache.get(text, key, elements)
        if hit is not None:
            return hit
        t0 = time.perf_counter()
        s_scn = scn if elements == "auto" else scn.model_copy(update={"elements": elements})
        if dt_s is not None:
            s_scn = s_scn.model_copy(update={"dt_s": dt_s})
        res = run_one(conv, s_scn, model=args.model, params=None)
        out = _summary(res)
        cache.put(out, text, key, elements)
        log(f"    {path.stem} {stop} {elements} elements: {time.perf_counter() - t0:.1f} s "
            f"({out.get('status')})")
        return out

    base = summary("auto")
    if base.get("status") == "failed":
        log(f"  {path.stem} {stop}: the run failed: {base.get('message')}")
        return None
    n = int(base["elements_used"])
    asked = (max(ELEMENTS_MIN, n // RATIO), n * RATIO, n * RATIO * RATIO)
    runs = {m: summary(m) for m in asked}
    # the step refined with the mesh where the automatic one does not follow it (a curve's
    # arc elements set it), as the run's bars do (accuracy.STEP_FOLLOWS): the 2n mesh at
    # half the step and the 4n reference at a quarter
    dt = float(base["dt_used_s"])
    for m, share in ((asked[1], 0.5), (asked[2], 0.25)):
        got = runs[m]
        if got.get("dt_used_s") and float(got["dt_used_s"]) > STEP_FOLLOWS * 2 * share * dt:
            runs[m] = summary(m, dt * n / int(got["elements_used"]))
    ok = {m: s for m, s in runs.items() if s.get("status") != "failed"}
    coarse, fine, ref = (ok.get(m) for m in asked)
    if ref is None:
        log(f"  {path.stem} {stop}: the 4n run failed")
        return None
    used = tuple(int(s["elements_used"]) if s else m
                 for s, m in ((coarse, asked[0]), (base, n), (fine, asked[1])))
    out = []
    for name, fe in bars([coarse, base, fine], used, DynamicsOptions().resistance_rtol).items():
        v4 = ref.get(name)
        if not isinstance(v4, int | float) or not math.isfinite(v4):
            continue
        miss = abs(v4 - fe.value) - fe.err
        holds = miss <= REL_SLACK * max(1.0, abs(v4))
        out.append({"conveyor": path.stem, "stop": stop, "figure": name, "value": fe.value,
                    "err": fe.err, "method": fe.method, "order": fe.order, "v4": v4,
                    "values": fe.values, "converged": fe.converged, "holds": holds,
                    "dt_s": base.get("dt_used_s"),
                    "elements": used + (int(ref["elements_used"]),)})
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--conveyors", help="comma-separated names (file stems) or paths; default: "
                    "the examples and benchmarks/conveyors")
    ap.add_argument("--stops", default=",".join(STOPS), help="comma-separated stop modes")
    ap.add_argument("--model", default="din", help="friction model (default din)")
    ap.add_argument("--quick", action="store_true", help="5 s of running instead of 30 s")
    ap.add_argument("--cache", default=str(ROOT / "benchmarks" / ".error-bars-cache"),
                    help="directory of cached run summaries (resumable)")
    ap.add_argument("--json", metavar="FILE", help="also write every figure to FILE")
    args = ap.parse_args(argv)
    os.environ.setdefault("NUMBA_NUM_THREADS", "1")

    def log(msg):
        print(msg, file=sys.stderr, flush=True)

    cache = Cache(Path(args.cache), _engine_hash())
    rows = []
    for path in _conveyors(args.conveyors):
        for stop in args.stops.split(","):
            log(f"  {path.stem} {stop} ...")
            try:
                got = run_case(path, stop.strip(), args, cache, log)
            except Exception as exc:  # one case failing does not lose the others
                log(f"  {path.stem} {stop}: {type(exc).__name__}: {exc}")
                continue
            if got:
                rows += got
                held = sum(r["holds"] for r in got)
                log(f"  {path.stem} {stop}: {held} of {len(got)} bars hold the 4n value")
    if not rows:
        print("no figures")
        return 1
    held = sum(r["holds"] for r in rows)
    print(f"{'conveyor':<16} {'stop':<11} {'figure':<24} {'n/2, n, 2n':>32} {'+-':>9} "
          f"{'4n':>10} {'method':<10}")
    for r in rows:
        if r["holds"]:
            continue
        vals = ", ".join("-" if v is None else f"{v:.4g}" for v in r["values"])
        print(f"{r['conveyor']:<16} {r['stop']:<11} {r['figure']:<24} {vals:>32} "
              f"{r['err']:>9.3g} {r['v4']:>10.4g} {r['method']:<10}")
    methods: dict[str, list[int]] = {}
    for r in rows:
        methods.setdefault(r["method"], [0, 0])
        methods[r["method"]][0] += r["holds"]
        methods[r["method"]][1] += 1
    print("by method: " + ", ".join(f"{m} {h}/{t}" for m, (h, t) in methods.items()))
    print(f"coverage: {held} of {len(rows)} figures ({100.0 * held / len(rows):.1f} %) "
          f"have a bar that holds the value at 4 x the elements (target >= 95 %)")
    moved = [r for r in rows if not (r["method"] == "unchanged" and r["v4"] == r["value"])]
    if moved:
        held_m = sum(r["holds"] for r in moved)
        print(f"  without the figures equal on all four meshes: {held_m} of {len(moved)} "
              f"({100.0 * held_m / len(moved):.1f} %)")
    if args.json:
        Path(args.json).write_text(json.dumps(rows, indent=1, default=float))
    return 0 if held >= 0.95 * len(rows) else 1


if __name__ == "__main__":
    sys.exit(main())
