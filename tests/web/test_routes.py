"""Pages, page data and plot routes through FastAPI's TestClient (no server, no Dask)."""

from __future__ import annotations

import pytest

from beltstudy.service.web import figures

PNG = b"\x89PNG\r\n\x1a\n"


@pytest.fixture
def done(web, tmp_path):
    """A finished four-run steady study whose conveyor name is HTML; (client, id, run ids)."""
    sid = web.finished_study(tmp_path, web.tiny_study(conveyor_name=web.XSS))
    c = web.client(tmp_path)
    runs = c.get(f"/studies/{sid}/runs").json()["runs"]
    return c, sid, [r["run_id"] for r in runs]


def test_pages_are_served_with_a_strict_policy(done):
    c, sid, runs = done
    for path in ("/", f"/ui/studies/{sid}", f"/ui/studies/{sid}/runs/{runs[0]}"):
        r = c.get(path)
        assert r.status_code == 200, path
        assert r.headers["content-type"].startswith("text/html")
        csp = r.headers["content-security-policy"]
        assert "script-src 'self'" in csp and "default-src 'self'" in csp
        assert '<script src="/ui/static/app.js"></script>' in r.text
        assert "http://" not in r.text and "https://" not in r.text  # nothing from elsewhere
    assert f'data-study-id="{sid}"' in c.get(f"/ui/studies/{sid}").text
    js = c.get("/ui/static/app.js")
    assert js.status_code == 200 and "javascript" in js.headers["content-type"]
    assert "innerHTML" not in js.text and "insertAdjacentHTML" not in js.text
    assert c.get("/ui/static/style.css").headers["content-type"].startswith("text/css")
    assert c.get("/ui/static/..%2Fsettings.py").status_code == 404


def test_pages_refuse_malformed_ids(done):
    c, sid, _ = done
    for path in ("/ui/studies/ABCDEF0123456789", "/ui/studies/%3Cb%3E", f"/ui/studies/{sid}/runs/x%3Cy"):
        r = c.get(path)
        assert r.status_code == 404
        assert r.json()["error"] == "not_found"


def test_html_in_names_is_never_markup_in_the_served_pages(web, tmp_path):
    sid = web.finished_study(tmp_path, web.tiny_study(conveyor_name=web.XSS), name=web.XSS)
    c = web.client(tmp_path)
    run_id = c.get(f"/studies/{sid}/runs").json()["runs"][0]["run_id"]
    for path in ("/", f"/ui/studies/{sid}", f"/ui/studies/{sid}/runs/{run_id}"):
        text = c.get(path).text
        assert "<script>alert" not in text and "<b>x</b>" not in text, path
    info = c.get(f"/ui/data/studies/{sid}").json()
    # the page data carries the text as it is; the script shows it with textContent
    assert info["name"] == web.XSS and info["conveyor_name"] == web.XSS
    assert c.get(f"/studies/{sid}/plots/power-temperature").status_code == 200


@pytest.mark.parametrize("name", list(figures.STUDY_PLOTS))
def test_study_plots_as_png_and_svg(done, name):
    c, sid, _ = done
    r = c.get(f"/studies/{sid}/plots/{name}")
    assert r.status_code == 200
    assert r.headers["content-type"] == "image/png"
    assert r.content.startswith(PNG) and len(r.content) > 1000
    r = c.get(f"/studies/{sid}/plots/{name}", params={"format": "svg"})
    assert r.status_code == 200 and r.headers["content-type"] == "image/svg+xml"
    assert b"<svg" in r.content[:1000]


def test_steady_only_study_says_so_on_the_transient_plots(done):
    c, sid, runs = done
    svg = c.get(f"/studies/{sid}/plots/peak-dynamic-tension", params={"format": "svg"}).text
    assert "no transient data (dynamics: false)" in svg
    svg = c.get(f"/studies/{sid}/runs/{runs[0]}/plots/transient", params={"format": "svg"}).text
    assert "no transient data (dynamics: false)" in svg


def test_ratio_falls_back_to_the_models_present(done):
    c, sid, _ = done
    svg = c.get(f"/studies/{sid}/plots/ratio", params={"format": "svg"}).text
    assert "din / cema" in svg  # no nonlin in this study: the other model over cema
    svg = c.get(f"/studies/{sid}/plots/ratio",
                params={"format": "svg", "baseline": "din", "candidate": "cema"}).text
    assert "cema / din" in svg
    r = c.get(f"/studies/{sid}/plots/ratio", params={"candidate": "nonlin"})
    assert r.status_code == 422 and r.json()["message"].startswith("candidate: model 'nonlin'")
    for param in ("baseline", "candidate"):  # empty: named, not drawn as an empty figure
        r = c.get(f"/studies/{sid}/plots/ratio", params={param: ""})
        assert r.status_code == 422 and r.json()["message"].startswith(f"query.{param}: empty")


@pytest.mark.parametrize("name", list(figures.RUN_PLOTS))
def test_run_plots(done, name):
    c, sid, runs = done
    for run_id in runs[:2]:
        r = c.get(f"/studies/{sid}/runs/{run_id}/plots/{name}")
        assert r.status_code == 200 and r.headers["content-type"] == "image/png"
        assert r.content.startswith(PNG) and len(r.content) > 1000


def test_plot_routes_404_for_unknown_ids(done):
    c, sid, runs = done
    for path in (
        "/studies/0123456789abcdef/plots/ratio",
        "/studies/not-an-id/plots/ratio",
        "/studies/0123456789abcdef/runs/0123456789abcdef/plots/transient",
        f"/studies/{sid}/runs/0123456789abcdef/plots/transient",
    ):
        r = c.get(path)
        assert r.status_code == 404, path
        body = r.json()
        assert body["error"] == "not_found" and "not found" in body["message"]


def test_plot_routes_422_for_unknown_names_name_the_valid_ones(done):
    c, sid, runs = done
    r = c.get(f"/studies/{sid}/plots/fig99")
    assert r.status_code == 422
    body = r.json()
    assert body["error"] == "invalid"
    assert "fig99" in body["message"]
    assert all(n in body["message"] for n in figures.STUDY_PLOTS)
    r = c.get(f"/studies/{sid}/runs/{runs[0]}/plots/power-temperature")
    assert r.status_code == 422
    assert all(n in r.json()["message"] for n in figures.RUN_PLOTS)
    r = c.get(f"/studies/{sid}/plots/ratio", params={"format": "gif"})
    assert r.status_code == 422 and "format" in r.json()["message"]


def test_a_misspelt_plot_name_or_a_plot_of_the_other_kind_says_which(done):
    """'power-temprature' names 'power-temperature'; a study plot asked of a run (and a run
    plot of the study) says where that plot is."""
    c, sid, runs = done
    r = c.get(f"/studies/{sid}/plots/power-temprature")
    assert r.status_code == 422
    assert "unknown plot 'power-temprature' (did you mean 'power-temperature'?)" in (
        r.json()["message"])
    r = c.get(f"/studies/{sid}/runs/{runs[0]}/plots/power-temperature")
    assert "(a plot of the whole study: /studies/{id}/plots/power-temperature)" in (
        r.json()["message"])
    r = c.get(f"/studies/{sid}/plots/steady-profile")
    assert "(a plot of one run: /studies/{id}/runs/{run_id}/plots/steady-profile)" in (
        r.json()["message"])


def test_token_guards_plots_and_data_but_not_the_page_shells(web, tmp_path):
    sid = web.finished_study(tmp_path, web.tiny_study())
    c = web.client(tmp_path, token="s3cret")
    assert c.get("/").status_code == 200  # the login field must be reachable
    assert c.get("/ui/static/app.js").status_code == 200
    for path in (f"/studies/{sid}/plots/ratio", f"/ui/data/studies/{sid}"):
        r = c.get(path)
        assert r.status_code == 401 and r.json()["error"] == "unauthorized"
        assert c.get(path, headers={"Authorization": "Bearer wrong"}).status_code == 401
        assert c.get(path, headers={"Authorization": "Bearer s3cret"}).status_code == 200


def test_page_data_names_the_axes(done):
    c, sid, _ = done
    info = c.get(f"/ui/data/studies/{sid}").json()
    assert [a["column"] for a in info["axes"]] == ["friction_model", "temperature_c"]
    assert info["axes"][1]["values"] == [-20, 20]
    assert info["dynamics"] is False
    assert set(info["study_plots"]) == set(figures.STUDY_PLOTS)
    # what the runs table pages with: the models for the filter and the stored columns, so
    # it asks for only the columns it shows
    assert info["models"] == ["din", "cema"]
    row = c.get(f"/studies/{sid}/runs", params={"limit": 1}).json()["runs"][0]
    assert {"run_id", "power_kw", "te_main_carry_kn"} <= set(info["columns"])
    assert set(info["columns"]) - set(row) == {c for c in info["columns"] if c.startswith("te_")
                                               and c not in ("te_kn",)}
    assert c.get("/ui/data/studies/0123456789abcdef").status_code == 404


def test_the_design_report_is_one_self_contained_page(web, tmp_path):
    """No script, nothing fetched (every image a data: URI), user text escaped, the verdicts
    with their governing runs, the design basis with what set each size."""
    import re

    sid = web.finished_study(tmp_path, web.tiny_study(conveyor_name=web.XSS), name=web.XSS)
    c = web.client(tmp_path)
    r = c.get(f"/studies/{sid}/report")
    assert r.status_code == 200 and r.headers["content-type"].startswith("text/html")
    assert "default-src 'none'" in r.headers["content-security-policy"]
    text = r.text
    assert "<script" not in text.lower()
    assert "http://" not in text and "https://" not in text
    srcs = re.findall(r'src="([^"]*)"', text)
    assert len(srcs) >= 2 and all(s.startswith("data:image/png;base64,") for s in srcs)
    assert not re.findall(r'href="(?!#)', text)  # no links out, no stylesheets
    assert "<b>x</b>" not in text and "&lt;script&gt;alert(1)&lt;/script&gt;" in text
    runs = c.get(f"/studies/{sid}/runs").json()["runs"]
    for label in ("largest tension, steady", "lowest tension, steady", "slip margin, running",
                  "largest sag, steady", "belt safety factor, steady",
                  "power at the drive pulleys, steady"):
        assert label in text
    governing = max(runs, key=lambda row: row["t_max_kn"])
    assert governing["run_id"] in text
    assert "take-up mass" in text and governing["takeup_governed_by"] in text
    assert "@media print" in text and "@page" in text
    assert c.get("/studies/0123456789abcdef/report").status_code == 404


def test_report_command_writes_the_page_from_the_local_store(web, tmp_path, monkeypatch,
                                                             capsys):
    from beltstudy.service.cli import main
    from beltstudy.service.cli.demo import free_port

    sid = web.finished_study(tmp_path, web.tiny_study(name="cli-report"))
    from beltstudy.service.cli import study

    # no service at the default address (an address given that does not answer is an error)
    monkeypatch.delenv("BELTSTUDY_URL", raising=False)
    monkeypatch.setattr(study, "DEFAULT_URL", f"http://127.0.0.1:{free_port()}")
    monkeypatch.setenv("BELTSTUDY_DATA_DIR", str(tmp_path))
    out = tmp_path / "report.html"
    assert main(["report", sid, "-o", str(out)]) == 0
    assert "wrote" in capsys.readouterr().out
    assert out.read_text().startswith("<!doctype html>") and "cli-report" in out.read_text()
    assert main(["report", sid, "-o", str(tmp_path / "report.pdf")]) == 2
    assert "use a .html file name" in capsys.readouterr().err


@pytest.mark.parametrize("name", list(figures.FIGURE_COLUMNS))
def test_study_page_figures_read_only_the_columns_they_draw(web, tmp_path, name):
    """The study page's figures are drawn from a few columns of the runs table, not every
    column of every run, and come out the same as from the whole table."""
    from beltstudy.service.settings import Settings
    from beltstudy.service.studies import StudyService

    body = web.tiny_study(grid={"friction_model": ["din", "cema"],
                                "temperature_c": [-20, 20], "load": ["full", 0.5]})
    sid = web.finished_study(tmp_path, body)
    service = StudyService(Settings(data_dir=tmp_path, warm_start=False), read_only=True)
    asked = []
    read = service.store.read_runs

    def spy(study_id, columns=None):
        asked.append(columns)
        return read(study_id, columns=columns)

    service.store.read_runs = spy
    png = figures.render(figures.study_figure(service, sid, name))
    assert len(asked) == 1 and asked[0] is not None, asked
    stored = service.store.runs_columns(sid)
    assert len(asked[0]) <= 12 < len(stored), asked[0]
    assert {"run_id", "status", "friction_model", "temperature_c", "load"} <= set(asked[0])
    whole = figures.figure_of(service.store.read(sid), read(sid), name, study_id=sid)
    assert figures.render(whole) == png


def test_a_study_of_one_model_draws_a_ratio_figure_saying_it_needs_two(web, tmp_path):
    """A steady study of din alone (one run at 20 C): GET /studies/{id}/plots/ratio without
    baseline or candidate answered 422 "candidate: model 'nonlin' (the default) is not in
    this study; it has: din: give candidate=NAME from those" (no NAME would do), and the study
    page, which loads that figure, showed the message as its error banner and a broken image.
    It is a figure saying a ratio needs two models, as a steady study's transient figures say
    there is no transient; a model named that the study lacks is still a 422."""
    sid = web.finished_study(tmp_path, web.tiny_study(
        name="one-model", grid={"friction_model": ["din"], "temperature_c": [20]}))
    c = web.client(tmp_path)
    r = c.get(f"/studies/{sid}/plots/ratio", params={"format": "svg"})
    assert r.status_code == 200 and r.headers["content-type"] == "image/svg+xml"
    assert "a ratio needs two friction models in the grid; this study ran din only" in r.text
    r = c.get(f"/studies/{sid}/plots/ratio")
    assert r.status_code == 200 and r.content.startswith(PNG)
    r = c.get(f"/studies/{sid}/plots/ratio", params={"candidate": "nonlin"})
    assert r.status_code == 422 and r.json()["message"].startswith("candidate: model 'nonlin'")
