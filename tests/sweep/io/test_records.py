"""Bundled records against their README, and readers for PEER .AT2 and two-column files."""
import importlib.resources

import numpy as np
import pytest

from sweep.io import records
from sweep.io.records import RecordError, load_record, read_at2, read_record_file, read_two_column

G = 9.80665

# sweep/data/records/README.md: n, dt, PGA [gal], peak value [g] and its time [s]
README = [
    ("elcentro1940_ns", 2688, 0.02, 342.0, 0.3487, 2.12),
    ("elcentro1940_ew", 2674, 0.02, 210.0, 0.2141, 11.44),
    ("elcentro1940_ud", 2690, 0.02, 206.0, -0.2101, 0.98),
    ("taft1952_ew_s69e", 5437, 0.01, 176.8, -0.1803, 3.75),
]


@pytest.mark.parametrize("name, n, dt, pga_gal, peak_g, t_peak", README)
def test_bundled_records_match_readme(name, n, dt, pga_gal, peak_g, t_peak):
    rec = load_record(name)
    assert rec.name == name
    assert len(rec.samples) == n
    assert rec.dt == dt
    assert rec.pga * 100 == pytest.approx(pga_gal, abs=0.1)
    k = int(np.argmax(np.abs(rec.samples)))
    assert rec.samples[k] / G == pytest.approx(peak_g, abs=5e-5)
    assert k * rec.dt == pytest.approx(t_peak, abs=1e-9)
    assert "README" in rec.provenance


def test_first_samples_not_baseline_corrected():
    # README: El Centro NS starts at -1.4 gal, Taft EW at -0.55 gal
    assert load_record("elcentro1940_ns").samples[0] * 100 == pytest.approx(-1.4, abs=0.005)
    assert load_record("taft1952_ew").samples[0] * 100 == pytest.approx(-0.55, abs=0.005)


def test_alias_and_cache():
    assert load_record("taft1952_ew") is load_record("taft1952_ew_s69e")


def test_samples_are_read_only():
    with pytest.raises(ValueError):
        load_record("elcentro1940_ew").samples[0] = 1.0


def test_unknown_name_lists_known_ones():
    with pytest.raises(RecordError, match="elcentro1940_ns"):
        load_record("miyagi1978_ns")


def test_package_data_has_readme():
    folder = importlib.resources.files("sweep.data") / "records"
    assert "Polarity" in (folder / "README.md").read_text()
    assert sorted(p.name for p in folder.iterdir() if p.name.endswith(".txt")) == \
        sorted(f"{n}.txt" for n in records.BUNDLED)


def _write_at2(path, values_g, dt, header4):
    lines = ["PEER NGA STRONG MOTION DATABASE RECORD",
             "Test event 2024, Station X, 90",
             "ACCELERATION TIME SERIES IN UNITS OF G",
             header4]
    for i in range(0, len(values_g), 5):
        lines.append("".join(f"{v:15.7E}" for v in values_g[i:i + 5]))
    path.write_text("\n".join(lines) + "\n")


@pytest.mark.parametrize("header", ["NPTS=   {n}, DT=   .0100 SEC",
                                    "   {n}   .0100    NPTS, DT"])
def test_at2_round_trip(tmp_path, header):
    values = np.round(0.3 * np.sin(np.arange(23) * 0.7), 7)
    path = tmp_path / "RSN0_TEST.AT2"
    _write_at2(path, values, 0.01, header.format(n=len(values)))
    rec = read_at2(path)
    assert rec.dt == 0.01
    np.testing.assert_allclose(rec.samples, values * G, rtol=1e-12)
    assert "NPTS = 23" in rec.provenance
    assert read_record_file(path) is read_record_file(path)  # cached


def test_at2_errors(tmp_path):
    path = tmp_path / "bad.AT2"
    _write_at2(path, [0.1, 0.2, 0.3], 0.01, "NPTS=   4, DT=   .0100 SEC")
    with pytest.raises(RecordError, match="NPTS = 4, found 3"):
        read_at2(path)
    _write_at2(path, [0.1, 0.2, 0.3], 0.01, "no numbers here")
    with pytest.raises(RecordError, match="line 4 should give NPTS and DT"):
        read_at2(path)
    velocity = tmp_path / "vel.VT2"
    velocity.write_text("x\ny\nVELOCITY TIME SERIES IN UNITS OF CM/S\nNPTS= 1, DT= .01\n1\n")
    with pytest.raises(RecordError, match="not an acceleration"):
        read_at2(velocity)
    with pytest.raises(RecordError, match=r"bad.AT2: a PEER .AT2 file is in g, not gal"):
        read_record_file(tmp_path / "bad.AT2", "gal")


def test_two_column_units(tmp_path):
    path = tmp_path / "rec.txt"
    path.write_text("# time accel\n0.0 10\n0.005 -20\n0.010 30\n")
    rec = read_two_column(path, "gal")
    assert rec.dt == 0.005
    np.testing.assert_allclose(rec.samples, [0.1, -0.2, 0.3])
    np.testing.assert_allclose(read_two_column(path, "g").samples, [10 * G, -20 * G, 30 * G])
    np.testing.assert_allclose(read_two_column(path).samples, [10, -20, 30])


def test_two_column_nonuniform_is_resampled(tmp_path):
    t = np.array([0.0, 0.01, 0.03, 0.04, 0.05, 0.07, 0.08])
    path = tmp_path / "jitter.txt"
    np.savetxt(path, np.column_stack([t, 2.0 * t + 1.0]))  # linear, so resampling is exact
    rec = read_two_column(path)
    assert rec.dt == 0.01
    np.testing.assert_allclose(rec.samples, 2.0 * np.arange(9) * 0.01 + 1.0, rtol=1e-12)
    assert "resampled" in rec.provenance


def test_two_column_time_relative_to_first_row(tmp_path):
    path = tmp_path / "late.txt"
    np.savetxt(path, np.column_stack([[5.0, 5.02, 5.04], [1.0, 2.0, 3.0]]))
    rec = read_two_column(path)
    assert rec.dt == 0.02 and list(rec.samples) == [1.0, 2.0, 3.0]


def test_two_column_errors(tmp_path):
    one = tmp_path / "one.txt"
    one.write_text("0.1\n0.2\n")
    with pytest.raises(RecordError, match="expected two columns"):
        read_two_column(one)
    text = tmp_path / "text.txt"
    text.write_text("time accel\n")
    with pytest.raises(RecordError, match="cannot read as a two-column text file"):
        read_two_column(text)
    back = tmp_path / "back.txt"
    back.write_text("0 1\n0.02 1\n0.01 1\n")
    with pytest.raises(RecordError, match="times must increase"):
        read_two_column(back)
    with pytest.raises(RecordError, match="cannot read"):
        read_record_file(tmp_path / "missing.txt")
    with pytest.raises(RecordError, match="relative to the body"):
        read_two_column(back, "west")


@pytest.mark.parametrize("text, message", [
    ("0 0.1\n0.01 nan\n", "acceleration of data row 2 is not a finite number"),
    ("0 0.1\ninf 0.2\n", "time of data row 2 is not a finite number"),
    ("0 0.1\n0.01 1e400\n", "not a finite number: inf"),
    ("", "no data rows"),
])
def test_two_column_non_finite_or_empty(tmp_path, text, message):
    path = tmp_path / "r.txt"
    path.write_text(text)
    with pytest.raises(RecordError, match=message):
        read_two_column(path)


def test_resampling_bounded(tmp_path):
    """A few rows whose median step is tiny would make trillions of samples."""
    path = tmp_path / "r.txt"
    path.write_text("0 0.1\n1e-12 0.2\n2e-12 0.3\n3e-12 0.1\n1000 0.0\n")
    with pytest.raises(RecordError, match=rf"r.txt: .*dt = 1e-12 s would make 1e\+15 samples, "
                                          rf"more than {records.MAX_SAMPLES}"):
        read_two_column(path)


def test_only_regular_files(tmp_path):
    with pytest.raises(RecordError, match="not a regular file"):
        read_record_file("/dev/zero")
    with pytest.raises(RecordError, match="not a regular file"):
        read_record_file(tmp_path)
