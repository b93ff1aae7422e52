"""The ``beltstudy sweep-temperature`` command that draws the paper's Fig. 2: one study on the
service's Dask executor, its CSV and figure agree with the engine's runs; bad arguments are one
line (exit 2). The findings themselves are tests/engine/integration/test_statics_paper_findings.py.
"""

from __future__ import annotations

import pandas as pd
import pytest

from beltstudy.engine.conveyor import load_conveyor, parse_conveyor, parse_scenario
from beltstudy.engine.friction import get_model
from beltstudy.engine.run import run_one
from beltstudy.service.cli import main
from beltstudy.service.cli.sweep import sweep_study
from beltstudy.service.door.studyfile import resolve_study
from tests.engine.integration.test_statics_paper_findings import DIN_PAPER, SLOPE, power


def test_sweep_temperature_command(tmp_path, capsys, monkeypatch):
    from beltstudy.service.studies import StudyService

    submitted = []
    submit = StudyService.submit

    def spy(self, data, **kw):  # the sweep is one study on the service's Dask executor
        submitted.append((data, self.settings.n_local_workers))
        return submit(self, data, **kw)

    monkeypatch.setattr(StudyService, "submit", spy)
    code = main(["sweep-temperature", str(SLOPE), "--models", "din,nonlin,cema", "--from", "-30",
                 "--to", "20", "--step", "25", "--param", "din.f_carry=0.010",
                 "--param", "din.f_return=0.008", "--load", "full", "--out", str(tmp_path)])
    assert code == 0
    df = pd.read_csv(tmp_path / "slope-5pct-full.csv")
    assert list(df["model"].unique()) == ["din", "nonlin", "cema"]
    assert sorted(df["temperature_c"].unique()) == [-30.0, -5.0, 20.0]
    nl = df[df["model"] == "nonlin"].set_index("temperature_c")
    # a study: the auto take-up is one installed design over the sweep, so Non-Lin (whose
    # resistance follows the sag) gives the power of the study's run at that design ...
    study = resolve_study(sweep_study(load_conveyor(SLOPE),
                                      [get_model(m) for m in ("din", "nonlin", "cema")],
                                      [-30.0, -5.0, 20.0], {"din": DIN_PAPER}, "full"))
    for t in (20.0, -30.0):
        spec = next(r for r in study.runs
                    if r.model == "nonlin" and r.axes["temperature_c"] == t)
        run = run_one(parse_conveyor(spec.conveyor), parse_scenario(spec.scenario),
                      model="nonlin", params=spec.params or None, dynamics=False)
        assert nl.loc[t, "power_kw"] == pytest.approx(run.summary["power_kw"], rel=1e-12)
    # ... within a few per cent of the case sized on its own
    assert nl.loc[20.0, "power_kw"] == pytest.approx(power("nonlin"), rel=0.03)
    din = df[df["model"] == "din"].set_index("temperature_c")  # DIN: no tension in the law
    assert din.loc[20.0, "power_kw"] == pytest.approx(power("din"), rel=1e-12)
    for part in ("idler_rotation", "indentation", "belt_flexure", "material_flexure"):
        assert (nl[f"te_{part}_kn"] > 0).all()
    png = tmp_path / "slope-5pct-full.png"
    assert png.read_bytes()[:4] == b"\x89PNG" and png.stat().st_size > 20_000
    assert "power [kW] against temperature" in capsys.readouterr().out
    [(body, workers)] = submitted
    assert body["grid"] == {"friction_model": ["din", "nonlin", "cema"],
                            "temperature_c": [-30.0, -5.0, 20.0]}
    assert body["dynamics"] is False and workers >= 1


@pytest.mark.parametrize("args, needle", [
    (["--models", "din,nonlni"], "did you mean 'nonlin'"),
    (["--step", "0"], "--step: must be > 0"),
    (["--from", "20", "--to", "-20"], "must not be below --from"),
    (["--param", "din.f_cary=0.01"], "did you mean 'f_carry'"),
    (["--param", "cema.ky=0.02", "--models", "din"], "not in --models"),
    (["--param", "f_carry=0.01"], "MODEL.NAME=VALUE"),
    (["--load", "heavy"], "--load"),
])
def test_sweep_temperature_bad_args(tmp_path, capsys, args, needle):
    code = main(["sweep-temperature", str(SLOPE), "--out", str(tmp_path / "o"), *args])
    err = capsys.readouterr().err
    assert code == 2 and needle in err
    assert len(err.strip().splitlines()) == 1
