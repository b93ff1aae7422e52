"""Sampled studies (SPEC 7.2 ``sample:``): drawn values, the runs they become, refusals."""

from __future__ import annotations

import re

import numpy as np
import pytest

from beltstudy.service.door.sample import SampleIn, draw, unit_points
from beltstudy.service.door.studyfile import resolve_study
from beltstudy.service.errors import Invalid
from beltstudy.service.grid.expand import study_from_json
from tests.service.conftest import ROOT, tiny_study

AXES = {
    "temperature_c": {"dist": "uniform", "low": -25, "high": 35},
    "models.din.f_carry": {"dist": "lognormal", "median": 0.02, "sigma": 0.2},
    "takeup.mass_kg": {"dist": "normal", "mean": 3000, "sd": 100},
}


def sampled(n=20, method="lhs", seed=7, axes=None, **over):
    over.setdefault("grid", {"friction_model": ["din"]})
    return tiny_study("sampled", sample={"n": n, "method": method, "seed": seed,
                                         "axes": axes or AXES}, **over)


def test_lhs_puts_one_point_in_each_stratum():
    s = SampleIn(n=50, method="lhs", seed=1, axes=AXES)
    u = unit_points(s)
    for k in range(3):
        assert sorted(np.floor(u[:, k] * 50).astype(int)) == list(range(50))


def test_distributions_have_their_moments():
    # 4000 LHS points: the sample mean of a stratified sample is far closer than 1/sqrt(n)
    s = SampleIn(n=4000, method="lhs", seed=2, axes={
        "a": {"dist": "uniform", "low": 2, "high": 6},
        "b": {"dist": "normal", "mean": 10, "sd": 2},
        "c": {"dist": "lognormal", "median": 1.5, "sigma": 0.3},
        "d": {"dist": "triangular", "low": 0, "mode": 1, "high": 5}})
    v = {k: np.array(x) for k, x in draw(s).items()}
    assert v["a"].min() >= 2 and v["a"].max() <= 6 and v["a"].mean() == pytest.approx(4, abs=0.01)
    assert v["b"].mean() == pytest.approx(10, abs=0.01)
    assert v["b"].std() == pytest.approx(2, rel=0.01)
    assert np.median(v["c"]) == pytest.approx(1.5, rel=0.01)
    assert np.log(v["c"]).std() == pytest.approx(0.3, rel=0.01)
    assert v["d"].mean() == pytest.approx(2.0, abs=0.01)  # (low + mode + high) / 3
    assert v["d"].min() >= 0 and v["d"].max() <= 5


def test_sobol_is_saltellis_design():
    # SALib's order per base point j: A_j, AB_1 .. AB_D, B_j; AB_i = A with column i of B
    d = 3
    s = SampleIn(n=8 * (d + 2), method="sobol", seed=3, axes=AXES)
    u = unit_points(s).reshape(8, d + 2, d)
    a, b = u[:, 0], u[:, -1]
    for i in range(d):
        ab = u[:, 1 + i]
        assert np.array_equal(ab[:, i], b[:, i])
        others = [k for k in range(d) if k != i]
        assert np.array_equal(ab[:, others], a[:, others])


def test_sampled_study_runs_crossed_with_the_grid_and_stable():
    study = resolve_study(sampled(n=12, grid={"friction_model": ["din", "cema"]},
                                  axes={"temperature_c": AXES["temperature_c"],
                                        "takeup.mass_kg": AXES["takeup.mass_kg"]}))
    assert study.total == 24 and study.grid_points == 24
    temps = {r.axes["temperature_c"] for r in study.runs}
    assert len(temps) == 12 and all(-25 <= t <= 35 for t in temps)
    # each run's conveyor holds its drawn take-up mass
    for r in study.runs:
        assert r.conveyor["takeup"]["mass_kg"] == r.axes["takeup.mass_kg"]
    again = resolve_study(sampled(n=12, grid={"friction_model": ["din", "cema"]},
                                  axes={"temperature_c": AXES["temperature_c"],
                                        "takeup.mass_kg": AXES["takeup.mass_kg"]}))
    assert again.id == study.id and [r.run_id for r in again.runs] == [
        r.run_id for r in study.runs]
    resumed = study_from_json(study.to_json(), study.id)
    assert [r.run_id for r in resumed.runs] == [r.run_id for r in study.runs]
    other = resolve_study(sampled(n=12, seed=8, grid={"friction_model": ["din", "cema"]},
                                  axes={"temperature_c": AXES["temperature_c"]}))
    assert not {r.run_id for r in other.runs} & {r.run_id for r in study.runs}


def test_design_is_sized_once_at_the_nominal_inputs():
    # the motor is sized for the nominal friction and held: the sample tests that design
    study = resolve_study(sampled(n=10, axes={"models.din.f_carry": AXES["models.din.f_carry"]}))
    rated = {r.conveyor["drives"][0]["rated_power_kw"] for r in study.runs}
    assert len(rated) == 1 and len(study.designs) == 1
    nominal = resolve_study(tiny_study("nominal", grid={"friction_model": ["din"]}))
    assert rated == {nominal.runs[0].conveyor["drives"][0]["rated_power_kw"]}


def test_sample_only_study_is_valid():
    data = sampled(n=6)
    del data["grid"]
    assert resolve_study(data).total == 6


@pytest.mark.parametrize("axes, message", [
    ({"temperature_c": {"dist": "normal", "mean": 0, "sd": -1}},
     r"sample\.axes\.temperature_c.*sd"),
    ({"temperature_c": {"dist": "uniform", "low": 10, "high": -10}},
     r"sample\.axes\.temperature_c.*high \(-10\) must be above low \(10\)"),
    ({"temperature_c": {"dist": "triangular", "low": 0, "mode": 12, "high": 10}},
     r"sample\.axes\.temperature_c.*mode \(12\) must lie between"),
    ({"temperature_c": {"dist": "weibull", "k": 2}}, r"sample\.axes\.temperature_c.*dist"),
    ({"temperature_c": {"dist": "lognormal", "median": -1, "sigma": 0.2}},
     r"sample\.axes\.temperature_c.*median"),
    ({"belt_type": {"dist": "uniform", "low": 0, "high": 1}},
     r"sample\.axes\.belt_type: 'belt_type' does not take a number"),
    ({"friction_model": {"dist": "uniform", "low": 0, "high": 1}},
     r"sample\.axes\.friction_model: .*does not take a number"),
    ({"takeup.mas_kg": {"dist": "uniform", "low": 1, "high": 2}},
     r"sample\.axes: unknown axis 'takeup\.mas_kg'.*did you mean 'takeup\.mass_kg'"),
    ({"models.din.f_carry": {"dist": "normal", "mean": 0.0, "sd": 0.01}},
     r"^sample\.axes\.models\.din\.f_carry: \d+ of 16 drawn values break the field's bound "
     r"models\.din\.f_carry >= 0 \(drawn -[0-9.e-]+.*\): give a distribution within it"),
    # a uniform beyond the field's bound: refused by its ends, before drawing, naming the
    # bound and the fix (it was blamed on the grid: "grid: 5 of 16 scenario variants ...")
    ({"temperature_c": {"dist": "uniform", "low": -100, "high": 35}},
     r"^sample\.axes\.temperature_c: low \(-100\) lies below the field's bound "
     r"temperature_c >= -60: draws beyond it would be refused; give low >= -60$"),
    ({"temperature_c": {"dist": "triangular", "low": -20, "mode": 0, "high": 90}},
     r"^sample\.axes\.temperature_c: high \(90\) lies above the field's bound "
     r"temperature_c <= 80: .*give high <= 80$"),
    ({"temperature_c": {"dist": "normal", "mean": -40, "sd": 15}},
     r"^sample\.axes\.temperature_c: \d+ of 16 drawn values break the field's bound "
     r"temperature_c >= -60 \(drawn -6\d.*a bounded one \(uniform or triangular"),
    # a key of another distribution: it said "unknown key 'sd'; did you mean 'sd'?"
    ({"temperature_c": {"dist": "uniform", "low": 0, "high": 10, "sd": 3}},
     r"^sample\.axes\.temperature_c\.sd: unknown key 'sd' \(a key of normal, not of this "
     r"kind\); valid keys: dist, low, high$"),  # uniform's own keys, not every member's
    # a parameter of a model the study does not run, named where it is written (it was
    # "grid: axis 'models.nonlin.m_star': ..." for a sample axis)
    ({"models.nonlin.m_star": {"dist": "uniform", "low": 0.003, "high": 0.008}},
     r"^sample\.axes: axis 'models\.nonlin\.m_star': model 'nonlin' is not run by this "
     r"study \(its models: din\); add nonlin to the friction_model axis"),
    ({"takeup.mass_kg": {"dist": "normal", "mean": 1e6, "sd": 1e6}},
     r"^sample\.axes\.takeup\.mass_kg: \d+ of 16 drawn values break the field's bound "
     r"takeup\.mass_kg > 0 and takeup\.mass_kg <= 2e\+06"),
])
def test_invalid_distributions_are_refused_naming_the_field(axes, message):
    with pytest.raises(Invalid, match=message):
        resolve_study(sampled(axes=axes, n=16, method="lhs"))


def test_an_open_bound_at_a_uniform_end_is_kept():
    """The draws never reach a uniform's ends: low 0 for a field > 0 draws only positives."""
    study = resolve_study(sampled(axes={"takeup.mass_kg": {"dist": "uniform", "low": 0,
                                                           "high": 3000}}, n=16, method="lhs"))
    assert study.total == 16


@pytest.mark.parametrize("n, points", [(100, 80), (512, 640), (480, 320), (80, 80),
                                       (10, 10)])
def test_sobol_draws_the_nearest_saltelli_design(n, points):
    """SPEC 7.2's ``n: 512`` over three axes runs: method sobol draws N (D + 2) points with N a
    power of two, the size nearest n (the smaller on a tie), n itself when it is one."""
    study = resolve_study(sampled(n=n, method="sobol"))
    assert study.total == points
    base = points // 5
    assert base & (base - 1) == 0 and base >= 2


def test_sobol_size_and_overlap_are_refused():
    with pytest.raises(Invalid, match=r"sample.*n = 9: method sobol.*use n >= 10"):
        resolve_study(sampled(n=9, method="sobol"))
    with pytest.raises(Invalid, match=r"^grid\.temperature_c and sample\.axes\.temperature_c "
                                      r"both set scenario\.temperature_c: give it in one of "
                                      r"them$"):
        resolve_study(sampled(grid={"temperature_c": [0, 10]}))


@pytest.mark.parametrize("axis", ["stop_time_s", "run_s", "start.time_s"])
def test_a_steady_study_refuses_a_sample_axis_its_runs_never_read(axis):
    """A steady run reads load, temperature and mesh of its scenario: drawing the stop time
    would make every draw one run (merged), and the sample's statistics nothing."""
    pattern = (rf"^sample\.axes\.{re.escape(axis)}: a steady study \(dynamics: false\) "
               r"does not read scenario\.")
    with pytest.raises(Invalid, match=pattern):
        resolve_study(sampled(n=8, axes={axis: {"dist": "uniform", "low": 10, "high": 20}}),
                      studies_dir=ROOT / "studies")
    # read fields stay samplable in a steady study
    resolve_study(sampled(n=8, axes={"temperature_c": {"dist": "uniform", "low": 0,
                                                       "high": 20}}),
                  studies_dir=ROOT / "studies")


def test_a_sample_axis_no_run_reads_is_refused():
    """Drawing the stop time of a study whose runs all coast to rest made every draw one run
    (a coast stop does not read its stop time): 4 points, 1 run and an uncertainty answer
    with sd 0. It is refused, naming the axis and what reads it; the same axis over
    controlled stops is drawn."""
    axes = {"stop_time_s": {"dist": "uniform", "low": 10, "high": 20}}
    with pytest.raises(Invalid, match=r"^sample\.axes\.stop_time_s: no run of this study reads "
                                      r"scenario\.stop\.time_s \(a coast stop does not read"):
        resolve_study(sampled(n=4, axes=axes, dynamics=True,
                              scenario={"stop": {"mode": "coast"}}),
                      studies_dir=ROOT / "studies")
    study = resolve_study(sampled(n=4, axes=axes, dynamics=True,
                                  scenario={"stop": {"mode": "controlled"}}),
                          studies_dir=ROOT / "studies")
    assert study.total == 4


@pytest.mark.parametrize("axis", ["scenario.elements", "idlers.return.count",
                                  "idlers.carry.rolls"])
def test_a_sample_axis_of_a_whole_number_field_is_refused_naming_it(axis):
    """A sample draws real values: ``scenario.elements`` drawn uniform 20 to 40 made every
    variant fail as 'grid: 8 of 8 scenario variants are invalid: ... scenario.elements:
    21.5048272628 is not of type "integer"' (a grid the study does not have). It is refused
    at the sample, naming the axis and the way out (a grid axis of its values)."""
    dynamic = axis.startswith("scenario.")
    pattern = (rf"^sample\.axes\.{re.escape(axis)}: '{re.escape(axis)}' takes a whole number "
               r"\(a count\) and a sample draws real values.*grid axis")
    with pytest.raises(Invalid, match=pattern):
        resolve_study(sampled(n=8, dynamics=dynamic,
                              axes={axis: {"dist": "uniform", "low": 2, "high": 40}}),
                      studies_dir=ROOT / "studies")


def test_drawn_values_the_conveyor_refuses_are_named_as_the_sample_s():
    """``profile.0.lift_m`` drawn uniform 3 to 80 on a 60 m section: the draws above 60 m were
    refused as 'grid: 2 of 4 conveyor variants are invalid: ...' in a study whose grid does
    not have the axis, with no way out; now as the sample's, with what to give instead."""
    axes = {"profile.0.lift_m": {"dist": "uniform", "low": 3, "high": 80}}
    with pytest.raises(Invalid, match=r"^sample\.axes: \d+ of \d+ conveyor variants are "
                                      r"invalid: \(profile\.0\.lift_m=.*lift_m .* length_m "
                                      r".*; give each sample axis a distribution whose draws "
                                      r"the field takes"):
        resolve_study(sampled(n=8, axes=axes), studies_dir=ROOT / "studies")
