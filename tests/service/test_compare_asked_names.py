"""``compare``: a metric asked by name that no run of the study has is refused, and "(the
default)" is said only of a model the request left to its default.

On a steady study of cema and din, ``metrics=t_max_dyn_kn`` (a transient figure) and
``metrics=te_idler_rotation_kn`` (Non-Lin's part, neither model writes it) answered 200 with
every value null, and ``beltstudy compare --metrics t_max_dyn_kn`` printed "(0 pairs)" and
exited 0; the README promises 422 for a name the study does not have. On a din-only study,
``baseline=cema`` given explicitly was said to be "(the default)".
"""

from __future__ import annotations

import pytest
from fastapi.testclient import TestClient

from beltstudy.service.api.app import create_app
from beltstudy.service.cli import main


@pytest.fixture
def steady(data_dir, finished_study, make_study, make_settings):
    """A finished steady study of cema and din, and a client of the service on its store."""
    sid = finished_study(data_dir, make_study(
        grid={"friction_model": ["cema", "din"], "temperature_c": [0, 20]}))
    return sid, TestClient(create_app(make_settings(data_dir)))


@pytest.mark.parametrize("metric", ["t_max_dyn_kn", "te_idler_rotation_kn"])
def test_a_metric_no_run_has_is_a_422_naming_it(steady, metric):
    sid, client = steady
    r = client.get(f"/studies/{sid}/compare",
                   params={"baseline": "cema", "candidate": "din", "metrics": metric})
    assert r.status_code == 422, r.text
    message = r.json()["message"]
    assert message.startswith(f"metrics: '{metric}' has no values in this study"), message
    assert "metrics with values: " in message and "power_kw" in message, message
    # one the study has is answered, and with a metric it lacks beside it the whole is refused
    ok = client.get(f"/studies/{sid}/compare",
                    params={"baseline": "cema", "candidate": "din", "metrics": "power_kw"})
    assert ok.status_code == 200 and ok.json()["summary"]["power_kw"]["overall"]["n"] == 2
    r = client.get(f"/studies/{sid}/compare",
                   params={"baseline": "cema", "candidate": "din",
                           "metrics": f"power_kw,{metric}"})
    assert r.status_code == 422 and f"'{metric}' has no values" in r.json()["message"]


def test_the_defaults_still_keep_those_with_values(steady):
    """The default metrics are not asked by name: a steady study compares power alone."""
    sid, client = steady
    r = client.get(f"/studies/{sid}/compare", params={"baseline": "cema", "candidate": "din"})
    assert r.status_code == 200, r.text
    assert r.json()["metrics"] == ["power_kw"]


def test_beltstudy_compare_refuses_it_and_exits_non_zero(env, capsys, finished_study,
                                                         make_study):
    sid = finished_study(env, make_study(
        grid={"friction_model": ["cema", "din"], "temperature_c": [0, 20]}))
    code = main(["compare", sid, "--baseline", "cema", "--candidate", "din",
                 "--metrics", "t_max_dyn_kn"])
    captured = capsys.readouterr()
    assert code == 2, captured.out
    assert "(0 pairs)" not in captured.out
    assert captured.err.startswith("error: --metrics: 't_max_dyn_kn' has no values in this "
                                   "study"), captured.err


def test_the_default_is_said_only_of_a_model_left_to_it(data_dir, finished_study, make_study,
                                                        make_settings):
    sid = finished_study(data_dir, make_study(grid={"temperature_c": [0, 20]}, model="din"))
    client = TestClient(create_app(make_settings(data_dir)))
    url = f"/studies/{sid}/compare"
    given = client.get(url, params={"baseline": "cema", "candidate": "din"})
    assert given.status_code == 422
    assert given.json()["message"] == ("baseline: model 'cema' is not in this study; it has: "
                                       "din: give baseline=NAME from those"), given.text
    left = client.get(url, params={"candidate": "din"})
    assert left.status_code == 422
    assert left.json()["message"] == ("baseline: model 'cema' (the default) is not in this "
                                      "study; it has: din: give baseline=NAME from those")
    left = client.get(url, params={"baseline": "din"})
    assert left.status_code == 422
    assert left.json()["message"].startswith("candidate: model 'nonlin' (the default) is not "
                                             "in this study"), left.text


def test_the_command_line_says_the_default_only_when_the_option_is_left_out(
        env, capsys, finished_study, make_study):
    sid = finished_study(env, make_study(grid={"temperature_c": [0, 20]}, model="din"))
    assert main(["compare", sid, "--baseline", "cema", "--candidate", "din"]) == 2
    assert capsys.readouterr().err == ("error: --baseline: model 'cema' is not in this study; "
                                       "it has: din: give baseline=NAME from those\n")
    assert main(["compare", sid, "--candidate", "din"]) == 2
    assert "--baseline: model 'cema' (the default) is not" in capsys.readouterr().err
