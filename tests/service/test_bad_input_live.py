"""Bad input a tester sent a real service (``beltstudy serve`` in a child process): each used
to be a 500 or was taken silently; now a 422 naming the field and the fix, nothing stored.
"""

from __future__ import annotations

import httpx
import pytest

from tests.service.conftest import LiveService

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def svc(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("bad-input")
    service = LiveService(tmp / "data", tmp / "beltstudy.service.log")
    yield service
    service.stop()


@pytest.fixture
def http(svc):
    with httpx.Client(base_url=svc.url, timeout=60) as client:
        yield client


def _stored(svc: LiveService, http: httpx.Client) -> tuple[list, list]:
    """The studies the service lists and the study folders in its store."""
    listed = sorted(s["id"] for s in http.get("/studies").json()["studies"])
    root = svc.data_dir / "studies"
    folders = sorted(p.name for p in root.iterdir()) if root.exists() else []
    return listed, folders


def _refused(http: httpx.Client, body: dict) -> str:
    """POST ``body``: a 422 whose message is one line; the message."""
    answer = http.post("/studies", json=body)
    assert answer.status_code == 422, answer.text
    message = answer.json()["message"]
    assert answer.json()["error"] == "invalid" and "\n" not in message
    return message


@pytest.mark.parametrize("path", [
    "a" * 5000 + ".yaml",                  # one name over the file system's 255 bytes
    "dddddd/" * 600 + "conveyor.yaml",     # 600 nested folders: the path over 4096 bytes
])
def test_a_conveyor_path_too_long_is_a_422_naming_conveyor(svc, http, make_study, path):
    # was a 500 (OSError: [Errno 36] File name too long)
    before = _stored(svc, http)
    message = _refused(http, make_study(name="long-path", conveyor=path))
    assert message.startswith("conveyor: cannot read the file: "), message
    assert "too long" in message and "give a shorter" in message
    assert len(message) < 400  # the path is shortened, not echoed 5000 characters long
    assert _stored(svc, http) == before
    assert http.get("/health").json()["status"] == "ok"


@pytest.mark.parametrize(("extra", "where", "index"), [
    ({"grid": {"profile.\u00b2.lift_m": [1, 2]}}, "grid", "\u00b2"),       # superscript two
    ({"grid": {"profile.\u0661.lift_m": [1, 2]}}, "grid", "\u0661"),       # Arabic-Indic one
    ({"zip": [{"profile.\u00b2.lift_m": [1, 2], "stop_time_s": [5, 6]}]}, "zip.0", "\u00b2"),
    ({"sample": {"n": 4, "method": "lhs", "seed": 1, "axes": {
        "profile.\u0661.lift_m": {"dist": "uniform", "low": 1, "high": 2}}}},
     "sample.axes", "\u0661"),
])
def test_an_axis_index_in_other_digits_is_a_422_asking_for_ascii(svc, http, make_study, extra,
                                                                  where, index):
    # '²' was a 500 (int() cannot read it); '١' was read as index 1
    before = _stored(svc, http)
    message = _refused(http, make_study(name="odd-index", **extra))
    assert message.startswith(f"{where}: axis 'profile.{index}.lift_m': the index '{index}' "
                              "into 'profile' must be a plain number 0-9 (ASCII digits only"), \
        message
    assert _stored(svc, http) == before


def test_negative_zero_is_zero_in_an_axis(svc, http, make_study):
    # [0.0, -0.0] were two runs with different run ids and identical inputs
    before = _stored(svc, http)
    message = _refused(http, make_study(name="zeros", grid={"temperature_c": [0.0, -0.0]}))
    assert message == "grid.temperature_c: value 0.0 appears twice (-0.0 is 0.0)"
    message = _refused(http, make_study(name="zeros", grid={"load": ["empty", -0.0]}))
    assert message.startswith("grid.load: 'empty' and 0.0 are the same load")
    assert _stored(svc, http) == before
    # -0.0 alone is the study of 0.0: the same study id, so the same runs, stored once
    first = http.post("/studies", json=make_study(name="zero", grid={"temperature_c": [0.0]}))
    again = http.post("/studies", json=make_study(name="zero", grid={"temperature_c": [-0.0]}))
    assert (first.status_code, again.status_code) == (202, 200)
    assert again.json()["id"] == first.json()["id"]
    assert svc.wait(first.json()["id"])["state"] == "done"


def test_a_ratio_plot_of_one_model_against_itself_is_a_422_like_compare(svc, http, make_study):
    # was a 200 PNG saying "a ratio needs two friction models in the grid"
    sid = http.post("/studies", json=make_study(name="ratio-pair")).json()["id"]  # din, cema
    assert svc.wait(sid)["state"] == "done"
    compare = http.get(f"/studies/{sid}/compare", params={"baseline": "din", "candidate": "din"})
    assert compare.status_code == 422
    said = "candidate: 'din' is the baseline too; compare two different models"
    assert compare.json()["message"] == said
    for candidate in ("din", "iso5048"):  # by its name or its alias
        plot = http.get(f"/studies/{sid}/plots/ratio",
                        params={"baseline": "din", "candidate": candidate})
        assert plot.status_code == 422, plot.headers.get("content-type")
        assert plot.json() == {"error": "invalid", "message": said}
    # the candidate alone: the baseline is the study's other model, a real ratio figure
    plot = http.get(f"/studies/{sid}/plots/ratio", params={"candidate": "cema"})
    assert plot.status_code == 200 and plot.content.startswith(b"\x89PNG")
    pair = http.get(f"/studies/{sid}/plots/ratio", params={"baseline": "din",
                                                           "candidate": "cema"})
    assert pair.status_code == 200 and pair.content == plot.content
