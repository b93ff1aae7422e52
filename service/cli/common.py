"""Helpers shared by the CLI sub-commands (argument parsing, output)."""

from __future__ import annotations

import dataclasses
import json
import math
import os
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from beltstudy.engine import LOAD_MAX, InputError, get_model, parse_scenario, section_loads
from beltstudy.engine.drives import GIVEN
from beltstudy.engine.friction import canonical_name
from beltstudy.service.errors import file_reason, shown_path
from beltstudy.service.settings import data_dir_setting

LOAD_HELP = ("full, empty, inclines, declines, a fraction of the design load up to 1.3 (a "
             "surge above 1), or one fraction per carry profile section: 1,0,0.5")
ELEMENTS_HELP = ("belt elements round the loop, at least 8, or auto (default: auto, the "
                 "engine's count)")


def _auto_or(number, text: str, fix: str) -> int | float | str:
    """``auto``, or ``text`` read by ``number`` (an :class:`argparse.ArgumentTypeError` with
    ``fix`` where it is neither)."""
    import argparse

    if text.strip().lower() == "auto":
        return "auto"
    try:
        return number(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not {fix}, or auto") from None


def elements_option(text: str) -> int | str:
    """``--elements``: a whole number of elements, or ``auto`` (the engine's count; on
    ``simulate`` it overrides a scenario file's fixed count). The scenario's own checks
    judge the number (at least 8)."""
    return _auto_or(int, text, "a whole number of elements: give one such as 400")


def step_option(text: str) -> float | str:
    """``--dt-s``: a time step in seconds, or ``auto`` (half the stability limit; on
    ``simulate`` it overrides a scenario file's fixed step)."""
    return _auto_or(float, text, "a time step in seconds: give one such as 0.002")


def auto_elements(value: int | str | None) -> int | None:
    """An ``--elements`` value for the steady commands: None for auto (the engine's)."""
    return None if value == "auto" else value


def model_option(name: str, option: str = "--model"):
    """The friction model an option names, an unknown name refused naming the option (not
    the result column ``friction_model``)."""
    from beltstudy.engine import InputError

    try:
        return get_model(name)
    except InputError as exc:
        raise InputError(exc.reason, field=option) from None


def parse_load(text: str) -> str | float | list[float]:
    """A load case (SPEC 6.2) from the command line: a name, a fraction or a comma list.

    The value is checked by the same scenario model as scenario files and studies
    (:func:`check_scenario_fields`)."""
    text = text.strip()
    if text in ("full", "empty", "inclines", "declines"):
        return text
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        raise InputError(f"--load: expected {LOAD_HELP}; got {text!r}") from None
    for val in values:
        if not 0.0 <= val <= LOAD_MAX:
            # from twice the design load, as the conveyor's own check reads a per cent (1.3
            # to 2 is a surge past the largest: 1.5 read "0.015 if 1.5 is %")
            pct = (f": {val / 100:g} if {val:g} is %" if 2.0 <= val <= 100.0 * LOAD_MAX
                   else "")
            raise InputError(f"--load: fractions run from 0 to {LOAD_MAX:g} of the design load "
                             f"(got {val:g}){pct}")
    return values if "," in text else values[0]


def check_scenario_fields(conveyor=None, **fields):
    """Validate command-line scenario fields with the scenario model (one set of bounds for
    ``static``, ``simulate``, ``sweep-temperature`` and studies); the error names the option.
    With ``conveyor``, a load given per section must match its profile."""

    given = {k: v for k, v in fields.items() if v is not None}
    try:
        scn = parse_scenario(given, prefix="")
        if conveyor is not None:
            section_loads(scn.load, conveyor)
        return scn
    except InputError as exc:
        text = str(exc)
        for key in given:
            text = text.replace(f"scenario.{key}:", f"{key}:", 1)
            text = text.replace(f"{key}:", f"--{key.replace('_', '-')}:", 1)
        raise InputError(text) from None


def read_conveyor(path: str | os.PathLike):
    """A conveyor file as the door reads it (:func:`beltstudy.service.door.parse.load_mapping`:
    size, depth and alias limits, finite numbers, every key once), then parsed; a file the door
    refuses is an :class:`~beltstudy.service.errors.Invalid` naming it, a value of the wrong
    type gets its fix (:func:`~beltstudy.service.door.messages.with_type_fixes`)."""
    from beltstudy.engine import Conveyor, parse_conveyor
    from beltstudy.service.door.messages import with_type_fixes
    from beltstudy.service.door.parse import expect_kind, load_mapping

    data = load_mapping(path)
    expect_kind(data, "conveyor", str(path))
    try:
        return parse_conveyor(data, prefix=f"{path}: ")
    except InputError as exc:  # a wrong type with its fix, as the study door says it
        raise InputError(with_type_fixes(str(exc), data, Conveyor, f"{path}: ")) from None


def with_sag_at_rest(conv, on: bool | None):
    """The conveyor with ``takeup.sag_at_rest`` set by the CLI switch ``--no-sag-at-rest``
    (``on`` False); ``None`` (no switch) keeps the file's own ``takeup.sag_at_rest``."""
    if on is None or conv.takeup.sag_at_rest == on:
        return conv
    return conv.model_copy(update={"takeup": conv.takeup.model_copy(update={"sag_at_rest": on})})


def drives_given(conv) -> list[bool]:
    """Per drive (file order): whether the conveyor file gives its ``rated_power_kw`` (omitted
    or ``auto`` is an auto size)."""
    return [d.rated_power_kw is not None for d in conv.drives]


def drive_governed(joined: str | None, given: bool | None) -> str | None:
    """What set one drive's rated power, from the run's ``rated_power_governed_by`` (the
    drives' constraints joined by ``+``, e.g. ``given+peripheral_force``) and whether the file
    gives that drive's ``rated_power_kw`` (None: not known, the joined text as it is)."""
    if not joined or given is None:
        return joined
    if given:
        return GIVEN
    auto = [part for part in joined.split("+") if part != GIVEN]
    return "+".join(auto) or joined


def design_lines(s: dict, indent: str = "  ", drives_given: list[bool] | None = None
                 ) -> list[str]:
    """Where the run's sizes came from: each size with its governing constraint, then the
    capacity check. ``drives_given``: per drive (file order), whether the conveyor file gives
    its ``rated_power_kw``; each drive's row then names its own constraint (``given``, or what
    set its auto size) instead of the drives' joined ``rated_power_governed_by``."""
    rows = []
    if s.get("takeup_mass_kg") is not None:
        rows.append(("take-up mass", s["takeup_mass_kg"], "kg", s.get("takeup_governed_by")))
    rows.append(("take-up tension per strand", s.get("takeup_pretension_kn"), "kN",
                 None if s.get("takeup_mass_kg") is not None else s.get("takeup_governed_by")))
    i = 1
    while f"drive{i}_rated_power_kw" in s:
        given = (drives_given[i - 1] if drives_given is not None and i <= len(drives_given)
                 else None)
        rows.append((f"rated power, drive {i}", s[f"drive{i}_rated_power_kw"], "kW",
                     drive_governed(s.get("rated_power_governed_by"), given)))
        i += 1
    if s.get("brake_force_kn") is not None:
        rows.append(("brake force (all brakes)", s["brake_force_kn"], "kN",
                     s.get("brake_governed_by")))
    lines = [f"{indent}sizes and what set them"]
    for label, value, unit, why in rows:
        if value is None:
            continue
        tail = f"  {why}" if why else ""
        lines.append(f"{indent}  {label:<36} {value:>12.3f} {unit:<3}{tail}".rstrip())
    if s.get("fill_pct") is not None:
        lines.append(f"{indent}  {'fill (design flow / cross-section)':<36} "
                     f"{s['fill_pct']:>12.1f} %")
    return lines


def parse_params(items: list[str] | None, model: str | None = None) -> dict[str, Any]:
    """``NAME=VALUE`` pairs into a dict. With ``model`` given, names may be prefixed
    ``MODEL.NAME`` with that model's name in any case or an alias of it (``iso5048.f_carry``
    for din); a prefix naming another model is refused, as is a name given twice (neither
    would be read). Values are numbers."""
    out: dict[str, Any] = {}
    given: dict[str, str] = {}
    for item in items or []:
        if "=" not in item:
            raise InputError(f"--param {item!r}: expected NAME=VALUE, e.g. f_carry=0.010")
        name, _, value = item.partition("=")
        name = name.strip()
        if "." in name:
            prefix, _, name = name.partition(".")
            if model is not None:
                named = model_option(prefix.strip(), f"--param {item!r}").name
                runs = canonical_name(model)
                if named != runs:
                    own = [f.name for f in dataclasses.fields(get_model(runs).params_class)]
                    fix = (f"give {name}=VALUE for {runs}, or --model {named}" if name in own
                           else f"--model {named} ({runs} has no {name}; its parameters: "
                                f"{', '.join(own)})")
                    raise InputError(
                        f"--param {item!r}: sets a parameter of model {named}, but this run "
                        f"uses {runs} (--model) and would not read it: {fix}")
        if name in given:
            raise InputError(f"--param {item!r}: {name} is already set by --param "
                             f"{given[name]!r}; give each parameter once")
        given[name] = item
        try:
            out[name] = float(value)
        except ValueError:
            raise InputError(f"--param {item!r}: the value must be a number") from None
    return out


def parse_model_params(items: list[str] | None) -> dict[str, dict[str, float]]:
    """``MODEL.NAME=VALUE`` pairs into ``{model: {name: value}}``, the model by its
    registry name (aliases and case folded: ``ISO5048.f_carry`` is din's); a parameter given
    twice is refused (the later would silently win)."""
    out: dict[str, dict[str, float]] = {}
    given: dict[tuple[str, str], str] = {}
    for item in items or []:
        if "=" not in item or "." not in item.partition("=")[0]:
            raise InputError(f"--param {item!r}: expected MODEL.NAME=VALUE, e.g. din.f_carry=0.010")
        key, _, value = item.partition("=")
        model, _, name = key.partition(".")
        model, name = canonical_name(model.strip()), name.strip()
        if (model, name) in given:
            raise InputError(f"--param {item!r}: {model}.{name} is already set by --param "
                             f"{given[model, name]!r}; give each parameter once")
        given[model, name] = item
        try:
            out.setdefault(model, {})[name] = float(value)
        except ValueError:
            raise InputError(f"--param {item!r}: the value must be a number") from None
    return out


def jsonable(obj: Any) -> Any:
    """Make numpy scalars and non-finite floats JSON-safe (NaN/inf become null)."""
    if isinstance(obj, dict):
        return {k: jsonable(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [jsonable(v) for v in obj]
    if hasattr(obj, "item") and not isinstance(obj, str):
        obj = obj.item()
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    return obj


def dumps(obj: Any) -> str:
    return json.dumps(jsonable(obj), indent=2)


#: What the store keeps in the data folder: an output path within one of these is refused.
STORE_PARTS = ("studies", "bodies", ".beltstudy.lock")


def outside_store(path: str | os.PathLike, option: str, what: str = "file") -> None:
    """Refuse an output ``path`` that resolves (symbolic links followed) into the store's own
    part of the data folder, ``BELTSTUDY_DATA_DIR`` (:data:`STORE_PARTS`: its studies, bodies
    and lock): :class:`InputError` ``OPTION PATH: inside the data folder DIR (beltstudy's
    store); write the file elsewhere``. The store's files are the service's
    own: ``results -o data/studies/<id>/study.json`` replaced the study's document with its
    runs (the study lost, GET /studies a 500), and a file dropped into ``studies/<id>/runs/``
    was read as part of the table (``pd.read_parquet`` of the folder gave 170 rows of 85)."""
    root = data_dir_setting()
    try:
        full, base = Path(path).resolve(), root.resolve()
        part = full.relative_to(base).parts if full.is_relative_to(base) else ()
    except (OSError, RuntimeError):  # a name over the limits, a symlink loop: said on writing
        return
    # the store's own: its studies, the bodies of records, its lock (a file beside them in
    # the data folder's root is the user's, as a script or a log kept there)
    if part and part[0] in STORE_PARTS:
        raise InputError(f"{option} {shown_path(path)}: inside the data folder "
                         f"{shown_path(root.resolve())} (beltstudy's store); write the {what} "
                         "elsewhere")


def check_output(path: str | os.PathLike, option: str) -> Path:
    """``path`` as an output file the command can write, checked before any work starts:
    :class:`InputError` ``cannot write PATH: the folder DIR does not exist`` (or it is a
    folder itself, or the folder is not writable), or ``OPTION PATH: inside the data folder``
    (:func:`outside_store`; ``option`` names the option that gave it: ``-o``, ``--plot``)."""
    outside_store(path, option)
    out = Path(path)
    folder = out.parent
    try:
        if out.is_dir():
            raise InputError(f"cannot write {out}: it is a folder; give a file name")
        if not folder.exists():
            raise InputError(f"cannot write {out}: the folder {folder} does not exist")
        if not folder.is_dir():
            raise InputError(f"cannot write {out}: {folder} is a file, not a folder")
    except OSError as exc:  # a name over the file system's limits, ...
        raise InputError(f"cannot write {shown_path(out)}: {file_reason(exc)}") from None
    if not os.access(folder, os.W_OK):
        raise InputError(f"cannot write {out}: no permission to write in the folder {folder}")
    return out


@contextmanager
def writing(path: str | os.PathLike):
    """Write ``path`` in the ``with`` block; an ``OSError`` (disk full, the folder gone since
    :func:`check_output`) becomes one line: ``cannot write PATH: REASON``."""
    try:
        yield Path(path)
    except OSError as exc:
        raise InputError(f"cannot write {shown_path(path)}: {file_reason(exc)}") from None


def write_table(df, path: str) -> None:
    """Write a DataFrame as CSV or Parquet by the file extension."""
    if not path.endswith((".parquet", ".csv")):
        raise InputError(f"{path}: give a .csv or .parquet file name")
    with writing(path):
        if path.endswith(".parquet"):
            df.to_parquet(path, index=False)
        else:
            df.to_csv(path, index=False)
