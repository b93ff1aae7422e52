"""``GET /studies/{id}/runs`` with ``columns=`` and ``sort=`` (the study page's paging):
exactly the columns asked, the order over every row before the page is cut, errors that name
the parameter. In-process (TestClient without the lifespan; no Dask)."""

from __future__ import annotations

import io

import pandas as pd
import pytest
from fastapi.testclient import TestClient

from beltstudy.service.api.app import create_app
from beltstudy.service.store import query


@pytest.fixture
def done(data_dir, make_settings, finished_study, make_study):
    """A finished six-run study: (client, id, every row as the API gives it)."""
    sid = finished_study(data_dir, make_study())
    client = TestClient(create_app(make_settings(data_dir)))
    rows = client.get(f"/studies/{sid}/runs").json()["runs"]
    return client, sid, rows


def _page(client, sid, **params):
    r = client.get(f"/studies/{sid}/runs", params=params)
    assert r.status_code == 200, r.text
    return r.json()


def test_columns_gives_exactly_those_columns_in_that_order(done):
    client, sid, rows = done
    page = _page(client, sid, columns="power_kw,run_id,status", limit=4)
    assert page["total"] == 6 and len(page["runs"]) == 4
    assert [list(r) for r in page["runs"]] == [["power_kw", "run_id", "status"]] * 4
    by_id = {r["run_id"]: r for r in rows}
    for r in page["runs"]:  # the same values as the full rows
        assert r["power_kw"] == by_id[r["run_id"]]["power_kw"]
    # a filter on a column not asked for still filters
    page = _page(client, sid, columns="run_id", filter="temperature_c=0")
    assert page["total"] == 2
    assert {r["run_id"] for r in page["runs"]} == {
        r["run_id"] for r in rows if r["temperature_c"] == 0}
    # downloads take the same columns
    csv = client.get(f"/studies/{sid}/runs", params={"format": "csv", "columns": "run_id,te_kn"})
    assert list(pd.read_csv(io.StringIO(csv.text)).columns) == ["run_id", "te_kn"]
    pq = client.get(f"/studies/{sid}/runs", params={"format": "parquet", "columns": "te_kn"})
    assert list(pd.read_parquet(io.BytesIO(pq.content)).columns) == ["te_kn"]


def test_sort_orders_every_row_before_the_page_is_cut(done):
    client, sid, rows = done
    powers = sorted(r["power_kw"] for r in rows)
    first = _page(client, sid, sort="power_kw", columns="run_id,power_kw", limit=2)
    last = _page(client, sid, sort="power_kw", columns="run_id,power_kw", limit=2, offset=4)
    assert [r["power_kw"] for r in first["runs"]] == powers[:2]
    assert [r["power_kw"] for r in last["runs"]] == powers[4:]
    down = _page(client, sid, sort="-power_kw", limit=1)
    assert down["runs"][0]["power_kw"] == powers[-1]
    assert "te_components_kn" in down["runs"][0]  # without columns=: the whole row
    # text as text; ties keep their stored order (pages never overlap)
    stored = [r["run_id"] for r in rows]
    by_model = _page(client, sid, sort="friction_model", columns="run_id,friction_model")
    models = [r["friction_model"] for r in by_model["runs"]]
    assert models == sorted(models)
    for model in set(models):
        ids = [r["run_id"] for r in by_model["runs"] if r["friction_model"] == model]
        assert ids == [i for i in stored if i in ids]
    for sort in ("friction_model", "-friction_model"):
        seen = []
        for offset in range(0, 6, 2):
            seen += [r["run_id"] for r in _page(client, sid, sort=sort, columns="run_id",
                                                limit=2, offset=offset)["runs"]]
        assert sorted(seen) == sorted(stored), sort


def test_sort_puts_missing_values_last_both_ways():
    df = pd.DataFrame({"run_id": list("abcde"), "x": [2.0, None, 1.0, None, 3.0],
                       "t": ["b", None, "a", "c", None]})
    assert list(query.sort_rows(df, "x")["run_id"]) == ["c", "a", "e", "b", "d"]
    assert list(query.sort_rows(df, "x", True)["run_id"]) == ["e", "a", "c", "b", "d"]
    assert list(query.sort_rows(df, "t")["run_id"]) == ["c", "a", "d", "b", "e"]
    assert list(query.sort_rows(df, "t", True)["run_id"]) == ["d", "a", "c", "b", "e"]
    mixed = pd.DataFrame({"run_id": list("abc"), "load": ["full", 0.5, None]})
    assert list(query.sort_rows(mixed, "load")["run_id"]) == ["b", "a", "c"]


def test_columns_and_sort_errors_name_the_parameter_and_the_fix(done):
    client, sid, _ = done
    cases = {
        ("columns", "run_id,powr_kw"): "columns: this study has no column 'powr_kw' (did you "
                                       "mean 'power_kw'?); columns: study_id, run_id",
        ("columns", "run_id,,power_kw"): "columns: an empty name in 'run_id,,power_kw'; give "
                                         "column names separated by commas",
        ("columns", "run_id,run_id"): "columns: 'run_id' is named twice; give each column once",
        ("columns", "te_components_kn"): "columns: te_components_kn is the JSON object the "
                                         "te_<part>_kn columns are folded into; name those "
                                         "(te_main_carry_kn,",
        ("sort", "-nope"): "sort: this study has no column 'nope'; columns: study_id",
        ("sort", ""): "query.sort: empty; give a value",
        ("sort", "te_kn,power_kw"): "sort: one column ('te_kn' or '-te_kn'); several keys "
                                    "are not supported ('te_kn,power_kw'): sort in pandas",
        ("sort", "-power_kw, te_kn"): "sort: one column ('power_kw' or '-power_kw'); several",
    }
    for (name, value), message in cases.items():
        r = client.get(f"/studies/{sid}/runs", params={name: value})
        assert r.status_code == 422, (name, value)
        assert r.json()["message"].startswith(message), r.json()["message"]
    # a filter on a column the study lacks names the filter, also with columns=
    r = client.get(f"/studies/{sid}/runs", params={"columns": "run_id", "filter": "nope=1"})
    assert r.status_code == 422
    assert r.json()["message"].startswith("filter: this study has no column 'nope'")


def test_a_few_columns_come_from_the_kept_table_and_match_the_parts(data_dir, finished_study,
                                                                      make_study, monkeypatch):
    import pyarrow.parquet as pq

    from beltstudy.service.store import parquet
    from beltstudy.service.store.parquet import Store

    sid = finished_study(data_dir, make_study())
    store = Store(data_dir)
    reads = []
    dataset = pq.ParquetDataset

    class Counted(dataset):
        def read(self, columns=None, **kw):
            reads.append(columns)
            return super().read(columns=columns, **kw)

    monkeypatch.setattr(parquet.pq, "ParquetDataset", Counted)
    cols = ["run_id", "power_kw", "message"]
    cold = store.read_runs(sid, columns=cols)  # nothing kept yet: these three from the parts
    assert reads == [cols] and sid not in store._runs_cache
    again = store.read_runs(sid, columns=["message", "run_id", "te_kn"])
    assert reads == [cols, ["te_kn"]]  # only the column not kept yet is read
    assert list(again.columns) == ["message", "run_id", "te_kn"]
    full = store.read_runs(sid)
    pd.testing.assert_frame_equal(cold, full[cols])
    pd.testing.assert_frame_equal(again, full[["message", "run_id", "te_kn"]])
    assert sid in store._runs_cache
    reads.clear()
    warm = store.read_runs(sid, columns=cols)  # from the whole table kept
    assert reads == []
    pd.testing.assert_frame_equal(warm, full[cols])
    assert store.runs_columns(sid) == list(full.columns)
    # a new part: nothing kept is used, the new rows are there
    table = pq.read_table(store.parts(sid, "runs")[0])
    store.write_part(sid, "runs", "zz-more", table.slice(0, 2))
    more = store.read_runs(sid, columns=cols)
    assert len(more) == len(full) + 2 and reads == [cols]


def test_a_mixed_axis_sorts_its_numbers_as_numbers():
    """``takeup.mass_kg: [auto, 500, 3000]`` is stored as text: sorted as text '3000.0' came
    before '500.0'. Its numbers now sort as numbers, before its words, reversed for
    descending, missing values last."""
    df = pd.DataFrame({"run_id": list("abcde"),
                       "m": ["3000.0", "auto", None, "500.0", "12000.0"]})
    assert list(query.sort_rows(df, "m")["run_id"]) == ["d", "a", "e", "b", "c"]
    assert list(query.sort_rows(df, "m", True)["run_id"]) == ["b", "e", "a", "d", "c"]
