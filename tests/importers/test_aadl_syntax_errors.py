"""The AADL v2 concrete syntax on bad input: located syntax errors that say what was expected,
unterminated strings and annexes, bytes that are not UTF-8, garbage that fails fast, and the
lexical edge cases that once went wrong."""

from __future__ import annotations

import random
import time

import pytest
from aadl_syntax_helpers import aadl_syntax, in_type, only, parse

from rosaadl.errors import AadlSyntaxError

# --------------------------------------------------------------------------- bad input


def syntax_error(text: str | bytes) -> AadlSyntaxError:
    with pytest.raises(AadlSyntaxError) as info:
        parse(text, "bad.aadl")
    error = info.value
    assert error.location.file == "bad.aadl"
    assert error.location.line is not None and error.location.column is not None
    assert error.stage == "parse"
    return error


def test_unclosed_component() -> None:
    error = syntax_error(
        "package P public\n thread T\n  features\n   p: in data port;\n thread U end U;\nend P;\n"
    )
    assert (error.location.line, error.location.column) == (5, 2)
    assert "unexpected 'thread'" in error.message and "'end'" in error.message
    assert "expected one of:" in error.message


def test_missing_end_at_end_of_file() -> None:
    error = syntax_error("package P public\n system S\n")
    assert error.message.startswith("unexpected end of file, expected one of:")
    assert (error.location.line, error.location.column) == (3, 1)


def test_unknown_category_word() -> None:
    error = syntax_error("package P public\n threed T\n end T;\nend P;\n")
    assert (error.location.line, error.location.column) == (2, 9)
    assert "after 'threed'" in error.message and "expected 'renames'" in error.message


def test_misspelled_keyword() -> None:
    error = syntax_error("package P public\n thread T\n featurs\n  p: in data port;\n end T;\nend P;\n")
    assert (error.location.line, error.location.column) == (3, 2)
    assert "unexpected 'featurs'" in error.message
    assert "'features'" in error.message and "'end'" in error.message


def test_missing_semicolon_lists_only_viable_tokens() -> None:
    error = syntax_error("package P public\n thread T\n properties\n  Period => 10 ms\n end T;\nend P;\n")
    assert (error.location.line, error.location.column) == (5, 2)
    assert "';'" in error.message and "'applies'" in error.message
    assert "'=>'" not in error.message  # an LALR look-ahead that leads nowhere here is not listed


def test_unexpected_character() -> None:
    error = syntax_error("package P public\n system S @ end S;\nend P;\n")
    assert (error.location.line, error.location.column) == (2, 11)
    assert error.message.startswith("unexpected character '@', expected one of:")


def test_unterminated_annex() -> None:
    error = syntax_error("package P public\n system S\n  annex EMV2 {** error types\n end S;\nend P;\n")
    assert (error.location.line, error.location.column) == (3, 14)
    assert "unterminated annex" in error.message


def test_unterminated_string() -> None:
    error = syntax_error('package P public\n system S\n  properties\n   X => "abc;\n end S;\nend P;\n')
    assert (error.location.line, error.location.column) == (4, 9)
    assert "unterminated string" in error.message


def test_non_utf8_bytes() -> None:
    error = syntax_error(b"package P public\n system S\xff\xfe end S;\nend P;\n")
    assert (error.location.line, error.location.column) == (2, 10)
    assert "UTF-8" in error.message and "0xff" in error.message


def test_empty_input() -> None:
    error = syntax_error("-- nothing but a comment\n")
    assert "end of file" in error.message and "'package'" in error.message


def test_five_megabytes_of_garbage_fail_fast() -> None:
    rng = random.Random(20240601)
    alphabet = b"abcdefghijklmnopqrstuvwxyz0123456789 \n\t;:,.(){}[]=>-+*\"'#@!"
    table = bytes(alphabet[i % len(alphabet)] for i in range(256))
    garbage = rng.randbytes(5 * 1024 * 1024).translate(table).decode("ascii")
    start = time.process_time()
    error = syntax_error(garbage)
    elapsed = time.process_time() - start
    assert error.location.line == 1
    assert "expected" in error.message
    assert elapsed < 1.0, f"reporting garbage took {elapsed:.2f}s"


def test_no_regex_backtracking_on_comments_of_dashes() -> None:
    aadl_syntax._reader()
    dashes = "-" * 200
    text = f"package P public\n system S\n  features\n   p: in {dashes}\n data port;\n end S;\nend P;\n"
    start = time.process_time()
    assert only(parse(text), "data_port").children[0] == "p"
    assert time.process_time() - start < 0.5


def test_in_binding_across_a_comment() -> None:
    pa = only(in_type("properties\n  X => 5 in -- bound to\n binding (Q::C);"), "property_association")
    assert pa.children[5].data == "in_binding"


def test_garbage_after_a_valid_package() -> None:
    error = syntax_error("package P public end P;\n)))")
    assert (error.location.line, error.location.column) == (2, 1)
    assert "end of file" in error.message
