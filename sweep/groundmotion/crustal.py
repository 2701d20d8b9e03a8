"""Published parameters of the stochastic point-source model: active crust, western North America.

:data:`WNA` is the western North America set of Campbell (2003, BSSA 93, 1012-1033),
with the generic-rock crustal amplification of Boore & Joyner (1997, BSSA 87, 327-341) it
tabulates, the finite-fault factor of Yenier & Atkinson (2015, BSSA 105, 1989-2009, eqs. 5-6)
and, for sites other than generic rock, the linear site term of Boore, Stewart, Seyhan &
Atkinson (2014, Earthquake Spectra 30, 1057-1085; BSSA14).  SI units throughout; the papers'
units are given beside each value.
"""
import math
from dataclasses import dataclass


@dataclass(frozen=True)
class PointSourceParameters:
    """Source, path and site parameters of Boore's (2003) stochastic point-source model.

    Attributes
    ----------
    name : str
        Short citation of the set.
    beta, rho : float
        Shear-wave speed [m/s] and density [kg/m^3] near the source.
    stress : float
        Brune stress parameter [Pa].
    radiation, partition, free_surface : float
        Average S-wave radiation pattern, partition onto one horizontal component and free
        surface amplification (Boore 2003: 0.55, 1/sqrt(2), 2).
    reference_distance : float
        Distance at which the geometric spreading is 1 [m] (R0 = 1 km).
    spreading_hinge : float
        Distance where the geometric spreading changes from 1/R to 1/sqrt(R) [m].
    spreading_near, spreading_far : float
        Exponents of R before and after the hinge.
    q0, q_exponent : float
        Anelastic attenuation Q(f) = q0 f^q_exponent (f in Hz).
    duration_slope : float
        Path duration per unit distance [s/m]; the source duration is 1/f0.
    kappa0 : float
        High-frequency decay exp(-pi kappa0 f) near the site [s].
    amplification_frequency, amplification : tuple of float
        Crustal amplification of the reference site at these frequencies [Hz].
    reference_vs30 : float
        Vs30 of the reference site [m/s].
    finite_fault_a, finite_fault_b : float
        log10(h / 1 km) = a + b M: pseudo-depth of the effective point-source distance.
    """

    name: str
    beta: float
    rho: float
    stress: float
    radiation: float
    partition: float
    free_surface: float
    reference_distance: float
    spreading_hinge: float
    spreading_near: float
    spreading_far: float
    q0: float
    q_exponent: float
    duration_slope: float
    kappa0: float
    amplification_frequency: tuple
    amplification: tuple
    reference_vs30: float
    finite_fault_a: float
    finite_fault_b: float


WNA = PointSourceParameters(
    name="Campbell (2003) western North America",
    beta=3500.0,                  # 3.5 km/s
    rho=2800.0,                   # 2.8 g/cm^3
    stress=100.0e5,               # 100 bar
    radiation=0.55,               # Boore (2003)
    partition=1.0 / math.sqrt(2.0),
    free_surface=2.0,
    reference_distance=1.0e3,     # R0 = 1 km
    spreading_hinge=40.0e3,       # 1/R to 40 km, 1/sqrt(R) beyond
    spreading_near=1.0,
    spreading_far=0.5,
    q0=180.0,                     # Q(f) = 180 f^0.45
    q_exponent=0.45,
    duration_slope=0.05e-3,       # 0.05 s/km
    kappa0=0.04,                  # s
    # Boore & Joyner (1997) generic rock, Vs30 = 620 m/s (as tabulated by Campbell 2003)
    amplification_frequency=(0.01, 0.09, 0.16, 0.51, 0.84, 1.25, 2.26, 3.17, 6.05, 16.60,
                             61.20, 100.0),
    amplification=(1.00, 1.10, 1.18, 1.42, 1.58, 1.74, 2.06, 2.25, 2.58, 3.13, 4.00, 4.40),
    reference_vs30=620.0,
    finite_fault_a=-0.405,        # Yenier & Atkinson (2015), h in km
    finite_fault_b=0.235,
)

# BSSA14 linear site term F_lin = c ln(min(Vs30, V_c) / V_ref), V_ref = 760 m/s, at a few of
# its periods [s] (coefficients revised 2014-07-15).
BSSA14_PERIOD = (0.01, 0.02, 0.03, 0.05, 0.075, 0.1, 0.15, 0.2, 0.25, 0.3, 0.4, 0.5, 0.75, 1.0,
                 1.5, 2.0, 3.0, 4.0, 5.0, 7.5, 10.0)
BSSA14_C = (-0.60372, -0.57388, -0.53414, -0.45795, -0.44411, -0.48724, -0.57962, -0.68762,
            -0.77177, -0.84165, -0.91092, -0.9693, -1.0154, -1.05, -1.0454, -1.0392, -1.0112,
            -0.96938, -0.91954, -0.77665, -0.65575)
BSSA14_VC = (1500.2, 1500.36, 1502.95, 1501.42, 1494.0, 1479.12, 1442.85, 1392.61, 1356.21,
             1308.47, 1252.66, 1203.91, 1147.59, 1109.95, 1072.39, 1009.49, 922.43, 844.48,
             793.13, 771.01, 775.0)
