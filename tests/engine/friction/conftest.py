"""The friction models' hand conveyor: its numbers for the hand calculations, the Non-Lin
variant with a rubber bottom cover (``nl_dict``, fixture ``conv``) and the cover rubber's
tan(delta) and E' by hand."""

from __future__ import annotations

import math

import pytest

from beltstudy.engine.conveyor import parse_conveyor
from tests.conftest import hand_conveyor_dict

G = 9.81

# The hand conveyor (tests/conftest.py): L = 1000 m, H = 50 m, v = 4 m/s; the Non-Lin variant
# has a 5 mm bottom cover of standard rubber on a lighter carcass, the same
# m'_G = (14.25 + 5 x 1.15) x 1.0 = 20 kg/m; m'_L = 720 / (3.6 x 4) = 50 kg/m
L, H, V = 1000.0, 50.0, 4.0
SIN = H / L
COS = math.sqrt(1 - SIN**2)  # 0.998749
MG, ML, MRC, MRR = 20.0, 50.0, 10.0, 3.0  # kg/m
SC, SR = 1.25, 2.5  # idler spacing carry, return [m]
D = 0.133  # idler roll diameter [m]
HC = 0.005  # bottom cover [m]
LBF = 4.4482216  # N


def nl_dict(**over):
    d = hand_conveyor_dict()
    d["belt"] = {"width_m": 1.0, "rating_kn_m": 1000, "modulus_kn_m": 60000,
                 "carcass_mass_kg_m2": 14.25, "top_cover_mm": 0, "bottom_cover_mm": 5,
                 "compound": "standard"}
    d.update(over)
    return d


@pytest.fixture
def conv():
    return parse_conveyor(nl_dict())


def rubber_by_hand(temperature_c: float, f_hz: float):
    """tan(delta) and E' of the standard compound (catalogue constants, module equations)."""
    dt = temperature_c + 50.0
    x = math.log10(f_hz) - 17.44 * dt / (51.6 + dt) + 0.25
    u = x / 1.75
    tan = 0.105 + 0.85 / math.cosh(u)
    gd = 2 * math.atan(math.tanh(u / 2))
    e = 5.0e6 * math.exp((2 / math.pi) * math.log(10) * 0.85 * 1.75 * (gd + math.pi / 2))
    return tan, e
