"""Input models: the conveyor file and the operating scenario (SPEC sections 1 and 2).

These Pydantic models are the one source of truth for the contract. Every key that carries a
unit ends in that unit. Unknown keys are rejected with the nearest valid key; every error
names the field path. Everything past :func:`load_conveyor` / :func:`parse_conveyor` trusts
its types.
"""

from __future__ import annotations

import difflib
import json
import math
import re
import typing
import unicodedata
from collections.abc import Sequence
from pathlib import Path
from typing import Annotated, Any, Literal

import yaml
from pydantic import (
    AfterValidator,
    BaseModel,
    ConfigDict,
    Field,
    ValidationError,
    field_validator,
    model_validator,
)

from beltstudy.engine.errors import InputError
from beltstudy.engine.results import MAX_CURVES, MAX_DRIVES, MAX_HCURVES
from beltstudy.engine.textfile import read_text
from beltstudy.engine.wording import gnum

__all__ = [
    "InputError",
    "Belt",
    "Material",
    "ProfileSection",
    "IdlerSet",
    "Idlers",
    "Drive",
    "DEFAULT_MOTOR_CURVE",
    "DRIVE_EFFICIENCY",
    "check_motor_curve",
    "TakeUp",
    "Brake",
    "SagLimit",
    "Accessories",
    "Conveyor",
    "StartSpec",
    "StopSpec",
    "Scenario",
    "load_conveyor",
    "parse_conveyor",
    "parse_scenario",
    "load_mapping",
    "format_validation_error",
    "strict_validate",
    "conveyor_variant",
    "check_visible",
    "NameText",
    "Yaml12Floats",
    "yaml12_int",
    "yaml11_hint",
    "json_numbers",
    "load_fraction",
    "section_loads",
    "LOAD_MAX",
    "TEMPERATURE_MIN_C",
    "TEMPERATURE_MAX_C",
]


class _Model(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True, populate_by_name=True)


def _compound_enum(schema: dict) -> None:
    """The catalogue's compounds as the JSON Schema's enum (read when a schema is made)."""
    from beltstudy.engine.catalog import compounds

    schema["enum"] = sorted(compounds())


PositiveFloat = Annotated[float, Field(gt=0)]
NonNegFloat = Annotated[float, Field(ge=0)]

#: Unicode categories refused in names: control characters (NUL, escape, ...), format
#: characters (the bidi overrides U+202A-202E and isolates U+2066-2069 that reorder what a page
#: or a terminal shows, zero-width characters), line and paragraph separators.
_HIDDEN_CATEGORIES = ("Cc", "Cf", "Zl", "Zp")


def check_visible(text: str, allow: str = "") -> str:
    """``text`` if it has no control, format (bidi) or separator character (but those in
    ``allow``); ``ValueError`` naming the first one by its code point otherwise."""
    for i, ch in enumerate(text):
        if ch not in allow and unicodedata.category(ch) in _HIDDEN_CATEGORIES:
            name = unicodedata.name(ch, "a control character")
            raise ValueError(
                f"contains U+{ord(ch):04X} ({name}) at character {i + 1}; names and descriptions are plain "
                "text without control or bidi characters")
    return text


def _not_blank(text: str) -> str:
    if not text.strip():
        raise ValueError("is blank (spaces only): give a name that shows")
    return text


#: A name: plain visible text (:func:`check_visible`), not blank.
NameText = Annotated[str, AfterValidator(check_visible), AfterValidator(_not_blank)]

# Bounds a design can reach and no more (each with its reason): a value beyond one describes
# no conveyor, and a run of it would report figures of nothing real (a take-up mass of 1e300
# kg, a fill of 1e10 %). The catalogue's strongest belt, ST5400 (5 400 N/mm), at 3.2 m (the
# widest steel-cord belts built) breaks at 17 280 kN.
#: Largest design capacity [t/h]: about five times the largest conveyors built (bucket-wheel
#: excavator lines of open-cast lignite mines carry up to about 40 000 t/h).
CAPACITY_MAX_T_H = 200_000.0
#: Largest surcharge angle [deg]: CEMA, Belt Conveyors for Bulk Materials, Table 4-1
#: (flowability), whose classes run from 5 deg (very free flowing, angle of repose below
#: 20 deg) to 30 deg (sluggish, angle of repose 40 deg and more). A steeper surcharge is no
#: material's on a moving belt and, through tan(theta), would credit the belt with a heap of
#: any height: tan(89 deg) = 57 times the cross-section of tan(45 deg).
SURCHARGE_MAX_DEG = 30.0
#: Largest fill of the belt's cross-section [%] a capacity may imply (ISO 5048 cross-section at
#: the design speed): three times the cross-section heaps the material far above the belt's
#: edges; no belt carries it. Between 100 % and this a run warns (an overload or a surge).
FILL_MAX_PCT = 300.0
#: Largest gravity counterweight and carriage [kg]: 2 000 t pull 9.8 MN on each strand, more
#: than half the breaking force of the strongest catalogue belt (17 280 kN); belts run at a
#: safety factor of 5 to 10 (DIN 22101), so no belt holds such a take-up.
TAKEUP_MASS_MAX_KG = 2.0e6
#: Largest fixed take-up pretension [kN]: the breaking force of the strongest belt (see above).
PRETENSION_MAX_KN = 17_280.0
#: Largest force of one brake or lumped resistance [kN]: the strongest belt's breaking force.
FORCE_MAX_KN = 17_280.0
#: Largest rated power of one drive [kW]: about three times the largest conveyor drives built
#: (gearless drives of 7 to 10 MW per pulley).
POWER_MAX_KW = 30_000.0
#: Largest pulley diameter [m]: the largest conveyor pulleys are about 2.5 m (DIN 22101's
#: pulley diameters for the strongest steel-cord belts: engine/data/pulleys.csv).
PULLEY_DIAMETER_MAX_M = 5.0
#: Smallest pulley diameter [m]: the smallest of DIN 22101's table (engine/data/pulleys.csv).
PULLEY_DIAMETER_MIN_M = 0.1
#: Largest inertia reduced to a pulley shaft [kg m2]: a 5 m pulley of 100 t is 3e5 kg m2;
#: motors and flywheels behind gearboxes count with the ratio squared: 1e7 is beyond any.
INERTIA_MAX_KG_M2 = 1.0e7
#: Largest time of a drive's or a brake's own law [s] (coupling fill, trip, brake delay and
#: ramp): an hour; a transient run simulates every step of its cycle.
LAW_TIME_MAX_S = 3600.0
#: Largest total route length [m]: the longest single-flight conveyors are about 20 to 30 km.
ROUTE_MAX_M = 200_000.0
#: Largest vertical curve radius ``profile[i].curve_radius_m`` [m].
CURVE_RADIUS_MAX_M = 1e6


#: Thinnest rubber cover [mm] other than none: a cover is a calendered rubber sheet, and the
#: thinnest a belt carries is a skim coat of a few tenths of a millimetre (the catalogue's
#: thinnest are 2 mm); a thickness below this one is a cover written in metres (0.005 for
#: 5 mm), which read as millimetres leaves the belt without covers. 0 is a bare carcass.
COVER_MIN_MM = 0.2


class Belt(_Model):
    """Belt: a catalogue type plus optional overrides (SPEC section 1).

    Overrides replace catalogue values; with ``type`` omitted, ``rating_kn_m``,
    ``modulus_kn_m`` and ``carcass_mass_kg_m2`` (or ``mass_kg_m``) are required. A published
    belt mass per metre is ``mass_kg_m`` (SPEC 7.1; docs/routes.md): it replaces the mass from
    carcass and covers, the covers staying for the rubber model.
    """

    type: str | None = Field(None, description="belt id in the catalogue, e.g. ST2000, EP630/4; "
                             "auto: the lightest catalogue belt of belt.kind that passes the "
                             "safety factors (engine/beltselect.py)")
    kind: Literal["steel_cord", "fabric"] | None = Field(
        None, description="belt kind, required with type: auto (the catalogue belts it picks "
        "from); with a catalogue type it must be that belt's kind")
    # bounds beyond the standard widths (DIN 22102 / ISO 251: 0.3 to 3.2 m)
    width_m: float = Field(..., ge=0.1, le=5.0, description="belt width B [m] (0.1 to 5)")
    top_cover_mm: NonNegFloat | None = Field(None, le=100.0,
                                             description="carry-side cover [mm] (at most 100)")
    bottom_cover_mm: NonNegFloat | None = Field(
        None, le=100.0, description="pulley-side cover [mm] (at most 100)")
    compound: str = Field("standard", description="cover rubber compound id (catalogue)",
                          json_schema_extra=_compound_enum)
    # bounds far beyond the catalogues (EP 250 to ST 10 000; carcasses of a few to about
    # 60 kg/m2): they keep the belt's mass, stiffness and strength physical numbers
    rating_kn_m: float | None = Field(None, ge=1.0, le=1e5,
                                      description="nominal strength [kN/m] (1 to 1e5)")
    modulus_kn_m: float | None = Field(
        None, ge=1.0, le=1e9,
        description="static axial modulus E per width [kN/m] (elongation, take-up travel)")
    dynamic_modulus_kn_m: float | None = Field(
        None, ge=1.0, le=1e9, description="dynamic axial modulus per width [kN/m] (wave fronts); default: the "
        "static modulus times the catalogue's dynamic/static ratio (steel cord 1.1, fabric 1.5)")
    carcass_mass_kg_m2: float | None = Field(None, ge=0.1, le=1000.0,
                                             description="carcass mass [kg/m2] (0.1 to 1000)")
    # bound far beyond the catalogues (a 3.2 m ST 10 000 belt weighs about 200 kg/m)
    mass_kg_m: float | None = Field(
        None, gt=0.0, le=2000.0, description="belt mass per metre m'_G as the catalogue "
        "prints it [kg/m] (above 0, at most 2000): replaces (carcass + covers) x width; the "
        "covers still set the rubber (indentation) model; not with carcass_mass_kg_m2")

    @field_validator("top_cover_mm", "bottom_cover_mm")
    @classmethod
    def _cover_in_mm(cls, v: float | None) -> float | None:
        if v is not None and 0.0 < v < COVER_MIN_MM:
            raise ValueError(f"a rubber cover is 0 (none) or at least {COVER_MIN_MM:g} mm thick")
        return v

    @model_validator(mode="after")
    def _type_or_fields(self) -> Belt:
        if self.type == "auto":
            _check_auto_belt(self)
        if self.mass_kg_m is not None and self.carcass_mass_kg_m2 is not None:
            raise ValueError(
                "give the belt's mass per metre (mass_kg_m) or its carcass "
                "mass per square metre (carcass_mass_kg_m2), not both: each sets m'_G")
        if self.type is None:
            mass = ("carcass_mass_kg_m2",) if self.mass_kg_m is None else ()
            missing = [
                k
                for k in ("rating_kn_m", "modulus_kn_m") + mass
                if getattr(self, k) is None
            ]
            if missing:
                raise ValueError(
                    "give a catalogue belt 'type' or all of rating_kn_m, modulus_kn_m, "
                    f"carcass_mass_kg_m2 (missing: {', '.join(missing)})"
                )
        return self


def _check_auto_belt(b: Belt) -> None:
    """``type: auto`` needs ``kind`` and takes no override of the catalogue's values (each
    candidate belt is its catalogue row; covers and compound apply to every candidate)."""
    if b.kind is None:
        raise ValueError("type: auto needs belt.kind, the kind of catalogue belt to pick "
                         "from: give kind: steel_cord or kind: fabric")
    over = [k for k in ("rating_kn_m", "modulus_kn_m", "dynamic_modulus_kn_m",
                        "carcass_mass_kg_m2", "mass_kg_m") if getattr(b, k) is not None]
    if over:
        raise ValueError(f"type: auto takes no {', '.join(over)} (an override would replace "
                         "every candidate's catalogue value): leave it out, or give a "
                         "catalogue type to override its values")


#: Skirt-board friction coefficient mu_2 between the material and the skirt plates [-]:
#: ISO 5048:1989 / DIN 22101 give 0.5 to 0.7; the middle of that range (unverified against
#: the primary text).
SKIRT_FRICTION = 0.6
#: Clear width between the skirt boards as a share of the belt width [-] when
#: ``skirt_width_m`` is not given: CEMA's rule of thumb, skirt boards two thirds of the belt
#: width apart (CEMA Belt Conveyors for Bulk Materials, 7th ed., ch. 12; unverified).
SKIRT_WIDTH_SHARE = 2.0 / 3.0
#: Friction coefficient mu_1 between the material and the belt in the acceleration zone [-]:
#: ISO 5048:1989 gives 0.5 to 0.7 (the middle taken, as for ``SKIRT_FRICTION``); it sets the
#: acceleration length l_b = (v^2 - v_0^2) / (2 g mu_1) of DIN 22101's skirt friction F_f.
FEED_BELT_FRICTION = 0.6


class FeedPoint(_Model):
    """One feed point on the carry strand (SPEC 7.1 ``material.feed``), with its skirts."""

    at_m: float = Field(..., ge=0.0, description="position along the carry from the tail "
                        "[m] (0 to the carry length, the head excluded)")
    share: float = Field(..., gt=0.0, le=1.0,
                         description="share of the design capacity fed here [-] (0 to 1; "
                                     "the shares of all feed points sum to 1)")
    skirt_length_m: NonNegFloat = Field(
        0.0, description="length of the skirt boards from the feed point downstream [m] "
        "(0: no skirts)")
    skirt_width_m: PositiveFloat | None = Field(
        None, le=5.0, description="clear width b_1 between the skirt boards [m]; default two "
        "thirds of the belt width (CEMA)")
    skirt_friction: float = Field(
        SKIRT_FRICTION, ge=0.0, le=1.5, description="friction coefficient mu_2 material / "
        "skirt [-] (ISO 5048: 0.5 to 0.7)")
    belt_friction: float = Field(
        FEED_BELT_FRICTION, gt=0.0, le=1.5, description="friction coefficient mu_1 material "
        "/ belt while the belt accelerates the material fed here [-] (ISO 5048: 0.5 to 0.7); "
        "sets the acceleration length (v^2 - v_0^2) / (2 g mu_1) over which DIN's skirt "
        "friction F_f acts")
    loading_speed_m_s: float | None = Field(
        None, ge=-30.0, le=30.0, description="along-belt speed of the material fed here "
        "[m/s]; default material.loading_speed_m_s")


class Material(_Model):
    """Bulk material on the carry strand."""

    capacity_t_h: NonNegFloat = Field(
        ..., le=CAPACITY_MAX_T_H, description="design capacity [t/h] (at most 200 000: about "
        "five times the largest conveyors built; the fill it implies at the design speed is "
        "held to at most 300 % of the belt's cross-section, FILL_MAX_PCT)")
    density_t_m3: float = Field(1.0, ge=0.01, le=25.0,
                                description="bulk density [t/m3] (0.01 to 25)")
    loading_speed_m_s: float = Field(
        0.0, ge=-30.0, le=30.0,
        description="along-belt speed of the material at the feed point [m/s] (-30 to 30)"
    )
    surcharge_deg: float = Field(
        20.0, ge=0, le=SURCHARGE_MAX_DEG, description="surcharge angle of the material on the "
        "moving belt [deg] (0 to 30: CEMA's flowability classes run from 5 deg, very free "
        "flowing, to 30 deg, sluggish with an angle of repose of 40 deg and more; capacity "
        "check, ISO 5048; 20 deg is the usual default for free-flowing bulk)"
    )
    edge_distance_m: NonNegFloat | None = Field(
        None, description="unloaded belt edge on each side [m]; default ISO 5048 / DIN 22101: "
        "usable width 0.9 B - 0.05 m up to B = 2 m, B - 0.25 m above"
    )
    feed: list[FeedPoint] | None = Field(
        None, min_length=1, description="feed points along the carry (SPEC 7.1); default: "
        "all the material at the tail")


#: Largest turn of one horizontal curve section, ``length_m / horizontal_radius_m`` [deg]: a
#: constant-radius arc longer than its circumference 2 pi R comes back over its own start in
#: plan (geometry; a troughed belt on idler sets is not built as a helix). No conveyor
#: standard or design guide we hold gives a smaller bound (docs/routes.md).
HCURVE_TURN_MAX_DEG = 360.0


class ProfileSection(_Model):
    """One straight section of the carry route, tail -> head; with ``horizontal_radius_m`` a
    horizontal curve, checked in statics (:mod:`beltstudy.engine.hcurves`)."""

    length_m: float = Field(..., gt=0.0, le=1e5,
                            description="length along the belt [m] (at most 100 km)")
    lift_m: float = Field(0.0, description="rise over the section, negative downhill [m]")
    # at least 1 m: a tighter bend is a pulley or a kink, not a curve on idlers (its 1 deg arc
    # elements, R x 0.017 m, would also set the transient step)
    curve_radius_m: float | None = Field(
        None, ge=1.0, le=CURVE_RADIUS_MAX_M,
        description="radius of the vertical curve joining this section's grade to the next "
                    "section's [m] (1 to 1e6; SPEC 7.1; convex or concave by the two grades; "
                    "its arc takes half its length from each of the two sections: "
                    "docs/routes.md)")
    # bounds: a troughed belt needs hundreds of metres of radius (SPEC 7.1; docs/routes.md)
    horizontal_radius_m: float | None = Field(
        None, ge=10.0, le=1e6, description="the section is a horizontal curve of this radius "
        "[m] (10 to 1e6): a statics check of the tension that keeps the belt in the curve "
        "(hcurve{k}_* results, docs/routes.md)")
    superelevation_deg: float = Field(
        0.0, ge=0.0, le=20.0, description="horizontal curve: the idler sets' tilt, raised on "
        "the inside of the curve [deg] (0 to 20)")

    @model_validator(mode="after")
    def _lift_fits(self) -> ProfileSection:
        if abs(self.lift_m) >= self.length_m:
            raise ValueError(
                f"lift_m ({self.lift_m}) must be smaller in size than length_m ({self.length_m}): "
                "length is measured along the belt"
            )
        if self.superelevation_deg and self.horizontal_radius_m is None:
            raise ValueError(
                f"superelevation_deg ({self.superelevation_deg:g}) belongs to a horizontal "
                "curve: give horizontal_radius_m too, or leave superelevation_deg out")
        if self.horizontal_radius_m is not None:
            turn_deg = math.degrees(self.length_m / self.horizontal_radius_m)
            if turn_deg > HCURVE_TURN_MAX_DEG:
                # the turn to the digits that show it past 360 deg, and the least radius
                # rounded up to a tenth of a metre, which the file then takes (238.7 m for
                # 1500 m read "turns the belt 360 deg" and was refused again)
                shown = next((gnum(turn_deg, d) for d in range(4, 12)
                              if float(gnum(turn_deg, d)) > HCURVE_TURN_MAX_DEG),
                             repr(turn_deg))
                least = math.ceil(self.length_m / math.radians(HCURVE_TURN_MAX_DEG) * 10.0
                                  ) / 10.0
                raise ValueError(
                    f"horizontal_radius_m ({self.horizontal_radius_m:g} m) over length_m "
                    f"({self.length_m:g} m) turns the belt {shown} deg (L / R), more "
                    f"than a full turn ({HCURVE_TURN_MAX_DEG:g} deg): an arc of constant "
                    "radius longer than 2 pi R comes back over itself; give a radius of at "
                    f"least {least:g} m (length_m / 2 pi, rounded up) or a shorter section")
        return self


#: Largest angle in radians a wrap or a trough angle written in radians could be, and so the
#: bound below which a value in degrees reads as radians: a pulley wrap below 2 pi deg
#: (6.3 deg) grips nothing (e^(0.35 x 0.11) = 1.04), a trough below pi / 3 deg is flat.
RADIANS_WRAP_MAX = 2.0 * math.pi
RADIANS_TROUGH_MAX = math.pi / 3.0


def degrees_not_radians(v: float, bound: float, what: str, practice: str) -> float:
    """``v`` [deg], refused when it is below ``bound`` (the largest such angle in radians):
    an angle written in radians where degrees are asked for, named with its degrees."""
    if 0.0 < v < bound:
        # as radians, a value whose degrees are under the bound too is no real angle either
        # (wrap_deg 1e-300 was told to write 5.73e-299 deg)
        hint = (f"{v:g} reads as radians, {gnum(math.degrees(v))} deg: write that"
                if math.degrees(v) >= bound else f"give the {what} in degrees")
        raise ValueError(
            f"the {what} is in degrees ({practice}): {v:g} deg is no real {what}; {hint}")
    return v


class IdlerSet(_Model):
    """An idler set; rotating mass and seal drag default from the catalogue by roll diameter."""

    # bounds far beyond practice (CEMA's pitch tables run 0.6-3 m carry and up to 6 m
    # return; rolls are 0.1-0.22 m across, sets weigh tens of kg and drag a few N): they
    # only keep nonsense out of the sag, capacity and auto-size checks
    spacing_m: float | None = Field(
        None, ge=0.1, le=20.0, description="idler set pitch S [m] (0.1 to 20); or count")
    count: int | None = Field(
        None, ge=1, le=1_000_000, description="number of idler sets along the route, as a "
        "layout drawing counts them: the pitch is the conveyor length / count (the same "
        "length on the return); give spacing_m or count")
    roll_diameter_m: PositiveFloat = Field(
        0.152, le=1.0, description="roll diameter [m] (at most 1)")
    rolls: int = Field(3, ge=1, le=5, description="rolls per set")
    trough_deg: float = Field(0.0, ge=0, le=60, description="trough angle [deg]")
    cema_class: str | None = Field(None, description="CEMA idler class B..F (catalogue lookup)")
    rotating_mass_kg: NonNegFloat | None = Field(
        None, le=500.0, description="rotating mass per set [kg] (at most 500)")
    rotating_mass_per_roll_kg: NonNegFloat | None = Field(
        None, le=200.0, description="rotating mass per roll [kg] (at most 200), as roll "
        "catalogues print it: the set's is this x rolls; not with rotating_mass_kg")
    seal_drag_n: NonNegFloat | None = Field(
        None, le=500.0, description="seal drag per set [N] (at most 500)")
    roll_length_m: PositiveFloat | None = Field(
        None, le=5.0, description="length of the middle (horizontal) roll of a three-roll set, "
        "of each roll of a two-, four- or five-roll set [m], capacity and horizontal-curve "
        "checks; default by belt width (DIN 22107, engine/data/trough.csv; B / rolls for four "
        "or five, B / 2 for two)"
    )

    @field_validator("trough_deg")
    @classmethod
    def _trough_in_degrees(cls, v: float) -> float:
        # 0 is a flat set; a trough of a degree or less is none anybody builds (20, 35, 45 deg)
        if v == 0.0:
            return v
        return degrees_not_radians(v, RADIANS_TROUGH_MAX, "trough angle",
                                   "troughed sets are 20 to 45 deg, flat ones 0")

    @model_validator(mode="after")
    def _one_of_each(self) -> IdlerSet:
        if (self.spacing_m is None) == (self.count is None):
            raise ValueError(
                "give the idler pitch spacing_m [m] or the number of sets count along the "
                "route, " + ("not both" if self.count is not None else "one of them"))
        if self.rolls == 1 and self.trough_deg > 0.0:
            raise ValueError(
                f"trough_deg {self.trough_deg:g} with rolls: 1: a set of one roll carries the "
                "belt flat; give trough_deg: 0 (or leave it out), or the rolls of the troughed "
                "set (2 for a V, 3 or more)")
        if self.rotating_mass_kg is not None and self.rotating_mass_per_roll_kg is not None:
            raise ValueError(
                "give the rotating mass per set (rotating_mass_kg) or per roll "
                "(rotating_mass_per_roll_kg, times rolls), not both")
        return self

    @property
    def set_rotating_mass_kg(self) -> float | None:
        """Rotating mass of one set [kg]: ``rotating_mass_kg``, or ``rotating_mass_per_roll_kg
        x rolls``; None when neither is given (the catalogue's then)."""
        if self.rotating_mass_per_roll_kg is not None:
            return float(self.rotating_mass_per_roll_kg) * self.rolls
        return self.rotating_mass_kg

    def pitch_m(self, length_m: float) -> float:
        """Idler set pitch S [m]: ``spacing_m``, or ``length_m / count``."""
        if self.spacing_m is not None:
            return float(self.spacing_m)
        return float(length_m) / self.count


class Idlers(_Model):
    carry: IdlerSet
    return_: IdlerSet = Field(..., alias="return")


#: Most points in a motor or brake curve (the transient kernel's fixed curve arrays).
CURVE_POINTS_MAX = 16
#: Largest speed of a motor curve point, over the speed at design belt speed [-]: its
#: zero-torque (synchronous) point lies at 0.9 to 1.2 (:func:`check_motor_curve`).
CURVE_SPEED_MAX = 1.2
#: Largest torque of a motor curve point and largest ``torque_limit``, over the rated [-]:
#: induction motors' breakdown torque is 2 to 3.5 x rated and vfd torque limits 1.5 to 2.5 x
#: (IEC 60034-12 design N and H minima; drive makers' overload ratings): 10 is beyond any.
CURVE_TORQUE_MAX = 10.0
TORQUE_LIMIT_MAX = 10.0
#: Most brakes on one conveyor: two per pulley of the largest drive stations (the six drives'
#: pulleys), as the brake force is shared evenly among auto brakes.
MAX_BRAKES = 12

#: Typical induction-motor torque-speed curve (SPEC 6.1 ``motor_curve`` default): torque over
#: rated torque against pulley speed over the pulley speed at design belt speed. Shape of a
#: NEMA MG 1 design B / IEC 60034-12 design N cage motor: locked-rotor torque 1.6, pull-up 1.4
#: near half speed, breakdown 2.2 at about 87 % of synchronous speed, rated torque at the
#: design speed (rated slip 1.5 %), zero at synchronous speed. Typical values, not a maker's
#: curve: give the motor's own curve when it is known (docs/dynamics.md).
DEFAULT_MOTOR_CURVE = ((0.0, 1.6), (0.25, 1.5), (0.5, 1.4), (0.7, 1.6), (0.87, 2.2),
                       (0.95, 1.9), (1.0, 1.0), (1.015, 0.0))


#: Range accepted for a drive's speed-loop bandwidth [rad/s]: from a loop slower than any
#: start to one near the inner torque loop of a large drive.
SPEED_LOOP_RAD_S = (0.1, 50.0)

#: Default efficiency of a drive train from the motor shaft to the pulley [-]: a helical or
#: bevel-helical gear unit (about 0.97 for two to three stages) and a coupling (0.98-0.99; a
#: fluid coupling's slip costs 2-4 % more): 0.95. Belt makers' design manuals following DIN
#: 22101 quote 0.85-0.95 for drives (*unverified*; docs/drives.md): give the drive's own.
DRIVE_EFFICIENCY = 0.95


class Drive(_Model):
    """A drive pulley (SPEC sections 1 and 6.1).

    Several drives at one end are separate pulleys, met by the belt in the order of the file.
    A booster (tripper) drive sits along the carry or the return strand (``position: carry``
    or ``return`` with ``at_m``, SPEC 7.1): its own pulley in the belt's path there.
    """

    position: Literal["head", "tail", "carry", "return"] = "head"
    at_m: NonNegFloat | None = Field(
        None, description="booster drive (position carry or return): where it sits, from the "
        "tail along the conveyor [m]")
    # one pulley: the belt meets and leaves it within a turn (a snubbed drive pulley takes
    # about 180-240 deg; two pulleys in tandem are two drives)
    wrap_deg: float = Field(210.0, gt=0, lt=360, description="wrap angle of this pulley "
                            "[deg] (below 360: tandem pulleys are two drives)")
    friction: float = Field(0.35, gt=0, le=1.0, description="belt-pulley friction coefficient")
    friction_kinetic: float | None = Field(
        None, gt=0, le=1.0, description="sliding friction while the belt slips [-] "
        "(default: friction)")
    share: float = Field(1.0, gt=0, le=1.0, description="share of the peripheral force")
    pulley_diameter_m: float = Field(
        1.0, ge=PULLEY_DIAMETER_MIN_M, le=PULLEY_DIAMETER_MAX_M, description="pulley diameter "
        "[m] (0.1 to 5: DIN 22101's table of pulley diameters starts at 100 mm; the largest "
        "conveyor pulleys are about 2.5 m)")
    inertia_kg_m2: NonNegFloat = Field(
        0.0, le=INERTIA_MAX_KG_M2, description="rotating parts reduced to the pulley shaft "
        "[kg m2] (at most 1e7, beyond any drive train)"
    )
    # "auto" in the type, not only in the validator below, so that a grid axis and the
    # published schema take it as the file does ([500, auto, 800])
    rated_power_kw: Annotated[float, Field(gt=0, le=POWER_MAX_KW)] | Literal["auto"] | None = Field(
        None, description="rated power [kW], or auto (the same as leaving "
        "it out): steady power x 1.25 (at most 30 000: three times the largest conveyor drives "
        "built)"
    )
    torque_limit: float = Field(1.5, gt=0, le=TORQUE_LIMIT_MAX,
                                description="max force as a multiple of rated force (at most "
                                f"{TORQUE_LIMIT_MAX:g})")
    control: Literal["vfd", "dol"] = Field(
        "vfd", description="vfd: speed loop with a torque limit; dol: motor on the line")
    motor_curve: list[tuple[float, float]] | None = Field(
        None, max_length=CURVE_POINTS_MAX, description="dol: torque / rated torque against pulley speed / pulley speed at "
        "design belt speed (default: a typical induction-motor curve); speeds 0 to "
        f"{CURVE_SPEED_MAX:g}, torques 0 to {CURVE_TORQUE_MAX:g}")
    motor_inertia_kg_m2: NonNegFloat | None = Field(
        None, le=INERTIA_MAX_KG_M2, description="motor rotor inertia reduced to the pulley shaft [kg m2], part of "
        "inertia_kg_m2; used with a fluid coupling (default: 2/3 of inertia_kg_m2)")
    coupling: Literal["none", "fluid", "fluid_fill_controlled"] = Field(
        "none", description="coupling between motor and pulley (dol only)")
    coupling_fill_s: PositiveFloat = Field(
        20.0, le=LAW_TIME_MAX_S,
        description="fill-controlled coupling: time from empty to full [s] (at most 3600)")
    flywheel_kg_m2: NonNegFloat = Field(
        0.0, le=INERTIA_MAX_KG_M2,
        description="extra inertia reduced to the pulley shaft [kg m2] (at most 1e7)")
    trip_s: NonNegFloat = Field(
        0.0, le=LAW_TIME_MAX_S,
        description="power failure: motor torque falls to zero over this time [s] (at most "
        "3600)")
    speed_loop_rad_s: float | None = Field(
        None, json_schema_extra={"minimum": SPEED_LOOP_RAD_S[0], "maximum": SPEED_LOOP_RAD_S[1]},
        description="vfd: bandwidth of the speed loop closed on this pulley's own speed "
        "[rad/s], 0.1 to 50 (the master drive's is used; default: "
        "beltstudy.engine.dynamics.model.DEFAULT_SPEED_LOOP_RAD_S)")
    efficiency: float = Field(
        DRIVE_EFFICIENCY, gt=0, le=1.0, description="drive train efficiency from the motor "
        "shaft to the pulley (gear unit and coupling) [-]: the motor power a drive needs is "
        "its pulley power / efficiency (x efficiency regenerating); default 0.95")

    @field_validator("wrap_deg")
    @classmethod
    def _wrap_in_degrees(cls, v: float) -> float:
        return degrees_not_radians(v, RADIANS_WRAP_MAX, "wrap angle",
                                   "a drive pulley takes about 180-240 deg")

    @field_validator("speed_loop_rad_s")
    @classmethod
    def _loop_in_range(cls, v: float | None) -> float | None:
        if v is not None and not SPEED_LOOP_RAD_S[0] <= v <= SPEED_LOOP_RAD_S[1]:
            raise ValueError(
                f"speed_loop_rad_s {v:g} is outside {SPEED_LOOP_RAD_S[0]:g} to "
                f"{SPEED_LOOP_RAD_S[1]:g} rad/s (large conveyor drives run their speed "
                "loops at a few rad/s)")
        return v

    @field_validator("rated_power_kw", mode="before")
    @classmethod
    def _auto_power(cls, v):
        # auto, as the take-up mass and the brake force say it: the size of the design basis
        return None if isinstance(v, str) and v.strip().lower() == "auto" else v

    @model_validator(mode="after")
    def _curve_and_coupling(self) -> Drive:
        _check_at(self.position, self.at_m, "a booster drive")
        if math.exp(self.friction * math.radians(self.wrap_deg)) == 1.0:
            # below about 1e-16 / theta the capstan factor is 1 in floating point: the slack
            # side the grip needs, Te / (e^(mu theta) - 1), is a division by zero (a pulley that
            # barely grips, friction 1e-6, is kept: its verdict names the take-up it needs)
            raise ValueError(
                f"friction {self.friction:g} over {self.wrap_deg:g} deg of wrap grips nothing: "
                "e^(mu theta) is 1 to the last digit, and no slack-side tension makes the "
                "pulley drive the belt; give the belt-pulley friction coefficient (DIN 22101: "
                "about 0.1 wet and bare to 0.35-0.4 lagged)")
        if self.friction_kinetic is not None and self.friction_kinetic > self.friction:
            raise ValueError(
                f"friction_kinetic {self.friction_kinetic:g} is above friction "
                f"{self.friction:g}: a sliding belt grips no more than a sticking one (Coulomb "
                "friction: the sliding coefficient is at most the static one); give "
                "friction_kinetic at most friction, or leave it out")
        if (self.motor_inertia_kg_m2 is not None
                and self.motor_inertia_kg_m2 > self.inertia_kg_m2):
            raise ValueError(
                f"motor_inertia_kg_m2 {self.motor_inertia_kg_m2:g} is above inertia_kg_m2 "
                f"{self.inertia_kg_m2:g}: the motor's inertia is part of all the rotating parts "
                "reduced to the pulley shaft; give inertia_kg_m2 with the motor in it, or the "
                "motor's own (at most inertia_kg_m2)")
        if self.coupling != "none" and self.control != "dol":
            raise ValueError(f"coupling '{self.coupling}' needs control: dol (a vfd drive "
                             "controls its torque itself); use coupling: none")
        if self.speed_loop_rad_s is not None:
            bw = float(self.speed_loop_rad_s)
            if self.control != "vfd":
                raise ValueError(f"speed_loop_rad_s {bw:g} needs control: vfd (a dol motor "
                                 "runs on the line without a speed loop)")
        if self.motor_curve is not None:
            # checked whatever the control: SPEC 6.1's drive block gives a curve beside
            # control: vfd, which does not read it (checks._unread_drive_fields says so)
            check_motor_curve(self.motor_curve)
        return self

    @property
    def where(self) -> str:
        """Where the drive sits, for messages: ``head``, ``tail`` or ``carry at 1000 m``."""
        return place(self.position, self.at_m)

    @property
    def curve(self) -> tuple[tuple[float, float], ...]:
        """The motor curve used: the file's or the default."""
        return tuple(self.motor_curve) if self.motor_curve is not None else DEFAULT_MOTOR_CURVE

    @property
    def mu_kinetic(self) -> float:
        return self.friction if self.friction_kinetic is None else self.friction_kinetic


def place(position: str, at_m: float | None) -> str:
    """A position for messages: ``head``, ``tail``, or ``carry at 1000 m`` (along the route
    from the tail)."""
    return position if at_m is None else f"{position} at {at_m:g} m"


def _check_at(position: str, at_m: float | None, what: str,
              strands: tuple[str, ...] = ("carry", "return")) -> None:
    """``at_m`` goes with a position along a strand (carry or return) and only with one;
    ``strands`` are the strand positions ``what`` may take (a take-up: return only)."""
    if position in ("carry", "return") and at_m is None:
        raise ValueError(f"position: {position} places {what} along the {position} strand; "
                         "give at_m, its distance from the tail along the conveyor [m]")
    if position in ("head", "tail") and at_m is not None:
        along = " or ".join(strands)
        raise ValueError(f"at_m: {at_m:g} m goes with position {along} (along "
                         f"{'a strand' if len(strands) > 1 else 'the ' + along + ' strand'}); "
                         f"at the {position} drop at_m")


def check_motor_curve(curve) -> None:
    """A motor curve rises strictly in speed, starts at standstill and has a zero-torque point
    (synchronous speed) at its end; raises ValueError naming what is wrong."""
    xs = [float(p[0]) for p in curve]
    ys = [float(p[1]) for p in curve]
    for k, (x, y) in enumerate(zip(xs, ys, strict=True)):
        if not (math.isfinite(x) and math.isfinite(y)) or y > CURVE_TORQUE_MAX:
            raise ValueError(f"motor_curve point {k} [{x:g}, {y:g}]: speeds and torques are "
                             f"finite numbers, torques at most {CURVE_TORQUE_MAX:g} x rated "
                             "(an induction motor's breakdown torque is 2 to 3.5 x)")
    if len(xs) < 2:
        raise ValueError("motor_curve needs at least two [speed, torque] points")
    if any(b <= a for a, b in zip(xs, xs[1:], strict=False)):
        raise ValueError("motor_curve speeds must increase strictly from point to point "
                         f"(got {xs})")
    if xs[0] != 0.0:
        raise ValueError(f"motor_curve must start at speed 0 (locked rotor), got {xs[0]:g}")
    if ys[-1] != 0.0 or any(y <= 0.0 for y in ys[:-1]):
        raise ValueError("motor_curve needs a zero-torque point (synchronous speed) as its "
                         "last point and positive torque below it "
                         f"(got torques {ys})")
    if not 0.9 <= xs[-1] <= CURVE_SPEED_MAX:
        raise ValueError(f"motor_curve: the zero-torque point at speed {xs[-1]:g} is not near "
                         f"the design speed (expected 0.9-{CURVE_SPEED_MAX:g} of it)")


class TakeUp(_Model):
    """Take-up: gravity (counterweight) or fixed (screw/winch at a set pretension)."""

    type: Literal["gravity", "fixed"] = "gravity"
    position: Literal["tail", "head", "return"] = "tail"
    at_m: NonNegFloat | None = Field(
        None, description="take-up along the return (position: return): where it sits, from "
        "the tail along the conveyor [m]")
    mass_kg: Annotated[float, Field(gt=0, le=TAKEUP_MASS_MAX_KG)] | Literal["auto"] = Field(
        "auto", description="gravity counterweight [kg] or auto (the smallest meeting slip at "
        "start-up and the sag limits, running and held at rest, at the full design load); at "
        "most 2e6 kg: 2 000 t pull 9.8 MN on each strand, more than half the breaking force "
        "of the strongest catalogue belt"
    )
    pretension_kn: Annotated[float, Field(gt=0, le=PRETENSION_MAX_KN)] | Literal["auto"] = Field(
        "auto", description="fixed take-up: tension at the take-up [kN] or auto; at most "
        "17 280 kN, the breaking force of the strongest catalogue belt"
    )
    sag_at_rest: bool = Field(
        True, description="auto sizing also meets the sag limits with the belt held at rest "
        "(conservative: DIN 22101 checks sag only running); false sizes for running only"
    )
    travel_m: PositiveFloat | None = Field(
        None, description="carriage travel between end stops [m]; default 1.5 % of length"
    )
    carriage_mass_kg: NonNegFloat = Field(
        0.0, le=TAKEUP_MASS_MAX_KG,
        description="carriage and pulley mass in addition to the counterweight [kg] (at most "
        "2e6, as the counterweight)"
    )

    @model_validator(mode="after")
    def _kind_fields(self) -> TakeUp:
        _check_at(self.position, self.at_m, "the take-up", strands=("return",))
        if self.position == "carry":
            raise ValueError("position: carry; a take-up sits on the return (head, tail or "
                             "return with at_m)")
        if self.type == "fixed" and self.mass_kg != "auto":
            raise ValueError("a fixed take-up has no counterweight: give pretension_kn, not mass_kg")
        if self.type == "gravity" and self.pretension_kn != "auto":
            raise ValueError("a gravity take-up is set by its mass: give mass_kg, not pretension_kn")
        return self


class Brake(_Model):
    """A brake (SPEC sections 1 and 6.1): on the head or tail pulley, or on a drive's shaft.

    The force builds over ``ramp_s`` after ``delay_s`` (or follows ``force_curve``, the fraction
    of the force against the time since the brake was applied) and acts through the pulley's
    friction (capstan-limited). ``hold`` sets the brake once the belt has stopped, in every
    stop mode, and keeps it set; a brake without ``hold`` is released once the belt has
    stopped.
    """

    position: Literal["head", "tail"] | None = Field(
        None, description="head | tail pulley (default head when no drive is given)")
    drive: int | None = Field(None, ge=1, description="1-based drive whose shaft is braked")
    force_kn: Annotated[float, Field(gt=0, le=FORCE_MAX_KN)] | Literal["auto"] = Field(
        "auto", description="brake force at the belt [kN] or auto; at most 17 280 kN, the "
        "breaking force of the strongest catalogue belt")
    delay_s: NonNegFloat = Field(0.5, le=LAW_TIME_MAX_S,
                                 description="from the stop command to application [s]")
    ramp_s: NonNegFloat = Field(
        1.0, le=LAW_TIME_MAX_S,
        description="from application to full force [s] (disc brakes build in 0.2-2 s)")
    force_curve: list[tuple[float, float]] | None = Field(
        None, max_length=CURVE_POINTS_MAX,
        description="fraction of the force against time since applied [s, -]")
    hold: bool = Field(True, description="set once the belt has stopped and stay set")

    @model_validator(mode="after")
    def _where(self) -> Brake:
        if self.position is not None and self.drive is not None:
            raise ValueError("give either position (head | tail) or drive (N), not both")
        if self.force_curve is not None:
            ts = [float(p[0]) for p in self.force_curve]
            fs = [float(p[1]) for p in self.force_curve]
            if len(ts) < 1 or any(b <= a for a, b in zip(ts, ts[1:], strict=False)):
                raise ValueError("force_curve times must increase strictly (got "
                                 f"{ts})")
            if ts[0] < 0.0 or any(not 0.0 <= f <= 1.0 for f in fs):
                raise ValueError("force_curve: times from 0 up and fractions of the force in "
                                 f"0..1 (got {list(self.force_curve)})")
            if max(fs) < 1.0:
                # force_kn is the brake's full force: the auto size, the stop-time estimate,
                # the grip check and brake_force_kn all take it as the force the brake gives
                raise ValueError(
                    f"force_curve: its fractions reach {max(fs):g} of force_kn, never the full "
                    "force (1): force_kn is the force the brake gives; let the curve reach 1 "
                    "and give force_kn the brake's largest force"
                    + (" (a curve of zeros is a brake that never brakes)" if max(fs) == 0.0
                       else ""))
        return self

    @property
    def where(self) -> str:
        """'head', 'tail' or 'drive N'."""
        if self.drive is not None:
            return f"drive {self.drive}"
        return self.position or "head"


#: A sag counts as past its limit above ``limit x (1 + SAG_LIMIT_RTOL)``: an auto take-up
#: sized by a sag limit meets it exactly, and the belt's rest and running states give it back
#: to rounding (the steady check and the transient one alike).
SAG_LIMIT_RTOL = 1e-9


class SagLimit(_Model):
    # a limit near zero asks for an unbounded tension (T_min = w S / (8 h/S)): at least 0.1 %,
    # well below practice (DIN 22101 and CEMA use about 0.5 to 3 %)
    # and at most 50 %: a span sagging by half its length is no belt on idlers any more
    carry: float = Field(1.5, ge=0.1, le=50.0,
                         description="admissible carry sag h/S [%] (0.1 to 50)")
    return_: float = Field(3.0, ge=0.1, le=50.0, alias="return",
                           description="admissible return sag [%] (0.1 to 50)")


#: Belt cleaner friction coefficient mu_3 [-]: ISO 5048:1989 gives 0.5 to 0.7 (middle taken;
#: unverified against the primary text).
SCRAPER_FRICTION = 0.6
#: Plough resistance per metre of belt width k_a [N/m]: ISO 5048:1989, 1500 N/m (unverified).
PLOUGH_K_N_M = 1500.0


class Scraper(_Model):
    """A belt cleaner (ISO 5048 F_r = A p mu_3) at the head or tail pulley."""

    at: Literal["head", "tail"] = Field("head", description="the pulley it cleans at")
    contact_area_m2: PositiveFloat = Field(..., le=5.0,
                                           description="contact area A of the blade [m2]")
    pressure_n_m2: PositiveFloat = Field(..., le=1e6, description="blade pressure p [N/m2] "
                                         "(ISO 5048: 3e4 to 1e5)")
    friction: float = Field(SCRAPER_FRICTION, ge=0.0, le=1.5,
                            description="friction coefficient mu_3 blade / belt [-] (0.5 to 0.7)")


class Plough(_Model):
    """A discharge plough on the carry (ISO 5048 F_a = B k_a)."""

    at_m: NonNegFloat = Field(..., description="position along the carry from the tail [m]")
    k_n_m: NonNegFloat = Field(PLOUGH_K_N_M, le=1e5,
                               description="resistance per metre of belt width k_a [N/m] "
                                           "(ISO 5048: 1500)")


class Accessories(_Model):
    head_kn: NonNegFloat = Field(0.0, le=FORCE_MAX_KN,
                                 description="lumped resistance at the head [kN]")
    tail_kn: NonNegFloat = Field(0.0, le=FORCE_MAX_KN,
                                 description="lumped resistance at the tail [kN]")
    scrapers: list[Scraper] = Field(default_factory=list,
                                    description="belt cleaners (ISO 5048 F_r), beside head_kn")
    ploughs: list[Plough] = Field(default_factory=list,
                                  description="discharge ploughs (ISO 5048 F_a)")


class Conveyor(_Model):
    """A belt conveyor (SPEC section 1)."""

    name: NameText = Field(..., min_length=1, max_length=200,
                           description="free text without control or bidi characters")
    # bounds beyond practice (belt conveyors run about 0.1 to 10 m/s)
    speed_m_s: float = Field(..., ge=0.01, le=30.0,
                             description="design belt speed [m/s] (0.01 to 30)")
    belt: Belt
    material: Material
    profile: list[ProfileSection] = Field(..., min_length=1)
    idlers: Idlers
    drives: list[Drive] = Field(..., min_length=1, max_length=MAX_DRIVES,
                                description="drive pulleys, at most 6 (head and tail)")
    takeup: TakeUp = TakeUp()
    brakes: list[Brake] = Field(default_factory=list, max_length=MAX_BRAKES,
                                description=f"brakes, at most {MAX_BRAKES} (two per pulley of "
                                "the largest drive stations)")
    holdback: bool = False
    sag_limit_pct: SagLimit = SagLimit()
    accessories: Accessories = Accessories()
    # 1 to 50: below 1 the belt is allowed to break; DIN 22101's minima are 3 to 12
    safety_factor_min: float | None = Field(
        None, ge=1.0, le=50.0,
        description="minimum running belt safety factor [-] (1 to 50); default by belt kind"
    )

    @model_validator(mode="after")
    def _route_length(self) -> Conveyor:
        total = sum(p.length_m for p in self.profile)
        if total > ROUTE_MAX_M:
            raise ValueError(
                f"profile: {total:g} m of route in all; at most {ROUTE_MAX_M:g} m (the longest "
                "single-flight conveyors are about 20 to 30 km)")
        return self

    @model_validator(mode="after")
    def _shares(self) -> Conveyor:
        total = sum(d.share for d in self.drives)
        if abs(total - 1.0) > 1e-6:
            parts = " + ".join(f"drives.{i} ({d.where}) {d.share:g}"
                               for i, d in enumerate(self.drives))
            raise ValueError(f"drives: shares sum to {total:g} ({parts}); they must sum to 1")
        controls = {d.control for d in self.drives}
        if len(controls) > 1:
            raise ValueError("drives: every drive of a conveyor has the same control (vfd "
                             "drives share one speed loop, dol motors run on the line); got "
                             + ", ".join(f"drives.{i}.control = {d.control}"
                                         for i, d in enumerate(self.drives)))
        master = max(range(len(self.drives)), key=lambda i: (self.drives[i].share, -i))
        for i, d in enumerate(self.drives):
            if d.speed_loop_rad_s is not None and i != master:
                raise ValueError(
                    f"drives.{i}.speed_loop_rad_s: drive {i + 1} follows the master's torque "
                    f"(drive {master + 1}, the largest share) and runs no speed loop of its "
                    f"own; set speed_loop_rad_s on drives.{master}")
        for i, b in enumerate(self.brakes):
            if b.drive is not None and b.drive > len(self.drives):
                raise ValueError(f"brakes.{i}.drive: there is no drive {b.drive} (the conveyor "
                                 f"has {len(self.drives)} drive(s), numbered from 1)")
        _check_feed(self)
        _check_along(self)
        n_curves = sum(p.horizontal_radius_m is not None for p in self.profile)
        if n_curves > MAX_HCURVES:
            raise ValueError(f"profile: {n_curves} horizontal curves; at most {MAX_HCURVES} "
                             "(sections with horizontal_radius_m)")
        vertical = [i for i, p in enumerate(self.judged_profile())
                    if p.curve_radius_m is not None]
        if len(vertical) > MAX_CURVES:
            raise ValueError(
                f"profile: {len(vertical)} vertical curves (curve_radius_m on profile."
                f"{', profile.'.join(str(i) for i in vertical)}); at most {MAX_CURVES}, each "
                f"with its own result columns (curve1_* to curve{MAX_CURVES}_*): join "
                "sections of nearly the same grade into one, or give the radius only to "
                "the curves to be checked (a grade change without curve_radius_m is judged "
                "as the circle through its survey points, docs/routes.md)")
        for strand in ("carry", "return"):
            s = self.idlers.carry if strand == "carry" else self.idlers.return_
            if s.count is not None and not 0.1 <= s.pitch_m(self.length_m) <= 20.0:
                raise ValueError(
                    f"idlers.{strand}.count: {s.count} sets over {self.length_m:g} m is a pitch "
                    f"of {gnum(s.pitch_m(self.length_m), 3)} m, outside 0.1 to 20 m: count the sets "
                    f"along the whole route ({self.length_m / 20.0:.0f} to "
                    f"{self.length_m / 0.1:.0f} here)")
        return self

    @model_validator(mode="after")
    def _curves(self) -> Conveyor:
        _curves_fit(self.profile, self.judged_profile(), self.curve_pitch_m())
        arcs = curve_arcs(self.judged_profile())
        for name, at in route_points(self):
            for k, (a, b) in enumerate(arcs, start=1):
                tol = 1e-9 * max(1.0, b)
                if a + tol < at < b - tol:
                    # the places named are rounded outwards, off the arc
                    before = math.floor(10.0 * a + 1e-6) / 10.0
                    after = math.ceil(10.0 * b - 1e-6) / 10.0
                    raise ValueError(
                        f"{name}: {at:g} m lies on vertical curve {k} (its arc runs from "
                        f"{a:.3f} to {b:.3f} m); place it on a straight grade, before "
                        f"{before:.1f} or after {after:.1f} m")
        _drives_off_hcurves(self)
        return self

    def short_curves(self) -> list[tuple[int, float, float]]:
        """The vertical curves whose arc is shorter than an idler pitch, ``(i, |delta|, arc)``
        per ``profile[i].curve_radius_m`` in profile order (docs/routes.md, part (c)).

        The belt is held by idler sets a pitch S apart (the smaller of the carry and return
        pitches: a turn shorter than it is a kink on both strands); a curve is built by
        setting the sets on its arc to the radius R, so the belt follows R only where the arc
        holds sets, R |delta| >= S. A shorter arc holds at most one set: the belt runs
        straight from the last set on one grade to that set and on to the first set on the
        other, turning by delta there on that one set. Every verdict taken with R (lift-off
        at T > R m'_G g cos a, the convex edge strain (h - z_mean) / R, the idler load
        T S / R) would judge a bend the belt does not make, and the transient's step, set by
        the arc's elements, would shrink with the arc (an arc of 2e-7 m asked for 1e12
        steps). Such a curve is judged at the radius whose arc spans one pitch, or as the
        grade change without it where that does not fit (:meth:`judged_profile`), and the
        run says so (``beltstudy.engine.checks.input_notes``). A curve between equal grades (no turn) or on the last section is
        refused at input, not listed."""
        pitch = self.curve_pitch_m()
        out = []
        for i, sec in enumerate(self.profile):
            arc = curve_arc_m(self.profile, i)
            if sec.curve_radius_m is not None and 0.0 < arc < pitch:
                out.append((i, arc / sec.curve_radius_m, arc))
        return out

    def judged_profile(self) -> list[ProfileSection]:
        """The profile as every check, the loop and the transient read it: the sections as
        given, but a vertical curve whose arc is shorter than an idler pitch
        (:meth:`short_curves`) at the radius whose arc spans one pitch, ``S / |delta|``
        (:meth:`short_curve_radius_m`): the turn is taken on one idler set, as the tightest
        bend the sets give the belt. Where that curve does not fit its sections (or is above
        ``CURVE_RADIUS_MAX_M``, a turn of a hair) the grade change is judged as one given
        without a curve (the circle through its survey points,
        :func:`beltstudy.engine.curves.junction_checks`). The conveyor's own ``profile`` keeps
        what the file gave. Read ``curve_radius_m`` (and :func:`curve_arc_m`,
        :func:`curve_arcs`) from this list, never from ``profile``."""
        short = self.short_curves()
        drop = {i for i, _, _ in short}
        out = [sec.model_copy(update={"curve_radius_m": None}) if i in drop else sec
               for i, sec in enumerate(self.profile)]
        for i, turn, _arc in short:
            radius = self.short_curve_radius_m(turn)
            if radius is None:
                continue
            trial = list(out)
            trial[i] = out[i].model_copy(update={"curve_radius_m": radius})
            fits = all(
                0.5 * curve_arc_m(trial, k) + (0.5 * curve_arc_m(trial, k - 1) if k else 0.0)
                <= trial[k].length_m and _rest_takes_its_lift(trial, k) for k in (i, i + 1))
            if fits:
                out = trial
        return out

    def short_curve_radius_m(self, turn_rad: float) -> float | None:
        """The radius a vertical curve shorter than an idler pitch is judged at [m]: ``S /
        |delta|``, whose arc spans one pitch S (:meth:`curve_pitch_m`), None above
        ``CURVE_RADIUS_MAX_M``. The belt cannot bend tighter than its idler sets let it: on an
        arc shorter than a pitch it runs straight to one set and turns there by delta, so
        that set takes the resultant ``T |delta|`` against the belt's weight over a pitch,
        ``m' g S``, the balance of a curve of ``S / |delta|`` (``T = R m' g`` at lift-off, the
        idler load ``T S / R``). A tighter radius given is judged no milder than that: a
        6.3 deg valley given R 10 m (arc 1.1 m of a 1.2 m pitch) had been judged as the circle
        through its survey points, 3 135 m, and said the empty belt stays on its idlers with
        463 kN to spare, where R 11 m said it lifts (the kink pulls 2.9 kN up against 188 N of
        belt on the set). Raised by 1e-9 so its arc is not read as under the pitch."""
        radius = self.curve_pitch_m() / turn_rad * (1.0 + 1e-9)
        return radius if radius <= CURVE_RADIUS_MAX_M else None

    def curve_pitch_m(self) -> float:
        """The idler pitch a vertical curve's arc must span to be a curve [m]: the smaller of
        the carry and return pitches (:meth:`short_curves`)."""
        return min(self.idler_spacing_m("carry"), self.idler_spacing_m("return"))

    def idler_spacing_m(self, strand: str) -> float:
        """Idler set pitch of ``carry`` or ``return`` [m]: ``spacing_m``, or the conveyor
        length over ``count``."""
        s = self.idlers.carry if strand == "carry" else self.idlers.return_
        return s.pitch_m(self.length_m)

    @property
    def length_m(self) -> float:
        """Length along the carry strand [m]."""
        return float(sum(p.length_m for p in self.profile))

    @property
    def lift_m(self) -> float:
        """Net lift tail -> head [m]."""
        return float(sum(p.lift_m for p in self.profile))


def _check_feed(conv: Conveyor) -> None:
    """Feed points inside the carry, shares summing to 1, one feed per position, skirts and
    ploughs on the carry (SPEC 7.1)."""
    L = conv.length_m
    feed = conv.material.feed or []
    for i, f in enumerate(feed):
        if f.at_m >= L:
            raise ValueError(f"material.feed.{i}.at_m: {f.at_m:g} m is out of the carry "
                             f"(0 to {L:g} m from the tail, the head excluded)")
        if f.at_m + f.skirt_length_m > L + 1e-9:
            raise ValueError(f"material.feed.{i}.skirt_length_m: skirts of {f.skirt_length_m:g}"
                             f" m from {f.at_m:g} m run past the head ({L:g} m)")
        if f.skirt_width_m is not None and f.skirt_width_m >= conv.belt.width_m:
            raise ValueError(f"material.feed.{i}.skirt_width_m: {f.skirt_width_m:g} m between "
                             f"the skirt boards is not less than the belt width "
                             f"{conv.belt.width_m:g} m: the boards stand on the belt, inside its "
                             f"edges; give less (leave it out for two thirds of the width, "
                             f"{gnum(SKIRT_WIDTH_SHARE * conv.belt.width_m, 3)} m)")
        if f.skirt_width_m is not None and f.skirt_length_m == 0.0:
            raise ValueError(f"material.feed.{i}.skirt_width_m: give skirt_length_m too (no "
                             "skirts without a length)")
        if f.skirt_width_m is not None and f.skirt_length_m > 0.0:
            # ISO 5048's F_gL = mu_2 I_V^2 rho g l_b / (v^2 b_1^2) per metre of skirt at the
            # design load, m'_L = capacity / v: a width whose square underflows makes it
            # infinite (1e-200 m: every tension inf, a traceback in the pulley checks)
            m_l = conv.material.capacity_t_h / 3.6 / conv.speed_m_s
            rho = conv.material.density_t_m3 * 1e3
            per_m = f.skirt_friction * 9.81 * m_l * m_l / (rho * f.skirt_width_m ** 2) \
                if f.skirt_width_m ** 2 > 0.0 else math.inf
            if not math.isfinite(per_m):
                raise ValueError(
                    f"material.feed.{i}.skirt_width_m: {f.skirt_width_m:g} m between the skirt "
                    "boards makes their friction infinite (ISO 5048: F_gL grows as 1 / b_1^2); "
                    "give the clear width between the boards (leave it out for two thirds of "
                    f"the belt width, {gnum(SKIRT_WIDTH_SHARE * conv.belt.width_m, 3)} m)")
        for j in range(i):
            if abs(feed[j].at_m - f.at_m) < 1e-6:
                raise ValueError(f"material.feed.{i}.at_m: {f.at_m:g} m is also "
                                 f"material.feed.{j}'s position; give one feed point per "
                                 "position with the summed share")
    if feed:
        total = sum(f.share for f in feed)
        if abs(total - 1.0) > 1e-6:
            parts = " + ".join(f"material.feed.{i}.share {f.share:g}"
                               for i, f in enumerate(feed))
            raise ValueError(f"material.feed: shares sum to {total:g} ({parts}); they must "
                             "sum to 1")
    for i, p in enumerate(conv.accessories.ploughs):
        if p.at_m >= L:
            raise ValueError(f"accessories.ploughs.{i}.at_m: {p.at_m:g} m is out of the "
                             f"carry (0 to {L:g} m)")


def _check_along(conv: Conveyor) -> None:
    """Booster drives and a take-up along a strand lie inside the route (SPEC 7.1)."""
    L = conv.length_m
    for i, d in enumerate(conv.drives):
        if d.at_m is not None and not 0.0 < d.at_m < L:
            raise ValueError(f"drives.{i}.at_m: {d.at_m:g} m is not inside the route (0 to "
                             f"{L:g} m from the tail, both ends excluded: a drive at an end is "
                             "position: head or tail)")
    tu = conv.takeup
    if tu.at_m is not None and not 0.0 < tu.at_m < L:
        raise ValueError(f"takeup.at_m: {tu.at_m:g} m is not inside the route (0 to {L:g} m "
                         "from the tail, both ends excluded: a take-up at an end is position: "
                         "head or tail)")
    if tu.travel_m is not None and tu.travel_m > L:
        # the carriage stores belt in its loop, two strands' worth: 2 x travel of belt, which
        # cannot exceed the belt's whole loop, 2 x the route length
        raise ValueError(f"takeup.travel_m: {tu.travel_m:g} m of carriage travel would store "
                         f"{2.0 * tu.travel_m:g} m of belt in the take-up loop, more than the "
                         f"whole belt loop ({2.0 * L:g} m, twice the {L:g} m route); give at "
                         f"most {L:g} m (or leave it out: 1.5 % of the length, "
                         f"{gnum(0.015 * L, 3)} m)")


def _drives_off_hcurves(conv: Conveyor) -> None:
    """Refuse a booster drive inside a horizontal curve (a profile section with
    ``horizontal_radius_m``), as one on a vertical arc is: a drive pulley turns the belt about
    an axis across it and needs the belt running straight into and out of it."""
    start = 0.0
    for i, sec in enumerate(conv.profile):
        end = start + sec.length_m
        if sec.horizontal_radius_m is not None:
            tol = 1e-9 * max(1.0, end)
            for k, d in enumerate(conv.drives):
                if d.at_m is not None and start + tol < float(d.at_m) < end - tol:
                    raise ValueError(
                        f"drives.{k}.at_m: {float(d.at_m):g} m lies in the horizontal curve of "
                        f"profile.{i} ({start:g} to {end:g} m from the tail); a drive pulley "
                        "needs the belt straight into and out of it: place it on a straight "
                        f"section, at or before {start:g} or at or after {end:g} m")
        start = end


def route_points(conv: Conveyor) -> list[tuple[str, float]]:
    """The points along the route where the loop is cut (element ends): feed points, booster
    drives and a take-up along the return; (field name, distance from the tail [m])."""
    out = [(f"material.feed.{i}.at_m", float(f.at_m))
           for i, f in enumerate(conv.material.feed or []) if f.at_m > 0.0]
    out += [(f"drives.{i}.at_m", float(d.at_m)) for i, d in enumerate(conv.drives)
            if d.at_m is not None]
    if conv.takeup.at_m is not None:
        out.append(("takeup.at_m", float(conv.takeup.at_m)))
    return out


def curve_arcs(profile: list[ProfileSection]) -> list[tuple[float, float]]:
    """Each vertical curve's arc along the route from the tail, (start, end) [m] (of the
    profile given: :meth:`Conveyor.judged_profile` for the curves the run builds)."""
    out, at = [], 0.0
    for i, sec in enumerate(profile):
        at += sec.length_m
        h = 0.5 * curve_arc_m(profile, i)
        if h > 0.0:
            out.append((at - h, at + h))
    return out


def curve_arc_m(profile: list[ProfileSection], i: int) -> float:
    """Arc length R |delta| of the vertical curve that ends ``profile[i]`` [m] (0 without one):
    delta the change of slope angle between section i's grade and section i+1's (of the
    profile given: :meth:`Conveyor.judged_profile` for the curves the run builds)."""
    sec = profile[i]
    if sec.curve_radius_m is None or i + 1 >= len(profile):
        return 0.0
    nxt = profile[i + 1]
    delta = (math.asin(nxt.lift_m / nxt.length_m) - math.asin(sec.lift_m / sec.length_m))
    return sec.curve_radius_m * abs(delta)


def _curves_fit(profile: list[ProfileSection], judged: list[ProfileSection],
                pitch_m: float) -> None:
    """Refuse a vertical curve that cannot be built (docs/routes.md, part (c)): on the last
    section (no next grade), between equal grades, or longer than its sections: its arc takes
    half its length from the end of its section and half from the start of the next, and a
    section must hold the halves of the curves at both its ends. ``profile`` is the profile
    as given, ``judged`` as judged (:meth:`Conveyor.judged_profile`: a curve shorter than an
    idler pitch ``pitch_m`` is a grade change without a curve, and takes no room)."""
    for i, sec in enumerate(profile):
        if sec.curve_radius_m is None:
            continue
        name = f"profile.{i}.curve_radius_m"
        if i + 1 == len(profile):
            raise ValueError(f"{name}: the last section has no next grade to curve into")
        if curve_arc_m(profile, i) <= 0.0:
            raise ValueError(f"{name}: sections {i} and {i + 1} have the same grade; there is "
                             "no curve to make (drop curve_radius_m)")
    for i, sec in enumerate(judged):
        need = 0.5 * curve_arc_m(judged, i) + (0.5 * curve_arc_m(judged, i - 1) if i else 0.0)
        j = i if sec.curve_radius_m is not None else i - 1
        if need > sec.length_m:
            # to the millimetre where a tenth would print the section's own length
            shown = f"{need:.1f}" if f"{need:.1f}" != f"{sec.length_m:.1f}" else f"{need:.3f}"
            raise ValueError(
                f"profile.{j}.curve_radius_m: the curve's arcs need {shown} m of "
                f"profile.{i} (half of each curve's R |delta| at its ends) but the section "
                f"is {sec.length_m:g} m long; {_curve_fit_fix(judged, j, pitch_m)}")
        if not _rest_takes_its_lift(judged, i):
            excess = 0.5 * sum(_lift_excess_m(judged, k) for k in (i - 1, i) if k >= 0)
            raise ValueError(
                f"profile.{j}.curve_radius_m: the curve's arcs leave {sec.length_m - need:.3f} "
                f"m of straight grade in profile.{i}, too little to keep the section's lift "
                f"(the arcs rise {-excess:+.3f} m beyond the grades they replace there); "
                f"{_curve_fit_fix(judged, j, pitch_m)}")


#: Largest change of slope angle from one element to the next on a vertical curve [deg]: the
#: mesh on a curve is the automatic element size or finer, so that it follows the arc
#: (engine/loop.py builds the arcs).
CURVE_STEP_DEG = 1.0


def _lift_excess_m(profile: list[ProfileSection], i: int) -> float:
    """What the two straight halves replaced by the curve ending ``profile[i]`` rise beyond its
    arc [m] (0 without one): ``R |delta| / 2 (sin a_1 + sin a_2) - R sgn(delta) (cos a_1 -
    cos a_2)``; engine/loop.py gives half of it to each section's straight rest."""
    arc = curve_arc_m(profile, i)
    if arc <= 0.0:
        return 0.0
    a1 = math.asin(profile[i].lift_m / profile[i].length_m)
    a2 = math.asin(profile[i + 1].lift_m / profile[i + 1].length_m)
    r = profile[i].curve_radius_m
    return 0.5 * arc * (math.sin(a1) + math.sin(a2)) - math.copysign(r, a2 - a1) * (
        math.cos(a1) - math.cos(a2))


def _rest_takes_its_lift(profile: list[ProfileSection], i: int) -> bool:
    """Whether section i's straight rest takes its curves' halves of the lift excess
    (:func:`_lift_excess_m`) within the turn engine/loop.py allows it off its grade (the larger
    of :data:`CURVE_STEP_DEG` and its curves' own turns), so the route keeps its lift (to a
    millimetre where no rest is left). The largest radius a section held by length alone
    left 0.03 m of rest after a 0 to 30 % convex curve, which cannot take the 0.35 m of lift
    its half of the excess asks: the route rose 90.69 m, not 90."""
    sec = profile[i]
    halves = [0.5 * curve_arc_m(profile, j) for j in (i - 1, i) if j >= 0]
    rest = sec.length_m - sum(halves)
    need = 0.5 * sum(_lift_excess_m(profile, j) for j in (i - 1, i) if j >= 0)
    if rest <= 1e-9 * sec.length_m:
        return abs(need) <= 1e-3
    ang = math.asin(sec.lift_m / sec.length_m)
    turn = max([math.radians(CURVE_STEP_DEG)] + [
        curve_arc_m(profile, j) / profile[j].curve_radius_m
        for j in (i - 1, i) if j >= 0 and curve_arc_m(profile, j) > 0.0])
    lift = rest * math.sin(ang) + need
    # the turned grades bounded at the vertical: a section 0.05 m short of vertical turned by
    # another degree falls below its own sine, and its straight rest failed its own lift
    hi, lo = min(ang + turn, 0.5 * math.pi), max(ang - turn, -0.5 * math.pi)
    return rest * math.sin(lo) <= lift <= rest * math.sin(hi)


def _radius_keeps_lift(profile: list[ProfileSection], j: int, r: float) -> bool:
    """Whether the curve ending ``profile[j]`` at radius ``r`` leaves both its sections able to
    keep their lift (:func:`_rest_takes_its_lift`)."""
    trial = list(profile)
    trial[j] = profile[j].model_copy(update={"curve_radius_m": r})
    return all(_rest_takes_its_lift(trial, i) for i in (j, j + 1))


def _lift_radius_max(profile: list[ProfileSection], j: int, r_max: float) -> int:
    """The largest whole radius up to ``r_max`` [m] at which the curve ending ``profile[j]``
    keeps its sections' lift (:func:`_radius_keeps_lift`; fewer metres of radius leave more
    rest and less excess), 0 when none does."""
    lo, hi = 0, int(math.floor(r_max))
    if hi >= 1 and _radius_keeps_lift(profile, j, hi):
        return hi
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if _radius_keeps_lift(profile, j, mid):
            lo = mid
        else:
            hi = mid
    return lo


def _curve_fit_fix(profile: list[ProfileSection], j: int, pitch_m: float) -> str:
    """What fits the curve ending ``profile[j]`` into its two sections: the largest radius
    whose half arc, ``R |delta| / 2``, fits each of them beside the half of the curve at its
    other end (rounded down to the metre), or, where that curve's half takes the section, a
    smaller radius there. Where that radius's arc would be shorter than an idler pitch
    ``pitch_m`` it is no curve (the belt kinks on one idler set, :meth:`Conveyor.short_curves`):
    a 0.5 m section after a 4.6 deg turn was offered 'a radius of at most 12 m', an arc of
    0.96 m under the 1.5 m pitch; then the levers are longer sections or no curve there."""
    sec = profile[j]
    turn = curve_arc_m(profile, j) / sec.curve_radius_m
    rooms = [profile[j].length_m - (0.5 * curve_arc_m(profile, j - 1) if j else 0.0),
             profile[j + 1].length_m - 0.5 * curve_arc_m(profile, j + 1)]
    room = min(rooms)
    if room <= 0.0:
        k = j - 1 if rooms[0] <= 0.0 else j + 1
        return (f"the half arc of profile.{k}.curve_radius_m takes all of profile."
                f"{j if k < j else j + 1}: a smaller radius there or longer sections")
    r_max = _lift_radius_max(profile, j, math.floor(2.0 * room / turn))
    tight = j if rooms[0] <= rooms[1] else j + 1
    if r_max * turn < pitch_m:
        return (f"no curve fits there: the largest radius that does, {r_max:g} m (the grades "
                f"turn by {math.degrees(turn):.2f} deg, R |delta| / 2 within the {room:.2f} m "
                f"left to the curve in profile.{tight}), makes an arc of "
                f"{r_max * turn:.2f} m, shorter than an idler pitch ({pitch_m:g} m), which is "
                f"no curve but a grade change on one idler set; longer sections, or no "
                f"curve_radius_m (a grade change without a curve, judged as one)")
    return (f"a radius of at most {r_max:g} m (the grades turn by {math.degrees(turn):.2f} deg: "
            f"R |delta| / 2 within the {room:.1f} m left to the curve in profile.{tight}) or "
            "longer sections")


class StartSpec(_Model):
    control: Literal["s-curve", "linear", "torque"] = Field(
        "s-curve", description="start law of vfd drives: an s-curve (cycloid) or linear speed "
        "reference over time_s, or torque (design speed at once, the force limit ramping up "
        "from the holding force over time_s) [-]; dol drives switch on the line")
    time_s: PositiveFloat = Field(60.0, le=LAW_TIME_MAX_S,
                                  description="start (acceleration) time [s], at most an hour "
                                              "(a transient run simulates every step)")


class StopSpec(_Model):
    mode: Literal["coast", "brake", "controlled"] = Field(
        "coast", description="coast (power failure: the drive force drops to zero), brake "
        "(coast plus the brakes after their delay) or controlled (the vfd drives follow a "
        "reverse s-curve to rest over time_s) [-]")
    time_s: PositiveFloat = Field(30.0, le=LAW_TIME_MAX_S,
                                  description="target stop time [s], at most an hour")


#: Largest load as a fraction of the design load: a surge up to 30 % above the design
#: capacity (SPEC 6.2); anything above 1 is reported as a warning.
LOAD_MAX = 1.3
#: Ambient temperature range of every entry point (files, studies, the command line) [C]: the
#: range the cover-rubber data of engine/data/compounds.csv are meant for.
TEMPERATURE_MIN_C = -60.0
TEMPERATURE_MAX_C = 80.0

LoadFraction = Annotated[float, Field(ge=0, le=LOAD_MAX)]
#: A load case (SPEC 6.2): full | empty | a fraction (a surge above 1) | one fraction per carry
#: profile section | inclines (loaded where a section rises) | declines (where it falls).
LoadCase = (
    Literal["full", "empty", "inclines", "declines"]
    | LoadFraction
    | Annotated[list[LoadFraction], Field(min_length=1)]
)


def load_fraction(load: str | float) -> float:
    """A uniform load case as a fraction of the design load: full -> 1, empty -> 0.

    Patterns (``inclines``, ``declines``, a list per section) have no single fraction: use
    :func:`section_loads`.
    """
    if isinstance(load, str):
        if load not in ("full", "empty"):
            raise ValueError(f"load '{load}' is a pattern, not one fraction: use section_loads")
        return {"full": 1.0, "empty": 0.0}[load]
    if isinstance(load, list | tuple):
        raise ValueError("a load per section is not one fraction: use section_loads")
    return float(load)


def section_loads(load, conveyor: Conveyor) -> tuple[float, ...]:
    """The load case as one fraction of the design load per carry profile section.

    ``full`` 1, ``empty`` 0, a number that number everywhere, a list one value per section
    (tail to head, as in ``profile``), ``inclines`` 1 on sections that rise (``lift_m > 0``)
    and 0 elsewhere, ``declines`` 1 on sections that fall (``lift_m < 0``): the loaded-uphill
    and loaded-downhill cases of DIN 22101 and CEMA for undulating profiles.

    Raises
    ------
    InputError
        A list whose length is not the number of profile sections (names ``scenario.load``).
    """
    sections = conveyor.profile
    if isinstance(load, str):
        if load == "inclines":
            return tuple(1.0 if p.lift_m > 0 else 0.0 for p in sections)
        if load == "declines":
            return tuple(1.0 if p.lift_m < 0 else 0.0 for p in sections)
        return (load_fraction(load),) * len(sections)
    if isinstance(load, list | tuple):
        if len(load) != len(sections):
            raise InputError(
                f"{len(load)} fractions for {len(sections)} profile sections; "
                "give one per carry section, tail to head", field="scenario.load")
        for x in load:
            if not (0.0 <= float(x) <= LOAD_MAX):
                raise InputError(_fraction_problem(float(x)), field="scenario.load")
        return tuple(float(x) for x in load)
    frac = float(load)
    if not (0.0 <= frac <= LOAD_MAX):
        raise InputError(_fraction_problem(frac), field="scenario.load")
    return (frac,) * len(sections)


def _fraction_problem(frac: float) -> str:
    """Why ``frac`` is no load fraction, and the fix: a value from twice the design load (no
    belt runs so overfilled; 1.3 to 2 is a surge past the largest) up to 100 x the largest
    fraction reads as a per cent (a plant log's load in % of the design capacity: 50 for 0.5),
    a NaN as no value."""
    if math.isnan(frac):
        return "not a number: give the load case (full, empty or a fraction of the design load)"
    text = f"{frac:g} is outside 0..{LOAD_MAX:g} of the design load"
    if 2.0 <= frac <= 100.0 * LOAD_MAX:
        text += (f": give a fraction, not a per cent ({frac:g} % of the design load is "
                 f"{frac / 100.0:g})")
    return text


class Scenario(_Model):
    """Operating scenario for a run (SPEC section 2)."""

    load: LoadCase = Field(
        "full", description="full | empty | a fraction of the design load up to 1.3 (above 1 a "
        "surge, warned) | a list, one fraction per carry profile section | inclines | declines"
    )
    temperature_c: float = Field(20.0, ge=TEMPERATURE_MIN_C, le=TEMPERATURE_MAX_C,
                                 description="ambient temperature [C]")
    start: StartSpec = Field(default_factory=StartSpec,
                             description="the start: control law and time_s [s]")
    run_s: NonNegFloat = Field(30.0, le=LAW_TIME_MAX_S,
                               description="steady running between start and stop [s], at most "
                                           "an hour (a transient run simulates every step)")
    stop: StopSpec = Field(default_factory=StopSpec,
                           description="the stop: mode and target time_s [s]")
    formulation: Literal["relative", "support"] = Field(
        "relative", description="relative (paper Eq. 2: the drive force from a speed "
        "controller) or support (paper Eq. 3: the drive pulley's motion imposed) [-]")
    elements: Literal["auto"] | Annotated[int, Field(ge=8, le=200_000)] = Field(
        "auto", description="belt elements around the loop [-], 8 to 200 000, or auto (the "
        "mesh of docs/dynamics.md, about 200)")
    dt_s: Literal["auto"] | PositiveFloat = Field(
        "auto", description="time step [s], or auto (a fraction of the stability limit, "
        "docs/dynamics.md)")
    # at most a minute: the start's fronts, the waves and the stop happen within seconds, and a
    # spacing beyond the cycle would leave a time series of its two ends
    record_dt_s: PositiveFloat = Field(0.1, le=60.0, description="time-series sample spacing "
                                       "[s] (at most 60)")

    @property
    def load_fraction(self) -> float:
        return load_fraction(self.load)


# --------------------------------------------------------------------------------------
# Error formatting: one line per problem, naming the field path and the fix.


def _model_at(model: type[BaseModel], loc: tuple) -> type[BaseModel] | None:
    """Walk a location tuple down the model tree; return the model that owns the last key
    (the first member where a union of models owns it: :func:`_models_at` gives them all)."""
    found = _models_at(model, loc)
    return found[0] if found else None


def _models_at(model: type[BaseModel], loc: tuple) -> list[type[BaseModel]]:
    """Every model that may own the last key of ``loc``: one, or the members of a union of
    models (a sample axis's ``dist``: uniform, normal, ...). A mapping's own keys (a sample
    axis's path) are stepped over; a union member's tag in ``loc`` picks that member."""
    current: list[Any] = [model]
    skip_key = False
    for part in loc[:-1]:
        if isinstance(part, int):
            continue
        if skip_key:  # a key of a mapping (dict[str, Model]), not a field
            skip_key = False
            continue
        tagged = [m for m in current if part in _tags(m)]
        if tagged and len(current) > 1:
            current = tagged  # the tag Pydantic puts in a location: that member
            continue
        field = next((f for m in current for name, f in m.model_fields.items()
                      if part in (name, f.alias)), None)
        if field is None:
            return []
        skip_key = typing.get_origin(field.annotation) is dict
        current = _inner_models(field.annotation)
        if not current:
            return []
    return current


def _tags(model: type[BaseModel]) -> set[str]:
    """The literal values of a model's ``Literal`` fields (a union member's tag)."""
    out: set[str] = set()
    for f in model.model_fields.values():
        if typing.get_origin(f.annotation) is Literal:
            out.update(str(a) for a in typing.get_args(f.annotation))
    return out


def _inner_models(annotation: Any) -> list[type[BaseModel]]:
    """The models inside an annotation (a list's, a dict's values, a union's members)."""
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return [annotation]
    args = typing.get_args(annotation)
    if typing.get_origin(annotation) is dict and len(args) == 2:
        args = args[1:]  # the values' type, not the keys'
    found: list[type[BaseModel]] = []
    for arg in args:
        found += [m for m in _inner_models(arg) if m not in found]
    return found


def _inner_model(annotation: Any) -> Any:
    found = _inner_models(annotation)
    return found[0] if found else None


def valid_keys(model: type[BaseModel]) -> list[str]:
    return [f.alias or name for name, f in model.model_fields.items()]


#: A key written in a handbook's unit where the contract has its SI twin: the unit suffix, the
#: twin's suffix and how to convert (exact factors: 1 ft = 0.3048 m, 1 in = 0.0254 m,
#: 1 lb = 0.45359237 kg, 1 short ton = 0.90718474 t, 1 lbf = 4.4482216 N, 1 hp = 0.7457 kW,
#: 1 lb ft2 = 0.45359237 x 0.3048^2 = 0.0421401 kg m2).
UNIT_SUFFIXES = (
    ("_kg_m3", "_t_m3", "t/m3: kg/m3 / 1000"),
    ("_lb_ft3", "_t_m3", "t/m3: lb/ft3 x 0.016018"),
    ("_stph", "_t_h", "metric t/h: short tons/h x 0.90718"),
    ("_tph", "_t_h", "metric t/h, or short tons/h x 0.90718 if the tph are US short tons "
               "as in CEMA"),
    ("_fpm", "_m_s", "m/s: ft/min x 0.00508"),
    ("_ft", "_m", "metres: ft x 0.3048"),
    ("_mm", "_m", "metres: mm / 1000"),
    ("_in", "_m", "metres: in x 0.0254"),
    ("_rad", "_deg", "degrees: rad x 57.296"),
    ("_lbf", "_kn", "kN: lbf x 0.0044482"),
    ("_lb", "_kg", "kg: lb x 0.45359"),
    ("_hp", "_kw", "kW: hp x 0.7457"),
    ("_mw", "_kw", "kW: MW x 1000"),
    ("_w", "_kw", "kW: W / 1000"),
    ("_mn", "_kn", "kN: MN x 1000"),
    ("_n", "_kn", "kN: N / 1000"),
    ("_f", "_c", "degrees Celsius: (F - 32) / 1.8"),
    ("_k", "_c", "degrees Celsius: K - 273.15"),
    ("_min", "_s", "seconds: min x 60"),
    ("_ms", "_s", "seconds: ms / 1000"),
    ("_h", "_s", "seconds: h x 3600"),
    ("_lb_ft2", "_kg_m2", "kg m2: lb ft2 x 0.042140"),
)

#: Handbook words with no key of their own, and the key that carries them.
KEY_HINTS = {
    "lagging": "the pulley lagging (bare, rubber, ceramic) enters as the belt-pulley friction "
               "coefficient: give 'friction' for that lagging and its wet or dry duty (belt "
               "maker's data or DIN 22101's table)",
    "mu": "the belt-pulley friction coefficient (mu) is 'friction'",
    **{name: "a section rises by lift_m over length_m, its length along the belt: give "
             "lift_m = length_m x sin(angle) (negative downhill)"
       for name in ("angle_deg", "slope_deg", "inclination_deg", "incline_deg")},
}

#: Handbook words for a choice the contract names otherwise: (field, word) -> the fix.
VALUE_HINTS = {
    **{("type", word): "a counterweight take-up is type: gravity"
       for word in ("counterweight", "counter_weight", "weighted", "vertical_gravity",
                    "horizontal_gravity")},
    **{("type", word): "a take-up set by hand or by a winch and then held is type: fixed "
                       "(give pretension_kn)"
       for word in ("screw", "manual", "winch", "hydraulic")},
}

#: Out-of-range values that are the right quantity in another unit: the field, a test on the
#: value and the hint.
UNIT_SLIPS = {
    "density_t_m3": (lambda v: v > 25.0, lambda v: f"{v / 1000:g} t/m3 if {v:g} is kg/m3"),
    # a friction coefficient in per cent: from 5 (0.05, below the wet bare pulley's 0.1 of
    # DIN 22101) up; 1.08 is no per cent anyone writes (it read "0.0108 if 1.08 is %")
    "friction": (lambda v: v >= 5.0, lambda v: f"a coefficient, {v / 100:g} if {v:g} is %"),
    "friction_kinetic": (lambda v: v >= 5.0,
                         lambda v: f"a coefficient, {v / 100:g} if {v:g} is %"),
    "efficiency": (lambda v: 1.0 < v <= 100.0,
                   lambda v: f"a fraction, {v / 100:g} if {v:g} is %"),
    # a temperature in kelvin that is one in the range read in degrees Celsius
    "temperature_c": (lambda v: TEMPERATURE_MIN_C + 273.15 <= v <= TEMPERATURE_MAX_C + 273.15,
                      lambda v: f"in degrees Celsius, {gnum(v - 273.15)} C if {v:g} is K"),
    **{name: (lambda v: 0.0 < v < COVER_MIN_MM,
              lambda v: f"in millimetres, {v * 1000:g} mm if {v:g} is m")
       for name in ("top_cover_mm", "bottom_cover_mm")},
    **{name: (lambda v: v > 5.0, lambda v: f"in metres, {v / 1000:g} m if {v:g} is mm")
       for name in ("spacing_m", "width_m", "roll_diameter_m", "pulley_diameter_m",
                    "skirt_width_m", "roll_length_m")},
    # a motor's power in watts, a force in newtons, a belt speed in metres per minute
    "rated_power_kw": (lambda v: v > POWER_MAX_KW,
                       lambda v: f"in kilowatts, {v / 1000:.6g} kW if {v:.12g} is W"),
    **{name: (lambda v: v > FORCE_MAX_KN,
              lambda v: f"in kilonewtons, {v / 1000:.6g} kN if {v:.12g} is N")
       for name in ("force_kn", "pretension_kn", "head_kn", "tail_kn")},
    "speed_m_s": (lambda v: v > 30.0,
                  lambda v: f"in metres per second, {v / 60:g} m/s if {v:g} is m/min"),
    # a start, stop or running time in milliseconds
    **{name: (lambda v: LAW_TIME_MAX_S < v <= 1000.0 * LAW_TIME_MAX_S,
              lambda v: f"in seconds, {v / 1000:g} s if {v:g} is ms")
       for name in ("time_s", "run_s")},
    # a load or a sampled share of runs in per cent
    # from twice the design load, as _fraction_problem reads it (1.3 to 2 is a surge past
    # the largest, not a per cent: 1.5 read "0.015 if 1.5 is %")
    "load": (lambda v: 2.0 <= v <= 130.0,
             lambda v: f"a fraction of the design load, {v / 100:g} if {v:g} is %"),
    "sample": (lambda v: 1.0 < v <= 100.0,
               lambda v: f"a fraction of the runs, {v / 100:g} if {v:g} is %"),
}


def nearest_word(got: Any, expected: str) -> str:
    """``did you mean 'inclines'?`` for a text near one of the words a choice takes (the
    quoted words of ``expected``, as Pydantic lists a literal's values: ``'full', 'empty'
    or 'inclines'``); the word itself when only its case differs (``Full``); "" otherwise."""
    if not isinstance(got, str):
        return ""
    words = re.findall(r"'([^']*)'", expected)
    text = got.strip()
    close = ([w for w in words if w.lower() == text.lower()]
             or difflib.get_close_matches(text.lower(), words, n=1, cutoff=0.6))
    return f"did you mean '{close[0]}'?" if close and close[0] != got else ""


def unit_twin(key: str, keys: Sequence[str]) -> str:
    """``did you mean 'power_kw'? (in kW: MW x 1000)`` for a ``key`` that is a valid key
    with its unit written in another one (``power_MW``, ``te_N``, ``mass_lb``; any case), "" for
    any other: the name alone would be renamed and its numbers kept in the other unit."""
    low = key.lower()
    for suffix, repl, conv in UNIT_SUFFIXES:
        twin = low[: -len(suffix)] + repl
        if low.endswith(suffix) and twin in keys and twin != key:
            return f"did you mean '{twin}'? (in {conv})"
    return _bracket_twin(key, keys)


#: A name with its unit in brackets or parentheses, as spreadsheets head their columns:
#: ``temperature_c [F]``, ``power (W)``, ``power_kw [kW]``.
_BRACKETED = re.compile(r"\s*([A-Za-z_][\w ]*?)\s*[\[(]\s*([^\])]+?)\s*[\])]\s*")


def _bracket_twin(key: str, keys: Sequence[str]) -> str:
    """:func:`unit_twin` of a name whose unit is written in brackets: the name's stem (without
    a unit suffix of its own) joined to that unit (``temperature_c [F]`` -> ``temperature_f``),
    whose twin gives the conversion; ``did you mean 'power_kw'? (the unit is in the name)``
    where the bracket repeats the name's own unit. A column headed ``temperature_c [F]`` was
    told "did you mean 'temperature_c'?", and renamed so its degrees Fahrenheit were read as
    Celsius."""
    m = _BRACKETED.fullmatch(key)
    if not m:
        return ""
    name = m.group(1).strip().lower().replace(" ", "_")
    unit = (m.group(2).lower().replace("°", "").replace("deg", "").replace("/", "_")
            .replace(" ", "").strip("_"))
    if not unit:
        return ""
    # the name's own unit suffix off (temperature_c -> temperature), where it is a key
    own = next((repl for _, repl, _ in UNIT_SUFFIXES if name.endswith(repl)), "")
    stem = name[: -len(own)] if own and name in keys else name
    candidate = f"{stem}_{unit}"
    if candidate in keys:
        return (f"did you mean '{candidate}'? (its unit, {m.group(2).strip()}, is in the "
                "name)")
    return unit_twin(candidate, keys)


def _unknown_key_hint(key: str, keys: list[str], missing: list[str] = ()) -> str:
    """What to write instead of the unknown ``key``: its SI twin with the conversion, the key
    a handbook word maps to, else the nearest valid key (first among the required keys
    ``missing`` beside it: ``stpe`` beside a missing ``step`` is that, not ``stop``) or the
    list."""
    if key in KEY_HINTS:
        return f"; {KEY_HINTS[key]}"
    twin = unit_twin(key, keys)
    if twin:
        return f"; {twin}"
    close = (difflib.get_close_matches(key, [k for k in missing if k in keys], n=1, cutoff=0.5)
             or difflib.get_close_matches(key, keys, n=1, cutoff=0.5))
    return f"; did you mean '{close[0]}'?" if close else f"; valid keys: {', '.join(keys)}"


#: YAML 1.1's base-60 numbers (``1:30`` is 90, ``1:30.5`` is 90.5): text in YAML 1.2.
_BASE_60 = re.compile(r"^[-+]?[0-9][0-9_]*(?::[0-5]?[0-9])+(?:\.[0-9_]*)?$")
#: Pydantic error types of a value that should be a number, and of one that should be a boolean.
_NUMBER_ERRORS = {"float_type", "float_parsing", "int_type", "int_parsing"}
_BOOL_ERRORS = {"bool_type", "bool_parsing"}


def yaml11_hint(got: Any, error_type: str) -> str:
    """The fix for a text that YAML 1.1 read as another type and YAML 1.2 (the readers here)
    reads as text: ``yes``/``no``/``on``/``off`` where a boolean belongs, a base-60 ``1:30``
    where a number belongs; "" for every other value. The conveyor's messages and the door's
    JSON-type ones (studies, calibrations) both add it."""
    if not isinstance(got, str):
        return ""
    if error_type in _BOOL_ERRORS and got.strip().lower() in ("yes", "no", "on", "off", "y", "n"):
        return "write true or false (YAML 1.2 reads yes, no, on and off as text)"
    text = got.strip()
    if error_type in _NUMBER_ERRORS and _BASE_60.match(text):
        value = 0.0
        for part in text.lstrip("+-").replace("_", "").split(":"):
            value = 60.0 * value + float(part)
        value = -value if text.startswith("-") else value
        return (f"write the number itself (YAML 1.2 reads {text} as text, not as YAML 1.1's "
                f"base 60, {value:g})")
    return ""


#: Pydantic error types that say a value has the wrong JSON type -> the type it should have.
#: Every door says such an error alike: ``speed_m_s: "4.5" is not of type "number"`` (the
#: field, the value given as JSON writes it, the type to write), then :func:`type_hint`.
JSON_TYPES = {
    "float_type": "number", "float_parsing": "number", "int_type": "integer",
    "int_parsing": "integer", "int_from_float": "integer", "bool_type": "boolean",
    "bool_parsing": "boolean", "string_type": "string", "list_type": "array",
    "tuple_type": "array", "dict_type": "object", "model_type": "object",
    "model_attributes_type": "object", "none_required": "null",
}
_JSON_NUMBER = re.compile(r"^-?(?:0|[1-9][0-9]*)(?:\.[0-9]+)?(?:[eE][-+]?[0-9]+)?$")


def as_json(value: Any) -> str:
    """``value`` as JSON writes it (``"4.5"``, ``[1,2]``, ``true``); ``repr`` where JSON
    cannot."""
    try:
        return json.dumps(value, ensure_ascii=False, separators=(",", ":"), allow_nan=False)
    except (TypeError, ValueError):
        return repr(value)


def type_hint(got: Any, error_type: str) -> str:
    """What to write for a value of the wrong type: :func:`yaml11_hint`'s fixes, a number or
    boolean written as text (``"4.5"``: ``write 4.5 without quotes``) and a number or boolean
    where text belongs (``name: 5``: ``write "5" in quotes``); "" for every other value."""
    hint = yaml11_hint(got, error_type)
    if hint:
        return hint
    if isinstance(got, str):
        text = got.strip()
        if error_type in _NUMBER_ERRORS and _JSON_NUMBER.match(text):
            return f"write {text} without quotes"
        if error_type in _BOOL_ERRORS and text.lower() in ("true", "false"):
            return f"write {text.lower()} without quotes"
    elif error_type == "string_type" and isinstance(got, int | float | bool):
        return f"write {json.dumps(as_json(got))} in quotes"
    return ""


#: The union member tags Pydantic adds to an error's location (``literal['auto']``,
#: ``function-after[...]``, ``constrained-float``): a user's key with a bracket in it
#: (``speed_m_s [m/s]``, a unit written into the name) is none of them.
_PYDANTIC_TAG = re.compile(
    r"^(?:literal|function-(?:after|before|wrap|plain)|json-or-python|lax-or-strict|"
    r"is-instance|chain|definition-ref|nullable|tagged-union|union|list|dict|tuple|set|"
    r"frozenset|model|dataclass|default|constrained-[a-z]+)\[|^constrained-[a-z]+$")


def _clean_loc(loc: tuple) -> tuple:
    """A location without the union member tags Pydantic adds (``literal['auto']``,
    ``float``); a key of the input with a bracket in it is kept (``speed_m_s [m/s]``: it was
    taken for a tag, and a top-level one left no location at all, a traceback)."""
    return tuple(
        p for p in loc
        if not (isinstance(p, str) and (p in {"float", "int", "str", "list", "bool", "dict"}
                                        or _PYDANTIC_TAG.match(p)))
    )


def _said_errors(exc: ValidationError) -> list[dict]:
    """The errors worth saying: a union member's wrong type is left out where another member
    took the value and found it out of range (a load of 2: its range is the problem) or
    looked inside it (a mapping that is no text, with a problem inside)."""
    errors = [{**e, "clean": _clean_loc(tuple(e["loc"]))} for e in exc.errors()]
    valued = {e["clean"] for e in errors
              if e["type"] not in JSON_TYPES and e["type"] not in ("literal_error", "missing",
                                                                    "extra_forbidden")}
    deeper = {e["clean"][:i] for e in errors for i in range(len(e["clean"]))}

    def outshone(e: dict) -> bool:
        return e["type"] in JSON_TYPES and (
            e["clean"] in valued
            or (isinstance(e.get("input"), dict | list) and e["clean"] in deeper))

    return [e for e in errors if not outshone(e)]


def format_validation_error(exc: ValidationError, model: type[BaseModel], prefix: str = "") -> str:
    """Turn a Pydantic error into short lines naming the field path and the fix; a value of
    the wrong type as JSON Schema says it (``speed_m_s: "4.5" is not of type "number"``),
    the same words as a study's door (:mod:`beltstudy.service.door.messages`)."""
    lines = []
    near: dict[str, str] = {}  # path -> the choice a misspelt word is nearest
    said = _said_errors(exc)
    # the required keys missing beside an unknown one: the key it most likely misspells
    missing: dict[tuple, list[str]] = {}
    for err in said:
        if err["type"] == "missing" and err["clean"]:
            missing.setdefault(err["clean"][:-1], []).append(str(err["clean"][-1]))
    for err in said:
        clean = err["clean"]  # Pydantic's union member tags taken off (_clean_loc)
        path = prefix + ".".join(str(p) for p in clean)
        if err["type"] == "extra_forbidden":
            owners = _models_at(model, clean)
            key = str(clean[-1])
            hint = ""
            lacking = missing.get(clean[:-1], [])
            # a union of models (a sample axis's dist): the members that lack those keys
            owners = [m for m in owners if set(lacking) <= set(valid_keys(m))] or owners
            # a key of another member of the union (a normal's sd on a uniform): not the
            # key to suggest for itself; say which members take it
            others = [m for m in owners if key not in valid_keys(m)]
            takers = [m for m in owners if key in valid_keys(m)] if others else []
            owners = others or owners
            # the member the input names (its tag, kept by the caller in ``ctx``): its keys
            tags = set((err.get("ctx") or {}).get("tags") or ())
            owners = [m for m in owners if _tags(m) & tags] or owners
            if owners:
                keys = list(dict.fromkeys(k for m in owners for k in valid_keys(m)))
                hint = _unknown_key_hint(key, keys, lacking)
                tags = sorted(t for m in takers for t in _tags(m))
                if tags:
                    hint = f" (a key of {' and '.join(tags)}, not of this kind){hint}"
            lines.append(f"{path}: unknown key '{key}'{hint}")
        elif err["type"] == "missing":
            lines.append(f"{path}: required field is missing")
        else:
            msg = err["msg"]
            if msg.startswith("Value error, "):
                msg = msg[len("Value error, ") :]
            got = err.get("input")
            if err["type"] in JSON_TYPES:
                # the value given, the type to write and how (one wording on every path)
                hint = type_hint(got, err["type"])
                lines.append((path, f'is not of type "{JSON_TYPES[err["type"]]}"',
                              f": {hint}" if hint else "", f"{as_json(got)} "))
                continue
            # a YAML null as the file writes it, not Python's None
            shown = "" if isinstance(got, dict | list) else (
                " (got null)" if got is None else f" (got {got!r})")
            if isinstance(got, float) and not math.isfinite(got):
                msg = "Input should be a finite number"  # not a bound a NaN fails
            slip = UNIT_SLIPS.get(str(clean[-1])) if clean else None
            num = got
            if isinstance(got, str):  # a CSV's cells are text: '253.15' under temperature_c
                try:
                    num = float(got)
                except ValueError:
                    num = None
            if (slip is not None and isinstance(num, int | float) and not isinstance(num, bool)
                    and math.isfinite(num) and slip[0](num)):
                shown += f": {slip[1](num)}"
            hint = yaml11_hint(got, err["type"])
            if not hint and clean and isinstance(got, str):
                hint = VALUE_HINTS.get((str(clean[-1]), got.strip().lower()), "")
            if not hint and err["type"] == "literal_error":
                hint = nearest_word(got, msg)
                if hint:
                    # kept beside a union's wrong-type line ('"inclnes" is not of type ...')
                    near[path] = hint
            if err["type"] == "union_tag_not_found" and "ctx" in err:
                # a tagged choice given without its tag (a sample axis with no dist): the
                # key to add and the words it takes, not Pydantic's "Unable to extract tag"
                key = str(err["ctx"]["discriminator"]).strip(chr(39))
                path += f".{key}"
                words = list(dict.fromkeys(t for m in _models_at(model, (*clean, key))
                                           for t in sorted(_tags(m))))
                msg = "required field is missing" + (
                    f"; give {key}: one of {', '.join(words)}" if words else "")
                shown = ""
            if err["type"] == "union_tag_invalid" and "ctx" in err:
                # a tagged choice (a sample axis's dist): the key, the word given and the words
                ctx = err["ctx"]
                path += f".{str(ctx['discriminator']).strip(chr(39))}"
                msg = f"unknown value '{ctx['tag']}'; valid: {ctx['expected_tags']}"
                hint = nearest_word(ctx["tag"], str(ctx["expected_tags"]))
                shown = ""
            if hint:
                shown += f": {hint}"
            if not clean:
                # A check across fields names its own field first ("drives: shares sum ...").
                m = re.match(r"([A-Za-z_][\w\[\]\.]*): (.*)$", msg, re.S)
                if m:
                    path, msg = prefix + m.group(1), m.group(2)
                else:
                    path = prefix.rstrip(".") or "(top level)"
            lines.append((path, msg, shown, ""))
    # Union types produce one error per member: one line per field, the members' conditions
    # joined by "or" ("Input should be 'auto' or greater than or equal to 8"; a wrong type
    # first: '"x" is not of type "number" or 'auto'').
    merged: dict[str, list] = {}
    for line in lines:
        if isinstance(line, str):
            merged.setdefault(line, [])
            continue
        path, msg, shown, lead = line
        key = f"\x00{path}"
        if key not in merged:
            merged[key] = [path, [msg], shown, lead]
        elif msg not in merged[key][1]:
            if lead and not merged[key][3]:  # the wrong type leads, its value and fix too
                merged[key][2:] = [shown, lead]
            merged[key][1].append(msg)
    out = []
    for key, item in merged.items():
        if not item:
            out.append(key)
            continue
        path, msgs, shown, lead = item
        # the types first, then the members' other conditions (the door's order)
        msgs = sorted(msgs, key=lambda m: not m.startswith("is not of type "))
        text = msgs[0] + "".join(" or " + _or_part(m) for m in msgs[1:])
        if path in near and near[path] not in shown:
            shown += f": {near[path]}"
        out.append(f"{path}: {lead}{text}{shown}")
    return "; ".join(out)


def _or_part(msg: str) -> str:
    """A union member's condition after the first's: ``'auto'`` of ``Input should be 'auto'``,
    ``"null"`` of ``is not of type "null"``."""
    for lead in ("Input should be ", "is not of type "):
        if msg.startswith(lead):
            return msg[len(lead):]
    return msg


#: YAML 1.2's floats that YAML 1.1 (PyYAML) reads as text: an exponent without its sign
#: (``6.0e4``, ``1e5``) or with it but no decimal point (``1e-2``, ``2e+4``). Read as
#: numbers: with numbers held to their type, ``"6.0e4"`` would otherwise be refused where the
#: writer meant 60 000.
_FLOAT_12 = re.compile(r"^[-+]?(?:[0-9][0-9_]*(?:\.[0-9_]*)?|\.[0-9_]+)[eE][-+]?[0-9]+$")


#: YAML 1.2's integers that YAML 1.1 (PyYAML) reads otherwise: a decimal with leading zeros
#: (``0210``: YAML 1.1 reads octal 136, or text where a digit is 8 or 9) and ``0o``
#: octal (text in YAML 1.1). Read as YAML 1.2 reads them (:func:`yaml12_int`).
_INT_12 = re.compile(r"^[-+]?(?:0[0-9_]+|0[oO]_*[0-7][0-7_]*)$")


def yaml12_int(text: str) -> int | None:
    """The integer YAML 1.2's core schema reads in ``text`` where YAML 1.1 reads another
    (:data:`_INT_12`): ``0210`` is 210 (a wrap angle written with a leading zero was read as
    136 degrees), ``0o20`` is 16. ``None`` for every other notation, which both read alike."""
    if not _INT_12.match(text):
        return None
    bare = text.replace("_", "")
    sign = -1 if bare.startswith("-") else 1
    bare = bare.lstrip("+-")
    # ``0_`` is 0 (``bare[1:2]`` is empty there, and "" is in every text): octal by its o only
    return sign * (int(bare[2:], 8) if bare[1:2] in ("o", "O") else int(bare, 10))


class Yaml12Floats(yaml.resolver.Resolver):
    """PyYAML's resolver with YAML 1.2's exponent floats (:data:`_FLOAT_12`) as floats, its
    integers with leading zeros or ``0o`` (:data:`_INT_12`) as integers (read by
    :func:`yaml12_int` in the loaders' constructors) and its booleans (``true``/``false``
    only: ``yes``, ``no``, ``on``, ``off`` are text)."""


Yaml12Floats.add_implicit_resolver("tag:yaml.org,2002:float", _FLOAT_12,
                                   list("-+0123456789."))
Yaml12Floats.add_implicit_resolver("tag:yaml.org,2002:int", _INT_12, list("-+0"))
# YAML 1.2's booleans are true and false alone: YAML 1.1's yes/no/on/off (and y/n) are
# text, so ``holdback: yes`` is refused as no boolean and ``position: on`` names the text it
# got, where YAML 1.1 read them as true
_BOOL_12 = re.compile(r"^(?:true|True|TRUE|false|False|FALSE)$")
Yaml12Floats.yaml_implicit_resolvers = {
    first: [(tag, rx) for tag, rx in rules if tag != "tag:yaml.org,2002:bool"]
    for first, rules in Yaml12Floats.yaml_implicit_resolvers.items()}
Yaml12Floats.add_implicit_resolver("tag:yaml.org,2002:bool", _BOOL_12, list("tTfF"))


class _KeyTwice(Exception):
    """A mapping with a key given twice: the key and its lines (1-based; ``None`` in JSON)."""

    def __init__(self, key: str, first: int | None = None, line: int | None = None):
        super().__init__(key)
        self.key, self.first, self.line = key, first, line

    def message(self, what: str) -> str:
        if self.line is None:
            return f"{what}: key '{self.key}' given twice in one object; give each key once"
        return (f"{what}: line {self.line}: key '{self.key}' given twice (first at line "
                f"{self.first}); give each key once")


_MERGE_TAG = "tag:yaml.org,2002:merge"


class _SafeLoader(yaml.SafeLoader, Yaml12Floats):
    """``yaml.safe_load`` with :class:`Yaml12Floats`; a key given twice in one mapping is
    refused (:class:`_KeyTwice`) where PyYAML would keep the last one silently. Keys merged
    in with ``<<`` may still be overridden, as YAML means them to be."""

    def construct_mapping(self, node, deep=False):
        if isinstance(node, yaml.MappingNode):
            seen: dict[tuple[str, str], int] = {}
            for key_node, _ in node.value:
                if not isinstance(key_node, yaml.ScalarNode) or key_node.tag == _MERGE_TAG:
                    continue
                line = key_node.start_mark.line + 1
                key = (key_node.tag, key_node.value)
                if key in seen:
                    raise _KeyTwice(key_node.value, seen[key], line)
                seen[key] = line
        return super().construct_mapping(node, deep=deep)

    def construct_yaml_int(self, node):
        """An integer as YAML 1.2 reads it (:func:`yaml12_int`), else as PyYAML does; YAML
        1.1's base 60 (``1:30``, 90) is text, as YAML 1.2 reads it."""
        if ":" in str(node.value):
            return str(node.value)
        value = yaml12_int(str(node.value))
        return super().construct_yaml_int(node) if value is None else value

    def construct_yaml_float(self, node):
        """YAML 1.1's base-60 float (``1:30.5``, 90.5) is text, as YAML 1.2 reads it."""
        text = str(node.value)
        return text if ":" in text else super().construct_yaml_float(node)


_SafeLoader.add_constructor("tag:yaml.org,2002:int", _SafeLoader.construct_yaml_int)
_SafeLoader.add_constructor("tag:yaml.org,2002:float", _SafeLoader.construct_yaml_float)


def _json_pairs(pairs: list[tuple[str, Any]]) -> dict:
    out = dict(pairs)
    if len(out) != len(pairs):
        seen: set[str] = set()
        raise _KeyTwice(next(k for k, _ in pairs if k in seen or seen.add(k)))
    return out


def load_mapping(path: str | Path) -> dict:
    """Read a YAML or JSON file into a mapping, with a one-line error on failure (text
    encodings: :func:`beltstudy.engine.textfile.read_text`; a key given twice in one mapping
    is an error)."""
    p = Path(path)
    text = read_text(p)
    try:
        data = (json.loads(text, object_pairs_hook=_json_pairs) if p.suffix.lower() == ".json"
                else yaml.load(text, _SafeLoader))  # noqa: S506
    except _KeyTwice as exc:
        raise InputError(exc.message(str(p))) from None
    except (yaml.YAMLError, json.JSONDecodeError) as exc:
        first = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        mark = getattr(exc, "problem_mark", None)
        where = f" at line {mark.line + 1}, column {mark.column + 1}" if mark else ""
        raise InputError(f"{p}: not valid YAML/JSON{where}: {first}") from None
    if not isinstance(data, dict):
        raise InputError(f"{p}: expected a mapping of keys at the top level")
    return data


def json_numbers(value: Any) -> Any:
    """``value`` with its integral numbers written as integers, as JSON Schema counts them
    (``12.0`` is the integer 12): those from 1 to 2**53 in size (0 keeps its sign, a larger
    number is meant as a float). Integers are integers by value, whatever their notation."""
    if isinstance(value, float) and value.is_integer() and 1 <= abs(value) <= 2**53:
        return int(value)
    if isinstance(value, dict):
        return {k: json_numbers(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [json_numbers(v) for v in value]
    return value


def strict_validate(model: type[BaseModel], data: Any) -> BaseModel:
    """The one strict path of every input (files, JSON and YAML bodies, study axes): ``data``
    validated as JSON with JSON's types exactly, so ``"4.5"`` is no number and ``true`` no
    number either, wherever it comes from; integral numbers as integers
    (:func:`json_numbers`). Raises :class:`ValidationError`."""
    try:
        text = json.dumps(json_numbers(data), default=str, allow_nan=True)
    except (TypeError, ValueError) as exc:
        raise InputError(f"not JSON data: {exc}") from None
    return model.model_validate_json(text, strict=True)


def parse_conveyor(data: dict, prefix: str = "", *, strict: bool = True) -> Conveyor:
    """Validate a mapping as a :class:`Conveyor` (strictly: :func:`strict_validate`); raise
    :class:`InputError` on problems. ``strict=False`` is for data whose types were held to
    JSON's already (a study's variants, built at the door from checked values): Pydantic's
    own validation, without the JSON round trip."""
    from beltstudy.engine import catalog

    try:
        conv = strict_validate(Conveyor, data) if strict else Conveyor.model_validate(data)
    except ValidationError as exc:
        raise InputError(format_validation_error(exc, Conveyor, prefix)) from None
    catalog.check_conveyor(conv, prefix)
    _check_whole(conv, prefix)
    return conv


#: Top-level conveyor fields the catalogue check and the fill read.
_CATALOGUE_FIELDS = frozenset({"belt", "idlers", "material", "profile", "speed_m_s"})


def conveyor_variant(base: Conveyor, base_data: dict, changed: dict[str, Any],
                     prefix: str = "") -> tuple[Conveyor, dict]:
    """``base`` with some top-level fields replaced, validated, and its dumped mapping.

    ``changed`` maps top-level keys (as in the file) to their new (dumped) values; ``base_data``
    is ``base`` dumped (``model_dump(mode="json", by_alias=True)``). Only the changed fields are
    validated again, the others are ``base``'s own validated parts (Pydantic takes a model
    instance as it is); the conveyor's own checks (its model validators, the catalogue and
    the fill) run on the whole. The same conveyor as :func:`parse_conveyor` of the whole
    mapping gives, at a fraction of the cost for a study's many variants.
    """
    from beltstudy.engine import catalog

    names = {(f.alias or n): n for n, f in Conveyor.model_fields.items()}
    data = {n: getattr(base, n) for n in Conveyor.model_fields}
    for key, value in changed.items():
        data[names.get(key, key)] = value
    try:
        conv = Conveyor.model_validate(data)
    except ValidationError as exc:
        raise InputError(format_validation_error(exc, Conveyor, prefix)) from None
    if _CATALOGUE_FIELDS & {names.get(k, k) for k in changed}:
        catalog.check_conveyor(conv, prefix)
        _check_whole(conv, prefix)
    fields = {names.get(k, k) for k in changed}
    dumped = {**base_data, **conv.model_dump(mode="json", by_alias=True, include=fields)}
    return conv, dumped


#: Checks of a whole conveyor that need more than its model (``fn(conv, prefix)``, raising
#: :class:`InputError`): registered by the module that holds what they need (the fill:
#: :mod:`beltstudy.engine.capacity`), so this module imports none of them; run by
#: :func:`parse_conveyor` and :func:`conveyor_variant`.
WHOLE_CHECKS: list = []


def register_check(check) -> None:
    """Run ``check(conv, prefix)`` on every conveyor parsed (once per function)."""
    if check not in WHOLE_CHECKS:
        WHOLE_CHECKS.append(check)


def _check_whole(conv: Conveyor, prefix: str = "") -> None:
    for check in WHOLE_CHECKS:
        check(conv, prefix)


def _beside_the_wrapper(key: str, prefix: str) -> str:
    """The problem of a key beside a scenario file's ``scenario:`` mapping."""
    both = ("a scenario file holds its fields under 'scenario:' or at the top level, not "
            "both")
    if key in Scenario.model_fields:
        return (f"{prefix}{key}: a scenario field outside the 'scenario:' mapping ({both}; "
                f"move {key} into scenario:)")
    return (f"{prefix}{key}: unknown key beside the 'scenario:' mapping ({both}; drop it; "
            f"valid keys under scenario: {', '.join(Scenario.model_fields)})")


def scenario_fields(data: dict, prefix: str = "") -> tuple[dict, str]:
    """A scenario mapping with a top-level ``scenario:`` key taken off (the prefix then gains
    ``scenario.``); that key holding no mapping is an :class:`InputError` saying so."""
    if "scenario" not in data:
        return data, prefix
    if set(data) != {"scenario"} and isinstance(data["scenario"], dict):
        # 'scenario: {...}' and a stray key beside it: the stray key is the fault, not the
        # wrapper (it was told 'scenario.scenario: unknown key', to drop a valid wrapper)
        raise InputError("; ".join(_beside_the_wrapper(k, prefix) for k in data
                                   if k != "scenario"))
    if set(data) != {"scenario"}:
        return data, prefix
    if not isinstance(data["scenario"], dict):
        got = "nothing" if data["scenario"] is None else type(data["scenario"]).__name__
        raise InputError(f"{prefix}scenario: expected a mapping of its fields (start, stop, "
                         f"run_s, ...), got {got}")
    return data["scenario"], prefix + "scenario."


def parse_scenario(data: dict, prefix: str = "", *, strict: bool = True) -> Scenario:
    """Validate a mapping as a :class:`Scenario` (accepts a top-level ``scenario:`` key,
    :func:`scenario_fields`); ``strict``: as in :func:`parse_conveyor`."""
    data, prefix = scenario_fields(data, prefix)
    try:
        return strict_validate(Scenario, data) if strict else Scenario.model_validate(data)
    except ValidationError as exc:
        raise InputError(format_validation_error(exc, Scenario, prefix)) from None


def load_conveyor(path: str | Path) -> Conveyor:
    """Load a conveyor file (YAML or JSON); its problems name the file first
    (``c.yaml: speed_m_s: ...``)."""
    return parse_conveyor(load_mapping(path), prefix=f"{path}: ")
