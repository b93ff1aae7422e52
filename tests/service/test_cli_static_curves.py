"""`beltstudy static`'s vertical-curve table (service/cli/static.py): the radius a curve needs
is a minimum, printed rounded up as the warnings name it."""

from __future__ import annotations

from beltstudy.service.cli.static import _curve_lines


def test_the_radius_column_rounds_the_minimum_up():
    """A concave curve needing 323.4 m running and 417.2 m at start-up printed 323 and 417,
    radii on which the belt still lifts (the warning beside it named 324 and 418)."""
    s = {"curve1_kind": "concave", "curve1_at_m": 1500.0, "curve1_tension_kn": 86.9,
         "curve1_liftoff_tension_kn": 80.6, "curve1_liftoff": True,
         "curve1_radius_min_m": 323.4, "curve1_tension_start_kn": 112.1,
         "curve1_liftoff_start": True, "curve1_radius_min_start_m": 417.2}
    running, start = _curve_lines(s)[1:3]
    assert running.split()[-1] == "324" and start.split()[-1] == "418"
