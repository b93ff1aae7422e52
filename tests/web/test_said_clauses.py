"""A failure group shows each finding with its own fix (service/web/verdicts.py
``said_clauses``): the clauses that go on with a finding join it, a clause that opens a
finding of its own does not."""

from __future__ import annotations

from beltstudy.service.web.verdicts import CAUSES, finding_clauses, said_clauses

#: An overspeed, then a settling warning whose doc reference names overspeed (a run's own
#: words, shortened).
OVERSPEED = (
    "overspeed in the start: the mean belt speed reached 3.68 m/s, 117 % of design speed, at "
    "t = 24.9 s (plant overspeed switches trip at 110 %): the belt released the stretch of "
    "its acceleration; a gentler start stretches it less: a longer start (start.time_s); "
    "not settled while running: the mean belt speed still swings by 0.06 m/s; a slower speed "
    "loop (drives.0.speed_loop_rad_s, now 5 rad/s) may swing less: rerun to check; a longer "
    "run_s shows whether the swing decays (docs/dynamics.md, Settling and overspeed)")

#: A high-stress brake stop with its remedies, then a take-up end stop.
HIGH_STRESS = (
    "stop in 3.8 s is faster than 5 wave loop times (5 x 2.84 s = 14.2 s): a high-stress "
    "stop; its tensions ranged 0 to 76.11 kN against 19.66 to 70.29 kN running; less brake "
    "force would be slower than that: a smaller brake force (brakes[].force_kn): at most "
    "about 15.7 kN in all, now 49.83 kN; a controlled stop (vfd drives) would be slower than "
    "that, with stop.time_s at least 37 s; take-up carriage reached the running end at "
    "t = 9.1 s: its travel is 4.5 m; more travel (takeup.travel_m) would avoid it")


def _cause(key: str):
    return next(c for c in CAUSES if c.key == key)


def test_an_overspeed_shows_its_own_fix_and_not_the_settling_words():
    said = finding_clauses(OVERSPEED, _cause("overspeed").words)
    assert len(said) == 1
    assert said[0].startswith("overspeed in the start")
    assert "a longer start (start.time_s)" in said[0]
    assert "run_s" not in said[0] and "swing" not in said[0]


def test_a_high_stress_stop_shows_its_remedies_and_the_end_stop_stays_apart():
    parts = said_clauses(HIGH_STRESS)
    assert [f.split(" ")[0] for f, _ in parts] == ["stop", "take-up"]
    stop = parts[0][1]
    assert "at most about 15.7 kN" in stop and "stop.time_s at least 37 s" in stop
    assert "travel" not in stop
    assert parts[1][1].endswith("would avoid it")


def test_a_settling_warning_keeps_its_own_fixes():
    parts = said_clauses(OVERSPEED)
    settle = next(s for f, s in parts if f.startswith("not settled while running"))
    assert "a slower speed loop" in settle and "a longer run_s" in settle


def test_a_run_that_slipped_is_past_the_transient_slip_margin_whatever_its_margin():
    """The transient slip margin is read from the springs beside the pulley: a run that
    slipped 1.92 s reported 1.000011. The row counts it past the limit, as the time slipping
    does."""
    import pandas as pd

    from beltstudy.service.web.verdicts import study_limits, verdict_rows

    runs = pd.DataFrame([
        {"run_id": "a", "status": "warning", "slip_margin_min_dyn": 1.000011,
         "drive1_slip_s": 1.92,
         "message": "drive 1 (head) slipped on its pulley during the start: from t = 3.0 to "
                    "4.9 s, 1.92 s in all, 2.3 m of belt slipped (lowest slip margin 1.00)"},
        {"run_id": "b", "status": "ok", "slip_margin_min_dyn": 1.4, "drive1_slip_s": 0.0,
         "message": ""},
        {"run_id": "c", "status": "warning", "slip_margin_min_dyn": 0.97,
         "drive1_slip_s": 0.5, "message": "drive 1 (head) slipped on its pulley ..."}])
    rows = {r["column"]: r for r in verdict_rows(runs, study_limits({"conveyor": {}}, 6.7,
                                                                     2 / 3))}
    row = rows["slip_margin_min_dyn"]
    assert row["past"] == 2 and row["row"]["run_id"] == "c"


def test_a_transient_slip_margin_at_its_limit_says_the_pulley_slipped():
    """While a pulley slips it passes its whole grip, so its margin reads the limit itself:
    the report's row read '1 | 1 | past the limit in 4 of 6 runs', a contradiction without
    the why. A margin below the limit needs no such words."""
    import pandas as pd

    from beltstudy.service.web.report import _verdict_words
    from beltstudy.service.web.verdicts import study_limits, verdict_rows

    def words(margin):
        runs = pd.DataFrame([
            {"run_id": "a", "status": "warning", "slip_margin_min_dyn": margin,
             "drive1_slip_s": 6.64, "message": "drive 1 (head) slipped on its pulley during "
                                               "the start"},
            {"run_id": "b", "status": "ok", "slip_margin_min_dyn": 1.4, "drive1_slip_s": 0.0,
             "message": ""}])
        rows = {r["column"]: r for r in verdict_rows(runs, study_limits({"conveyor": {}}, 6.7,
                                                                         2 / 3))}
        return _verdict_words(rows["slip_margin_min_dyn"])

    assert "past the limit in 1 of 2 runs: a drive pulley slipped" in words(1.0)
    assert "slipped" not in words(0.97) and "past the limit in 1 of 2 runs" in words(0.97)
