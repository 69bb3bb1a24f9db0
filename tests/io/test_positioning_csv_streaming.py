"""The positioning CSV reader streams large files: the same dataset as reading the text whole,
memory that grows with the readings, the same one-line errors, a progress callback."""

import csv
import io
import tracemalloc

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.datasets import PositioningDataset
from axiscal.errors import DataFormatError
from axiscal.io import STREAM_ABOVE_BYTES, read_positioning
from axiscal.io import csv as pcsv


def _reference(text: str) -> PositioningDataset:
    """An independent reading of a simple tidy CSV: the csv module and ``from_records``."""
    lines = [ln for ln in text.splitlines() if ln.strip() and not ln.lstrip().startswith("#")]
    rows = list(csv.reader(io.StringIO("\n".join(lines))))
    head = [c.strip() for c in rows[0]]
    recs = []
    for row in rows[1:]:
        rec = dict(zip(head, row))
        if rec["deviation"].strip().lower() in ("", "nan", "na", "missing"):
            continue
        recs.append((float(rec["target"]), rec["direction"], int(float(rec["run"])),
                     float(rec["deviation"])))
    return PositioningDataset.from_records("linear", recs, "mm", "um")


def _same(a: PositioningDataset, b: PositioningDataset) -> bool:
    return (np.array_equal(a.targets, b.targets) and np.array_equal(a.up, b.up, equal_nan=True)
            and np.array_equal(a.down, b.down, equal_nan=True) and a.metadata == b.metadata
            and (a.target_unit, a.deviation_unit, a.axis_kind)
            == (b.target_unit, b.deviation_unit, b.axis_kind))


_DIRECTIONS = {"+": ["+", "up", "UP", "fwd", " + ", '"+"'], "-": ["-", "down", "bwd", "Neg"]}


@st.composite
def _csv_texts(draw):
    m = draw(st.integers(1, 6))
    n_up, n_down = draw(st.integers(1, 4)), draw(st.integers(0, 4))
    targets = sorted(draw(st.lists(st.floats(-1e3, 1e3, allow_nan=False).map(lambda x: round(x, 3)),
                                   min_size=m, max_size=m, unique=True)))
    rows = []
    for d, n in (("+", n_up), ("-", n_down)):
        for run in range(1, n + 1):
            for t in targets:
                dev = draw(st.one_of(st.floats(-50, 50, allow_nan=False).map(lambda x: f"{x:.4f}"),
                                     st.sampled_from(["", "nan", "missing"])))
                spelled = draw(st.sampled_from(_DIRECTIONS[d]))
                run_text = draw(st.sampled_from([str(run), f"{run}.0", f'"{run}"']))
                rows.append(f"{t!r},{spelled},{run_text},{dev}")
    rows = draw(st.permutations(rows))
    newline = draw(st.sampled_from(["\n", "\r\n", "\r"]))
    head = ["# target_unit=mm deviation_unit=um axis=X", "target,direction,run,deviation"]
    if not any(r.split(",")[3] not in ("", "nan", "missing") for r in rows):
        rows.append(f"{targets[0]!r},+,1,0.5")   # at least one reading
    return newline.join(head + list(rows)) + newline


@settings(max_examples=60, deadline=None)
@given(text=_csv_texts(), chunk=st.sampled_from([5, 17, 64, 1 << 20]), bom=st.booleans())
def test_streaming_equals_an_independent_reading(tmp_path_factory, text, chunk, bom):
    """Whatever the line ends, quoting, spelling of directions or where the chunks are cut, the
    streamed file gives the dataset an independent reading (the csv module) gives."""
    f = tmp_path_factory.mktemp("s") / "p.csv"
    f.write_bytes((b"\xef\xbb\xbf" if bom else b"") + text.encode())
    old = pcsv._CHUNK_BYTES
    pcsv._CHUNK_BYTES = chunk
    try:
        try:
            ref = _reference(text.replace("\r\n", "\n").replace("\r", "\n"))
        except Exception:      # an all-missing column the reference cannot build
            return
        got = pcsv.read_positioning_csv(f)
    finally:
        pcsv._CHUNK_BYTES = old
    np.testing.assert_array_equal(got.targets, ref.targets)
    np.testing.assert_array_equal(got.up, ref.up)
    np.testing.assert_array_equal(got.down, ref.down)
    assert got.metadata.axis == "X"
    assert _same(got, pcsv.parse_positioning_csv(text, source=str(f)))


def _big_file(path, m=2001, runs=10):
    rng = np.random.default_rng(7)
    t = np.linspace(0, 1000, m)
    with open(path, "w") as fh:
        fh.write("# target_unit=mm deviation_unit=um axis=X\ntarget,direction,run,deviation\n")
        for r in range(1, runs + 1):
            for d in "+-":
                fh.write("".join(f"{a:.4f},{d},{r},{b:.3f}\n" for a, b in zip(t, rng.normal(0, 1, m))))
    return m * runs * 2


def _peak(fn) -> int:
    tracemalloc.start()
    try:
        fn()
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def test_a_large_file_is_streamed_with_memory_that_grows_with_the_readings(tmp_path):
    """Files of 80,000 and 160,000 readings (1.5 and 3.1 MB) are streamed: each further reading
    costs under 60 bytes at the peak (its stored target number, value, direction and run, and the
    sorting into the table), under half what reading the text whole costs (its lines and strings),
    and the same dataset comes out."""
    small, large = tmp_path / "small.csv", tmp_path / "large.csv"
    n_small, n_large = _big_file(small, m=10001, runs=4), _big_file(large, m=10001, runs=8)
    assert small.stat().st_size > STREAM_ABOVE_BYTES
    read_positioning(small)                     # imports and caches out of the measurement
    calls = []
    stream = [_peak(lambda: read_positioning(f, progress=lambda d, t: calls.append((d, t))))
              for f in (small, large)]
    text = [_peak(lambda: pcsv.parse_positioning_csv(f.read_text(), source=str(f)))
            for f in (small, large)]
    per_reading = (stream[1] - stream[0]) / (n_large - n_small)
    per_reading_text = (text[1] - text[0]) / (n_large - n_small)
    assert per_reading < 60, per_reading
    assert per_reading < per_reading_text / 2, (per_reading, per_reading_text)
    ds = read_positioning(large)
    assert _same(ds, pcsv.parse_positioning_csv(large.read_text(), source=str(large)))
    assert ds.up.shape == (10001, 8) and ds.down.shape == (10001, 8)
    # the progress callback saw the bytes grow to each file's size
    size = large.stat().st_size
    assert calls[-1] == (size, size)
    assert any(done < total for done, total in calls)


@pytest.mark.parametrize("content, words", [
    (b"# target_unit=mm deviation_unit=um\ntarget,direction,run,deviation\n"
     + b"1" * (pcsv.MAX_LINE_BYTES + 10),
     "line 3 is longer than 1 MiB"),
    (b"# target_unit=mm deviation_unit=um\ntarget,direction,run,deviation\n0,+,1,\xb5\n",
     "not UTF-8 text (byte 72 is 0xB5)"),
    (b"# target_unit=mm deviation_unit=um\ntarget,direction,run,deviation\n"
     + b"".join(b"%d,+,%d,1\n" % (i, 1 + 3 * i) for i in range(4)),
     "e.csv:6: run '10' is beyond the 4 readings in the file"),
    (b"# target_unit=mm deviation_unit=um\ntarget,direction,run,deviation\n0,+,1,1\n0,+,1,2\n",
     "two readings for target 0, direction +, run 1"),
])
def test_streamed_errors_name_the_problem(tmp_path, content, words):
    f = tmp_path / "e.csv"
    f.write_bytes(content)
    with pytest.raises(DataFormatError) as exc:
        pcsv.read_positioning_csv(f)
    assert words in str(exc.value) and str(f) in str(exc.value)


def test_a_table_of_mostly_missing_runs_is_refused_before_it_is_allocated(tmp_path):
    """Run numbers up to the number of readings at as many targets would make a table of
    readings x readings cells; it is refused by name instead of allocating it."""
    n = 200_000
    f = tmp_path / "sparse.csv"
    f.write_text("# target_unit=mm deviation_unit=um\ntarget,direction,run,deviation\n"
                 + "".join(f"{i},+,{i + 1},1\n" for i in range(n)))
    with pytest.raises(DataFormatError, match="almost all missing"):
        read_positioning(f)
