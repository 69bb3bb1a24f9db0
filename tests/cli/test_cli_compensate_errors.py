"""``axiscal compensate`` user errors found by the CLI review: one line, exit code 2, no file."""

import json

from typer.testing import CliRunner

from axiscal.cli import app
from axiscal.compensation.controllers import controller
from axiscal.compensation.tables import table_from_deviations

runner = CliRunner()

RESULT = {"axis_kind": "linear", "target_unit": "mm", "unit": "um",
          "targets": [{"target": 0, "mean_up": 1.0, "mean_down": -1.0},
                      {"target": 100, "mean_up": 3.0, "mean_down": 1.0},
                      {"target": 200, "mean_up": 5.0, "mean_down": 3.0}]}


def _one_line_error(r):
    assert r.exit_code == 2, r.output
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("axiscal: error: "), r.stderr
    return lines[0]


def test_tiny_spacing_is_one_line_and_writes_nothing(tmp_path):
    src = tmp_path / "r.json"
    src.write_text(json.dumps(RESULT))
    out = tmp_path / "X.INI"
    line = _one_line_error(runner.invoke(app, ["compensate", str(src), "--spacing", "1e-9",
                                               "--controller", "siemens-840d", "--out", str(out)]))
    assert "200000000001 table points" in line
    assert not out.exists()


def test_fanuc_zero_detection_unit_is_one_line(tmp_path):
    src = tmp_path / "r.json"
    src.write_text(json.dumps(RESULT))
    line = _one_line_error(runner.invoke(app, ["compensate", str(src), "--spacing", "50",
                                               "--controller", "fanuc", "-o", "detection_unit=0"]))
    assert "detection_unit = 0" in line


def test_reading_a_fanuc_file_without_3626_is_one_line(tmp_path):
    t = table_from_deviations([0, 100, 200], [1.0, 3.0, 5.0], [-1.0, 1.0, 3.0], spacing=50)
    text = controller("fanuc").write(t).text
    f = tmp_path / "PITCH.TXT"
    f.write_text("".join(x + "\n" for x in text.splitlines() if not x.startswith("N3626")))
    line = _one_line_error(runner.invoke(app, ["compensate", "--read", str(f), "--controller", "fanuc"]))
    assert "parameter 3626 is missing" in line


def test_nan_target_in_a_result_is_one_line(tmp_path):
    d = json.loads(json.dumps(RESULT))
    d["targets"][1]["target"] = float("nan")
    src = tmp_path / "r.json"
    src.write_text(json.dumps(d))
    line = _one_line_error(runner.invoke(app, ["compensate", str(src), "--spacing", "50"]))
    assert "targets[1].target = nan" in line
