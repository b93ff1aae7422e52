"""The belt loop cut into elements (engine/loop.py): its layout and where a position is."""

from __future__ import annotations

import pytest

from beltstudy.engine.loop import build_loop
from tests.engine.conftest import two_sections


def test_loop_layout(hand_conveyor):
    loop = build_loop(hand_conveyor, 1.0, n_elements=40)
    assert loop.nc == 20 and loop.strand[loop.i_head] == 2 and loop.strand[-1] == 3
    assert loop.dx_m[:20].sum() == pytest.approx(1000.0)
    # return strand runs the profile backwards: its slope is negated, it ends at the tail
    assert loop.sin_a[0] == pytest.approx(0.05) and loop.sin_a[loop.i_head + 1] == -0.05
    assert loop.z_end_m[loop.nc - 1] == pytest.approx(50.0)
    assert abs(loop.z_end_m[-2]) < 1e-9
    # element count from a target length
    assert build_loop(hand_conveyor, 1.0, target_dx_m=10.0).nc == 100
    # masses per metre (PHYSICS 1)
    assert loop.mL_kg_m[0] == pytest.approx(50.0) and loop.mL_kg_m[loop.i_head + 1] == 0
    assert loop.mR_kg_m[0] == pytest.approx(10.0)
    assert loop.mR_kg_m[loop.i_head + 1] == pytest.approx(3.0)


def test_loop_where_names_the_strand_and_the_distance_from_the_tail():
    loop = build_loop(two_sections(), 1.0, n_elements=40)
    assert loop.where(100.0) == ("carry", 100.0)
    head_end = float(loop.s_end_m[loop.i_head])
    strand, x = loop.where(head_end + 250.0)
    assert strand == "return" and x == pytest.approx(1000.0 - 250.0)
    assert loop.where(float(loop.s_end_m[-1]) - 1e-6)[0] == "tail"


def test_many_short_sections_split_without_hanging():
    """A route given as survey points (one long section and many short ones): each short
    section is floored up to one element, so the counts first exceed the strand's elements,
    and the surplus must come back from sections that keep one. Before, the largest surplus
    was looked for among every section, found at a one-element section, left unchanged, and
    the loop never ended (a 2500 m route with 18 chords of 2-5 m hung `beltstudy static`).
    The split is run in a thread with a generous join so a regression fails, not hangs."""
    import threading

    from beltstudy.engine.loop import _split

    lengths = [964.0] + [4.0] * 9 + [800.0] + [4.0] * 9 + [700.0]
    box = []
    th = threading.Thread(target=lambda: box.append(_split(100, lengths)), daemon=True)
    th.start()
    th.join(60.0)
    assert box, "_split did not return"
    counts = box[0]
    assert sum(counts) == 100 and min(counts) == 1
    assert counts[0] > counts[-1] > counts[1]  # the long sections keep the most
