"""A run whose belt went slack sagged past its limit (a slack span's sag has no bound): the
report's failure groups and the uncertainty summary's "sagged past its limit" count it, as
the verdict rows do (``service/web/verdicts.py``)."""

from __future__ import annotations

import pandas as pd
import yaml

from beltstudy.engine.conveyor import parse_conveyor
from beltstudy.engine.statics import solve_steady
from beltstudy.service.web.verdicts import CAUSES
from tests.conftest import CONVEYORS


def _steady_rows(masses_kg) -> pd.DataFrame:
    """overland-4km's steady rows with a take-up of each mass (DIN)."""
    base = yaml.safe_load((CONVEYORS / "overland-4km.yaml").read_text())
    rows = []
    for m in masses_kg:
        conv = parse_conveyor({**base, "takeup": {**base["takeup"], "mass_kg": m}})
        s = solve_steady(conv, model="din").summary
        rows.append({k: s.get(k) for k in ("sag_max_pct", "t_min_kn", "message", "status")})
    return pd.DataFrame(rows)


def test_a_steady_slack_run_is_counted_as_sagged():
    """Take-ups of 0.5, 3 and 8 t leave overland-4km's carry slack at the tail (steady lowest
    tension -69.3, -57.0 and -32.5 kN): no sag figure, and a message that says the strand is
    slack with no sag bound, not 'sag ... exceeds'. 31.5 t holds it (0.35 % against 1.5 %).
    Counted by the sag warning alone, a study of take-ups from 0.5 to 30 t read 'went slack
    19 / 40' and 'sagged past its limit 7 / 40'."""
    runs = _steady_rows([500, 3000, 8000, 31500])
    slack_rows = runs["t_min_kn"] <= 0.0
    assert slack_rows.tolist() == [True, True, True, False]
    assert runs.loc[slack_rows, "sag_max_pct"].isna().all()
    assert not runs["message"].str.contains(r"sag on the \w+ strand [\d.]+ % exceeds").any()
    assert runs.loc[slack_rows, "message"].str.contains("its sag there has no bound").all()
    cause = {c.key: c for c in CAUSES}
    sagged = cause["sag"].detect(runs).fillna(False).astype(bool)
    assert sagged.tolist() == [True, True, True, False]
    slack = cause["slack"].detect(runs).fillna(False).astype(bool)
    assert (sagged >= slack).all()  # every run that went slack sagged past its limit
