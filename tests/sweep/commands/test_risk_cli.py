"""``python -m sweep.risk``: a known fragility on a curve file against the closed form, the
report's keys, a small stripe run end to end, and bad inputs refused with one line each and
exit status 2."""
import json
import math

import numpy as np
import pytest
import yaml

from sweep.probability import nrml
from sweep.risk import main

from risk_cases import G, K, K0, SOURCE


def _curve_file(tmp_path, levels_g, rates):
    path = tmp_path / "curve.txt"
    path.write_text("pga_g,annual_rate\n" + "".join(f"{x!r},{r!r}\n" for x, r in
                                                    zip(levels_g, rates)))
    return path


def _json(capsys):
    return json.loads(capsys.readouterr().out)


def test_known_fragility_on_a_curve_file_gives_the_closed_form(tmp_path, capsys):
    levels_g = np.geomspace(0.005, 20.0, 200)
    path = _curve_file(tmp_path, levels_g.tolist(), (K0 * (levels_g * G) ** -K).tolist())
    status = main(["--hazard", str(path), "--im", "pga", "--units", "g", "--median", "0.4g",
                   "--beta", "0.3", "--years", "50", "--json"])
    assert status == 0
    body = _json(capsys)["bodies"][0]
    exact = K0 * (0.4 * G) ** -K * math.exp(0.5 * (K * 0.3) ** 2)
    assert body["annual_rate"] == pytest.approx(exact, rel=1e-3)
    assert body["probability"] == pytest.approx(1 - math.exp(-50 * exact), rel=1e-3)
    assert body["return_period"] == pytest.approx(1 / exact, rel=1e-3)
    assert sum(body["deaggregation"]["share"]) == pytest.approx(1.0)
    assert body["fragility"]["median"] == pytest.approx(0.4 * G)
    assert set(body) >= {"annual_rate", "probability", "years", "return_period", "interval",
                         "fragility", "deaggregation"}


def _risk_file(tmp_path, **sections):
    path = tmp_path / "risk.yaml"
    path.write_text(yaml.safe_dump({"name": "t", "hazard": {"source": SOURCE}, **sections}))
    return path


@pytest.mark.parametrize("sections, line", [
    ({"scene": {"body": {"B": "15 cm", "H": "60 cm"}},
      "stripes": {"levels": ["2 m/s^2", "40 m/s^2"], "motions": 3}},
     "stripes.levels[1]: outside the hazard curve"),
    ({"fragility": {"median": "30 cm/s", "beta": 0.3}},
     "fragility.median: must be an acceleration, as pga"),
    ({"fragility": {"median": "0.5 g", "beta": 0.3}, "years": 0},
     "years: must be greater than 0"),
])
def test_bad_risk_files_get_one_line_and_status_2(tmp_path, capsys, sections, line):
    with pytest.raises(SystemExit) as ended:
        main([str(_risk_file(tmp_path, **sections))])
    assert ended.value.code == 2
    assert line in capsys.readouterr().err


def test_a_curve_that_rises_is_refused(tmp_path, capsys):
    path = _curve_file(tmp_path, [0.1, 0.2, 0.4], [1e-3, 2e-3, 1e-4])
    with pytest.raises(SystemExit) as ended:
        main(["--hazard", str(path), "--im", "pga", "--units", "g", "--median", "0.3 g",
              "--beta", "0.3"])
    assert ended.value.code == 2
    err = capsys.readouterr().err
    assert "never increases" in err and "Traceback" not in err


def test_stripes_end_to_end(tmp_path, capsys):
    """3 stripes of 6 motions of a 15 x 60 cm block: the fit's θ and β, carried through the
    risk integral of the computed curve, the NRML file and the dataset agree."""
    import xarray as xr

    from sweep.probability import risk as risk_integral
    from sweep.probability.source_hazard import Recurrence, SourceModel, point_source

    path = _risk_file(tmp_path, scene={"body": {"B": "15 cm", "H": "60 cm"},
                                       "contact": {"mu": 0.8}},
                      stripes={"levels": ["3 m/s^2", "5 m/s^2", "8 m/s^2"], "motions": 6},
                      years=50, target=0.02, replicates=200)
    assert main([str(path), "--json"]) == 0
    report = _json(capsys)
    body = report["bodies"][0]
    fit = body["fragility"]
    assert fit["stripes"]["motions"] == [6, 6, 6]
    assert fit["status"] == "fitted"
    model = SourceModel([point_source(Recurrence(0.02, 5.5, 7.5), 10e3, 8e3)], 760.0)
    curve = model.curve(np.geomspace(0.02 * G, 2.5 * G, 25))
    np.testing.assert_allclose(report["hazard"]["annual_rates"], curve.rates, rtol=1e-12)
    expected = risk_integral.risk(curve, fit["median"], fit["beta"])
    assert body["annual_rate"] == pytest.approx(expected.annual_rate, rel=1e-12)
    lo, hi = body["interval"]["annual_rate"]
    assert lo <= hi
    back = nrml.read_fragility_model(tmp_path / "results" / "t" / "fragility.xml")["body"]
    assert back.median == pytest.approx(fit["median"], rel=1e-9)
    assert back.beta == pytest.approx(fit["beta"], rel=1e-9)
    ds = xr.open_dataset(tmp_path / "results" / "t" / "risk.nc")
    assert ds["stripe_motions"].values.tolist() == [6, 6, 6]
    assert ds["annual_rate"].attrs["units"] == "yr-1"


def test_record_stripes_resample_records(tmp_path, capsys):
    """The same records at every stripe: the counts per stripe are those of the records."""
    records = ["elcentro1940_ns", "elcentro1940_ew", "taft1952_ew_s69e"]
    path = _risk_file(tmp_path, scene={"body": {"B": "15 cm", "H": "60 cm"},
                                       "contact": {"mu": 0.8}},
                      stripes={"levels": ["2 m/s^2", "6 m/s^2"], "records": records},
                      replicates=50)
    assert main([str(path), "--json"]) == 0
    stripes = _json(capsys)["bodies"][0]["fragility"]["stripes"]
    assert stripes["records"] == records and stripes["motions"] == [3, 3]


@pytest.mark.parametrize("im, levels, key", [
    ("pgv", ["10 cm/s", "40 cm/s"], "pgv"),
    ("sa(0.3)", ["3 m/s^2", "10 m/s^2"], "sa"),
])
def test_stripes_of_pgv_and_sa_scale_the_motions_to_their_level(tmp_path, capsys, im, levels,
                                                                   key):
    """A PGV or Sa(0.3 s) hazard: every motion of a stripe has that IM at the stripe's level
    (measured on the motion the cell applies), and the fit runs on those levels."""
    from sweep.groundmotion.oscillator import pseudo_acceleration
    from sweep.io.scene_schema import load_scene, resolve_scene

    path = tmp_path / "risk.yaml"
    path.write_text(yaml.safe_dump({"name": "t", "hazard": {"source": {
        **SOURCE, "im": im, "levels": None}}, "scene": {"body": {"B": "15 cm", "H": "60 cm"},
                                                         "contact": {"mu": 0.8}},
        "stripes": {"levels": levels, "motions": 3}, "replicates": 20}))
    assert main([str(path), "--json"]) == 0
    report = _json(capsys)
    assert report["hazard"]["im"] == im
    assert report["bodies"][0]["fragility"]["stripes"]["motions"] == [3, 3]
    for j, level in enumerate(report["bodies"][0]["fragility"]["stripes"]["levels"]):
        study = yaml.safe_load((tmp_path / "results" / "t" / f"t_stripe{j}.yaml").read_text())
        assert key in study["scene"]["excitation"]["horizontal"]
        for seed in study["grid"]["seed"]:
            scene = study["scene"]
            scene["excitation"]["horizontal"]["seed"] = seed
            ground = resolve_scene(load_scene(scene))["excitation"]["horizontal"]
            samples = ground["scale"] * ground["source"].samples
            measured = (ground["scale"] * ground["source"].intensity.pgv if key == "pgv"
                        else pseudo_acceleration(samples, ground["dt"], 0.3))
            assert measured == pytest.approx(level, rel=1e-9)


def test_records_take_no_scenario(tmp_path, capsys):
    path = _risk_file(tmp_path, scene={"body": {"B": "15 cm", "H": "60 cm"}},
                      stripes={"levels": ["2 m/s^2", "6 m/s^2"], "records": ["a", "a"],
                               "scenario": {"magnitude": 6, "distance": "20 km"}})
    with pytest.raises(SystemExit):
        main([str(path)])
    err = capsys.readouterr().err
    assert "stripes.scenario: synthetic motions only" in err
    assert "stripes.records: a record is given twice" in err


def test_openquake_curve_on_the_command_line(tmp_path, capsys):
    """The format is found from the file; a P in 50 years and the same curve as rates give
    the same rate of overturning."""
    from sweep.probability.hazard_curve import HazardCurve
    from sweep.probability.hazard_files import write_openquake_csv

    levels = np.geomspace(0.05, 100.0, 120)
    write_openquake_csv(tmp_path / "hazard_curve-mean-PGA_0.csv",
                        HazardCurve("pga", levels, K0 * levels ** -K), 50.0)
    assert main(["--hazard", str(tmp_path / "hazard_curve-mean-PGA_0.csv"), "--median",
                 "4 m/s^2", "--beta", "0.4", "--json"]) == 0
    rate = _json(capsys)["bodies"][0]["annual_rate"]
    assert rate == pytest.approx(K0 * 4.0 ** -K * math.exp(0.5 * (K * 0.4) ** 2), rel=1e-3)


@pytest.mark.parametrize("arguments, line", [
    (["--im", "pgv"], "--im: the curve is of pga"),
    (["--median", "30 cm/s"], "--median"),
])
def test_command_line_mismatches_are_refused(tmp_path, capsys, arguments, line):
    from sweep.probability.hazard_curve import HazardCurve
    from sweep.probability.hazard_files import write_openquake_csv

    path = write_openquake_csv(tmp_path / "c.csv", HazardCurve("pga", [1.0, 2.0], [1e-2, 1e-3]))
    options = {"--median": "4 m/s^2", "--beta": "0.4"}
    options.update(dict(zip(arguments[::2], arguments[1::2])))
    with pytest.raises(SystemExit) as ended:
        main(["--hazard", str(path), *[w for kv in options.items() for w in kv]])
    assert ended.value.code == 2
    assert line in capsys.readouterr().err


def test_a_missing_curve_file_is_one_line(tmp_path, capsys):
    path = tmp_path / "risk.yaml"
    path.write_text(yaml.safe_dump({"hazard": {"file": {"path": "none.csv",
                                                        "format": "openquake"}},
                                    "fragility": {"median": "0.3 g", "beta": 0.4}}))
    with pytest.raises(SystemExit) as ended:
        main([str(path)])
    assert ended.value.code == 2
    assert "hazard.file.path: cannot read" in capsys.readouterr().err


def test_a_fragility_model_of_openquake_is_read(tmp_path, capsys):
    """Our NRML file back in: the same rate as --median and --beta; an IM it does not have is
    refused."""
    levels_g = np.geomspace(0.005, 20.0, 120)
    path = _curve_file(tmp_path, levels_g.tolist(), (K0 * (levels_g * G) ** -K).tolist())
    model = nrml.write_fragility_model(tmp_path / "f.xml", [("block", 0.4 * G, 0.3)], "pga")
    common = ["--hazard", str(path), "--im", "pga", "--units", "g", "--json"]
    assert main(common + ["--fragility-model", str(model)]) == 0
    from_model = _json(capsys)["bodies"][0]["annual_rate"]
    assert main(common + ["--median", "0.4 g", "--beta", "0.3"]) == 0
    assert from_model == pytest.approx(_json(capsys)["bodies"][0]["annual_rate"], rel=1e-9)
    pgv = nrml.write_fragility_model(tmp_path / "v.xml", [("block", 0.3, 0.3)], "pgv")
    with pytest.raises(SystemExit):
        main(common + ["--fragility-model", str(pgv)])
    assert "a fragility of pgv, the hazard is of pga" in capsys.readouterr().err
