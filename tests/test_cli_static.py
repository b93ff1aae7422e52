"""`beltstudy static` as a user runs it: real subprocess, JSON output, clean errors."""

from __future__ import annotations

import json
import math
import subprocess
import sys

import pandas as pd
import pytest

from tests.conftest import CONVEYORS

EXE = [sys.executable, "-m", "beltstudy.service.cli"]


def run(*args, check=True):
    p = subprocess.run([*EXE, *args], capture_output=True, text=True, timeout=120)
    if check:
        assert p.returncode == 0, p.stderr
    return p


def test_static_json_and_profile(tmp_path):
    prof = tmp_path / "profile.csv"
    plot = tmp_path / "fig.png"
    p = run("static", str(CONVEYORS / "slope-5pct.yaml"), "--model", "din", "--param",
            "f_carry=0.010", "--param", "f_return=0.008", "--json", "--profile", str(prof),
            "--plot", str(plot), "--elements", "200")
    out = json.loads(p.stdout)
    for key in ("te_kn", "power_kw", "t1_kn", "t2_kn", "t_max_kn", "t_max_at_m", "t_min_kn",
                "t_min_at_m", "sag_max_pct", "takeup_mass_kg", "slip_margin", "safety_factor",
                "belt_mass_kg_m", "load_mass_kg_m", "idler_mass_carry_kg_m",
                "idler_mass_return_kg_m", "belt_modulus_kn", "belt_rating_kn",
                "wave_speed_carry_m_s", "wave_speed_return_m_s", "te_components_kn", "status",
                "message"):
        assert key in out
    assert set(out["te_components_kn"]) >= {"main_carry", "main_return", "lift", "feed",
                                            "secondary", "accessories"}
    assert out["power_kw"] == pytest.approx(out["te_kn"] * 4.5, rel=1e-9)
    df = pd.read_csv(prof)
    assert list(df.columns) == ["s_m", "strand", "elevation_m", "tension_kn", "sag_pct"]
    assert df["tension_kn"].max() == pytest.approx(out["t_max_kn"], rel=1e-9)
    assert plot.stat().st_size > 10_000 and plot.read_bytes()[:4] == b"\x89PNG"


def test_static_table_output():
    p = run("static", str(CONVEYORS / "fabric-1km.yaml"), "--model", "cema", "--load", "empty")
    assert "peripheral force Te" in p.stdout and "status:" in p.stdout


@pytest.mark.parametrize("args, needle", [
    (["--model", "cemx"], "did you mean 'cema'"),
    (["--param", "f_cary=0.01"], "did you mean 'f_carry'"),
    (["--param", "f_carry"], "NAME=VALUE"),
    # a parameter of a model the run does not use, or one given twice, was dropped silently
    (["--param", "cema.f_carry=0.05"], "sets a parameter of model cema, but this run uses din"),
    (["--param", "f_carry=0.05", "--param", "f_carry=0.01"],
     "f_carry is already set by --param 'f_carry=0.05'; give each parameter once"),
    (["--load", "heavy"], "--load"),
    (["--profile", "x.txt"], ".csv or .parquet"),
])
def test_static_bad_args_one_line(args, needle):
    p = run("static", str(CONVEYORS / "slope-5pct.yaml"), *args, check=False)
    assert p.returncode == 2
    assert needle in p.stderr
    assert "Traceback" not in p.stderr and len(p.stderr.strip().splitlines()) == 1


def test_a_parameter_under_the_runs_model_by_alias_or_case_is_read():
    # iso5048.f_carry with --model iso5048 (din) and DIN.f_carry were dropped: Te unchanged
    te = {}
    for args in (["--model", "din"], ["--model", "din", "--param", "f_carry=0.03"],
                 ["--model", "iso5048", "--param", "iso5048.f_carry=0.03"],
                 ["--model", "din", "--param", "DIN.f_carry=0.03"]):
        p = run("static", str(CONVEYORS / "fabric-1km.yaml"), *args, "--json")
        te[" ".join(args)] = json.loads(p.stdout)["te_kn"]
    base, *given = te.values()
    assert given[0] > base * 1.1
    assert given == pytest.approx([given[0]] * 3, rel=1e-12)


def test_model_params_fold_aliases_and_refuse_a_repeat():
    from beltstudy.engine import InputError
    from beltstudy.service.cli.common import parse_model_params, parse_params

    assert parse_model_params(["ISO5048.f_carry=0.01", "cema.ky=0.02"]) == {
        "din": {"f_carry": 0.01}, "cema": {"ky": 0.02}}
    with pytest.raises(InputError, match=r"din.f_carry is already set by --param "
                                         r"'din.f_carry=0.01'"):
        parse_model_params(["din.f_carry=0.01", "iso5048.f_carry=0.02"])
    assert parse_params(["non-lin.mu_b=0.002"], "NONLIN") == {"mu_b": 0.002}
    with pytest.raises(InputError, match=r"give f_carry=VALUE for din, or --model cema"):
        parse_params(["cema.f_carry=0.05"], "din")
    # cema.ky under din told the user to 'give ky=VALUE for din', a name din does not have
    with pytest.raises(InputError) as ky:
        parse_params(["cema.ky=0.03"], "din")
    assert "ky=VALUE for din" not in str(ky.value)
    assert str(ky.value).endswith(": --model cema (din has no ky; its parameters: f_carry, "
                                  "f_return, c)")
    with pytest.raises(InputError, match=r"^--param 'xx.f=1': unknown model 'xx'"):
        parse_params(["xx.f=1"], "din")


def test_static_bad_file_one_line(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("name: x\nspeed_m_s: [1\n")
    p = run("static", str(bad), check=False)
    assert p.returncode == 2 and "not valid YAML" in p.stderr and "Traceback" not in p.stderr
    bad.write_text((CONVEYORS / "slope-5pct.yaml").read_text().replace("speed_m_s: 4.5",
                                                                        "speed_m_s: 0"))
    p = run("static", str(bad), check=False)
    assert p.returncode == 2 and "speed_m_s" in p.stderr and "Traceback" not in p.stderr
    p = run("static", str(tmp_path / "missing.yaml"), check=False)
    assert p.returncode == 2 and "file not found" in p.stderr


@pytest.mark.parametrize("args, needle", [
    (["--temperature-c", "-70"], "--temperature-c: Input should be greater than or equal to -60"),
    (["--load", "1.4"], "--load: fractions run from 0 to 1.3"),
    (["--load", "1,0"], "--load: 2 fractions for 1 profile sections"),
    (["--elements", "4"], "--elements: Input should be 'auto' or greater than or equal to 8"),
])
def test_static_refuses_what_a_scenario_refuses(args, needle, capsys):
    from beltstudy.service.cli import main

    assert main(["static", str(CONVEYORS / "slope-5pct.yaml"), *args]) == 2
    err = capsys.readouterr().err
    assert needle in err and len(err.strip().splitlines()) == 1


def test_static_simulate_and_sweep_share_the_scenario_bounds(tmp_path, capsys):
    """The temperature range is the scenario model's in every command (-60 to 80 C)."""
    from beltstudy.service.cli import main

    conveyor = str(CONVEYORS / "slope-5pct.yaml")
    for args in (["static", conveyor, "--temperature-c", "-70"],
                 ["simulate", conveyor, "--temperature-c", "-70"],
                 ["sweep-temperature", conveyor, "--from", "-70", "--to", "0",
                  "--out", str(tmp_path)]):
        assert main(args) == 2, args
        assert "-60" in capsys.readouterr().err


def test_static_prints_what_set_each_size_and_the_rest_sag_switch(capsys, tmp_path):
    """downhill-regen with a 0.2 % carry sag limit: held at rest by its head brake the carry
    arriving at the head needs g (m'_G + m'_L) S / (8 x 0.002), about 157 kN, more than the
    121.5 kN its drive needs to take the loaded belt from the brake (``slip_breakaway``, which
    sets the take-up of the file as it is), so the rest-sag switch decides the take-up."""
    from beltstudy.service.cli import main

    text = (CONVEYORS / "downhill-regen.yaml").read_text()
    limit = "sag_limit_pct: {carry: 1.5, return: 3.0}"
    assert limit in text
    conveyor = tmp_path / "downhill-regen-sag.yaml"
    conveyor.write_text(text.replace(limit, "sag_limit_pct: {carry: 0.2, return: 3.0}"))
    conveyor = str(conveyor)
    assert main(["static", conveyor, "--json"]) == 0
    on = json.loads(capsys.readouterr().out)
    assert main(["static", conveyor, "--json", "--no-sag-at-rest"]) == 0
    off = json.loads(capsys.readouterr().out)
    assert on["takeup_governed_by"] == "sag_at_rest"
    assert off["takeup_governed_by"] != "sag_at_rest"
    assert off["takeup_mass_kg"] < on["takeup_mass_kg"]
    assert on["brake_governed_by"] == "holding" and on["rated_power_governed_by"] == "given"
    assert main(["static", conveyor]) == 0
    table = capsys.readouterr().out
    assert "sizes and what set them" in table and "sag_at_rest" in table
    assert "fill (design flow / cross-section)" in table


def test_static_table_shows_the_horizontal_curves(tmp_path):
    """A curve on slope-5pct's route, its idlers by count and its belt by mass per metre
    (docs/routes.md): the table has a line per curve, its verdict matches the JSON's."""
    import yaml

    conv = yaml.safe_load((CONVEYORS / "slope-5pct.yaml").read_text())
    conv["belt"]["mass_kg_m"] = 38.5
    conv["idlers"]["carry"].pop("spacing_m")
    conv["idlers"]["carry"]["count"] = 1334
    conv["profile"] = [{"length_m": 1000, "lift_m": 50},
                       {"length_m": 1000, "lift_m": 50, "horizontal_radius_m": 2000,
                        "superelevation_deg": 3}]
    path = tmp_path / "curved.yaml"
    path.write_text(yaml.safe_dump(conv))
    out = json.loads(run("static", str(path), "--model", "din", "--json", check=False).stdout)
    assert out["belt_mass_kg_m"] == 38.5
    table = run("static", str(path), "--model", "din", check=False).stdout
    line = next(ln for ln in table.splitlines() if ln.strip().startswith("curve 1"))
    assert line.split()[-1] == ("yes" if out["hcurve1_ok"] else "NO")
    assert f"{out['hcurve1_tension_max_kn']:.1f}" in line


def test_static_table_shows_a_concave_curve_at_start_up(capsys):
    """valley-booster's concave curve (the README's table): under the running line a line
    at start-up with the start-up walk's tension at the curve, the same lift-off tension,
    the verdict and the radius the start needs, as the JSON gives them (the radius rounded
    up, as a least value is advised)."""
    from beltstudy.service.cli import main

    path = str(CONVEYORS / "valley-booster.yaml")
    assert main(["static", path, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert main(["static", path]) == 0
    lines = capsys.readouterr().out.splitlines()
    i = next(n for n, ln in enumerate(lines) if ln.strip().startswith("curve 1: concave"))
    start = lines[i + 1].split()
    assert lines[i + 1].strip().startswith("at start-up")
    assert start[-4:] == [f"{out['curve1_tension_start_kn']:.1f}",
                          f"{out['curve1_liftoff_tension_kn']:.1f}",
                          "YES" if out["curve1_liftoff_start"] else "no",
                          f"{math.ceil(out['curve1_radius_min_start_m']):.0f}"]
    assert out["curve1_tension_start_kn"] > out["curve1_tension_kn"]


def test_static_output_in_a_missing_folder_is_one_line(tmp_path, capsys):
    from beltstudy.service.cli import main

    for option, name in (("--plot", "p.png"), ("--profile", "p.csv")):
        out = tmp_path / "missing" / name
        assert main(["static", str(CONVEYORS / "slope-5pct.yaml"), option, str(out)]) == 2
        err = capsys.readouterr().err
        assert err == (f"error: cannot write {out}: the folder {out.parent} does not exist\n")


BOMB = "".join(f"{b}: &{b} [{', '.join(['*' + a] * 9)}]\n"
               for a, b in zip("abcdefgh", "bcdefghi", strict=True))


@pytest.mark.parametrize("extra, needle", [
    ("a: &a [1, 2, 3, 4, 5, 6, 7, 8, 9]\n" + BOMB, "(YAML aliases expanded)"),
    ("deep: " + "[" * 200 + "]" * 200 + "\n", "nested deeper than"),
    ("nan: .nan\n", "NaN is not a number"),
])
def test_every_command_reads_a_conveyor_file_within_the_doors_limits(tmp_path, capsys, extra,
                                                                     needle):
    """A conveyor file read by static, simulate and sweep-temperature meets the limits a study's
    conveyor file meets (beltstudy.service.door.parse): an alias bomb of a few hundred bytes, a
    deep nesting and a NaN are one-line errors, before anything is expanded or run."""
    from beltstudy.service.cli import main

    bad = tmp_path / "bad.yaml"
    bad.write_text((CONVEYORS / "slope-5pct.yaml").read_text() + extra)
    for args in (["static", str(bad)], ["simulate", str(bad), "--no-check"],
                 ["sweep-temperature", str(bad), "--out", str(tmp_path)]):
        assert main(args) == 2, args
        err = capsys.readouterr().err
        assert needle in err and len(err.strip().splitlines()) == 1, (args, err)


def test_static_keeps_the_files_rest_sag_switch(capsys):
    """benchmarks' ISO 5048 example says ``takeup.sag_at_rest: false``: without the CLI switch
    the file's choice stands (running sag sets the take-up, 2 T / g with T the carry's sag
    minimum less the tail's resistances), as it does with ``--no-sag-at-rest``; the rule held at
    rest would ask for the full 22005 N per strand (4486 kg)."""
    from beltstudy.service.cli import main
    from tests.conftest import ROOT

    conveyor = ROOT / "benchmarks" / "conveyors" / "iso5048-flat-143m.yaml"
    assert "sag_at_rest: false" in conveyor.read_text()
    assert main(["static", str(conveyor), "--json"]) == 0
    plain = json.loads(capsys.readouterr().out)
    assert main(["static", str(conveyor), "--json", "--no-sag-at-rest"]) == 0
    off = json.loads(capsys.readouterr().out)
    assert plain["takeup_governed_by"] == off["takeup_governed_by"] == "sag_running"
    assert plain["takeup_mass_kg"] == off["takeup_mass_kg"] < 4486.0


def test_static_loads_no_other_commands_stack():
    """Issue 3: ``beltstudy static`` on the 16.8 km example answers in under a second with
    start-up. It did in 0.8 s until every command's module was imported to build the parser:
    the study commands' Dask and HTTP client and the calibration took it to 1.5 s of CPU. The
    command now imports its own module only (no timing here: what it loads)."""
    code = (
        "import sys, contextlib, io\n"
        "from beltstudy.service.cli import main\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        f"    code = main(['static', {str(CONVEYORS / 'slope-5pct.yaml')!r}, '--json'])\n"
        "heavy = ['distributed', 'httpx', 'beltstudy.service.cli.study',\n"
        "         'beltstudy.service.cli.demo', 'beltstudy.service.calibration']\n"
        "print(code, [m for m in heavy if m in sys.modules])\n"
    )
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       timeout=120)
    assert p.returncode == 0, p.stderr
    assert p.stdout.strip() == "0 []"


def test_the_command_table_names_each_commands_module():
    """Each command runs with the parser of its own module alone (``COMMANDS``): the table
    holds every command the modules register, each under the module that registers it."""
    import argparse
    import importlib

    from beltstudy.service import cli

    found = {}
    for name in cli.COMMAND_MODULES:
        sub = argparse.ArgumentParser().add_subparsers()
        importlib.import_module(f"beltstudy.service.cli.{name}").register(sub)
        found.update(dict.fromkeys(sub.choices, name))
    assert found == cli.COMMANDS
    assert list(found) == list(cli.COMMANDS)  # the order of --help


def test_elements_auto_is_the_engines_count(capsys):
    """``--elements auto`` (the help's default) is read, and gives the count of no option;
    a word that is neither a number nor auto is refused naming the option and the fix."""
    from beltstudy.service.cli import main

    slope = str(CONVEYORS / "slope-5pct.yaml")
    assert main(["static", slope, "--json"]) == 0
    plain = json.loads(capsys.readouterr().out)
    assert main(["static", slope, "--json", "--elements", "auto"]) == 0
    auto = json.loads(capsys.readouterr().out)
    assert auto["te_kn"] == plain["te_kn"]
    with pytest.raises(SystemExit):
        main(["static", slope, "--elements", "many"])
    err = capsys.readouterr().err
    assert "--elements" in err and "or auto" in err


@pytest.mark.parametrize("radius_m, tight", [(40.0, True), (400.0, False)])
def test_static_table_marks_a_convex_curve_below_its_radius(tmp_path, capsys, radius_m, tight):
    """A crest (flat, then falling 4 %) of R 40 m needs about 111 m for its centre line: its
    row says so beside the radius it needs; at R 400 m the row has no mark. A convex curve
    has no lift-off verdict ("-")."""
    import yaml

    from beltstudy.service.cli import main
    from tests.conftest import hand_conveyor_dict

    d = hand_conveyor_dict(profile=[{"length_m": 500, "lift_m": 0, "curve_radius_m": radius_m},
                                    {"length_m": 500, "lift_m": -20}])
    path = tmp_path / "crest.yaml"
    path.write_text(yaml.safe_dump(d))
    assert main(["static", str(path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert main(["static", str(path)]) == 0
    (row,) = [ln for ln in capsys.readouterr().out.splitlines()
              if ln.strip().startswith("curve 1: convex")]
    assert row.split()[6] == "-"  # no lift-off verdict on a crest
    assert row.split()[7] == f"{math.ceil(out['curve1_radius_min_m']):.0f}"
    assert (out["curve1_radius_min_m"] > radius_m) is tight
    assert (f"TOO TIGHT: R {radius_m:g} m" in row) is tight
