"""The parse budget: YAML and JSON read within depth and size limits, before any expansion."""

from __future__ import annotations

import time

import pytest

from beltstudy.service.door import parse
from beltstudy.service.errors import Invalid, TooLarge

LOADERS = [pytest.param(parse._Loader, id="default"), pytest.param(parse._PyLoader, id="pure")]

#: A 400-byte nested alias bomb inside a grid value list: 9**9 values once expanded.
ALIAS_BOMB = """name: bomb
conveyor: conveyors/slope-5pct.yaml
grid:
  temperature_c:
    - &a [1,2,3,4,5,6,7,8,9]
    - &b [*a,*a,*a,*a,*a,*a,*a,*a,*a]
    - &c [*b,*b,*b,*b,*b,*b,*b,*b,*b]
    - &d [*c,*c,*c,*c,*c,*c,*c,*c,*c]
    - &e [*d,*d,*d,*d,*d,*d,*d,*d,*d]
    - &f [*e,*e,*e,*e,*e,*e,*e,*e,*e]
    - &g [*f,*f,*f,*f,*f,*f,*f,*f,*f]
    - &h [*g,*g,*g,*g,*g,*g,*g,*g,*g]
    - &i [*h,*h,*h,*h,*h,*h,*h,*h,*h]
"""


@pytest.mark.parametrize("loader", LOADERS)
def test_alias_bomb_is_refused_without_expanding_it(loader):
    t0 = time.perf_counter()
    with pytest.raises(TooLarge, match=r"grid\.temperature_c\.\d: more than 200000 values"):
        parse._loads_yaml(ALIAS_BOMB, "body", loader)
    assert time.perf_counter() - t0 < 1.0  # it is refused from the alias graph, not expanded


@pytest.mark.parametrize("loader", LOADERS)
@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("a: &a [1, *a]", r"a\.1: the alias \*a at line 1 is inside its own anchor"),
        ("a: &x 1\nb: &x 2", r"anchor &x at line 2 is defined twice"),
        ("a: 1\nb: 2\na: 3\n", r"body: key 'a' appears twice \(lines 1 and 3\)"),
        ("g:\n  t: {x: 1, x: 2}", r"g\.t: key 'x' appears twice"),
        # on one line: the columns, not 'lines 2 and 2'
        ("g:\n  t: {x: 1, x: 2}", r"^g\.t: key 'x' appears twice \(line 2, columns 7 and 13\)"),
        ("a: " + "[" * 40 + "]" * 40, r"nested deeper than 32 levels at line 1, column 35"),
        ("e: !!binary aGVsbG8=", r"YAML tag !!binary at line 1 is not allowed"),
        ("a: [1, .nan]", r"a\.1: NaN is not a number"),
        ("a: {b: -.inf}", r"a\.b: infinity is not a finite number"),
        ("a: " + "7" * 5000, r"a: a number with 5000 digits is out of range"),
        ("1: x", r"key 1 is not text"),
        ("a: [1, 2\n", r"body: not valid YAML at line 2, column 1"),
    ],
)
def test_yaml_problems_name_the_place(loader, text, message):
    with pytest.raises((Invalid, TooLarge), match=message):
        parse.check_tree(parse._loads_yaml(text, "body", loader))


@pytest.mark.parametrize("loader", LOADERS)
def test_plain_yaml_reads_as_before(loader):
    text = "base: &b {x: 1, y: 2}\nd:\n  <<: *b\n  x: 3\nday: 2024-01-01\nq: '1'\n1.5: ok\n"
    data = parse._loads_yaml(text, "body", loader)
    assert data == {"base": {"x": 1, "y": 2}, "d": {"x": 3, "y": 2}, "day": "2024-01-01",
                    "q": "1", 1.5: "ok"}


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ('{"a": [0, NaN]}', r"a\.1: NaN is not a number"),
        ('{"m": {"din": {"f": Infinity}}}', r"m\.din\.f: infinity is not a finite number"),
        ('{"a": 1e999}', r"a: infinity"),
        ('{"a": [' + "9" * 5000 + "]}", r"a\.0: a number with 5000 digits"),
        ('{"a": 1, "b": {"c": 1, "c": 2}}', r"b: key 'c' appears twice"),
        ("[" * 100_000 + "]" * 100_000, r"nested deeper than 32 levels"),
        ('{"a": ' + "[" * 40 + "]" * 40 + "}", r"a(\.0)+: nested deeper than 32 levels"),
        ("{not json", r"body: not valid JSON at line 1, column 2"),
    ],
)
def test_json_problems_name_the_place(text, message):
    with pytest.raises((Invalid, TooLarge), match=message):
        parse.loads(text, yaml_text=False)


def test_a_json_file_is_not_told_to_send_a_content_type(tmp_path):
    """A request body may be YAML under its content type; a .json file is JSON by its name:
    its error said to send YAML with Content-Type, which no file can."""
    path = tmp_path / "conveyor.json"
    path.write_text('{"name": "x",}')
    with pytest.raises(Invalid) as err:
        parse.load_mapping(path)
    assert err.value.message == (
        f"{path}: not valid JSON at line 1, column 14: Expecting property name enclosed in "
        "double quotes (a .json file is read as JSON: correct it there, or save it as YAML "
        "with a .yaml name)")
    with pytest.raises(Invalid, match=r"\(send YAML with Content-Type: application/yaml\)$"):
        parse.parse_body(b'{"name": "x",}', "application/json")


def test_an_oversize_file_is_not_told_to_send_a_smaller_study(tmp_path):
    """A conveyor file of 100 000 profile sections was told to 'send a smaller study'."""
    path = tmp_path / "conveyor.yaml"
    path.write_text("name: x\nprofile:\n" + "  - {length_m: 1, lift_m: 0}\n" * 70_000)
    with pytest.raises(TooLarge, match=r": profile: more than 200000 values or 4000000 "
                                       r"characters \(YAML aliases expanded\); give a smaller "
                                       r"file$"):
        parse.load_mapping(path)
    with pytest.raises(TooLarge, match=r"; send a smaller body$"):
        parse.parse_body(b"a: [" + b",".join([b"1"] * 200_001) + b"]", "application/yaml")


def test_the_value_budget_also_holds_for_plain_lists():
    with pytest.raises(TooLarge, match="more than 200000 values"):
        parse.loads("a: [" + ",".join(["1"] * 200_001) + "]", yaml_text=True)
    assert len(parse.loads('{"a": [' + ",".join(["1"] * 100_000) + "]}", yaml_text=False)["a"]) \
        == 100_000


def test_check_tree_counts_shared_parts_every_time_they_are_used():
    inner = list(range(100))
    data = {"a": [inner] * 100}
    parse.check_tree(data)  # 10 101 values: fine
    with pytest.raises(TooLarge):
        parse.check_tree({"a": [[inner] * 100] * 100})  # 1 010 101 values
    loop: list = []
    loop.append(loop)
    with pytest.raises(Invalid, match="contains itself"):
        parse.check_tree({"a": loop})


def test_study_files_take_utf8_bom_and_utf16_and_name_the_file(tmp_path):
    """The door's file reader: the engine's encodings; a problem deep in the file names it."""
    path = tmp_path / "study.yaml"
    path.write_bytes("name: s\n# Förderband\ngrid: {load: [full]}\n".encode("utf-16"))
    assert parse.load_mapping(path) == {"name": "s", "grid": {"load": ["full"]}}
    path.write_bytes("name: s\n# Förderband\n".encode("latin-1"))
    with pytest.raises(Invalid, match=r"study.yaml: not UTF-8 text \(byte 0xf6 at line 2, col"):
        parse.load_mapping(path)
    path.write_text("name: s\ngrid:\n  load: [full]\n  load: [empty]\n")
    with pytest.raises(Invalid, match=rf"^{path}: grid: key 'load' appears twice \(lines 3 "):
        parse.load_mapping(path)


@pytest.mark.parametrize("loader", LOADERS)
def test_a_tab_in_the_indentation_is_named_as_a_tab(loader):
    """A tab where YAML wants indentation: PyYAML says 'found character that cannot start any
    token'; the message names the tab and the fix."""
    with pytest.raises(Invalid, match=r"at line 3, column 1: .*\(a tab character: YAML indents "
                                      r"with spaces only; replace the tab\)"):
        parse._loads_yaml("idlers:\n  carry: {spacing_m: 1.2}\n\treturn: {spacing_m: 3}\n",
                          "body", loader)


@pytest.mark.parametrize("loader", LOADERS)
def test_a_second_yaml_document_is_named_as_one(loader):
    """Two studies in one body or file ('---' between them): PyYAML says 'but found another
    document'; the message says a second document begins there and what to do."""
    with pytest.raises(Invalid, match=r"^body: not valid YAML at line 3, column 1: a second YAML "
                                      r"document \('---'\) begins here; give one study"):
        parse._loads_yaml("---\nname: a\n---\nname: b\n", "body", loader)


@pytest.mark.parametrize("content_type", ["application/json", "application/yaml"])
def test_a_body_with_a_utf8_byte_order_mark_reads_as_without(content_type):
    """Windows editors save UTF-8 with a byte order mark: a JSON body with one was refused
    ('Unexpected UTF-8 BOM (decode using utf-8-sig)') while a YAML body and every file reader
    take it; RFC 8259 8.1 lets a parser ignore it."""
    text = b'{"name": "bom", "grid": {"temperature_c": [1, 2]}}'
    assert parse.parse_body(b"\xef\xbb\xbf" + text, content_type) == \
        parse.parse_body(text, content_type)
