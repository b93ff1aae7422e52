"""An input error repeats no value whole past a readable length: a conveyor whose name was
300 000 characters long was refused with a 300 086-character message (the name echoed after
``got``), and a 300 000-character unknown key with a 600 000-character one (the key as the
path and again in quotes). Now the long run keeps its first 60 and last 40 characters and
says its length; the field and the fix are still said."""

from __future__ import annotations

import pytest

from beltstudy.engine.conveyor import InputError, parse_conveyor
from tests.conftest import short30_dict

LONG = 300_000


def _refusal(data: dict) -> str:
    with pytest.raises(InputError) as info:
        parse_conveyor(data)
    return str(info.value)


def test_a_long_name_is_shortened_in_the_message():
    message = _refusal({**short30_dict(), "name": "x" * LONG})
    assert message.startswith("name: String should have at most 200 characters (got '")
    assert message.endswith("x" * 40 + f" ({LONG} characters)')")
    assert len(message) < 300


def test_a_long_unknown_key_is_shortened_twice():
    message = _refusal({**short30_dict(), "k" * LONG: 1})
    assert "unknown key '" in message
    # the key as the path and again in quotes
    assert message.count("k" * 60 + "..." + "k" * 40 + f" ({LONG} characters)") == 2
    assert len(message) < 600  # with the valid keys


def test_a_long_choice_keeps_the_valid_words():
    data = short30_dict()
    data["drives"][0]["position"] = "h" * LONG
    message = _refusal(data)
    assert message.startswith("drives.0.position: Input should be 'head', 'tail', 'carry' or "
                              "'return' (got 'hhh")
    assert len(message) < 300


def test_shown_text_keeps_short_runs_and_cuts_a_long_message():
    from beltstudy.engine.errors import shown_text

    said = "belt.type: unknown belt type 'ST9'; valid: ST1000, ST1250"
    assert shown_text(said) == said
    assert shown_text("a" * 300) == "a" * 300  # at ECHO_MAX, whole
    assert shown_text("a" * 301) == "a" * 60 + "..." + "a" * 40 + " (301 characters)"
    assert shown_text(f"got '{'b' * 400}')") == f"got '{'b' * 60}...{'b' * 40} (400 characters)')"
    spaced = "x " * 10_000  # no long run, but 20 000 characters in all
    cut = shown_text(spaced)
    assert len(cut) < 4100 and cut.endswith("(20000 characters)")
