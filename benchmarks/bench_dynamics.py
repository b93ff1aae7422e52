"""Benchmark of the Euler-X transient kernel.

Prints, with the date and the machine:

1. kernel throughput (element-steps per second, one core, full physics: Ernst stiffness,
   standard-linear-solid damping, gravity take-up, PI drives, the friction model's laws) on
   the 16.8 km example with 1 000 elements, for DIN (constant resistances), CEMA and Non-Lin
   (speed and sag exponents, its law expanded between exact evaluations: the share of
   element-steps it was evaluated exactly is printed), measured in alternating rounds, best of
   five each; and Non-Lin's throughput over DIN's in the same run (acceptance: at least
   0.67, i.e. Non-Lin at no more than 1.5 x DIN's cost per element-step);
2. the whole start-run-stop cycle of that example (kernel time, and run_one with statics);
3. the baselines measured in the same run: the numpy reference of the same equations (the
   speed ratio of the kernel to it), and engine 0.2's kernel on the same case, checked out
   from its commit (``BASELINE_REV``);
4. the same equations integrated by scipy.integrate.solve_ivp (RK45, rtol 1e-6) on a small,
   short case: speed ratio and difference in peak tension;
5. the time step against element length with damping on: the kernel's damper (standard
   linear solid, exact exponential) keeps dt ~ dx, an explicit Kelvin-Voigt term gives
   dt ~ dx^2 on fine meshes.

Run: ``.venv/bin/python benchmarks/bench_dynamics.py`` (about a minute after compilation).
"""

from __future__ import annotations

import datetime
import platform
import subprocess
import time
from pathlib import Path

import numpy as np

from beltstudy.engine.conveyor import Scenario, load_conveyor
from beltstudy.engine.dynamics import DynamicsOptions, build_system
from beltstudy.engine.dynamics.model import stability_limit_s
from beltstudy.engine.dynamics.reference import run_reference
from beltstudy.engine.dynamics.simulate import run_kernel
from beltstudy.engine.run import run_one
from beltstudy.engine.statics import solve_steady

ROOT = Path(__file__).resolve().parents[1]
CONVEYORS = ROOT / "studies" / "conveyors"
OVERLAND = dict(start={"control": "s-curve", "time_s": 120}, run_s=30,
                stop={"mode": "controlled", "time_s": 60})


def machine() -> str:
    try:
        cpu = subprocess.run(["lscpu"], capture_output=True, text=True).stdout.splitlines()
        cpu = [ln for ln in cpu if ln.startswith(("Model name", "CPU(s):", "L1d", "L2"))]
    except OSError:
        cpu = [platform.processor()]
    return "; ".join(" ".join(ln.split()) for ln in cpu)


def best_of(fn, repeat=3):
    best, out = float("inf"), None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def kernel_throughput(model: str, n: int = 1000):
    conv = load_conveyor(CONVEYORS / "overland-16km.yaml")
    st = solve_steady(conv, model=model, n_elements=n)
    system = build_system(conv, Scenario(**OVERLAND), st)
    run_kernel(system)  # compile / load the cache
    wall, (ki, _) = best_of(lambda: run_kernel(system))
    res = ki.run
    steps = int(res["steps"])
    return system, wall, steps, float(res["t"]), int(res["status"])


#: Throughput acceptance: Non-Lin's element-steps per second over DIN's (1 / 1.5).
NONLIN_OVER_DIN_MIN = 0.67


def kernel_throughputs(models, n: int = 1000, rounds: int = 5) -> dict:
    """Kernel wall time of each model on the 16.8 km example, best of ``rounds`` taken in
    alternating rounds (each round runs every model once), so a slower spell of a shared
    machine falls on all of them. Returns model -> (system, wall, steps, t_end, status,
    share of element-steps whose law was evaluated exactly after the first)."""
    conv = load_conveyor(CONVEYORS / "overland-16km.yaml")
    systems = {}
    for model in models:
        st = solve_steady(conv, model=model, n_elements=n)
        systems[model] = build_system(conv, Scenario(**OVERLAND), st)
        run_kernel(systems[model])  # compile / load the cache
    best = {model: (float("inf"), None) for model in models}
    for _ in range(rounds):
        for model in models:
            ki, wall = run_kernel(systems[model])
            if wall < best[model][0]:
                best[model] = (wall, ki)
    out = {}
    for model, (wall, ki) in best.items():
        res = ki.run
        steps = int(res["steps"])
        out[model] = (systems[model], wall, steps, float(res["t"]), int(res["status"]),
                      int(res["law_evals"]) / (steps * systems[model].n))
    return out


def reference_throughput(system, seconds: float):
    t0 = time.perf_counter()
    out = run_reference(system, t_end_s=system.model.cycle.t_pre + seconds)
    wall = time.perf_counter() - t0
    return out["steps"] * system.n / wall


#: Engine 0.2 (the release before drive pulleys with slip, brakes on shafts and slack carried
#: through): its kernel is measured in the same run, from its own commit.
BASELINE_REV = "d505d3f"

_BASELINE_SNIPPET = """
import json, sys
sys.path.insert(0, {root!r})
from benchmarks.bench_dynamics import kernel_throughput
out = {{}}
for model in ("din", "nonlin"):
    system, wall, steps, t_end, status = kernel_throughput(model)
    out[model] = dict(rate=steps * system.n / wall, dt=system.dt_s, steps=int(steps),
                      t_end=float(t_end), wall=wall)
print(json.dumps(out))
"""


def baseline_throughput(rev: str = BASELINE_REV) -> dict | None:
    """Element-steps/s of engine ``rev``'s kernel on the same case, in this run: its engine,
    benchmark and example conveyors checked out from git into a temporary directory and run
    in a subprocess. None (with the reason printed) if the commit is not in this clone."""
    import json
    import sys
    import tarfile
    import tempfile

    with tempfile.TemporaryDirectory(prefix="beltstudy-base-") as tmp:
        archive = subprocess.run(
            ["git", "-C", str(ROOT), "archive", "--format=tar", rev, "engine", "benchmarks",
             "studies/conveyors"], capture_output=True)
        if archive.returncode != 0:
            print(f"  baseline {rev} not in this clone: {archive.stderr.decode().strip()}")
            return None
        tar_path = Path(tmp) / "base.tar"
        tar_path.write_bytes(archive.stdout)
        with tarfile.open(tar_path) as tar:
            tar.extractall(tmp, filter="data")
        proc = subprocess.run([sys.executable, "-c", _BASELINE_SNIPPET.format(root=tmp)],
                              capture_output=True, text=True, cwd=tmp)
        if proc.returncode != 0:
            print(f"  baseline {rev} did not run: {proc.stderr.strip().splitlines()[-1:]}")
            return None
        return json.loads(proc.stdout.strip().splitlines()[-1])


def rk45_comparison():
    """Kernel against solve_ivp (RK45, rtol 1e-6) on the 1 km fabric belt, 40 elements,
    a 10 s s-curve start from rest, 14 s simulated; shafts stuck on their pulleys, no holdback,
    the resistance regularised over 1 cm/s (the ODE's scope, engine/dynamics/ode.py)."""
    from scipy.integrate import solve_ivp

    from beltstudy.engine.dynamics import ode

    conv = load_conveyor(CONVEYORS / "fabric-1km.yaml").model_copy(update={"holdback": False})
    st = solve_steady(conv, model="din", n_elements=40)
    scn = Scenario(start={"control": "s-curve", "time_s": 10}, run_s=60)
    opts = DynamicsOptions(pre_rest_s=0.0, slip=False, v_eps_m_s=1e-2)
    system = build_system(conv, scn, st, opts)
    t_end = 14.0
    run_kernel(system, t_end)
    k_wall, (ki, _) = best_of(lambda: run_kernel(system, t_end))
    peak_k = float(ki.run["tmax"])
    y0 = ode.initial_state(system)
    scale = np.concatenate([np.full(system.n, system.v_design),
                            np.full(2 * system.n, float(np.abs(system.tension_rest_n).max())),
                            [1.0, 1.0, abs(system.te_n) + 1.0]])
    t0 = time.perf_counter()
    sol = solve_ivp(ode.rhs, (0.0, t_end), y0, method="RK45", rtol=1e-6, atol=1e-6 * scale,
                    args=(system,), dense_output=True)
    r_wall = time.perf_counter() - t0
    ts = np.linspace(0.0, t_end, 20001)
    ys = sol.sol(ts)
    peak_r = float(ode.tension(system, ys).max())
    # the kernel at a tenth of its step, to show the first-order convergence of the peak
    fine = build_system(conv, scn.model_copy(update={"dt_s": system.dt_s / 10}), st, opts)
    kf, _ = run_kernel(fine, t_end)
    peak_f = float(kf.run["tmax"])
    return dict(k_wall=k_wall, r_wall=r_wall, nfev=sol.nfev, ok=sol.success, peak_k=peak_k,
                peak_r=peak_r, peak_f=peak_f, dt=system.dt_s, n=system.n)


def dt_scaling():
    conv = load_conveyor(CONVEYORS / "overland-16km.yaml")
    rows = []
    for n in (125, 250, 500, 1000, 2000, 4000, 8000):
        st = solve_steady(conv, model="din", n_elements=n)
        sls = build_system(conv, Scenario(**OVERLAND), st)
        # an explicit Kelvin-Voigt term with 5 % damping on the fundamental mode instead:
        # viscosity per spring (tension per relative speed) = c / len
        c = 2.0 * 0.05 * sls.model.springs.eb / (0.5 * np.pi / sls.wave_loop_time_s)
        kv_lim = stability_limit_s(sls.model.nodes.mass, sls.model.springs.len_m, sls.model.springs.eb, sls.implicit,
                                   c / sls.model.springs.len_m)
        rows.append((n, float(np.median(sls.dx_m)), sls.dt_s, 0.5 * kv_lim))
    return rows


def main() -> None:
    print("# bench_dynamics")
    print(f"date: {datetime.datetime.now().isoformat(timespec='seconds')}")
    print(f"machine: {machine()}")
    print(f"python {platform.python_version()}, numpy {np.__version__}")
    print()
    print("## 1-2. Kernel throughput and the 16.8 km cycle (1 000 elements, one core, slip on)")
    results = {}
    for model, (system, wall, steps, t_end, status, evals) in kernel_throughputs(
            ("din", "cema", "nonlin")).items():
        rate = steps * system.n / wall
        results[model] = (system, rate)
        law = f"  law evaluated exactly for {100 * evals:.2f} % of element-steps" if evals else ""
        print(f"  {model:7s} n={system.n} dt={system.dt_s * 1e3:.2f} ms steps={int(steps)} "
              f"simulated={t_end:.1f} s  kernel wall={wall:.4f} s  "
              f"{rate:.3g} element-steps/s  status={status}{law}")
    ratio = results["nonlin"][1] / results["din"][1]
    print(f"  nonlin / din element-steps/s in this run = {ratio:.3f} (acceptance >= "
          f"{NONLIN_OVER_DIN_MIN}: {'met' if ratio >= NONLIN_OVER_DIN_MIN else 'not met'}; "
          f"Non-Lin at {1 / ratio:.2f} x DIN's cost per element-step)")
    conv = load_conveyor(CONVEYORS / "overland-16km.yaml")
    # the default start (60 s s-curve) and run (30 s) with a controlled stop: the example's
    # power-failure coast ends early, slack at the head take-up (a design finding)
    cycles = (
        ("60 s s-curve start, 30 s run, 40 s controlled stop",
         Scenario(elements=1000, stop={"mode": "controlled", "time_s": 40}), ("din", "nonlin")),
        ("120 s s-curve start, 30 s run, 60 s controlled stop",
         Scenario(elements=1000, **OVERLAND), ("din",)),
    )
    for label, scn, models in cycles:
        for model in models:
            run_one(conv, scn, model=model)
            wall_run, r = best_of(lambda scn=scn, model=model: run_one(conv, scn, model=model),
                                  repeat=5)
            t_end = r.transient.raw["t_end"]
            print(f"  run_one {model}, {label}: {t_end:.0f} s simulated in {wall_run:.3f} s "
                  f"(kernel {r.transient.raw['wall_s']:.3f} s), status {r.summary['status']}")
    print()
    print("## 3. Baseline in the same run: the numpy reference of the same equations")
    for model in ("din", "nonlin"):
        system, rate = results[model]
        ref_rate = reference_throughput(system, seconds=3.0)
        print(f"  {model:7s} reference {ref_rate:.3g} element-steps/s; kernel / reference = "
              f"{rate / ref_rate:.0f} x")
    print()
    print(f"## 3b. Engine 0.2 (commit {BASELINE_REV}) in the same run, same case")
    base = baseline_throughput()
    if base is not None:
        for model in ("din", "nonlin"):
            system, rate = results[model]
            b = base[model]
            print(f"  {model:7s} 0.2: dt={b['dt'] * 1e3:.2f} ms steps={b['steps']} "
                  f"{b['rate']:.3g} element-steps/s; 0.3 (slip on): dt={system.dt_s * 1e3:.2f}"
                  f" ms {rate:.3g} element-steps/s; ratio 0.3 / 0.2 = {rate / b['rate']:.2f}")
    print()
    print("## 4. RK45 (scipy solve_ivp, rtol 1e-6) on the same equations")
    c = rk45_comparison()
    print(f"  fabric-1km, n={c['n']}, 10 s s-curve start, 14 s simulated")
    print(f"  kernel: dt={c['dt'] * 1e3:.2f} ms, wall {c['k_wall'] * 1e3:.2f} ms, "
          f"peak tension {c['peak_k'] / 1e3:.4f} kN (dt/10: {c['peak_f'] / 1e3:.4f} kN)")
    print(f"  RK45:   {c['nfev']} evaluations, wall {c['r_wall']:.2f} s, "
          f"peak tension {c['peak_r'] / 1e3:.4f} kN, success={c['ok']}")
    print(f"  speed ratio RK45 / kernel = {c['r_wall'] / c['k_wall']:.0f} x; peak tension "
          f"difference {100 * abs(c['peak_k'] / c['peak_r'] - 1):.3f} % "
          f"(dt/10: {100 * abs(c['peak_f'] / c['peak_r'] - 1):.3f} %)")
    print()
    print("## 5. Time step against element length, damping on (16.8 km, zeta 5 %)")
    print("  elements  dx [m]   dt kernel [ms]  dt explicit Kelvin-Voigt [ms]")
    rows = dt_scaling()
    for n, dx, dt, dt_kv in rows:
        print(f"  {n:8d} {dx:7.2f} {dt * 1e3:13.4f} {dt_kv * 1e3:22.5f}")
    print("  halving dx: kernel dt ratios " + ", ".join(
        f"{rows[i][2] / rows[i + 1][2]:.2f}" for i in range(len(rows) - 1)))
    print("              Kelvin-Voigt ratios " + ", ".join(
        f"{rows[i][3] / rows[i + 1][3]:.2f}" for i in range(len(rows) - 1)))


if __name__ == "__main__":
    main()
