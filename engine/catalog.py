"""Belt, idler and compound catalogues shipped as CSV files in ``engine/data``.

Every row names its source in the file (or says it is an estimate). Unknown ids raise an
:class:`~beltstudy.engine.errors.InputError` listing the valid ids and the nearest one.
"""

from __future__ import annotations

import csv
import difflib
import re
from dataclasses import dataclass
from functools import cache
from importlib import resources

from beltstudy.engine.errors import InputError
from beltstudy.engine.wording import gnum

__all__ = [
    "BeltData",
    "ResolvedBelt",
    "IdlerData",
    "belts",
    "belt",
    "idlers",
    "idler",
    "compounds",
    "resolve_belt",
    "idler_set_values",
    "idler_note",
    "check_conveyor",
    "COVER_MASS_KG_M2_PER_MM",
    "AUTO",
    "KIND_OF_FILE",
    "FILE_KIND",
]

#: Cover rubber mass per square metre per mm of thickness [kg/m2/mm] (PHYSICS section 4).
COVER_MASS_KG_M2_PER_MM = 1.15
#: ``belt.type`` that picks the belt (:mod:`beltstudy.engine.beltselect`).
AUTO = "auto"
#: ``belt.kind`` of the conveyor file -> the catalogue's ``kind`` column, and back.
KIND_OF_FILE = {"steel_cord": "steel", "fabric": "fabric"}
FILE_KIND = {v: k for k, v in KIND_OF_FILE.items()}


def _rows(name: str) -> list[dict[str, str]]:
    text = resources.files("beltstudy.engine").joinpath("data", name).read_text(encoding="utf-8")
    lines = [ln for ln in text.splitlines() if ln.strip() and not ln.startswith("#")]
    return list(csv.DictReader(lines))


def _unknown(kind: str, value: str, valid: list[str], field: str = "") -> str:
    close = difflib.get_close_matches(str(value), valid, n=1, cutoff=0.4)
    hint = f"; did you mean '{close[0]}'?" if close else ""
    where = f"{field}: " if field else ""
    return f"{where}unknown {kind} '{value}'{hint}{' ' if hint else '; '}valid: {', '.join(valid)}"


@dataclass(frozen=True)
class BeltData:
    """One catalogue belt. Units in the names."""

    id: str
    kind: str
    rating_kn_m: float
    modulus_kn_m: float
    dynamic_modulus_kn_m: float
    carcass_mass_kg_m2: float
    top_cover_mm: float
    bottom_cover_mm: float
    source: str


#: Dynamic over static modulus by belt kind, for belts without a catalogue row (the
#: catalogue's own ratios: ``engine/data/belts.csv``, source [DYN]).
DYNAMIC_RATIO = {"steel": 1.1, "fabric": 1.5}
#: Relaxation time of the belt from its dynamic to its static modulus [s] (an estimate; PHYSICS
#: section 5.1). It puts the relaxing arm's loss peak near 0.16 Hz, among a conveyor's low
#: modes (take-up bounce, the loop's first modes), where belt hysteresis is what damps them;
#: wave fronts (well under a second) see the dynamic modulus, settling (minutes) the static.
RELAXATION_S = 1.0


@dataclass(frozen=True)
class ResolvedBelt:
    """A belt after applying the conveyor file's overrides to the catalogue values."""

    id: str
    kind: str
    width_m: float
    rating_kn_m: float
    modulus_kn_m: float
    carcass_mass_kg_m2: float
    top_cover_mm: float
    bottom_cover_mm: float
    compound: str
    dynamic_modulus_kn_m: float = 0.0
    #: m'_G as the conveyor file gives it (``belt.mass_kg_m``) [kg/m]; 0: from carcass and covers
    given_mass_kg_m: float = 0.0

    @property
    def dynamic_stiffness_n(self) -> float:
        """Dynamic axial stiffness E_dyn B [N]: the modulus of wave fronts (SPEC 6.1)."""
        return self.dynamic_modulus_kn_m * 1e3 * self.width_m

    @property
    def relaxation_s(self) -> float:
        """Relaxation time from the dynamic to the static modulus [s] (estimate)."""
        return RELAXATION_S

    @property
    def mass_kg_m(self) -> float:
        """Belt mass per metre m'_G [kg/m]: the file's ``belt.mass_kg_m``, else (carcass +
        covers) x width."""
        if self.given_mass_kg_m > 0.0:
            return self.given_mass_kg_m
        covers = (self.top_cover_mm + self.bottom_cover_mm) * COVER_MASS_KG_M2_PER_MM
        return (self.carcass_mass_kg_m2 + covers) * self.width_m

    @property
    def stiffness_n(self) -> float:
        """Axial stiffness E B [N] (tension per unit strain)."""
        return self.modulus_kn_m * 1e3 * self.width_m

    @property
    def rating_n(self) -> float:
        """Breaking force rating x width [N]."""
        return self.rating_kn_m * 1e3 * self.width_m

    @property
    def thickness_m(self) -> float:
        """Approximate belt thickness [m]: covers plus a carcass of 1 mm per 1.2 kg/m2."""
        return (self.top_cover_mm + self.bottom_cover_mm + self.carcass_mass_kg_m2 / 1.2) * 1e-3


@dataclass(frozen=True)
class IdlerData:
    roll_diameter_m: float
    cema_class: str
    rotating_mass_kg_m: float
    seal_drag_n: float
    source: str


@cache
def belts() -> dict[str, BeltData]:
    """All catalogue belts by id."""
    out = {}
    for r in _rows("belts.csv"):
        out[r["id"]] = BeltData(
            id=r["id"],
            kind=r["kind"],
            rating_kn_m=float(r["rating_kn_m"]),
            modulus_kn_m=float(r["modulus_kn_m"]),
            dynamic_modulus_kn_m=float(r["dynamic_modulus_kn_m"]),
            carcass_mass_kg_m2=float(r["carcass_mass_kg_m2"]),
            top_cover_mm=float(r["top_cover_mm"]),
            bottom_cover_mm=float(r["bottom_cover_mm"]),
            source=r["source"],
        )
    return out


#: A belt id followed by its covers as belt makers print them, top + bottom in mm.
_COVERS = re.compile(r"^\s*(.*?)\s+(\d+(?:\.\d+)?)\s*\+\s*(\d+(?:\.\d+)?)\s*$")


def _belt_key(belt_id: str) -> str:
    """A belt id as handbooks vary its spelling (``St 1600``, ``ST-1600``, ``EP 630/4``,
    ``EP630-4``) reduced to the catalogue's form (``ST1600``, ``EP630/4``)."""
    text = str(belt_id).upper().replace(" ", "").replace("_", "")
    head, sep, tail = text.partition("-")
    if head[:2] == "ST" and not head[2:]:  # ST-1600
        return head + tail
    return head + ("/" + tail if sep else "")  # EP630-4


def belt(belt_id: str, field: str = "belt.type") -> BeltData:
    """The catalogue belt ``belt_id``. An id the catalogue does not hold is refused; the fix
    offered is the same belt spelled as the catalogue spells it, never a belt of another
    rating (EP500/3 is not EP400/3), else the belt given by its own data."""
    table = belts()
    if belt_id in table:
        return table[belt_id]
    where = f"{field}: " if field else ""
    covers = _COVERS.match(str(belt_id))  # EP630/4 5+2: the carcass, then top + bottom covers
    named = covers.group(1) if covers else belt_id
    same = [k for k in table if _belt_key(k) == _belt_key(named)]
    if same:
        extra = (f" with top_cover_mm: {covers.group(2)} and bottom_cover_mm: "
                 f"{covers.group(3)}" if covers else "")
        raise InputError(f"{where}unknown belt type '{belt_id}'; did you mean "
                         f"'{same[0]}'{extra}? valid: {', '.join(table)}")
    # a fabric belt's rating without its plies (EP630 for EP630/4): the catalogue's ply counts
    plies = [k for k in table if "/" in k and _belt_key(k.split("/")[0]) == _belt_key(named)]
    if plies:
        raise InputError(
            f"{where}unknown belt type '{belt_id}': a fabric belt's type names its plies too; "
            f"did you mean {' or '.join(repr(k) for k in plies)}? valid: {', '.join(table)}")
    raise InputError(
        f"{where}unknown belt type '{belt_id}': not in the catalogue ({', '.join(table)}); "
        "for a belt of its own, leave out type and give its data from the belt maker's "
        "sheet: rating_kn_m, modulus_kn_m, carcass_mass_kg_m2 (or mass_kg_m), top_cover_mm "
        "and bottom_cover_mm, or pick a "
        "catalogue belt of at least the rating you need")


@cache
def idlers() -> list[IdlerData]:
    return [
        IdlerData(
            roll_diameter_m=float(r["roll_diameter_m"]),
            cema_class=r["cema_class"],
            rotating_mass_kg_m=float(r["rotating_mass_kg_m"]),
            seal_drag_n=float(r["seal_drag_n"]),
            source=r["source"],
        )
        for r in _rows("idlers.csv")
    ]


#: Relative tolerance within which a roll diameter is a catalogue row's [-] (a file's 0.1524 m
#: for 6 in is the 0.152 m row).
DIAMETER_RTOL = 0.005


def _row_at(rows: list[IdlerData], roll_diameter_m: float) -> IdlerData | None:
    return next((r for r in rows if abs(r.roll_diameter_m - roll_diameter_m)
                 <= DIAMETER_RTOL * r.roll_diameter_m), None)


def _check_class(cema_class: str, field: str) -> None:
    classes = sorted({r.cema_class for r in idlers()})
    if cema_class not in classes:
        raise InputError(_unknown("CEMA idler class", cema_class, classes, field + "cema_class"))


def idler(roll_diameter_m: float, cema_class: str | None = None, field: str = "") -> IdlerData:
    """The catalogue idler of the roll diameter (and of the class, when given; without one,
    the first class of the file, the lightest, that holds the diameter).

    A diameter between two rows of a class is interpolated between them, on a physical basis
    for each column: the rotating mass is mostly the roll's steel shell, pi D t L rho, linear
    in D (at the wall interpolated between the rows), so the mass is linear in D; the seal
    drag A_i is the seals' friction torque over the roll's radius (the CEMA A_i of the rows,
    A_i D = 1.02 to 1.04 N m for 4, 5 and 6 in class C rolls), so A_i D is linear in D. The
    row's ``source`` says so; :func:`idler_note` words it for the run's message. A diameter
    beyond the class's rows (without a class, beyond the catalogue's) is the nearest row's
    roll scaled on the same basis: mass times D / D_row (its wall), A_i times D_row / D (its
    seals' torque), said the same way.
    """
    rows = idlers()
    if cema_class is not None:
        _check_class(cema_class, field)
        groups = [[r for r in rows if r.cema_class == cema_class]]
    else:
        order = list(dict.fromkeys(r.cema_class for r in rows))
        groups = [[r for r in rows if r.cema_class == c] for c in order]
    for group in groups:  # the exact row first, in file order
        row = _row_at(group, roll_diameter_m)
        if row is not None:
            return row
    for group in groups:
        below = [r for r in group if r.roll_diameter_m < roll_diameter_m]
        above = [r for r in group if r.roll_diameter_m > roll_diameter_m]
        if below and above:
            lo = max(below, key=lambda r: r.roll_diameter_m)
            hi = min(above, key=lambda r: r.roll_diameter_m)
            w = (roll_diameter_m - lo.roll_diameter_m) / (hi.roll_diameter_m - lo.roll_diameter_m)
            torque = ((1 - w) * lo.seal_drag_n * lo.roll_diameter_m
                      + w * hi.seal_drag_n * hi.roll_diameter_m)
            return IdlerData(
                roll_diameter_m=float(roll_diameter_m), cema_class=lo.cema_class,
                rotating_mass_kg_m=(1 - w) * lo.rotating_mass_kg_m + w * hi.rotating_mass_kg_m,
                seal_drag_n=torque / roll_diameter_m,
                source=(f"interpolated between the class {lo.cema_class} rows of "
                        f"{lo.roll_diameter_m:g} m and {hi.roll_diameter_m:g} m"))
    # beyond the class's rows (or, without a class, the catalogue's): the nearest row's roll
    # scaled to the diameter, its shell's mass linear in D at its wall (mass ~ D) and its
    # seals' torque kept (A_i ~ 1 / D)
    held = sorted({r.roll_diameter_m for g in groups for r in g})
    near = min((r for g in groups for r in g),
               key=lambda r: abs(r.roll_diameter_m - roll_diameter_m))
    k = roll_diameter_m / near.roll_diameter_m
    return IdlerData(
        roll_diameter_m=float(roll_diameter_m), cema_class=near.cema_class,
        rotating_mass_kg_m=near.rotating_mass_kg_m * k, seal_drag_n=near.seal_drag_n / k,
        source=(f"scaled from the class {near.cema_class} row of {near.roll_diameter_m:g} m, "
                f"beyond the {'class' if cema_class else 'catalogue'}'s rolls "
                f"({', '.join(f'{d:g}' for d in held)} m)"))


def _needs_catalogue(idler_set) -> bool:
    return idler_set.set_rotating_mass_kg is None or idler_set.seal_drag_n is None


#: Spread of a column over the classes that hold a roll diameter beyond which the class the
#: catalogue takes for a set without ``cema_class`` (the file's first, the lightest) is said
#: [-]: (largest - smallest) / the value taken. Every diameter held by two classes in
#: engine/data/idlers.csv differs by more (0.152 m: mass 17 to 20 kg/m, A_i 6.7 to 12.5 N).
CLASS_SPREAD_NOTE = 0.05


def _class_note(idler_set, row: IdlerData, width_m: float, field: str) -> str:
    """The note of a set without a ``cema_class`` at a catalogue diameter several classes
    hold, when the values it reads differ by more than :data:`CLASS_SPREAD_NOTE` between them:
    the class taken, the classes' range and the fields that give the set's own."""
    rows = [r for c in dict.fromkeys(r.cema_class for r in idlers())
            if (r := _row_at([x for x in idlers() if x.cema_class == c],
                             idler_set.roll_diameter_m)) is not None]
    cols = []  # (column, words with the value taken, unit of the classes' range)
    if idler_set.set_rotating_mass_kg is None:
        cols.append(("rotating_mass_kg_m", f"rotating mass {gnum(row.rotating_mass_kg_m * width_m, 3)}"
                     f" kg a set ({gnum(row.rotating_mass_kg_m, 3)} kg per m of belt width", "kg/m"))
    if idler_set.seal_drag_n is None:
        cols.append(("seal_drag_n", f"seal drag {gnum(row.seal_drag_n, 3)} N a set (", "N"))
    said, differ = [], False
    for col, taken, unit in cols:
        values = [getattr(r, col) for r in rows]
        differ |= max(values) - min(values) > CLASS_SPREAD_NOTE * getattr(row, col)
        sep = "; " if taken.endswith("width") else ""
        said.append(f"{taken}{sep}{gnum(min(values), 3)} to {gnum(max(values), 3)} {unit} over the "
                    "classes)")
    if not differ:
        return ""
    return (f"note: {field}.cema_class is not given: the {idler_set.roll_diameter_m:g} m roll "
            f"is read as class {row.cema_class}, the lightest of {', '.join(r.cema_class for r in rows)} "
            f"(engine/data/idlers.csv): {' and '.join(said)}; {field}.cema_class, or the roll "
            f"maker's rotating_mass_kg and seal_drag_n, give the set's own")


def idler_note(idler_set, width_m: float, field: str) -> str:
    """The note of an idler set whose rotating mass or seal drag is interpolated between two
    catalogue rows (:func:`idler`): the diameter given, the rows used and the values taken,
    and how to give the set's own; or, without a ``cema_class`` at a diameter several classes
    hold with values that differ (:func:`_class_note`), the class taken. "" when the set's
    diameter is a row's (of its class, or of the only class there) or the set gives both
    values itself."""
    if not _needs_catalogue(idler_set):
        return ""
    row = idler(idler_set.roll_diameter_m, idler_set.cema_class, field + ".")
    if not row.source.startswith(("interpolated", "scaled")):
        return "" if idler_set.cema_class else _class_note(idler_set, row, width_m, field)
    took = []
    if idler_set.set_rotating_mass_kg is None:
        took.append(f"rotating mass {gnum(row.rotating_mass_kg_m * width_m, 3)} kg a set "
                    f"({gnum(row.rotating_mass_kg_m, 3)} kg per m of belt width, the shell's "
                    "mass linear in D)")
    if idler_set.seal_drag_n is None:
        took.append(f"seal drag {gnum(row.seal_drag_n, 3)} N a set (the seals' torque A_i D "
                    "linear in D)")
    return (f"note: {field}.roll_diameter_m {idler_set.roll_diameter_m:g} m is no catalogue "
            f"row: {' and '.join(took)} {row.source} (engine/data/idlers.csv), "
            f"{field}.rotating_mass_kg (or rotating_mass_per_roll_kg) and seal_drag_n give "
            "the roll maker's values")


def idler_set_values(idler_set, width_m: float) -> tuple[float, float]:
    """Rotating mass [kg] and seal drag [N] of an idler set, catalogue filling gaps (a
    diameter between two rows interpolated: :func:`idler`)."""
    mass = idler_set.set_rotating_mass_kg  # per set, or per roll x rolls
    drag = idler_set.seal_drag_n
    if mass is None or drag is None:
        row = idler(idler_set.roll_diameter_m, idler_set.cema_class)
        if mass is None:
            mass = row.rotating_mass_kg_m * width_m
        if drag is None:
            drag = row.seal_drag_n
    return float(mass), float(drag)


@cache
def compounds() -> dict[str, dict[str, str]]:
    return {r["id"]: r for r in _rows("compounds.csv")}


def resolve_belt(b) -> ResolvedBelt:
    """Apply the conveyor file's belt overrides to the catalogue entry."""
    if b.type == AUTO:
        raise InputError("belt.type: auto is a choice, not a belt: pick it first "
                         "(beltstudy.engine.beltselect.resolve_auto_belt)")
    base = belt(b.type) if b.type is not None else None

    def pick(name: str) -> float:
        val = getattr(b, name)
        if val is not None:
            return float(val)
        return float(getattr(base, name))

    # a custom belt is of the kind its file says; without one, steel cord above 30 000 kN/m
    kind = (base.kind if base else KIND_OF_FILE[b.kind] if b.kind is not None else
            ("steel" if (b.modulus_kn_m or 0) > 30000 else "fabric"))
    static = pick("modulus_kn_m")
    if b.dynamic_modulus_kn_m is not None:
        dynamic = float(b.dynamic_modulus_kn_m)
    else:
        ratio = (base.dynamic_modulus_kn_m / base.modulus_kn_m) if base else DYNAMIC_RATIO[kind]
        dynamic = static * ratio
    top = pick("top_cover_mm") if (b.top_cover_mm is not None or base) else 0.0
    bottom = pick("bottom_cover_mm") if (b.bottom_cover_mm is not None or base) else 0.0
    if b.mass_kg_m is not None:
        carcass = _carcass_of_mass(float(b.mass_kg_m), float(b.width_m), top, bottom)
    else:
        carcass = pick("carcass_mass_kg_m2")
    return ResolvedBelt(
        id=b.type or "custom",
        kind=kind,
        width_m=float(b.width_m),
        rating_kn_m=pick("rating_kn_m"),
        modulus_kn_m=static,
        carcass_mass_kg_m2=carcass,
        top_cover_mm=top,
        bottom_cover_mm=bottom,
        compound=b.compound,
        dynamic_modulus_kn_m=dynamic,
        given_mass_kg_m=float(b.mass_kg_m or 0.0),
    )


def _carcass_of_mass(mass_kg_m: float, width_m: float, top_mm: float, bottom_mm: float
                     ) -> float:
    """The carcass mass per square metre a printed belt mass implies [kg/m2]:
    m'_G / B - (top + bottom cover) x 1.15 kg/m2/mm. Only the belt's thickness estimate reads
    it (m'_G itself is the printed mass). Raises InputError when the covers alone weigh more
    than the printed belt."""
    covers = (top_mm + bottom_mm) * COVER_MASS_KG_M2_PER_MM
    carcass = mass_kg_m / width_m - covers
    if carcass <= 0.0:
        raise InputError(
            f"belt.mass_kg_m: {mass_kg_m:g} kg/m is no more than the covers alone weigh "
            f"(top {top_mm:g} + bottom {bottom_mm:g} mm x {COVER_MASS_KG_M2_PER_MM} kg/m2/mm "
            f"x {width_m:g} m = {covers * width_m:.1f} kg/m): give the covers the catalogue "
            "prints (top_cover_mm, bottom_cover_mm) or check the mass")
    return carcass


def check_conveyor(conv, prefix: str = "") -> None:
    """Catalogue ids in a conveyor exist (raises InputError naming the field)."""
    if conv.belt.type is not None and conv.belt.type != AUTO:
        row = belt(conv.belt.type, prefix + "belt.type")
        if conv.belt.kind is not None and KIND_OF_FILE[conv.belt.kind] != row.kind:
            raise InputError(
                f"{prefix}belt.kind: {conv.belt.kind} does not match {row.id}, a "
                f"{FILE_KIND[row.kind]} belt in the catalogue; leave kind out or give "
                f"kind: {FILE_KIND[row.kind]}")
    if conv.belt.compound not in compounds():
        raise InputError(
            _unknown("compound", conv.belt.compound, list(compounds()), prefix + "belt.compound")
        )
    for strand in ("carry", "return_"):
        s = getattr(conv.idlers, strand)
        field = f"{prefix}idlers.{strand.rstrip('_')}."
        if _needs_catalogue(s):  # the class exists and holds the diameter (or brackets it)
            idler(s.roll_diameter_m, s.cema_class, field)
        elif s.cema_class is not None:  # the set's own values: the class alone is read
            _check_class(s.cema_class, field)
    if conv.belt.type is None and (conv.belt.top_cover_mm is None or conv.belt.bottom_cover_mm is None):
        raise InputError(
            f"{prefix}belt: a custom belt (no 'type') needs top_cover_mm and bottom_cover_mm (0 allowed)"
        )
    if conv.belt.type != AUTO and conv.belt.mass_kg_m is not None:
        try:  # the printed mass against the covers: named as the file or the body writes it
            resolve_belt(conv.belt)
        except InputError as exc:
            raise InputError(f"{prefix}{exc}") from None
    if conv.belt.type != AUTO and conv.belt.dynamic_modulus_kn_m is not None:
        b = resolve_belt(conv.belt)
        if b.dynamic_modulus_kn_m < b.modulus_kn_m:
            raise InputError(
                f"{prefix}belt.dynamic_modulus_kn_m: {b.dynamic_modulus_kn_m:g} kN/m is below the "
                f"static modulus {b.modulus_kn_m:g} kN/m; a belt's rubber and carcass stiffen "
                "under fast loading, never soften (dynamic over static about 1.1 for steel "
                "cord, 1.5 for fabric: PHYSICS 5.1), so give at least the static modulus or "
                "leave it out for the catalogue's ratio")
