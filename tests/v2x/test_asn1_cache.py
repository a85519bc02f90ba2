"""The ASN.1 parse cache (coopdrive/v2x/asn1_cache.py): read back as parsed, rebuilt when damaged, and read
without Python's compiler, so that the v2x service may read it in a thread while its main thread imports."""

import ast
import builtins
from importlib import resources

import asn1tools
import pytest

from coopdrive.v2x.asn1_cache import parsed_cached

SECURITY_FILES = ("IEEE1609dot2BaseTypes.asn", "IEEE1609dot2.asn", "TS103097v131.asn")


@pytest.fixture(scope="module")
def paths():
    package = resources.files("coopdrive.v2x.asn1.security")
    return [str(package.joinpath(name)) for name in SECURITY_FILES]


def test_the_second_read_comes_from_the_cache_and_equals_the_parse(paths, tmp_path, monkeypatch):
    parsed = parsed_cached(paths, tmp_path, "security")
    assert parsed == asn1tools.parse_files(paths)
    monkeypatch.setattr(asn1tools, "parse_files", lambda _: pytest.fail("parsed again despite the cache"))
    assert parsed_cached(paths, tmp_path, "security") == parsed


def test_a_damaged_cache_file_is_parsed_again_and_replaced(paths, tmp_path):
    parsed = parsed_cached(paths, tmp_path, "security")
    [cached] = tmp_path.glob("security-*.marshal")
    cached.write_bytes(b"\x00 not marshal")
    assert parsed_cached(paths, tmp_path, "security") == parsed
    assert cached.read_bytes() != b"\x00 not marshal"


def test_reading_the_cache_builds_no_python_syntax_tree(paths, tmp_path, monkeypatch):
    """CPython 3.11's AST builder keeps one recursion counter for all threads (CPython issue 106905): the cache read
    with ast.literal_eval raised SystemError ("AST constructor recursion depth mismatch") in the v2x service's
    compile thread while its main thread imported. The race did not come on demand here; what removes it does: the
    read uses no compiler."""
    expected = parsed_cached(paths, tmp_path, "security")

    def no_compiler(*_args, **_kwargs):
        raise AssertionError("the cache read built a syntax tree")

    monkeypatch.setattr(ast, "parse", no_compiler)
    monkeypatch.setattr(builtins, "compile", no_compiler)
    assert parsed_cached(paths, tmp_path, "security") == expected
