"""Reading studies at the door: YAML or JSON text within a size and depth budget.

A request body, a study file or a conveyor file is parsed with its limits checked while it is
parsed, before anything is expanded, copied or validated:

* nesting at most :data:`MAX_DEPTH` levels (YAML: counted while the parser builds the node
  graph, so a deep body is refused where it gets too deep; JSON: the decoder's own recursion
  guard, then the same limit on the result);
* at most :data:`MAX_VALUES` values and :data:`MAX_TEXT` characters of text once YAML aliases
  are expanded, counted on the alias graph with every anchor counted once, so an alias bomb
  of a few hundred bytes is refused without being expanded; an alias inside its own anchor
  (a cycle) is refused;
* every key once per mapping (the error names the key);
* JSON types only: text, numbers, true/false, null, lists and mappings with text keys (a YAML
  date stays text; ``!!binary``, ``!!set`` and the other tags are refused);
* numbers finite (no NaN or infinity) and of at most :data:`MAX_DIGITS` digits.

:func:`check_tree` checks the same limits on data built any other way (a Python mapping passed
to :func:`beltstudy.service.door.studyfile.resolve_study`); its errors name the path of the value
(``grid.temperature_c.1: ...``). Problems raise :class:`~beltstudy.service.errors.Invalid` (422), a body
over the size budget :class:`~beltstudy.service.errors.TooLarge` (413).
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import yaml

from beltstudy.engine.conveyor import Yaml12Floats, yaml12_int
from beltstudy.engine.errors import InputError
from beltstudy.engine.textfile import read_text
from beltstudy.service.errors import Invalid, TooLarge, file_reason

__all__ = [
    "expect_kind",
    "file_kind",
    "MAX_DEPTH",
    "MAX_VALUES",
    "MAX_TEXT",
    "MAX_DIGITS",
    "YAML_TYPES",
    "parse_body",
    "loads",
    "load_mapping",
    "check_tree",
    "tree_size",
]

#: Deepest nesting of lists and mappings (a study needs about 8).
MAX_DEPTH = 32
#: Most values (scalars, lists, mappings) in one document once aliases are expanded.
MAX_VALUES = 200_000
#: Most characters of text (keys and values) in one document once aliases are expanded.
MAX_TEXT = 4_000_000
#: Most digits of an integer (a float holds no more than 309).
MAX_DIGITS = 309
#: Content types read as YAML; everything else is read as JSON.
YAML_TYPES = ("application/yaml", "application/x-yaml", "text/yaml")


class _Huge(str):
    """An integer literal with more than :data:`MAX_DIGITS` digits (reported with its path)."""

    digits: int = 0  # decimal digits of its value


def _huge(text: str, digits: int) -> _Huge:
    out = _Huge(text)
    out.digits = digits
    return out


#: Bits of the largest integer of :data:`MAX_DIGITS` decimal digits (10**309 < 2**1027).
_MAX_BITS = math.ceil(MAX_DIGITS * math.log2(10))


class _Duplicate(dict):
    """A JSON object that had a key twice (reported with its path)."""

    duplicate: str = ""


# ------------------------------------------------------------------------------------ YAML
_MERGE = "tag:yaml.org,2002:merge"


class _Constructor(yaml.constructor.SafeConstructor):
    """PyYAML's safe constructor for JSON types only: dates stay text, other tags refused,
    integers too long for a float kept as a marker that :func:`check_tree` reports."""

    what = "body"

    def construct_yaml_int(self, node):
        """An integer by its value, whatever its notation (``0x10``, ``0o20``, ``0b10000``,
        ``1_6`` are 16; ``016`` is 16 as YAML 1.2 reads it, :func:`yaml12_int`): one of more
        than :data:`MAX_DIGITS` decimal digits is refused however it is written.
        Hexadecimal, octal and binary text is at least a quarter as long in bits, so it is
        measured before it is read."""
        text = str(node.value)
        if ":" in text:  # YAML 1.1's base 60 (1:30 is 90): text in YAML 1.2, as here
            return text
        decimal = sum(c.isdigit() for c in text)
        bare = text.lstrip("+-").replace("_", "")
        bits = {"0x": 4, "0b": 1, "0o": 3}.get(bare[:2].lower(), 0)
        if bits and ":" not in bare:
            # a text of more characters than the largest value has bits is refused unread
            chars = len(bare) - 2
            if bits * (chars - 1) > _MAX_BITS:
                return _huge(text, int(chars * bits * math.log10(2)) + 1)
            value = yaml12_int(text) if bits == 3 else super().construct_yaml_int(node)
            digits = len(str(abs(value))) if value.bit_length() <= _MAX_BITS + 8 else \
                int(value.bit_length() * math.log10(2)) + 1
            return _huge(text, digits) if digits > MAX_DIGITS else value
        if decimal > MAX_DIGITS:
            return _huge(text, decimal)
        value = yaml12_int(text)
        return super().construct_yaml_int(node) if value is None else value

    def refuse_tag(self, node):
        tag = node.tag.replace("tag:yaml.org,2002:", "!!")
        raise Invalid(
            f"{self.what}: YAML tag {tag} at line {node.start_mark.line + 1} is not allowed; "
            "use plain text, numbers, lists and mappings"
        )


    def construct_yaml_float(self, node):
        """A float as YAML 1.2 reads it: YAML 1.1's base 60 (``1:30.5``, 90.5) is text."""
        text = str(node.value)
        return text if ":" in text else super().construct_yaml_float(node)


_Constructor.yaml_constructors = dict(yaml.constructor.SafeConstructor.yaml_constructors)
_Constructor.add_constructor("tag:yaml.org,2002:int", _Constructor.construct_yaml_int)
_Constructor.add_constructor("tag:yaml.org,2002:float", _Constructor.construct_yaml_float)
_Constructor.add_constructor(
    "tag:yaml.org,2002:timestamp", yaml.constructor.SafeConstructor.construct_yaml_str
)
for _tag in ("binary", "set", "omap", "pairs"):
    _Constructor.add_constructor(f"tag:yaml.org,2002:{_tag}", _Constructor.refuse_tag)


class _PyLoader(
    yaml.reader.Reader,
    yaml.scanner.Scanner,
    yaml.parser.Parser,
    yaml.composer.Composer,
    _Constructor,
    Yaml12Floats,
):
    """PyYAML's pure-Python parser with the constructor above."""

    def __init__(self, stream: str, what: str):
        yaml.reader.Reader.__init__(self, stream)
        yaml.scanner.Scanner.__init__(self)
        yaml.parser.Parser.__init__(self)
        yaml.composer.Composer.__init__(self)
        _Constructor.__init__(self)
        Yaml12Floats.__init__(self)
        self.what = what


if yaml.__with_libyaml__:
    from yaml.cyaml import CParser

    class _CLoader(CParser, _Constructor, Yaml12Floats):
        """libyaml's parser and composer (several times faster) with the constructor above."""

        def __init__(self, stream: str, what: str):
            CParser.__init__(self, stream)
            _Constructor.__init__(self)
            Yaml12Floats.__init__(self)
            self.what = what

    _Loader: type = _CLoader
else:  # PyYAML built without libyaml
    _Loader = _PyLoader


class _Frame:
    """A list or mapping still open while the parser's events stream past."""

    __slots__ = ("path", "anchor", "mapping", "values", "text", "items", "key", "keys")

    def __init__(self, path: str, anchor: str | None, mapping: bool):
        self.path, self.anchor, self.mapping = path, anchor, mapping
        self.values, self.text = 1, 0
        self.items = 0  # children so far (a mapping's keys and values both count)
        self.key = "?"  # label of the value that comes next (mappings)
        self.keys: dict[tuple[str, str], tuple[int, int]] = {}  # (tag, text) -> line, column

    def child_path(self) -> str:
        label = self.key if self.mapping else str(self.items)
        return f"{self.path}.{label}" if self.path else label


def _check_events(loader, what: str) -> None:
    """One pass over the parser's events, before anything is composed or constructed:
    nesting depth; values and characters with every alias expanded (each anchor's size is
    recorded once, so this costs what the text costs); aliases inside their own anchor;
    duplicate anchors and keys."""
    top = _Frame("", None, False)  # holds the document
    stack = [top]
    sizes: dict[str, tuple[int, int]] = {}  # closed anchors -> (values, text)
    open_anchors: set[str] = set()

    def take(values: int, text: int) -> None:
        frame = stack[-1]
        frame.values += values
        frame.text += text
        frame.items += 1
        if frame.values > MAX_VALUES or frame.text > MAX_TEXT:
            raise TooLarge(
                f"{frame.path or what}: more than {MAX_VALUES} values or {MAX_TEXT} "
                "characters (YAML aliases expanded); "
                + ("send a smaller body" if what == "body" else "give a smaller file")
            )

    def line(event) -> int:
        return event.start_mark.line + 1

    def anchor(event) -> None:
        name = event.anchor
        if name is None:
            return
        if name in sizes or name in open_anchors:
            raise Invalid(f"{what}: anchor &{name} at line {line(event)} is defined twice")
        open_anchors.add(name)

    while loader.check_event():
        event = loader.get_event()
        frame = stack[-1]
        is_key = frame.mapping and frame.items % 2 == 0
        if isinstance(event, yaml.ScalarEvent):
            if is_key:
                tag = event.tag
                if tag is None or tag == "!":
                    tag = loader.resolve(yaml.ScalarNode, event.value, event.implicit)
                if tag != _MERGE:
                    first = frame.keys.get((tag, event.value))
                    if first is not None:
                        # two keys on one line (a flow mapping {a: 1, a: 2}): their columns
                        here = event.start_mark
                        where = (f"lines {first[0]} and {line(event)}" if first[0] != line(event)
                                 else f"line {first[0]}, columns {first[1]} and "
                                      f"{here.column + 1}")
                        raise Invalid(
                            f"{frame.path or what}: key '{event.value}' appears twice "
                            f"({where}); give each key once"
                        )
                    frame.keys[(tag, event.value)] = (line(event), event.start_mark.column + 1)
                frame.key = event.value
            anchor(event)
            if event.anchor:
                open_anchors.discard(event.anchor)
                sizes[event.anchor] = (1, len(event.value))
            take(1, len(event.value))
        elif isinstance(event, yaml.AliasEvent):
            size = sizes.get(event.anchor)
            if size is None:
                where = frame.child_path() if frame is not top else what
                if event.anchor in open_anchors:
                    raise Invalid(
                        f"{where}: the alias *{event.anchor} at line {line(event)} is inside "
                        "its own anchor; YAML aliases may not form a loop"
                    )
                raise Invalid(f"{where}: alias *{event.anchor} at line {line(event)} has no anchor")
            if is_key:
                frame.key = f"*{event.anchor}"
            take(*size)
        elif isinstance(event, yaml.SequenceStartEvent | yaml.MappingStartEvent):
            if len(stack) > MAX_DEPTH:
                raise Invalid(
                    f"{what}: nested deeper than {MAX_DEPTH} levels at line {line(event)}, "
                    f"column {event.start_mark.column + 1}"
                )
            if is_key:
                frame.key = "?"
            anchor(event)
            path = frame.child_path() if frame is not top else ""
            stack.append(_Frame(path, event.anchor, isinstance(event, yaml.MappingStartEvent)))
        elif isinstance(event, yaml.SequenceEndEvent | yaml.MappingEndEvent):
            done = stack.pop()
            if done.anchor:
                open_anchors.discard(done.anchor)
                sizes[done.anchor] = (done.values, done.text)
            take(done.values, done.text)


def _loads_yaml(text: str, what: str, loader_class: type | None = None) -> Any:
    """Check the events (:func:`_check_events`), then compose and construct (the composer's
    recursion is bounded by the depth checked before)."""
    loader_class = loader_class or _Loader
    for step in ("check", "load"):
        loader = loader_class(text, what)
        try:
            if step == "check":
                _check_events(loader, what)
            else:
                return loader.get_single_data()
        except yaml.YAMLError as exc:
            mark = getattr(exc, "problem_mark", None)
            where = f" at line {mark.line + 1}, column {mark.column + 1}" if mark else ""
            problem = getattr(exc, "problem", None) or str(exc).splitlines()[0]
            if "nesting depth" in problem:  # libyaml's own limit, met while it reads ahead
                raise Invalid(f"{what}: nested deeper than {MAX_DEPTH} levels{where}") from None
            if mark is not None and _tab_at(text, mark.line, mark.column) and "tab" not in problem:
                problem += " (a tab character: YAML indents with spaces only; replace the tab)"
            if "another document" in problem:  # PyYAML's "but found another document"
                problem = ("a second YAML document ('---') begins here; give one study, "
                           "conveyor or scenario per file or body (remove the '---' and what "
                           "follows, or send each document on its own)")
            raise Invalid(f"{what}: not valid YAML{where}: {problem}") from None
        finally:
            loader.dispose()
    return None


def _tab_at(text: str, line: int, column: int) -> bool:
    """Whether ``text`` has a tab at 0-based ``line`` and ``column`` (a YAML error's mark)."""
    lines = text.splitlines()
    return 0 <= line < len(lines) and 0 <= column < len(lines[line]) and \
        lines[line][column] == "\t"


# ------------------------------------------------------------------------------------ JSON
def _json_int(text: str) -> int | _Huge:
    if len(text) - text.startswith("-") > MAX_DIGITS:
        return _huge(text, len(text) - text.startswith("-"))
    return int(text)


def _json_object(pairs: list[tuple[str, Any]]) -> dict:
    out = dict(pairs)
    if len(out) == len(pairs):
        return out
    seen: set[str] = set()
    dup = next(k for k, _ in pairs if k in seen or seen.add(k))
    marked = _Duplicate(out)
    marked.duplicate = dup
    return marked


def _loads_json(text: str, what: str) -> Any:
    try:
        return json.loads(
            text,
            parse_int=_json_int,
            parse_constant=float,  # NaN / Infinity: refused with their path by check_tree
            object_pairs_hook=_json_object,
        )
    except json.JSONDecodeError as exc:
        # a request body may be YAML under its content type; a .json file is JSON by its name
        hint = (" (send YAML with Content-Type: application/yaml)" if what == "body" else
                " (a .json file is read as JSON: correct it there, or save it as YAML with "
                "a .yaml name)")
        raise Invalid(
            f"{what}: not valid JSON at line {exc.lineno}, column {exc.colno}: {exc.msg}{hint}"
        ) from None
    except RecursionError:
        raise Invalid(f"{what}: nested deeper than {MAX_DEPTH} levels") from None


# ------------------------------------------------------------------------------------ both
def loads(text: str, *, yaml_text: bool, what: str = "body") -> Any:
    """Parse YAML (``yaml_text``) or JSON within the budget; the result passed
    :func:`check_tree`."""
    data = _loads_yaml(text, what) if yaml_text else _loads_json(text, what)
    check_tree(data, what)
    return data


def parse_body(body: bytes, content_type: str, what: str = "a study") -> Any:
    """A request body as data: YAML for the YAML content types, JSON otherwise; ``what`` the
    route reads (for the message of an empty body)."""
    if not body.strip():
        raise Invalid(f"body: empty; send {what} as JSON or YAML")
    try:
        # a byte order mark (Windows editors write one) is no part of the text: RFC 8259 8.1
        # lets a parser ignore it, and the YAML reader and every file reader already do
        text = body.decode("utf-8").removeprefix("\ufeff")
    except UnicodeDecodeError:
        raise Invalid("body: not UTF-8 text") from None
    content_type = content_type.lower()
    return loads(text, yaml_text=any(t in content_type for t in YAML_TYPES))


def load_mapping(path: str | Path, what: str | None = None) -> dict:
    """A YAML or JSON file (JSON by its ``.json`` suffix) as a mapping, within the budget;
    errors start with ``what`` (default: the path)."""
    p = Path(path)
    what = what or str(p)
    try:
        text = read_text(p, what)  # UTF-8 (with or without BOM) or UTF-16 with its BOM
    except InputError as exc:
        raise Invalid(str(exc)) from None
    except OSError as exc:  # a name over the file system's limits, ...
        raise Invalid(f"{what}: cannot read it: {file_reason(exc)}") from None
    try:
        data = loads(text, yaml_text=p.suffix.lower() != ".json", what=what)
    except (Invalid, TooLarge) as exc:
        if not exc.message.startswith(what):  # a nested path ("belt: key 'x' appears twice")
            exc.message = f"{what}: {exc.message}"
            exc.args = (exc.message,)
        raise
    if data is None:  # no content (a UTF-16 byte order mark alone is no content either)
        raise Invalid(f"{what}: empty; expected a mapping of keys at the top level")
    if not isinstance(data, dict):
        raise Invalid(f"{what}: expected a mapping of keys at the top level")
    return data


#: Keys only a conveyor file has at its top level (SPEC 1), only a study file (SPEC 3), and the
#: scenario's own (SPEC 2): a file given in the wrong place is named for what it is.
_CONVEYOR_KEYS = ("speed_m_s", "belt", "material", "profile", "idlers", "drives")
_STUDY_KEYS = ("conveyor", "grid", "zip", "design", "models", "sample", "dynamics")
_SCENARIO_KEYS = ("scenario", "load", "temperature_c", "start", "run_s", "stop", "formulation",
                  "elements", "dt_s", "record_dt_s")
_FILE_USE = {
    "conveyor": "a conveyor file (SPEC 1: name, speed_m_s, belt, material, profile, idlers, "
                "drives)",
    "study": "a study file (SPEC 3: name, conveyor, scenario, grid, ...)",
    "scenario": "a scenario file (SPEC 2: load, temperature_c, start, run_s, stop, ...)",
}


def file_kind(data: Any) -> str | None:
    """What a top-level mapping looks like: ``conveyor`` (three or more of a conveyor's own
    keys), ``study`` (a ``conveyor:`` key, or two of a study's own keys), ``scenario`` (only a
    scenario's keys: its ``scenario:`` wrapper or two of its fields), or None."""
    if not isinstance(data, dict):
        return None
    if sum(k in data for k in _CONVEYOR_KEYS) >= 3 and "conveyor" not in data:
        return "conveyor"
    if "conveyor" in data or sum(k in data for k in _STUDY_KEYS) >= 2:
        return "study"
    if data and all(k in _SCENARIO_KEYS for k in data) and (
            "scenario" in data or len(data) >= 2):
        return "scenario"
    return None


def expect_kind(data: Any, kind: str, what: str) -> None:
    """Refuse a conveyor file given as a study or scenario, a study file given as a
    conveyor or scenario, or a scenario file given as a conveyor or study, in one line naming what the file is and where it goes (instead of
    one unknown key after another)."""
    got = file_kind(data)
    if got is None or got == kind:
        return
    own = {"conveyor": _CONVEYOR_KEYS, "study": _STUDY_KEYS, "scenario": _SCENARIO_KEYS}[got]
    keys = ", ".join(k for k in own if k in data)
    # a scenario file given as the conveyor ('beltstudy simulate sc.yaml --scenario conv.yaml')
    # was refused with every conveyor field missing and 'unknown key scenario'
    where = {"conveyor": "give it as the conveyor (a study names it under conveyor:)",
             "study": "run it as a study (beltstudy run FILE, or POST /studies); its conveyor: "
                      "names the conveyor file",
             "scenario": "give it with --scenario (beltstudy simulate CONVEYOR --scenario "
                         "FILE; a study writes it under scenario:)"}[got]
    raise Invalid(f"{what}: this is a {got} file (it has {keys}), not {_FILE_USE[kind]}: "
                  f"{where}")


def _describe(value: float) -> str:
    if math.isnan(value):
        return "NaN is not a number"
    return "infinity is not a finite number"


def _check_text(text: str, where: str) -> None:
    """Refuse text that is not Unicode, such as a JSON escape of half a surrogate pair
    (``"\\ud800"``): it cannot be stored, written to Parquet or shown."""
    try:
        text.encode("utf-8")
    except UnicodeEncodeError as exc:
        bad = ord(text[exc.start])
        raise Invalid(
            f"{where}: contains U+{bad:04X}, half of a UTF-16 surrogate pair, which is not a "
            "character; send the whole pair (e.g. \\ud83d\\ude00) or the character itself"
        ) from None


def check_tree(data: Any, what: str = "") -> None:
    """Check parsed data against the budget and JSON's types; :class:`Invalid` naming the
    path of the first bad value, :class:`TooLarge` when it is over the size budget.

    Shared lists and mappings (YAML aliases) are walked once and counted every time they are
    used, so the cost is that of the data as written, not as expanded.
    """
    memo: dict[int, tuple[int, int, int]] = {}  # id -> (values, text, height)
    active: set[int] = set()

    def where(path: str) -> str:
        return path or what or "(top level)"

    def visit(value: Any, path: str, depth: int) -> tuple[int, int, int]:
        if isinstance(value, _Huge):
            raise Invalid(
                f"{where(path)}: a number with {value.digits} digits is out "
                f"of range (at most {MAX_DIGITS} digits)"
            )
        if value is None or isinstance(value, bool | int):
            return 1, 0, 0
        if isinstance(value, float):
            if not math.isfinite(value):
                raise Invalid(f"{where(path)}: {_describe(value)}; give a finite value")
            return 1, 0, 0
        if isinstance(value, str):
            _check_text(value, where(path))
            return 1, len(value), 0
        if not isinstance(value, dict | list | tuple):
            raise Invalid(
                f"{where(path)}: a {type(value).__name__} is not a valid value; use text, "
                "numbers, true/false, null, lists or mappings"
            )
        key = id(value)
        if key in memo:
            if depth + memo[key][2] > MAX_DEPTH:  # a shared part used deeper than before
                raise Invalid(f"{where(path)}: nested deeper than {MAX_DEPTH} levels")
            return memo[key]
        if key in active:
            raise Invalid(f"{where(path)}: contains itself")
        if depth >= MAX_DEPTH:
            raise Invalid(f"{where(path)}: nested deeper than {MAX_DEPTH} levels")
        active.add(key)
        values, text, height = 1, 0, 0
        if isinstance(value, dict):
            if isinstance(value, _Duplicate):
                raise Invalid(
                    f"{where(path)}: key '{value.duplicate}' appears twice; give each key once"
                )
            items = []
            for k, v in value.items():
                if not isinstance(k, str):
                    raise Invalid(
                        f"{where(path)}: key {k!r} is not text; quote it ('{k}') or use a "
                        "field name"
                    )
                _check_text(k, f"{where(path)}: key {k.encode('utf-8', 'backslashreplace').decode()!r}")
                items.append((f"{path}.{k}" if path else k, v))
                text += len(k)
        else:
            items = [(f"{path}.{i}" if path else str(i), v) for i, v in enumerate(value)]
        for sub, v in items:
            n, t, h = visit(v, sub, depth + 1)
            values, text, height = values + n, text + t, max(height, h + 1)
        active.discard(key)
        if height > MAX_DEPTH:
            raise Invalid(f"{where(path)}: nested deeper than {MAX_DEPTH} levels")
        if values > MAX_VALUES or text > MAX_TEXT:
            raise TooLarge(
                f"{where(path)}: {values} values and {text} characters; the limit is "
                f"{MAX_VALUES} values and {MAX_TEXT} characters"
            )
        memo[key] = (values, text, height)
        return values, text, height

    visit(data, "", 0)


def tree_size(data: Any) -> int:
    """Values in ``data`` with shared parts counted every time they are used."""
    memo: dict[int, int] = {}

    def visit(value: Any) -> int:
        if isinstance(value, dict):
            children = value.values()
        elif isinstance(value, list | tuple):
            children = value
        else:
            return 1
        key = id(value)
        if key not in memo:
            memo[key] = 1 + sum(visit(v) for v in children)
        return memo[key]

    return visit(data)
