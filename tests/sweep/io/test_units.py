"""Quantities with units: parsing, dimensions, body-relative units, sine amplitudes."""
import math

import pytest

from sweep.io.units import (Quantity, acceleration_amplitude, fixed_factor, parse_quantity,
                         units_of)

BODY = {"B": 0.1, "H": 0.3, "i_g": None}


@pytest.mark.parametrize("raw, dimension, si", [
    ("341.7 gal", "acceleration", 3.417),
    ("0.5 g", "acceleration", 4.903325),
    ("2 m/s^2", "acceleration", 2.0),
    ("250 cm/s2", "acceleration", 2.5),
    ("10 cm", "length", 0.1),
    ("15 mm", "length", 0.015),
    ("100 cm/s", "velocity", 1.0),
    ("100 cm/sec", "velocity", 1.0),
    ("30 kine", "velocity", 0.3),
    ("2 Hz", "frequency", 2.0),
    ("2 hz", "frequency", 2.0),
    ("30 deg", "angle", math.pi / 6),
    ("90 deg/s", "angular_velocity", math.pi / 2),
    ("500 ms", "time", 0.5),
    ("1e-3", "time", 1e-3),
    (".5gal", "acceleration", 0.005),
    (-3, "acceleration", -3.0),
    (0.25, "length", 0.25),
])
def test_fixed_units(raw, dimension, si):
    assert parse_quantity(raw, dimension).to_si() == pytest.approx(si, rel=1e-12)


def test_bare_number_takes_first_dimension():
    q = parse_quantity(1.5, ("velocity", "acceleration"))
    assert (q.value, q.unit, q.dimension) == (1.5, "", "velocity")


def test_west():
    q = parse_quantity("1.5 west", "acceleration")
    assert q.body_relative
    assert q.to_si(BODY) == pytest.approx(1.5 * 9.80665 / 3, rel=1e-12)


def test_v_H_and_alpha_from_a11():
    assert parse_quantity("1 v_H", "velocity").to_si(BODY) == pytest.approx(0.485554, abs=5e-7)
    assert parse_quantity("0.4 V_H", "velocity").to_si(BODY) == pytest.approx(0.194222,
                                                                               abs=5e-7)
    assert parse_quantity("0.1 alpha", "angle").to_si(BODY) == pytest.approx(0.0321751,
                                                                              abs=5e-8)


def test_v_H_uses_the_radius_of_gyration():
    r = math.hypot(0.05, 0.15)
    uniform = {"B": 0.1, "H": 0.3, "i_g": r / math.sqrt(3)}
    heavier_rim = {"B": 0.1, "H": 0.3, "i_g": r}  # i^2 + r^2 = 2 r^2 instead of 4 r^2/3
    q = parse_quantity("1 v_H", "velocity")
    assert q.to_si(uniform) == pytest.approx(0.485554, abs=5e-7)
    assert q.to_si(heavier_rim) == pytest.approx(0.485554 * math.sqrt(1.5), abs=1e-6)


def test_body_relative_needs_the_body():
    with pytest.raises(ValueError, match="needs its B and H"):
        parse_quantity("1.5 west", "acceleration").to_si()


@pytest.mark.parametrize("raw, dimension, match", [
    ("10 cm", "acceleration", "unit of length, expected an acceleration"),
    ("1 west", "angle", "unit of acceleration, expected an angle"),
    ("2 s", "frequency", "unit of time"),
    ("1.5 wset", "acceleration", "unknown unit 'wset'"),
    ("fast", "velocity", "expected a number"),
    ("1.5 2 g", "acceleration", "expected a number"),
    (True, "length", "expected a number"),
    (None, "length", "expected a number"),
    ([1], "length", "expected a number"),
    (float("nan"), "length", "finite"),
    (10**400, "length", "finite"),
    ("1e400 m", "length", "finite"),
    ("inf", "length", "expected a number"),
    ("1 cm", ("acceleration", "velocity"), "expected an acceleration or a velocity"),
])
def test_errors(raw, dimension, match):
    with pytest.raises(ValueError, match=match):
        parse_quantity(raw, dimension)


def test_quantity_passes_through_with_its_dimension_checked():
    q = Quantity(2.0, "cm", "length")
    assert parse_quantity(q, ("acceleration", "length")) is q
    with pytest.raises(ValueError):
        parse_quantity(q, "velocity")


def test_str():
    assert str(parse_quantity("0.4 v_h", "velocity")) == "0.4 v_H"
    assert str(parse_quantity(3, "time")) == "3"


def test_units_of_lists_body_relative_units():
    assert "west" in units_of("acceleration") and "v_H" in units_of("velocity")
    assert units_of("angle") == ("rad", "deg", "alpha")


def test_fixed_factor():
    assert fixed_factor("gal", "acceleration") == 0.01
    assert fixed_factor("g", "acceleration") == 9.80665
    with pytest.raises(ValueError, match="relative to the body"):
        fixed_factor("west", "acceleration")


@pytest.mark.parametrize("raw, frequency, expected", [
    ("3 m/s^2", 2.0, 3.0),
    ("10 cm/s", 2.0, 0.1 * 4 * math.pi),            # A = V omega
    ("1 cm", 2.0, 0.01 * (4 * math.pi) ** 2),        # A = D omega^2
    ("0.4 v_H", 1 / 0.37332, 3.26888),               # point P of A11: a_o at T_c
])
def test_sine_acceleration_amplitude(raw, frequency, expected):
    q = parse_quantity(raw, ("acceleration", "velocity", "length"))
    assert acceleration_amplitude(q, frequency, BODY) == pytest.approx(expected, rel=2e-5)


def test_acceleration_amplitude_rejects_other_dimensions():
    with pytest.raises(ValueError):
        acceleration_amplitude(parse_quantity("1 deg", "angle"), 1.0)


# Exact factors of the international yard and pound agreement (1959): 1 yd = 0.9144 m
@pytest.mark.parametrize("unit, dimension, factor", [
    ("in", "length", 0.0254), ("inch", "length", 0.0254), ("inches", "length", 0.0254),
    ("ft", "length", 0.3048), ("foot", "length", 0.3048), ("feet", "length", 0.3048),
    ("yd", "length", 0.9144), ("mi", "length", 1609.344),
    ("in/s", "velocity", 0.0254), ("ft/s", "velocity", 0.3048), ("feet/sec", "velocity", 0.3048),
    ("mph", "velocity", 0.44704),                    # 1609.344 m / 3600 s
    ("in/s^2", "acceleration", 0.0254), ("ft/s2", "acceleration", 0.3048),
    ("ft/s/s", "acceleration", 0.3048), ("FT/SEC**2", "acceleration", 0.3048),
    ("mg", "acceleration", 0.00980665),
])
def test_imperial_units_exact(unit, dimension, factor):
    assert fixed_factor(unit, dimension) == pytest.approx(factor, rel=1e-15, abs=0)


def test_imperial_units_agree_with_each_other():
    length = lambda text: parse_quantity(text, "length").to_si()  # noqa: E731
    assert length("12 in") == pytest.approx(length("1 ft"), rel=1e-15)
    assert length("3 ft") == pytest.approx(length("1 yd"), rel=1e-15)
    assert length("5280 ft") == pytest.approx(length("1 mi"), rel=1e-15)
    assert parse_quantity("60 mph", "velocity").to_si() == pytest.approx(
        length("1 mi") / 60.0, rel=1e-15)                # a mile a minute
    assert parse_quantity("32.174 ft/s^2", "acceleration").to_si() == pytest.approx(
        9.80665, rel=2e-6)                               # standard gravity, 32.1740 ft/s^2


def test_imperial_units_listed_and_checked():
    assert units_of("length") == ("m", "cm", "mm", "km", "in", "ft", "yd", "mi")
    assert {"in/s", "ft/s", "mph"} <= set(units_of("velocity"))
    assert {"in/s^2", "ft/s^2"} <= set(units_of("acceleration"))
    with pytest.raises(ValueError, match="'in' is a unit of length, expected an acceleration"):
        parse_quantity("1 in", "acceleration")
    assert parse_quantity("2 min", "time").to_si() == 120.0  # minutes, not miles
