"""Record files of the strong-motion networks: K-NET/KiK-net ASCII, COSMOS V2, CSMIP Volume 2,
one column of accelerations with dt, and how a file's format is told.

Every file is written here from a known signal through the format's own encoding (K-NET
integer counts and scale factor, COSMOS and CSMIP header counts and Fortran fields) and read
back."""
import numpy as np
import pytest

import sweep
from sweep.io import records
from sweep.io.formats import knet
from sweep.io.problems import FileProblems
from sweep.io.records import RecordError, detect_format, read_record_file

G = 9.80665
GAL = 0.01  # m/s^2


def _signal(n=500, dt=0.01, peak=120.0, frequency=2.0):
    """A 2 Hz sine growing linearly to about ``peak`` at the end (its peak comes last)."""
    t = dt * np.arange(n)
    return peak * (t / t[-1]) * np.sin(2 * np.pi * frequency * t + 0.3)


def _rows(values, per_line, field):
    return ["".join(field.format(v) for v in values[k:k + per_line])
            for k in range(0, len(values), per_line)]


# --- K-NET ----------------------------------------------------------------------------------

NUMERATOR, DENOMINATOR = 7845, 8223790  # gal per count: about 0.00095
OFFSET = 8000  # counts of the sensor at rest: the mean the reader removes


def _knet_counts(gal):
    return np.round(gal * DENOMINATOR / NUMERATOR).astype(int) + OFFSET


def _knet_text(gal, frequency=100, scale=f"{NUMERATOR}(gal)/{DENOMINATOR}", max_acc=None):
    counts = _knet_counts(gal)
    read_back = counts * NUMERATOR / DENOMINATOR
    peak = np.max(np.abs(read_back - read_back.mean()))
    values = ["2011/03/11 14:46:00", "38.103", "142.860", "24", "9.0", "MYG004", "38.7290",
              "141.0213", "230", "2011/03/11 14:46:49", f"{frequency}Hz",
              f"{len(gal) // frequency}", "N-S", scale,
              f"{peak if max_acc is None else max_acc:.3f}", "2011/03/11 14:46:34", ""]
    lines = [f"{label:<18}{value}" for label, value in zip(knet.LABELS, values)]
    return "\n".join(lines + _rows(counts, 8, "{:9d}")) + "\n"


def test_knet_round_trip(tmp_path):
    """Counts x scale factor, mean removed, gal -> m/s^2; 100 Hz -> dt = 0.01 s."""
    gal = _signal()
    path = tmp_path / "MYG0041103111446.NS"
    path.write_text(_knet_text(gal))
    rec = read_record_file(path)
    assert rec.dt == 0.01 and len(rec.samples) == len(gal)
    expected = _knet_counts(gal) * NUMERATOR / DENOMINATOR
    np.testing.assert_allclose(rec.samples, (expected - expected.mean()) * GAL, atol=1e-12)
    np.testing.assert_allclose(rec.samples, (gal - gal.mean()) * GAL, atol=1e-5)  # a count
    assert rec.pga == pytest.approx(np.max(np.abs(gal - gal.mean())) * GAL, abs=1e-5)
    assert "MYG004" in rec.provenance and "7845(gal)/8223790" in rec.provenance
    assert "mean of the whole record" in rec.provenance


def test_kiknet_surface_channel_at_200_hz(tmp_path):
    gal = _signal(n=800, dt=0.005)
    path = tmp_path / "IWTH251103111446.EW2"
    path.write_text(_knet_text(gal, frequency=200))
    rec = read_record_file(path)
    assert rec.dt == 0.005 and len(rec.samples) == 800


@pytest.mark.parametrize("change, message", [
    ({"scale": f"3920(gal)/{DENOMINATOR}"}, r"line 15: Max\. Acc\. = \S+ gal, but the data's "
                                             r"peak .* is \S+ gal, 50 % apart"),
    ({"max_acc": 150.0}, r"line 15: Max\. Acc\. = 150 gal, .* a wrong scale factor or a "
                         r"truncated file"),
])
def test_knet_max_acc_checked(tmp_path, change, message):
    path = tmp_path / "X.UD"
    path.write_text(_knet_text(_signal(), **change))
    with pytest.raises(RecordError, match=message):
        read_record_file(path)


def test_knet_truncated_file_refused(tmp_path):
    """The last quarter of the lines (and the peak with them) lost."""
    lines = _knet_text(_signal()).splitlines()
    path = tmp_path / "X.NS"
    path.write_text("\n".join(lines[:len(lines) - 16]) + "\n")
    with pytest.raises(RecordError, match="truncated file"):
        read_record_file(path)


def test_knet_errors_name_the_line(tmp_path):
    lines = _knet_text(_signal()).splitlines()
    path = tmp_path / "X.EW"
    bad = lines.copy()
    bad[22] = bad[22].replace(bad[22].split()[3], "abc")
    path.write_text("\n".join(bad) + "\n")
    with pytest.raises(RecordError, match=r"X.EW: line 23: expected 8 integers, got 'abc'"):
        read_record_file(path)
    bad = lines.copy()
    bad[30] = " ".join(bad[30].split()[:7])
    path.write_text("\n".join(bad) + "\n")
    with pytest.raises(RecordError, match="line 31: expected 8 integers, found 7"):
        read_record_file(path)
    bad = lines.copy()
    bad[10] = "Sampling Freq(Hz) fast"
    path.write_text("\n".join(bad) + "\n")
    with pytest.raises(RecordError, match=r"line 11: Sampling Freq\(Hz\) should be .*'fast'"):
        read_record_file(path)
    bad = lines.copy()
    bad[13] = "Scale Factr       1(gal)/2"
    path.write_text("\n".join(bad) + "\n")
    with pytest.raises(RecordError, match="line 14: expected the K-NET header label 'Scale"):
        read_record_file(path)


def test_knet_refuses_units_and_dt(tmp_path):
    path = tmp_path / "X.NS"
    path.write_text(_knet_text(_signal()))
    with pytest.raises(RecordError, match=r"X.NS: line 14: the header's Scale Factor gives the "
                                          r"accelerations in gal, not g \(units: g\)"):
        read_record_file(path, "g")
    assert read_record_file(path, "cm/s^2").units == "gal"  # the same unit, written otherwise
    with pytest.raises(RecordError, match="dt applies to one-column files only"):
        read_record_file(path, dt=0.01)


# --- COSMOS V2 ------------------------------------------------------------------------------

def _cosmos_channel(cm, dt, name, units=(4, "cm/sec2")):
    """One COSMOS V2 component: acceleration ``cm`` [cm/s^2] every ``dt``, then velocity and
    displacement blocks; values in 9-character fields that touch below -999.999."""
    code, unit = units
    n = len(cm)
    ints = [-999] * 100
    ints[:3] = [2, 1, code]
    reals = [-999.0] * 100
    reals[61], reals[62] = 1000 * dt, n * dt
    lines = ["Corrected acceleration    (Format v01.20 with 13 text lines) Src: tests",
             "Record of Test Earthquake of Mon Jan 17, 1994 12:30 UTC",
             "Hypocenter: 34.206 -118.554 H= 18km Mw=6.7", "Origin: 01/17/1994 12:30:55 UTC",
             "Statn No: 05-24514  Code:CE-24514  CGS  Test Station",
             "Coords: 34.3260 -118.4440  Site geology: Alluvium", "Recorder: test",
             "Rcrd start time: 01/17/1994 12:31:01.0 UTC",
             f"Sta Chan   1: {name} (Rcrd Chan  1) Location:", "Raw record length = 5 sec",
             "Processed: tests", "Record filtered below 0.10 Hz and above 46.0 Hz",
             "Values used when parameter or data value is unknown/unspecified:   -999, -999.0",
             " 100 Integer-header values follow on  10 lines, Format= (10I8)",
             *_rows(ints, 10, "{:8d}"),
             " 100 Real-header values follow on  20 lines, Format= (5F15.6)",
             *_rows(reals, 5, "{:15.6f}"),
             '   1 Comment line(s) follow, each starting with a "|":', "| written by the tests"]
    velocity = np.cumsum(cm) * dt
    for quantity, unit_code, series in (("acceleration", f"{unit}({code:02d})", cm),
                                        ("velocity", "cm/sec(05)", velocity),
                                        ("displacement", "cm(06)", np.cumsum(velocity) * dt)):
        lines.append(f"{n:8d} {quantity} pts, approx {n * dt:.0f} secs, units={unit_code},"
                     "Format=(8F9.3)")
        lines += _rows(series, 8, "{:9.3f}")
        lines.append(f"End-of-data for Chan  1 {quantity}")
    return lines


def test_cosmos_round_trip(tmp_path):
    """A 1.2 g record: negative values fill their 9 characters and touch their neighbours."""
    cm = _signal(peak=1200.0)
    path = tmp_path / "CE24514.V2c"
    path.write_text("\n".join(_cosmos_channel(cm, 0.01, "360 deg")) + "\n")
    assert "-1" in path.read_text() and "9-1" in path.read_text().replace(" ", "")
    rec = read_record_file(path)
    assert rec.dt == 0.01 and len(rec.samples) == 500
    np.testing.assert_allclose(rec.samples, np.round(cm, 3) * GAL, atol=1e-12)
    assert "COSMOS V2" in rec.provenance and "Test Station" in rec.provenance
    assert "cm/s^2" in rec.provenance


def test_cosmos_units_from_the_header(tmp_path):
    g = _signal(peak=0.5)
    path = tmp_path / "in_g.v2"
    path.write_text("\n".join(_cosmos_channel(g, 0.02, "Up", units=(2, "g"))) + "\n")
    rec = read_record_file(path)
    assert rec.dt == 0.02
    np.testing.assert_allclose(rec.samples, np.round(g, 3) * G, atol=1e-12)
    path.write_text("\n".join(_cosmos_channel(g, 0.02, "Up", units=(5, "cm/sec"))) + "\n")
    with pytest.raises(RecordError, match=r"line 48: units code 05 is not an acceleration unit"):
        read_record_file(path)
    path.write_text("\n".join(_cosmos_channel(g, 0.02, "Up", units=(2, "g"))) + "\n")
    with pytest.raises(RecordError, match=r"line 48: the header gives the accelerations in g, "
                                          r"not gal"):
        read_record_file(path, "gal")


def test_cosmos_several_components(tmp_path):
    path = tmp_path / "two.V2"
    north, up = _signal(peak=300.0), _signal(peak=100.0)
    path.write_text("\n".join(_cosmos_channel(north, 0.01, "360 deg")
                              + _cosmos_channel(up, 0.01, "Up")) + "\n")
    with pytest.raises(RecordError, match=r"holds 2 components \(1 '360 deg', 2 'Up'\); give "
                                          "component"):
        read_record_file(path)
    np.testing.assert_allclose(read_record_file(path, component="UP").samples,
                               np.round(up, 3) * GAL, atol=1e-12)
    np.testing.assert_array_equal(read_record_file(path, component=1).samples,
                                  read_record_file(path, component="360").samples)


def test_cosmos_errors_name_the_line(tmp_path):
    lines = _cosmos_channel(_signal(peak=300.0), 0.01, "360 deg")
    path = tmp_path / "bad.V2"
    bad = lines.copy()
    bad[60] = bad[60][:9] + "      abc" + bad[60][18:]
    path.write_text("\n".join(bad) + "\n")
    with pytest.raises(RecordError, match=r"bad.V2: line 61: 'abc' is not a number"):
        read_record_file(path)
    bad = lines.copy()
    bad[60] = bad[60][:63]
    path.write_text("\n".join(bad) + "\n")
    with pytest.raises(RecordError, match="line 61: expected 8 values 9 characters wide "
                                          r"\(block of line 48\), found 7"):
        read_record_file(path)
    bad = lines.copy()
    bad[60] = bad[60][:9] + "      nan" + bad[60][18:]
    path.write_text("\n".join(bad) + "\n")
    with pytest.raises(RecordError, match="line 61: value 98 is not a finite number: nan"):
        read_record_file(path)
    bad = lines.copy()
    bad[37] = bad[37].replace("      10.000000", "    -999.000000")  # real 62: dt [ms]
    path.write_text("\n".join(bad) + "\n")
    with pytest.raises(RecordError, match="line 38: real-header value 62, the sample step"):
        read_record_file(path)
    path.write_text("\n".join(lines[:55]) + "\n")
    with pytest.raises(RecordError, match="line 55: the file ends inside the block of 500 "
                                          "values announced on line 48"):
        read_record_file(path)
    path.write_text("Uncorrected acceleration  (Format v01.20 with 13 text lines)\n" +
                    "\n".join(lines[1:]) + "\n")
    with pytest.raises(RecordError, match="line 1: 'Uncorrected acceleration': only "
                                          "corrected acceleration"):
        read_record_file(path)


# --- CSMIP Volume 2 -------------------------------------------------------------------------

CSMIP_NAMES = ("360 Deg", "Up", "90 Deg")


def _csmip_channel(number, name, cm, dt, old=False):
    """One CSMIP Volume 2 channel: 25 text lines, 100 integers (16I5), 100 reals (8F10),
    then acceleration, velocity and displacement blocks; ``old``: upper case, the units in
    parentheses and no format on the blocks' first lines, as in the 1980s."""
    n = len(cm)
    text = [f"Corrected accelerogram   89146-L2500-12044.02       Chan {number:2d}: "
            f"{name:<9} from",
            "Uncorrected Accelerogram Data             Processed: 02/13/12, CGS",
            "Record of Mon Feb 13, 2012 13:06:45.0 PST", "CSMIP Preliminary Processing",
            "89146-L2500-12044.02   Start time:  2/13/12, 21:06:45.0 UTC (GPS)",
            "Station No. 89146   40.941N, 123.633W      Etna  s/n 2500  (3 Chns of  3 at Sta)",
            "Willow Creek                              CGS"]
    text += [f"text line {k}" for k in range(len(text) + 1, 26)]
    reals = [-999.0] * 100
    reals[60] = dt
    step = f"{dt:.3f}".lstrip("0")
    lines = text + _rows([number] + [0] * 99, 16, "{:5d}") + _rows(reals, 8, "{:10.5f}")
    velocity = np.cumsum(cm) * dt
    for quantity, unit, series in (("accel", "cm/sec/sec" if old else "cm/sec2", cm),
                                   ("veloc", "cm/sec", velocity),
                                   ("displ", "cm", np.cumsum(velocity) * dt)):
        lines.append(f"{n:5d} POINTS OF {quantity} DATA EQUALLY SPACED AT {step:>5} SEC.  "
                     f"(UNITS: {unit})" if old else
                     f"{n:6d} points of {quantity} data equally spaced at {step:>6} sec, in "
                     f"{unit}. (8f10.3)")
        lines += _rows(series, 8, "{:10.3f}")
    lines.append(f"/&  ----------  End of data for channel {number:2d}  ----------")
    return [line.upper() for line in lines] if old else lines


@pytest.fixture
def csmip(tmp_path):
    """A CSMIP Volume 2 file of three channels, peaks 300, 100 and 200 gal, dt = 0.01 s."""
    path = tmp_path / "CE89146.V2"
    signals = [_signal(peak=peak) for peak in (300.0, 100.0, 200.0)]
    lines = sum((_csmip_channel(k, name, s, 0.01)
                 for k, (name, s) in enumerate(zip(CSMIP_NAMES, signals), 1)), [])
    path.write_text("\n".join(lines) + "\n")
    return path, signals, lines


def test_csmip_three_components(csmip):
    path, signals, _ = csmip
    with pytest.raises(RecordError, match=r"holds 3 components \(1 '360 Deg', 2 'Up', "
                                          r"3 '90 Deg'\)"):
        read_record_file(path)
    for component, k in ((1, 0), ("up", 1), ("90 deg", 2), ("90", 2), (3, 2)):
        rec = read_record_file(path, component=component)
        assert rec.dt == 0.01 and len(rec.samples) == 500
        np.testing.assert_allclose(rec.samples, np.round(signals[k], 3) * GAL, atol=1e-12)
    assert "component 3 of 3 (90 Deg)" in rec.provenance and "Willow Creek" in rec.provenance
    for wrong in (4, "45 deg"):
        with pytest.raises(RecordError, match=f"component {wrong!r} does not pick one of the "
                                              "file's 3 components"):
            read_record_file(path, component=wrong)


def test_csmip_older_layout(tmp_path):
    """Upper case, "(UNITS: CM/SEC/SEC)" and no format (CSMIP's 8F10 is read), a DOS
    end-of-file mark after the last channel."""
    signals = [_signal(peak=peak) for peak in (250.0, 90.0)]
    lines = sum((_csmip_channel(k, name, s, 0.02, old=True)
                 for k, (name, s) in enumerate(zip(("90 Deg", "Up"), signals), 1)), [])
    path = tmp_path / "CE36456.V2"
    path.write_text("\n".join(lines) + "\n" + "\x1a" * 80)
    assert "(UNITS: CM/SEC/SEC)" in lines[45]
    rec = read_record_file(path, component="up")
    assert rec.dt == 0.02 and len(rec.samples) == 500
    np.testing.assert_allclose(rec.samples, np.round(signals[1], 3) * GAL, atol=1e-12)


def test_csmip_errors_name_the_line(csmip):
    path, _, lines = csmip
    bad = lines.copy()
    bad[50] = bad[50][:20] + "    12.3x5" + bad[50][30:]
    path.write_text("\n".join(bad) + "\n")
    with pytest.raises(RecordError, match=r"line 51: '12.3x5' is not a number"):
        read_record_file(path, component=1)
    bad = lines.copy()
    bad[45] = bad[45].replace("accel", "acel")
    path.write_text("\n".join(bad) + "\n")
    with pytest.raises(RecordError, match=r"line 46: expected '12000 points of accel data"):
        read_record_file(path, component=1)


# --- one column with dt ---------------------------------------------------------------------

def test_single_column_with_dt(tmp_path):
    g = _signal(peak=0.3)
    path = tmp_path / "motion.txt"
    path.write_text("# accelerations in g, five to a line\n" + "\n".join(_rows(g, 5, " {:.17g}")))
    rec = read_record_file(path, "g", dt=0.005)
    assert rec.dt == 0.005 and len(rec.samples) == 500
    np.testing.assert_allclose(rec.samples, g * G, rtol=1e-15)
    one = tmp_path / "one.txt"
    one.write_text("\n".join(f"{v:.17g}" for v in g) + "\n")
    np.testing.assert_array_equal(read_record_file(one, "g", dt=0.005).samples, rec.samples)
    with pytest.raises(RecordError, match=r"one.txt: a file of accelerations alone has no "
                                          r"times: give dt"):
        read_record_file(one)
    one.write_text("0.1\n0.2\n0.3 zz\n")
    with pytest.raises(RecordError, match="one.txt: line 3: 'zz' is not a number"):
        read_record_file(one, dt=0.01)


def test_dt_refused_where_the_file_has_its_own(tmp_path):
    two = tmp_path / "two.txt"
    two.write_text("0 1\n0.01 2\n0.02 3\n")
    with pytest.raises(RecordError, match="dt applies to one-column files only: a two-column "
                                          "file gives its times"):
        read_record_file(two, dt=0.01)
    pairs = read_record_file(two, format="column", dt=0.01)  # accelerations, two to a line
    assert list(pairs.samples) == [0, 1, 0.01, 2, 0.02, 3]
    with pytest.raises(RecordError, match="dt must be a positive number of seconds"):
        read_record_file(two, format="column", dt=0.0)


def test_two_column_error_names_the_line(tmp_path):
    path = tmp_path / "rec.txt"
    path.write_text("# t a\n0 1\n\n0.01 2\n0.02 2 2\n")
    with pytest.raises(RecordError, match="rec.txt: line 5: expected two columns"):
        read_record_file(path)


# --- telling the format ---------------------------------------------------------------------

@pytest.mark.parametrize("name, text, expected", [
    ("a.AT2", "anything", "at2"),
    ("a.v2", "anything", "cosmos"),
    ("a.V2c", "anything", "cosmos"),
    ("a.NS", "anything", "knet"),
    ("a.ud1", "anything", "knet"),
    ("a.txt", "Origin Time       2011/03/11 14:46:00\n", "knet"),
    ("a.dat", "Corrected acceleration    (Format v01.20 with 13 text lines)\n", "cosmos"),
    ("a.txt", "Corrected accelerogram   89146-L2500  Chan  1: 360 Deg\n", "cosmos"),
    ("a.asc", "Converted from COSMOS\n", "cosmos"),
    ("a.txt", "# time accel\n\n0.0 0.1\n0.01 0.2\n", "columns"),
    ("a.txt", "0.1\n0.2\n", "column"),
    ("a.txt", "0.1 0.2 0.3\n0.4\n", "column"),
])
def test_detect_format(tmp_path, name, text, expected):
    path = tmp_path / name
    path.write_text(text)
    assert detect_format(path) == expected


def test_detect_format_refuses_what_it_does_not_know(tmp_path):
    path = tmp_path / "a.txt"
    path.write_text("# header\nSTATION XYZ 2011\n")
    with pytest.raises(RecordError, match=r"a.txt: line 2: not the start of a record file"):
        read_record_file(path)
    path.write_text("# only a comment\n")
    with pytest.raises(RecordError, match="no data rows"):
        read_record_file(path)


def test_explicit_format_and_cache(tmp_path):
    """A K-NET file under another name, read by its content or by an explicit format: cached
    by path and options."""
    path = tmp_path / "station.dat"
    path.write_text(_knet_text(_signal()))
    first = read_record_file(path)
    assert read_record_file(path) is first
    assert read_record_file(path, format="knet") is not first
    np.testing.assert_array_equal(read_record_file(path, format="knet").samples, first.samples)
    with pytest.raises(RecordError, match="line 1: 'Origin' is not a number"):
        read_record_file(path, format="column", dt=0.01)
    with pytest.raises(RecordError, match="unknown format 'sac'"):
        read_record_file(path, format="sac")
    with pytest.raises(RecordError, match="component applies to COSMOS and CSMIP files only"):
        read_record_file(path, component=1)


def test_records_module_keeps_its_names():
    assert records.read_two_column.__module__ == "sweep.io.formats.columns"
    assert records.read_at2.__module__ == "sweep.io.formats.at2"
    assert records.FORMATS == ("at2", "knet", "cosmos", "columns", "column")


# --- in scenes ------------------------------------------------------------------------------

def _scene(horizontal):
    return {"body": {"B": 0.1, "H": 0.3}, "contact": {"mu": 10},
            "excitation": {"horizontal": {"kind": "record", "pga": "0.4 g", **horizontal}},
            "solver": {"t_end": 6.0}}


def _files(tmp_path, csmip):
    """``{format: (file, options)}``: one file in each format, peak 1.2 m/s^2 or more."""
    knet_path = tmp_path / "MYG004.EW"
    knet_path.write_text(_knet_text(_signal()))
    cosmos_path = tmp_path / "CE24514.V2c"
    cosmos_path.write_text("\n".join(_cosmos_channel(_signal(peak=300.0), 0.01, "90 deg")))
    column = tmp_path / "column.txt"
    column.write_text("\n".join(_rows(_signal(peak=0.2), 8, " {:.6f}")))
    return {"knet": (knet_path, {}), "cosmos": (cosmos_path, {}),
            "csmip": (csmip[0], {"component": "up"}),
            "column": (column, {"dt": "10 ms", "units": "g"})}


@pytest.mark.parametrize("kind", ["knet", "cosmos", "csmip", "column"])
def test_record_formats_in_a_scene(tmp_path, csmip, kind):
    """Each file drives the same motion as a two-column file of the samples it was read into."""
    path, options = _files(tmp_path, csmip)[kind]
    result = sweep.simulate(_scene({"path": str(path), **options}))
    rec = read_record_file(path, options.get("units"), component=options.get("component"),
                           dt=0.01 if "dt" in options else None)
    two = tmp_path / "same.txt"
    np.savetxt(two, np.column_stack([rec.dt * np.arange(len(rec.samples)), rec.samples]),
               fmt="%.17g")
    same = sweep.simulate(_scene({"path": str(two)}))
    assert result.status == "ok" and result.max_abs_theta > 0.01
    assert result.impact_times == same.impact_times
    assert result.max_abs_theta == same.max_abs_theta


def test_scene_options_checked(tmp_path, csmip):
    files = _files(tmp_path, csmip)
    cases = [({"name": "elcentro1940_ns", "dt": 0.01}, "excitation.horizontal.dt",
              "given for a path: file only"),
             ({"path": str(files["column"][0])}, "excitation.horizontal.path", "give dt"),
             ({"path": str(files["knet"][0]), "dt": 0.01}, "excitation.horizontal.path",
              "dt applies to one-column files only"),
             ({"path": str(csmip[0])}, "excitation.horizontal.path", "holds 3 components"),
             ({"path": str(csmip[0]), "component": 0}, "excitation.horizontal.component",
              "start at 1"),
             ({"path": str(csmip[0]), "format": "sac"}, "excitation.horizontal.format",
              "'at2', 'knet', 'cosmos', 'columns' or 'column'")]
    for horizontal, where, message in cases:
        with pytest.raises(FileProblems) as err:
            sweep.simulate(_scene(horizontal))
        assert any(p.path == where and message in p.message for p in err.value.problems), \
            (horizontal, str(err.value))
