"""The worker tells the engine when the study's design sized a run's brake (the conveyor it runs
has the size written in), so a fast brake stop's advice offers the stop time that sizes it."""

from __future__ import annotations

import pytest

from beltstudy.engine import __version__
from beltstudy.service.dask.tasks import _auto_brakes
from beltstudy.service.grid.expand import RunSpec


def _spec(design: dict) -> RunSpec:
    return RunSpec(run_id="0" * 16, axes={}, conveyor={}, scenario={}, model="din", params={},
                   dynamics=True, engine_version=__version__, design=design)


@pytest.mark.parametrize("design, auto", [
    ({}, None),  # the design sized no brake: the engine reads the conveyor
    ({"brake_governed_by": "given"}, False),
    ({"brake_governed_by": "stop_time @ declines"}, True),
    ({"brake_governed_by": "holding"}, True),
    ({"brake_governed_by": "given+grip @ full"}, True),
    ({"takeup_governed_by": "slip_start"}, None),
])
def test_a_brake_the_design_sized_is_told_to_the_engine(design, auto):
    assert _auto_brakes(_spec(design)) is auto
