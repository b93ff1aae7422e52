"""The Parquet store: layout, atomic writes, explicit schema, orphan cleaning (service/store/parquet.py)."""

from __future__ import annotations

import pandas as pd
import pyarrow as pa
import pytest

from beltstudy.service.errors import NotFound
from beltstudy.service.store.columns import (
    RESULT_COLUMNS,
    TE_PART_COLUMNS,
    flatten_summary,
    rows_to_table,
    runs_schema,
    timeseries_schema,
)
from beltstudy.service.store.parquet import Store


def _doc(sid: str, **over) -> dict:
    """The least a study's document holds (:data:`~beltstudy.service.store.parquet.DOC_KEYS`:
    the store reads an object without them as damaged)."""
    return {"id": sid, "name": "x", "state": "queued", "total": 0, "study": {"axes": []},
            **over}


def test_finished_study_reads_back_with_pandas(data_dir, make_study, finished_study):
    sid = finished_study(data_dir, make_study())
    d = data_dir / "studies" / sid
    assert (d / "study.json").is_file()
    assert [p.name for p in (d / "runs").iterdir()] == ["part-all.parquet"]
    df = pd.read_parquet(d / "runs")
    assert len(df) == 6 and df["run_id"].is_unique
    assert set(RESULT_COLUMNS) <= set(df.columns)
    assert df["temperature_c"].dtype == "float64"
    assert (df["status"] != "failed").all()
    parts = df[[c for c in TE_PART_COLUMNS]].fillna(0).sum(axis=1)
    assert parts.to_numpy() == pytest.approx(df["te_kn"].to_numpy(), rel=1e-9)
    # nonlin's parts are null for din and cema, never zero
    assert df["te_indentation_kn"].isna().all()


def test_empty_study_has_the_full_schema(data_dir, make_study):
    from beltstudy.service.door.studyfile import resolve_study

    study = resolve_study(make_study())
    store = Store(data_dir)
    store.create(
        study.id,
        {"id": study.id, "name": "x", "state": "queued", "total": 6, "study": study.to_json()},
    )
    runs = store.read_runs(study.id)
    assert len(runs) == 0 and {"run_id", "temperature_c", "power_kw"} <= set(runs.columns)
    assert list(store.read_timeseries(study.id).columns)[:2] == ["run_id", "t_s"]


def test_parts_are_written_under_a_temporary_name(tmp_path, monkeypatch):
    store = Store(tmp_path)
    store.create("0123456789abcdef", _doc("0123456789abcdef"))
    seen = []
    import pyarrow.parquet as pq

    real = pq.write_table

    def spy(table, where, **kw):
        seen.append(where.name)
        real(table, where, **kw)

    monkeypatch.setattr(pq, "write_table", spy)
    table = rows_to_table([{"run_id": "r1", "t_s": 0.0}], timeseries_schema())
    path = store.write_part("0123456789abcdef", "timeseries", "k1", table)
    assert seen[0].startswith(".part-k1.parquet.") and seen[0].endswith(".tmp")
    assert path.name == "part-k1.parquet"
    assert [p.name for p in path.parent.iterdir()] == ["part-k1.parquet"]


def test_clean_removes_orphans_and_temporaries(tmp_path):
    sid = "0123456789abcdef"
    store = Store(tmp_path)
    store.create(sid, _doc(sid))
    ts = rows_to_table([{"run_id": "r", "t_s": 0.0}], timeseries_schema())
    runs = rows_to_table([{"run_id": "r"}], runs_schema([]))
    store.write_part(sid, "timeseries", "done", ts)
    store.write_part(sid, "runs", "done", runs)
    lost = rows_to_table([{"run_id": "r2", "t_s": 0.0}], timeseries_schema())
    store.write_part(sid, "timeseries", "orphan", lost)  # run r2's row never landed
    (store.table_dir(sid, "runs") / ".part-x.parquet.1234.tmp").write_bytes(b"half")
    assert store.clean(sid) == 2
    assert [p.name for p in store.parts(sid, "timeseries")] == ["part-done.parquet"]
    assert [p.name for p in store.table_dir(sid, "runs").iterdir()] == ["part-done.parquet"]


def test_sweep_removes_what_a_killed_process_left_and_keeps_the_rest(tmp_path):
    """A deleted study's folder moved away, and a half-created one older than the limit, are
    removed; a half-created one of a moment ago (another request creating it) and the stored
    studies stay, and read back as before."""
    import os
    import time

    store = Store(tmp_path)
    sid = "0123456789abcdef"
    store.create(sid, _doc(sid))
    before = store.read(sid)
    root = tmp_path / "studies"
    (root / f".{'a' * 16}.1234abcd.deleted" / "runs").mkdir(parents=True)
    old = root / f".{'b' * 16}.1234abcd.tmp"
    (old / "runs").mkdir(parents=True)
    past = time.time() - 3600
    os.utime(old, (past, past))
    fresh = root / f".{'c' * 16}.1234abcd.tmp"
    fresh.mkdir()
    assert store.sweep(tmp_age_s=600) == 2
    assert sorted(p.name for p in root.iterdir()) == sorted([sid, fresh.name])
    assert store.read(sid) == before and [d["id"] for d in store.list_studies()] == [sid]


def test_a_study_json_write_a_killed_process_cut_short_is_removed_on_resume(tmp_path):
    """``study.json`` is written under a temporary name, then renamed; a SIGKILL between the
    two leaves ``.study.json.<tag>-<random>.tmp`` in the study's folder (and a body record's
    in ``bodies/``). Those of another process go at the resume (:meth:`Store.clean`) and at
    start-up (:meth:`Store.sweep`); one of this process (a write in flight) stays."""
    from beltstudy.service.store.parquet import PROCESS_TAG
    from beltstudy.service.store.parquet import tmp_path as tmp_name

    sid = "0123456789abcdef"
    store = Store(tmp_path)
    store.create(sid, _doc(sid))
    store.update(sid, state="running")
    folder = store.study_dir(sid)
    dead = folder / ".study.json.0badf00d-12345678.tmp"
    dead.write_text('{"id": "half')
    live = tmp_name(folder / "study.json")
    live.write_text("{}")
    assert PROCESS_TAG in live.name and PROCESS_TAG not in dead.name
    assert store.clean(sid) == 1
    assert not dead.exists() and live.exists()
    assert store.read(sid)["state"] == "running"
    bodies = tmp_path / "bodies"
    bodies.mkdir()
    (bodies / "k1").write_text(sid)
    (bodies / ".k2.0badf00d-12345678.tmp").write_text(sid)
    assert store.sweep() == 1
    assert [p.name for p in bodies.iterdir()] == ["k1"]


@pytest.mark.parametrize("bad", ["../etc", "0123", "0123456789ABCDEF", "x" * 16, ""])
def test_ids_that_are_not_hashes_are_not_found(tmp_path, bad):
    with pytest.raises(NotFound):
        Store(tmp_path).read(bad)


def test_update_list_delete(tmp_path):
    store = Store(tmp_path)
    for i, sid in enumerate(["a" * 16, "b" * 16]):
        store.create(sid, _doc(sid, created_at=i, state="queued"))
    store.update("a" * 16, state="done")
    assert [d["state"] for d in store.list_studies()] == ["done", "queued"]
    store.delete("a" * 16)
    assert [d["id"] for d in store.list_studies()] == ["b" * 16]
    assert not list(store.root.glob(".*"))
    with pytest.raises(NotFound):
        store.delete("a" * 16)


def test_flatten_keeps_unknown_parts_summing_to_te():
    row = flatten_summary(
        {
            "te_kn": 10.0,
            "te_components_kn": {"main_carry": 6.0, "lift": 3.0, "magic": 1.0},
            "status": "warning",
            "message": "sag",
            "power_kw": float("nan"),
        }
    )
    assert row["te_main_carry_kn"] == 6.0 and row["te_other_kn"] == 1.0
    assert row["te_indentation_kn"] is None and row["power_kw"] is None
    assert row["status"] == "warning"
    table = rows_to_table([{"run_id": "r", **row, "not_a_column": 1}], runs_schema([]))
    assert table.schema.field("te_kn").type == pa.float64()
    assert "not_a_column" not in table.column_names


def test_workers_write_parts_only_into_the_study_they_were_given(tmp_path):
    from beltstudy.service.store.parquet import write_part_to

    sid = "0123456789abcdef"
    store = Store(tmp_path)
    store.create(sid, _doc(sid, store_token="t0k"))
    ts = rows_to_table([{"run_id": "r", "t_s": 0.0}], timeseries_schema())
    d = store.study_dir(sid)
    assert not write_part_to(d, "wrong", "timeseries", "k", ts)
    assert not write_part_to(tmp_path / "elsewhere", "t0k", "timeseries", "k", ts)
    assert store.parts(sid, "timeseries") == []
    assert write_part_to(d, "t0k", "timeseries", "k", ts)
    assert [p.name for p in store.parts(sid, "timeseries")] == ["part-k.parquet"]
    store.delete(sid)  # a worker finishing after a delete must not bring the study back
    assert not write_part_to(d, "t0k", "timeseries", "k", ts)
    assert not d.exists()


def test_flatten_keeps_the_horizontal_curve_fields():
    """A study of a conveyor with a horizontal curve stored hcurve1_* null in every row
    (0.0 / 146.9 kN limits, 26.8 to 30.9 kN run, ok in `beltstudy static`): the row builder
    took the vertical curves' columns and not the horizontal ones'."""
    summary = {"te_kn": 10.0, "status": "ok", "hcurve1_tension_min_kn": 0.0,
               "hcurve1_tension_max_kn": 146.9, "hcurve1_t_low_kn": 26.8,
               "hcurve1_t_high_kn": 30.9, "hcurve1_ok": True}
    row = flatten_summary(summary)
    assert row["hcurve1_tension_min_kn"] == 0.0 and row["hcurve1_tension_max_kn"] == 146.9
    assert row["hcurve1_t_low_kn"] == 26.8 and row["hcurve1_t_high_kn"] == 30.9
    assert row["hcurve1_ok"] is True
    assert row["hcurve2_ok"] is None and row["hcurve2_tension_min_kn"] is None
    table = rows_to_table([{"run_id": "r", **row}], runs_schema([]))
    assert table.schema.field("hcurve1_ok").type == pa.bool_()
    assert table.column("hcurve1_tension_max_kn").to_pylist() == [146.9]
