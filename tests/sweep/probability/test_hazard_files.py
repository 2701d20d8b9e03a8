"""Hazard curve files read as they are meant: every header form OpenQuake has written (the
first lines of OpenQuake's own expected files, a few columns kept), the units, IM, kind and
investigation time a two-column file states (a given one that contradicts it refused), files
that are missing or binary, and levels implausible in the units read warned.  Each value is
checked against the numbers written here: levels × the unit's factor, λ = −ln(1 − P)/T."""
import csv
import io
import json
import math
import warnings

import numpy as np
import pytest
import yaml

from sweep.io.problems import FileProblems, InputWarning
from sweep.io.risk_schema import load_risk
from sweep.probability import hazard_curve as hc
from sweep.probability import hazard_files as hf
from sweep.probability.risk_inputs import checked_hazard
from sweep.risk import main

G = 9.80665


def _rates(poes, years):
    return [-math.log1p(-p) / years for p in poes]


# (label, the file's first lines, im, investigation time, levels in g, P): OpenQuake's
# qa_tests_data/classical/<case>/expected/<file> at the version named, a few columns kept
OPENQUAKE = [
    ("case_1 hazard_curve-PGA.csv (2.x: imt in double quotes)",
     "# source_model_tree_path=('b1',), gsim_tree_path=('b1',), investigation_time=1.0,"
     "imt=\"PGA\"\nlon,lat,depth,poe-0.1,poe-0.4,poe-0.6\n"
     "0.00000,0.00000,-0.10000,4.528811E-01,5.589804E-02,5.585141E-03\n",
     "pga", 1.0, [0.1, 0.4, 0.6], [4.528811E-01, 5.589804E-02, 5.585141E-03]),
    ("case_14 ...AbrahamsonSilva2008.csv (a checksum after imt)",
     "# source_model_tree_path=('simple', 'fault'), gsim_tree_path=('AbrahamsonSilva2008',), "
     "investigation_time=50.0, imt=\"PGA\", checksum=2580379596\n"
     "lon,lat,depth,poe-0.0050000,poe-0.0070000,poe-0.0098000\n"
     "-122.50000,38.10000,0.00000,8.585606E-01,8.430470E-01,8.118057E-01\n",
     "pga", 50.0, [0.005, 0.007, 0.0098], [8.585606E-01, 8.430470E-01, 8.118057E-01]),
    ("case_13 hazard_curve-mean_PGA.csv (a statistic first)",
     "# mean, investigation_time=50.0, imt=\"PGA\", checksum=752446534\n"
     "lon,lat,depth,poe-0.0050000,poe-0.0070000,poe-0.0098000\n"
     "-122.34000,37.72000,0.00000,8.567829E-01,8.461299E-01,8.308143E-01\n",
     "pga", 50.0, [0.005, 0.007, 0.0098], [8.567829E-01, 8.461299E-01, 8.308143E-01]),
    ("case_15 hazard_curve-max-SA(0.1).csv (imt unquoted)",
     "# max, investigation_time=50.0,imt=SA(0.1)\nlon,lat,depth,poe-0.05,poe-0.1,poe-0.15\n"
     "-0.10000,0.00000,0.00000,9.990621E-01,9.964213E-01,9.879026E-01\n",
     "sa(0.1)", 50.0, [0.05, 0.1, 0.15], [9.990621E-01, 9.964213E-01, 9.879026E-01]),
    ("case_11 quantile_curve-0.1.csv (P = 0 at the last level)",
     "# quantile-0.1, investigation_time=1.0,imt=\"PGA\"\nlon,lat,depth,poe-0.1,poe-0.4,poe-0.6,"
     "poe-1.0\n0.00000,0.00000,0.00000,5.527092E-03,4.216419E-04,5.751541E-05,0.000000E+00\n",
     "pga", 1.0, [0.1, 0.4, 0.6], [5.527092E-03, 4.216419E-04, 5.751541E-05]),
    ("case_2 hazard_curve-smltp_b1-gsimltp_b1.csv (<IMT>-<level>:float32 columns)",
     "# source_model_tree_path=('b1',), gsim_tree_path=('b1',), investigation_time=1.0,imt=PGA"
     "\nlon,lat,depth,PGA-0.1:float32,PGA-0.4:float32,PGA-0.6:float32,PGA-1.0:float32\n"
     "0.00000,0.00000,0.00000,9.940266E-03,7.535517E-04,9.690080E-05,0.000000E+00\n",
     "pga", 1.0, [0.1, 0.4, 0.6], [9.940266E-03, 7.535517E-04, 9.690080E-05]),
    ("case_10 hazard_curve-smltp_b1_b3-gsimltp_b1.csv (no imt: <IMT>-<level> columns)",
     "# source_model_tree_path=('b1', 'b3'), gsim_tree_path=('b1',), investigation_time=1.0\n"
     "lon,lat,PGA-0.1,PGA-0.4,PGA-0.6,PGA-1.0\n"
     "0.00000,0.00000,4.300039E-02,1.196587E-03,7.371466E-05,0.000000E+00\n",
     "pga", 1.0, [0.1, 0.4, 0.6], [4.300039E-02, 1.196587E-03, 7.371466E-05]),
    ("case_15 hazard_curve-mean-PGA.csv (3.7: generated_by, a CSV cell)",
     "#,,,,,,,,,\"generated_by='OpenQuake engine 3.7.0-git5e91b20b88', start_date='2019-09-05"
     "T06:13:51', checksum=905885649, kind='mean', investigation_time=50.0, imt='PGA'\"\n"
     "lon,lat,depth,poe-0.0500000,poe-0.1000000,poe-0.1500000\n"
     "-0.10000,0.00000,0.00000,6.135122E-01,5.289103E-01,4.375274E-01\n",
     "pga", 50.0, [0.05, 0.1, 0.15], [6.135122E-01, 5.289103E-01, 4.375274E-01]),
    ("case_13 hazard_curve-mean-PGA.csv (3.26)",
     "#,,,,,,,,,,,,\"generated_by='OpenQuake engine 3.26.0-git968c3f72e4', start_date='2026-05-"
     "14T23:48:51', checksum=1118114606, kind='mean', investigation_time=1.0, imt='PGA'\"\n"
     "lon,lat,depth,poe-0.0100000,poe-0.0215443,poe-0.0464159\n"
     "-65.00000,0.00000,0.00000,1.252023E-02,1.212788E-02,1.046463E-02\n",
     "pga", 1.0, [0.01, 0.0215443, 0.0464159], [1.252023E-02, 1.212788E-02, 1.046463E-02]),
]


@pytest.mark.parametrize("label, text, im, years, levels_g, poes", OPENQUAKE,
                         ids=[case[0].split(" (")[0] for case in OPENQUAKE])
def test_every_header_openquake_has_written_reads(tmp_path, label, text, im, years, levels_g,
                                                  poes):
    path = tmp_path / "hazard_curve.csv"
    path.write_text(text)
    curve = hf.read_openquake_csv(path)
    assert curve.im == im
    np.testing.assert_allclose(curve.levels, np.array(levels_g) * G, rtol=1e-12)
    np.testing.assert_allclose(curve.rates, _rates(poes, years), rtol=1e-12)


def test_a_comment_cell_with_its_quotes_doubled_reads(tmp_path):
    """A comment written as a CSV cell doubles the quotes inside it (imt=""PGA"")."""
    cell = io.StringIO()
    csv.writer(cell).writerow(["#", "", "", "investigation_time=50.0, imt=\"SA(0.2)\""])
    assert 'imt=""SA(0.2)""' in cell.getvalue()
    path = tmp_path / "c.csv"
    path.write_text(cell.getvalue() + "lon,lat,poe-0.1,poe-0.2\n0,0,0.5,0.1\n")
    curve = hf.read_openquake_csv(path)
    assert curve.im == "sa(0.2)"
    np.testing.assert_allclose(curve.rates, _rates([0.5, 0.1], 50.0), rtol=1e-12)


def test_a_file_of_several_imts_takes_the_one_asked(tmp_path):
    path = tmp_path / "hazard_curve-mean.csv"
    path.write_text("# mean, investigation_time=50.0\n"
                    "lon,lat,PGA-0.005,PGA-0.007,SA(0.2)-0.005,SA(0.2)-0.007\n"
                    "-122.34000,37.72000,8.567724E-01,8.461150E-01,8.661472E-01,8.638480E-01\n")
    curve = hf.read_openquake_csv(path, im="sa(0.2)")
    np.testing.assert_allclose(curve.levels, [0.005 * G, 0.007 * G], rtol=1e-12)
    np.testing.assert_allclose(curve.rates, _rates([8.661472E-01, 8.638480E-01], 50.0),
                               rtol=1e-12)
    with pytest.raises(hc.HazardFileError, match=r"curves of pga, sa\(0.2\): say which") as err:
        hf.read_openquake_csv(path)
    assert err.value.key == "im"


@pytest.mark.parametrize("first, message", [
    ("#,,,\"generated_by='x', kind='mean', imt='PGA'\"", "investigation_time not found"),
    ("# investigation_time=abc, imt='PGA'", "not a number"),
    ("# investigation_time=0, imt='PGA'", "must be a positive number of years"),
    ("# investigation_time=50.0", "imt not found"),
    ("# investigation_time=50.0, imt='IA'", "unknown intensity measure 'IA'"),
    ("lon,lat,poe-0.1,poe-0.2", "not an OpenQuake hazard curve"),
])
def test_a_broken_openquake_comment_is_one_problem(tmp_path, first, message):
    path = tmp_path / "c.csv"
    path.write_text(first + "\nlon,lat,poe-0.1,poe-0.2\n0,0,0.5,0.1\n")
    with pytest.raises(hc.HazardFileError, match=message):
        hf.read_openquake_csv(path)


# (header, levels written, im, levels in SI): the name of the first column states the unit
NAMED_UNITS = [
    ("pga_g,annual_rate", "0.1,0.2", "pga", [0.1 * G, 0.2 * G]),
    ("pga [g],annual_rate", "0.1,0.2", "pga", [0.1 * G, 0.2 * G]),
    ("pga(g),annual_rate", "0.1,0.2", "pga", [0.1 * G, 0.2 * G]),
    ("PGA (cm/s^2),annual_rate", "100,200", "pga", [1.0, 2.0]),
    ("sa(0.2)_g,annual_rate", "0.1,0.2", "sa(0.2)", [0.1 * G, 0.2 * G]),
    ("SA(0.2) [g] annual_rate", "0.1,0.2", "sa(0.2)", [0.1 * G, 0.2 * G]),
    ("pga_gal;rate", "100,200", "pga", [1.0, 2.0]),
    ("PGV_cm/s\tannual_rate", "10,20", "pgv", [0.1, 0.2]),
]


@pytest.mark.parametrize("header, written, im, levels", NAMED_UNITS,
                         ids=[case[0] for case in NAMED_UNITS])
def test_the_header_names_the_im_and_its_units(tmp_path, header, written, im, levels):
    path = tmp_path / "c.txt"
    path.write_text(f"{header}\n" + "".join(f"{x} {r}\n" for x, r in
                                            zip(written.split(","), (1e-2, 1e-3))))
    curve = hf.read_columns(path)
    assert curve.im == im
    np.testing.assert_allclose(curve.levels, levels, rtol=1e-12)
    np.testing.assert_allclose(curve.rates, [1e-2, 1e-3])


def test_a_units_comment_is_read_and_a_given_unit_must_agree(tmp_path):
    path = tmp_path / "c.txt"
    path.write_text("# site X\n# units: m/s^2\npga,annual_rate\n1.0,1e-2\n4.0,1e-4\n")
    np.testing.assert_allclose(hf.read_columns(path).levels, [1.0, 4.0])
    np.testing.assert_allclose(hf.read_columns(path, "pga", "m/s2").levels, [1.0, 4.0])
    with pytest.raises(hc.HazardFileError) as err:
        hf.read_columns(path, "pga", "g")
    assert err.value.key == "units" and "m/s^2" in str(err.value)
    with pytest.raises(hc.HazardFileError) as err:
        hf.read_columns(path, "pgv")
    assert err.value.key == "im"


def test_gal_and_cm_s2_agree(tmp_path):
    path = tmp_path / "c.txt"
    path.write_text("pga [gal],rate\n100,1e-2\n300,1e-4\n")
    np.testing.assert_allclose(hf.read_columns(path, units="cm/s^2").levels, [1.0, 3.0])


def test_a_file_that_says_two_units_is_refused(tmp_path):
    path = tmp_path / "c.txt"
    path.write_text("# units: g\npga_m/s^2,annual_rate\n1.0,1e-2\n4.0,1e-4\n")
    with pytest.raises(hc.HazardFileError, match="disagree") as err:
        hf.read_columns(path)
    assert err.value.key is None


def test_neither_file_nor_caller_stating_units_or_im_is_refused(tmp_path):
    path = tmp_path / "c.txt"
    path.write_text("0.1 1e-2\n0.2 1e-3\n")
    for given, key in (({}, "im"), ({"im": "pga"}, "units")):
        with pytest.raises(hc.HazardFileError, match="required") as err:
            hf.read_columns(path, **given)
        assert err.value.key == key
    np.testing.assert_allclose(hf.read_columns(path, "pga", "g").rates, [1e-2, 1e-3])


# (second column's name, a comment, investigation time the test expects)
POE_NAMES = [
    ("poe", "# investigation_time: 50", 50.0),
    ("probability", "# investigation time = 50 years", 50.0),
    ("prob", "# Investigation_Time: 1", 1.0),
    ("poe_50yr", "", 50.0),
    ("PoE in 50 years", "", 50.0),
    ("poe (1 yr)", "", 1.0),
]


@pytest.mark.parametrize("name, comment, years", POE_NAMES, ids=[n for n, _, _ in POE_NAMES])
def test_the_header_says_probabilities_and_their_time(tmp_path, name, comment, years):
    path = tmp_path / "c.txt"
    path.write_text(f"{comment}\npga_g,{name}\n0.1,0.5\n0.2,0.1\n0.4,0.0\n")
    curve = hf.read_columns(path)
    np.testing.assert_allclose(curve.levels, [0.1 * G, 0.2 * G])  # P = 0 dropped
    np.testing.assert_allclose(curve.rates, _rates([0.5, 0.1], years), rtol=1e-12)


def test_probabilities_without_a_time_or_with_another_are_refused(tmp_path):
    path = tmp_path / "c.txt"
    path.write_text("pga_g,poe\n0.1,0.5\n0.2,0.1\n")
    with pytest.raises(hc.HazardFileError, match="investigation time") as err:
        hf.read_columns(path)
    assert err.value.key == "investigation_time"
    np.testing.assert_allclose(hf.read_columns(path, investigation_time=10.0).rates,
                               _rates([0.5, 0.1], 10.0), rtol=1e-12)
    path.write_text("pga_g,poe_50yr\n0.1,0.5\n0.2,0.1\n")
    with pytest.raises(hc.HazardFileError, match="50") as err:
        hf.read_columns(path, investigation_time=1.0)
    assert err.value.key == "investigation_time"
    with pytest.raises(hc.HazardFileError, match="poe") as err:
        hf.read_columns(path, kind="annual_rate")
    assert err.value.key == "kind"


@pytest.mark.parametrize("name", ["annual_rate", "rate", "AFE", "rate [1/yr]", "lambda"])
def test_the_header_says_annual_rates(tmp_path, name):
    path = tmp_path / "c.txt"
    path.write_text(f"pga_g,{name}\n0.1,0.5\n0.2,0.1\n")
    np.testing.assert_allclose(hf.read_columns(path).rates, [0.5, 0.1])
    with pytest.raises(hc.HazardFileError) as err:
        hf.read_columns(path, investigation_time=50.0)  # that is: probabilities
    assert err.value.key == "kind"


def test_written_columns_read_back_without_a_word(tmp_path):
    levels = np.geomspace(0.05, 0.5, 6)  # m/s, PGV
    curve = hc.HazardCurve("pgv", levels, 1e-2 * (levels / 0.05) ** -2.0)
    back = hf.read_columns(hf.write_columns(tmp_path / "c.txt", curve))
    assert back.im == "pgv"
    np.testing.assert_allclose(back.levels, levels, rtol=1e-7)
    np.testing.assert_allclose(back.rates, curve.rates, rtol=1e-7)


# (im, levels written, unit read, a word of the warning; None: no warning).  Bounds: above
# 10 g or all below 0.001 g for pga and sa, above 1000 cm/s or all below 0.1 cm/s for pgv
PLAUSIBLE = [
    ("pga", [0.5, 48.0], "g", "above 10 g"),
    ("pga", [0.5, 9.0], "g", None),
    ("sa(0.3)", [1e-5, 5e-4], "g", "below 0.001 g"),
    ("pga", [0.01, 0.05], "m/s^2", None),  # 0.001 g to 0.005 g
    ("pgv", [5.0, 2000.0], "cm/s", "above 1000 cm/s"),
    ("pgv", [0.01, 0.09], "cm/s", "below 0.1 cm/s"),
    ("pgv", [0.5, 300.0], "cm/s", None),
]


@pytest.mark.parametrize("im, written, unit, word", PLAUSIBLE)
def test_levels_implausible_in_the_units_read_are_warned(tmp_path, im, written, unit, word):
    path = tmp_path / "c.txt"
    path.write_text("".join(f"{x} {r}\n" for x, r in zip(written, (1e-2, 1e-4))))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        hf.read_columns(path, im, unit)
    said = [str(w.message) for w in caught if issubclass(w.category, InputWarning)]
    if word is None:
        assert said == []
    else:
        assert len(said) == 1 and word in said[0] and str(path) in said[0]


def test_binary_and_non_utf8_files_are_one_problem(tmp_path):
    for name, data, word in (("nul.txt", b"0.1 1e-2\n\0\x01\x02", "NUL byte"),
                             ("latin1.txt", "pga_g,r\xe9el\n".encode("latin-1"), "UTF-8")):
        (tmp_path / name).write_bytes(data)
        for read in (hf.read_columns, hf.read_openquake_csv, hf.read_usgs_json):
            with pytest.raises(hc.HazardFileError, match=word):
                read(tmp_path / name)


# --- the command line -----------------------------------------------------------------------

K0, K = 2e-4, 2.8  # λ(x) = K0 x^-K, x in m/s²
LEVELS_G = np.geomspace(0.005, 5.0, 150)


def _power_law_poe(years):
    return -np.expm1(-years * K0 * (LEVELS_G * G) ** -K)


def _run(args, capsys):
    """(exit status, stdout, stderr) of ``python -m sweep.risk args``."""
    try:
        status = main([str(a) for a in args])
    except SystemExit as end:
        status = end.code
    out, err = capsys.readouterr()
    return status, out, err


def test_a_poe_file_with_its_time_gives_the_closed_form(tmp_path, capsys):
    path = tmp_path / "c.csv"
    path.write_text("pga_g,poe_50yr\n" + "".join(f"{x:.17g},{p:.17g}\n" for x, p in
                                                 zip(LEVELS_G, _power_law_poe(50.0))))
    status, out, _ = _run(["--hazard", path, "--median", "0.4g", "--beta", "0.3", "--json"],
                          capsys)
    assert status == 0
    exact = K0 * (0.4 * G) ** -K * math.exp(0.5 * (K * 0.3) ** 2)
    assert json.loads(out)["bodies"][0]["annual_rate"] == pytest.approx(exact, rel=1e-3)


@pytest.mark.parametrize("text, args, line", [
    ("# units: m/s^2\npga,annual_rate\n1,1e-2\n4,1e-4\n", ["--im", "pga", "--units", "g"],
     "--units: contradicts the file, which says m/s^2"),
    ("pga_g,annual_rate\n0.1,1e-2\n0.4,1e-4\n", ["--im", "pga", "--units", "m/s^2"],
     "--units: contradicts the file, which says g"),
    ("pga_g,poe\n0.1,0.5\n0.4,0.01\n", ["--im", "pga", "--units", "g"],
     "--poe: required: the file does not state the investigation time"),
    ("pga_g,annual_rate\n0.1,1e-2\n0.4,1e-4\n", ["--poe", "50"],
     "--poe: contradicts the file, which says annual_rate"),
    ("pga_g,annual_rate\n0.1,1e-2\n0.4,1e-4\n", ["--im", "pgv"],
     "--im: contradicts the file, which says pga"),
    ("0.1,1e-2\n0.4,1e-4\n", [], "--im: required: the file does not state its intensity"),
    ("0.1,1e-2\n0.4,1e-4\n", ["--im", "pga"], "--units: required: the file does not state"),
])
def test_a_command_line_that_contradicts_the_file_is_refused(tmp_path, capsys, text, args,
                                                             line):
    path = tmp_path / "c.txt"
    path.write_text(text)
    status, _, err = _run(["--hazard", path, "--median", "0.3g", "--beta", "0.3", *args],
                          capsys)
    assert status == 2 and line in err and "Traceback" not in err


def test_an_older_openquake_header_through_the_command(tmp_path, capsys):
    label, text, im, years, levels_g, poes = OPENQUAKE[2]
    path = tmp_path / "hazard_curve-mean_PGA.csv"
    path.write_text(text)
    status, out, _ = _run(["--hazard", path, "--median", "0.01g", "--beta", "0.3", "--json"],
                          capsys)
    assert status == 0
    hazard = json.loads(out)["hazard"]
    np.testing.assert_allclose(hazard["levels"], np.array(levels_g) * G, rtol=1e-12)
    np.testing.assert_allclose(hazard["annual_rates"], _rates(poes, years), rtol=1e-12)
    status, out, _ = _run(["--hazard", path, "--im", "pga", "--units", "g", "--median",
                           "0.01g", "--beta", "0.3", "--json"], capsys)  # OpenQuake's unit
    assert status == 0
    np.testing.assert_allclose(json.loads(out)["hazard"]["levels"], np.array(levels_g) * G,
                               rtol=1e-12)
    for args, line in ((["--units", "m/s^2"], "--units: contradicts the file, whose levels are "
                                              "in g"),
                       (["--poe", "50"], "--poe: read from the openquake file itself")):
        status, _, err = _run(["--hazard", path, *args, "--median", "0.01g", "--beta", "0.3"],
                              capsys)
        assert status == 2 and line in err


def test_a_missing_or_binary_hazard_file_is_one_line(tmp_path, capsys):
    (tmp_path / "b.txt").write_bytes(bytes(range(256)))
    for name, line in (("none.txt", "--hazard: cannot read: No such file or directory"),
                       ("b.txt", "--hazard: not a text file")):
        status, _, err = _run(["--hazard", tmp_path / name, "--im", "pga", "--units", "g",
                               "--median", "0.3g", "--beta", "0.3"], capsys)
        assert status == 2 and line in err and "Traceback" not in err
        assert len([ln for ln in err.splitlines() if ln.startswith("  ")]) == 1


# --- risk files -----------------------------------------------------------------------------

def _risk(tmp_path, curve_text, **file):
    (tmp_path / "c.txt").write_text(curve_text)
    return {"hazard": {"file": {"path": str(tmp_path / "c.txt"), "format": "columns",
                                **file}},
            "fragility": {"median": "0.3 g", "beta": 0.3}}


def _problems(raw):
    with pytest.raises(FileProblems) as raised:
        load_risk(raw, hazard=checked_hazard)
    return [(p.path, p.message) for p in raised.value.problems]


def test_a_risk_file_takes_what_the_curve_file_states(tmp_path):
    raw = _risk(tmp_path, "# units: g\npga,poe_50yr\n0.1,0.5\n0.4,0.01\n")
    curve = load_risk(raw, hazard=checked_hazard).curve
    np.testing.assert_allclose(curve.levels, [0.1 * G, 0.4 * G])
    np.testing.assert_allclose(curve.rates, _rates([0.5, 0.01], 50.0), rtol=1e-12)
    [(path, message)] = _problems(_risk(tmp_path, "pga_g,poe\n0.1,0.5\n0.4,0.01\n",
                                        kind="annual_rate"))
    assert path == "hazard.file.kind" and "which says poe" in message
    [(path, message)] = _problems(_risk(tmp_path, "# units: m/s^2\npga,rate\n1,1e-2\n4,1e-4\n",
                                        units="g"))
    assert path == "hazard.file.units" and "which says m/s^2" in message
    [(path, message)] = _problems(_risk(tmp_path, "1,1e-2\n4,1e-4\n", im="pga"))
    assert path == "hazard.file.units" and message.startswith("required")


def test_a_risk_file_s_binary_curve_is_a_problem_of_its_path(tmp_path):
    raw = _risk(tmp_path, "", im="pga", units="g")
    (tmp_path / "c.txt").write_bytes(b"\xff\xfe\x00\x01" * 100)
    [(path, message)] = _problems(raw)
    assert path == "hazard.file.path" and "not a text file" in message


def test_a_risk_file_on_an_openquake_file_of_the_old_header(tmp_path):
    label, text, im, years, levels_g, poes = OPENQUAKE[0]
    (tmp_path / "c.csv").write_text(text)
    path = tmp_path / "risk.yaml"
    path.write_text(yaml.safe_dump({"hazard": {"file": {"path": "c.csv",
                                                        "format": "openquake"}},
                                    "fragility": {"median": "0.3 g", "beta": 0.3}}))
    curve = load_risk(path, hazard=checked_hazard).curve
    np.testing.assert_allclose(curve.rates, _rates(poes, years), rtol=1e-12)
    raw = yaml.safe_load(path.read_text())
    raw["hazard"]["file"].update(path=str(tmp_path / "c.csv"), units="gal")
    [(where, message)] = _problems(raw)
    assert where == "hazard.file.units" and "whose levels are in g" in message
    raw["hazard"]["file"].update(units="g", site=1)  # g agrees; the file has one site
    [(where, message)] = _problems(raw)
    assert where == "hazard.file.site" and "(1 sites)" in message
