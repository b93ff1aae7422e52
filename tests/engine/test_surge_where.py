"""A surge on some profile sections only is said with where it is.

``load: [1.3, 0]`` on an 800 m incline (a rise of 400 m, then a fall) warned 'surge: load 1.3
x the design load ... is above the design capacity; it fills the belt's cross-section to 68 %'
without saying that only the first 400 m carry it (and the lift and resistance are those of
that section's load alone). It now names the sections above the design load with their
distances from the tail; a uniform surge (``load: 1.2``) is the whole carry and is said as
before.
"""

from beltstudy.engine.statics import solve_steady
from tests.engine.conftest import DIN, L1, L2, two_sections


def _surge(load) -> str:
    msg = solve_steady(two_sections(), model="din", params=DIN, load=load).message
    return next(w for w in msg.split("; ") if w.startswith("surge:"))


def test_a_surge_on_one_section_names_it():
    said = _surge([1.3, 0.0])
    assert f"on profile.0 (0 to {L1:g} m from the tail)" in said, said
    assert "profile.1" not in said


def test_surges_of_their_own_sizes_are_each_said():
    said = _surge([1.1, 1.3])
    assert (f"on profile.0 (0 to {L1:g} m from the tail, 1.1 x), profile.1 ({L1:g} to "
            f"{L1 + L2:g} m from the tail, 1.3 x)") in said, said


def test_a_uniform_surge_is_the_whole_carry():
    said = _surge(1.2)
    assert said.startswith("surge: load 1.2 x the design load (material.capacity_t_h) is "
                           "above"), said
    assert "profile." not in said
