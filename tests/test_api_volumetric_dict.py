"""``axiscal.volumetric_map`` and ``axiscal.volumetric_compensation`` take the configuration as
a dict too (issue 33), read by the file's own reader; its relative file names are taken from
``base`` (default: the current directory)."""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

import axiscal
from axiscal.errors import AxiscalError, ConfigError, InputError, MissingFileError

CONFIG = Path(__file__).resolve().parents[1] / "examples" / "volumetric" / "volumetric.toml"


def _dict() -> dict:
    return tomllib.loads(CONFIG.read_text(encoding="utf-8"))


def test_the_dict_form_of_the_example_gives_the_files_result(monkeypatch):
    """The same ``to_dict()`` (the ``volumetric map --json`` object: map, diagonals, truth) from
    the dict with ``base`` the example's folder, and from the dict alone run in that folder."""
    from_file = axiscal.volumetric_map(CONFIG, grid=5)
    from_dict = axiscal.volumetric_map(_dict(), grid=5, base=CONFIG.parent)
    assert from_dict.to_dict() == from_file.to_dict()
    assert from_file.to_dict()["missing"] == [] and "truth" in from_file.to_dict()
    assert from_dict.name == "<dict>" and from_file.name == "volumetric.toml"
    monkeypatch.chdir(CONFIG.parent)
    assert axiscal.volumetric_map(_dict(), grid=5).to_dict() == from_file.to_dict()


def test_the_dict_form_gives_the_files_compensation_tables(tmp_path):
    """``volumetric_compensation`` likewise: the same tables (``volumetric compensate --json``)
    and the same files written."""
    a, b = tmp_path / "file", tmp_path / "dict"
    from_file = axiscal.volumetric_compensation(CONFIG, "csv", out=a)
    from_dict = axiscal.volumetric_compensation(_dict(), "csv", out=b, base=str(CONFIG.parent))
    d_file, d_dict = from_file.to_dict(), from_dict.to_dict()
    assert sorted(p.name for p in a.iterdir()) == sorted(p.name for p in b.iterdir())
    assert [(p.name, p.read_bytes()) for p in sorted(a.iterdir())] == \
        [(p.name, p.read_bytes()) for p in sorted(b.iterdir())]
    d_file.pop("out", None), d_dict.pop("out", None)    # the two folders
    assert d_dict == d_file


def test_a_missing_file_named_in_the_dict_is_one_line_naming_it(tmp_path, monkeypatch):
    cfg = _dict()
    cfg["errors"]["EYX"] = "no_such_EYX.csv"
    with pytest.raises(MissingFileError) as e:
        axiscal.volumetric_map(cfg, base=CONFIG.parent)
    msg = str(e.value)
    assert "\n" not in msg and str(CONFIG.parent / "no_such_EYX.csv") in msg
    monkeypatch.chdir(tmp_path)                                 # base: the current directory
    with pytest.raises(MissingFileError) as e:
        axiscal.volumetric_compensation(_dict(), "csv", out=tmp_path / "never")
    assert str(tmp_path / "X_EXX.csv") in str(e.value) and "\n" not in str(e.value)
    assert not (tmp_path / "never").exists()                   # nothing made before the error


def test_the_dict_is_checked_by_the_files_reader():
    """An unknown key is refused as in the file, the source named ``<dict>``."""
    cfg = _dict()
    cfg["machine"]["colour"] = "red"
    with pytest.raises(ConfigError) as e:
        axiscal.volumetric_map(cfg, base=CONFIG.parent)
    assert "colour" in str(e.value) and "<dict>" in str(e.value) and "\n" not in str(e.value)


@pytest.mark.parametrize("config, base, words", [
    (CONFIG, CONFIG.parent, "only for a configuration given as a dict"),
    ("dict", "no/such/folder", "not a folder"),
])
def test_base_is_checked(config, base, words):
    config = _dict() if config == "dict" else config
    with pytest.raises(InputError, match=words):
        axiscal.volumetric_map(config, base=base)
    with pytest.raises(AxiscalError, match=words):
        axiscal.volumetric_compensation(config, "csv", base=base)
