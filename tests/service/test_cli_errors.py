"""The CLI maps errors by type: user mistakes are one line and exit 2, anything else raises."""

from __future__ import annotations

import argparse
import errno

import pytest
import yaml

import beltstudy.service.cli as cli
from beltstudy.engine.errors import InputError
from beltstudy.service.errors import (
    Conflict,
    Invalid,
    NotFound,
    ServiceError,
    Unavailable,
    shown_path,
)


def _raising(monkeypatch, exc: BaseException) -> None:
    def build_parser():
        parser = argparse.ArgumentParser()

        def func(_args):
            raise exc

        parser.set_defaults(func=func)
        return parser

    monkeypatch.setattr(cli, "build_parser", build_parser)


@pytest.mark.parametrize("exc", [InputError("must be > 0", field="scenario.run_s"),
                                 Invalid("grid: empty"), NotFound("study 'x' not found"),
                                 Conflict("being deleted"), Unavailable("no service")])
def test_user_errors_are_one_line_and_exit_2(monkeypatch, capsys, exc):
    _raising(monkeypatch, exc)
    assert cli.main([]) == 2
    err = capsys.readouterr().err
    assert err == f"error: {exc}\n"


def test_a_service_error_prints_its_user_message(monkeypatch, capsys):
    class Custom(ServiceError):
        @property
        def user_message(self) -> str:
            return "said for people"

    _raising(monkeypatch, Custom("raw"))
    assert cli.main([]) == 2
    assert capsys.readouterr().err == "error: said for people\n"


def test_an_error_named_like_a_user_error_is_not_one(monkeypatch):
    """Only the types count: an unrelated exception class called Invalid is a bug."""
    Invalid = type("Invalid", (RuntimeError,), {})
    _raising(monkeypatch, Invalid("boom"))
    with pytest.raises(RuntimeError, match="boom"):
        cli.main([])


def test_input_error_keeps_its_field_apart():
    exc = InputError("unknown model 'x'", field="friction_model")
    assert str(exc) == "friction_model: unknown model 'x'"
    assert (exc.field, exc.reason) == ("friction_model", "unknown model 'x'")
    from beltstudy.engine.conveyor import InputError as FromConveyor

    assert FromConveyor is InputError


# ------------------------------------------------------------ files the user names
def test_an_os_error_on_a_named_file_is_one_line_and_exit_2(monkeypatch, capsys):
    name = "a" * 300 + ".yaml"
    _raising(monkeypatch, OSError(errno.ENAMETOOLONG, "File name too long", name))
    assert cli.main([]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: aaaa") and err.count("\n") == 1
    assert "file name too long: a name of 305 bytes, at most 255" in err


def test_an_os_error_about_no_file_is_not_a_user_error(monkeypatch):
    _raising(monkeypatch, OSError(errno.EIO, "Input/output error"))
    with pytest.raises(OSError, match="Input/output error"):
        cli.main([])


@pytest.fixture
def local(monkeypatch, data_dir, tmp_path, make_conveyor):
    """No service at the default address, the store in ``data_dir``, a conveyor file."""
    from beltstudy.service.cli import study
    from beltstudy.service.cli.demo import free_port

    monkeypatch.delenv("BELTSTUDY_URL", raising=False)
    monkeypatch.setattr(study, "DEFAULT_URL", f"http://127.0.0.1:{free_port()}")
    monkeypatch.setenv("BELTSTUDY_DATA_DIR", str(data_dir))
    conveyor = tmp_path / "conveyor.yaml"
    conveyor.write_text(yaml.safe_dump(make_conveyor()), encoding="utf-8")
    return conveyor


LONG = "a" * 300


@pytest.mark.parametrize(("argv", "said"), [
    (["static", f"{LONG}.yaml"], "error: "),
    (["run", f"{LONG}.yaml"], "error: "),
    (["static", "{conveyor}", "--profile", "{tmp}/" + LONG + ".csv"], "error: cannot write "),
    (["static", "{conveyor}", "--plot", "{tmp}/" + LONG + ".png"], "error: cannot write "),
    (["results", "{sid}", "-o", "{tmp}/" + LONG + ".csv"], "error: cannot write "),
    (["report", "{sid}", "-o", "{tmp}/" + LONG + ".html"], "error: cannot write "),
    (["calibrate", "{conveyor}", "--measured", "{tmp}/" + LONG + ".csv", "--model", "din",
      "--fit", "f_carry"], "error: "),
])
def test_a_file_name_too_long_is_one_line_naming_it(local, capsys, tmp_path, data_dir,
                                                    finished_study, make_study, argv, said):
    # each printed an OSError: [Errno 36] traceback and exited 1
    sid = finished_study(data_dir, make_study()) if "{sid}" in argv else ""
    fill = {"conveyor": str(local), "tmp": str(tmp_path), "sid": sid}
    argv = [a.format(**fill) for a in argv]
    named = next(a for a in argv if LONG in a)
    before = sorted(p.name for p in tmp_path.iterdir())
    assert cli.main(argv) == 2
    err = capsys.readouterr().err
    # the file named as given (a long one by its start and end: shown_path)
    assert err.startswith(said + shown_path(named)[:60]), err
    assert err.count("\n") == 1 and "Traceback" not in err
    assert ("file name too long: a name of 30" in err and "at most 255" in err
            and err.endswith("give a shorter name\n")), err
    assert sorted(p.name for p in tmp_path.iterdir()) == before  # nothing written


@pytest.mark.parametrize(("argv", "needle"), [
    (["status", "--url", "http://[::1"], "--url / BELTSTUDY_URL: 'http://[::1' is not the "
                                         "service's address"),
    (["status", "--url", "http://127.0.0.1:abc"], "(Invalid port: 'abc')"),
    (["status", "--url", "localhost:8000"], "expected http:// or https:// and a host"),
    (["status", "--url", "http://127.0.0.1:9", "--token", "é"],
     "--token / BELTSTUDY_TOKEN: a token is printable ASCII"),
    (["status", "--url", "http://127.0.0.1:9", "--token", "tok\n123"],
     "--token / BELTSTUDY_TOKEN: a token is printable ASCII"),
])
def test_a_bad_service_address_or_token_is_one_line(capsys, argv, needle):
    """Not a traceback (httpx.InvalidURL, UnicodeEncodeError in the header), nor 'cannot reach
    the service' for a token the service never saw."""
    assert cli.main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: ") and needle in err, err
    assert err.count("\n") == 1 and "Traceback" not in err


@pytest.mark.parametrize(("argv", "needle"), [
    (["compare", "0123456789abcdef", "--metrics", ""], "--metrics: an empty name in ''"),
    (["compare", "0123456789abcdef", "--metrics", ","], "--metrics: an empty name in ','"),
    (["sweep-temperature", "studies/conveyors/slope-5pct.yaml", "--from", "-40", "--to", "40",
      "--step", "7", "--out", "unused"], "--to 40 is not reached from --from -40 in steps of "
                                         "7: give --to 37 or 44"),
    (["sweep-temperature", "studies/conveyors/slope-5pct.yaml", "--models", "din,,cema",
      "--out", "unused"], "--models: an empty name in 'din,,cema'"),
])
def test_an_empty_list_item_or_an_unreached_end_is_refused(capsys, monkeypatch, argv, needle):
    """Not read as the defaults, nor silently dropped or ended short (a study's range says
    the same)."""
    from tests.conftest import ROOT

    monkeypatch.chdir(ROOT)
    assert cli.main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: ") and needle in err, err


@pytest.mark.parametrize("argv", [
    ["static", "studies/conveyors/slope-5pct.yaml", "--model", "dim"],
    ["simulate", "studies/conveyors/slope-5pct.yaml", "--model", "dim"],
    ["calibrate", "studies/conveyors/slope-5pct.yaml", "--measured",
     "studies/plant/slope-5pct-power.csv", "--model", "dim", "--fit", "f"],
    ["sweep-temperature", "studies/conveyors/slope-5pct.yaml", "--models", "din,dim",
     "--out", "unused"],
])
def test_an_unknown_model_names_the_option_that_gave_it(capsys, monkeypatch, argv):
    """The option the user typed (--model, --models), not the result column friction_model,
    with the near name."""
    from tests.conftest import ROOT

    monkeypatch.chdir(ROOT)
    assert cli.main(argv) == 2
    err = capsys.readouterr().err
    option = argv[argv.index("dim") - 1] if "dim" in argv else "--models"
    assert err.startswith(f"error: {option}: unknown model 'dim' (did you mean 'din'?)"), err


@pytest.fixture
def not_the_service():
    """A real HTTP server on a free loopback port that is not the service: an HTML page with
    200 at /studies and / (a web server's index), HTML 404 pages elsewhere."""
    import http.server
    import threading

    class Handler(http.server.BaseHTTPRequestHandler):
        def _answer(self):
            code = 200 if self.path.split("?")[0] in ("/", "/studies") else 404
            body = b"<!doctype html>\n<html>\n<body>\n<h1>It works</h1>\n</body>\n</html>\n"
            self.send_response(code)
            self.send_header("Content-Type", "text/html; charset=utf-8")
            self.send_header("Content-Length", str(len(body)))
            self.end_headers()
            self.wfile.write(body)

        do_GET = do_POST = _answer

        def log_message(self, *args):
            pass

    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    yield f"http://127.0.0.1:{server.server_address[1]}"
    server.shutdown()
    server.server_close()


@pytest.mark.parametrize("argv", [
    ["status"],
    ["status", "0123456789abcdef"],
    ["results", "0123456789abcdef", "-o", "{tmp}/runs.json"],
    ["results", "0123456789abcdef", "-o", "{tmp}/runs.parquet"],
    ["report", "0123456789abcdef", "-o", "{tmp}/report.html"],
    ["compare", "0123456789abcdef"],
    ["uncertainty", "0123456789abcdef", "--json"],
])
def test_an_address_that_is_not_the_service_is_one_line(capsys, tmp_path, not_the_service,
                                                         argv):
    """--url at another web server: `status` printed a JSONDecodeError traceback (exit 1), the
    others its whole HTML page as the 'message', over several lines."""
    argv = [a.format(tmp=tmp_path) for a in argv] + ["--url", not_the_service]
    assert cli.main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: the answer at {not_the_service} is not the beltstudy "
                          "service's (HTTP "), err
    assert "text/html" in err and "check --url / BELTSTUDY_URL" in err
    assert err.count("\n") == 1 and "Traceback" not in err and "<html>" not in err
    assert list(tmp_path.iterdir()) == []  # nothing written


@pytest.mark.parametrize(("args", "message"), [
    # a study file where a conveyor goes, a conveyor file where a scenario or a study goes:
    # one line saying what the file is and where it goes, not an unknown key per top key
    (["static", "studies/paper-comparison.yaml"],
     "studies/paper-comparison.yaml: this is a study file (it has conveyor, grid, models, "
     "dynamics), not a conveyor file"),
    (["simulate", "studies/conveyors/slope-5pct.yaml", "--scenario",
      "studies/conveyors/slope-5pct.yaml"],
     "studies/conveyors/slope-5pct.yaml: this is a conveyor file (it has speed_m_s, belt, "
     "material, profile, idlers, drives), not a scenario file"),
    (["run", "studies/conveyors/slope-5pct.yaml"],
     "studies/conveyors/slope-5pct.yaml: this is a conveyor file (it has speed_m_s, belt, "
     "material, profile, idlers, drives), not a study file"),
])
def test_a_file_in_the_wrong_place_is_named_for_what_it_is(monkeypatch, capsys, tmp_path, args,
                                                           message):
    from tests.conftest import ROOT

    monkeypatch.chdir(ROOT)
    monkeypatch.setenv("BELTSTUDY_DATA_DIR", str(tmp_path / "data"))
    assert cli.main(args) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: " + message), err
    assert len(err.strip().splitlines()) == 1 and "unknown key" not in err


@pytest.mark.parametrize("text", [
    "scenario:\n  load: full\n  temperature_c: 20\n  run_s: 10\n",  # the wrapper
    "load: full\ntemperature_c: 20\nrun_s: 10\n",  # the fields alone
])
@pytest.mark.parametrize("command", ["simulate", "static"])
def test_a_scenario_file_given_as_the_conveyor_says_to_give_it_with_scenario(
        monkeypatch, capsys, tmp_path, text, command):
    """``beltstudy simulate sc.yaml --scenario conveyor.yaml``: every conveyor field was
    'required field is missing' and 'scenario: unknown key', where the reverse mix-up (a
    conveyor given as --scenario) is named for what it is."""
    from tests.conftest import ROOT

    scenario = tmp_path / "sc.yaml"
    scenario.write_text(text, encoding="utf-8")
    monkeypatch.setenv("BELTSTUDY_DATA_DIR", str(tmp_path / "data"))
    argv = [command, str(scenario)]
    if command == "simulate":
        argv += ["--scenario", str(ROOT / "studies" / "conveyors" / "fabric-1km.yaml")]
    assert cli.main(argv) == 2
    err = capsys.readouterr().err
    keys = "scenario" if text.startswith("scenario:") else "load, temperature_c, run_s"
    assert err == (f"error: {scenario}: this is a scenario file (it has {keys}), not a "
                   "conveyor file (SPEC 1: name, speed_m_s, belt, material, profile, idlers, "
                   "drives): give it with --scenario (beltstudy simulate CONVEYOR --scenario "
                   "FILE; a study writes it under scenario:)\n"), err


def test_a_conveyor_posted_as_a_study_is_a_422_saying_so(tmp_path):
    from fastapi.testclient import TestClient

    from beltstudy.service.api.app import create_app
    from tests.service.conftest import settings_for, tiny_conveyor

    app = create_app(settings_for(tmp_path / "data"))
    with TestClient(app) as client:
        r = client.post("/studies", json=tiny_conveyor())
    assert r.status_code == 422
    assert r.json()["message"].startswith("body: this is a conveyor file (it has speed_m_s, "
                                          "belt, material, profile, idlers, drives), not a study")


def test_serve_on_a_port_in_use_is_one_line_before_the_service_starts(monkeypatch, capsys,
                                                                      tmp_path):
    """`beltstudy serve --port P` with P taken: uvicorn binds only after the app's startup, so
    the service resumed the data directory's unfinished studies (a second executor on them),
    then printed uvicorn's 'ERROR: [Errno 98] error while attempting to bind on address' and
    exited 3. It is now one line naming the port and the way out, exit 2, before any start."""
    import socket

    import beltstudy.service.api.app as app_module

    def no_app(*_a, **_k):
        raise AssertionError("the service started although its port is in use")

    monkeypatch.setattr(app_module, "create_app", no_app)
    monkeypatch.setenv("BELTSTUDY_DATA_DIR", str(tmp_path / "data"))
    monkeypatch.setenv("BELTSTUDY_WARM_START", "false")
    taken = socket.socket()
    taken.bind(("127.0.0.1", 0))
    taken.listen()
    port = taken.getsockname()[1]
    try:
        code = cli.main(["serve", "--port", str(port)])
    finally:
        taken.close()
    err = capsys.readouterr().err.strip()
    assert code == 2
    assert err == (f"error: --port {port}: 127.0.0.1:{port} is already in use (another "
                   "beltstudy serve, or another program); stop it, or give another port "
                   "with --port")


def test_a_misspelt_setting_in_the_environment_is_named(monkeypatch, capsys, tmp_path):
    """`BELTSTUDY_DATA_DIRR=/tmp/x beltstudy status` (one R too many) read ./data and said
    nothing: pydantic-settings ignores unknown variables. Each BELTSTUDY_ variable that no
    part of beltstudy reads is now a warning line naming it and the nearest setting."""
    monkeypatch.setenv("BELTSTUDY_DATA_DIRR", str(tmp_path / "x"))
    monkeypatch.setenv("BELTSTUDY_URL", "http://127.0.0.1:1")  # read by the CLI: no warning
    _raising(monkeypatch, NotFound("study 'x' not found"))
    assert cli.main([]) == 2
    err = capsys.readouterr().err.splitlines()
    assert err[0] == ("warning: BELTSTUDY_DATA_DIRR: not a beltstudy setting, ignored; did "
                      "you mean BELTSTUDY_DATA_DIR?")
    assert err[1:] == ["error: study 'x' not found"]
