"""A lognormal fragility as an OpenQuake fragility model (NRML 0.5), written and read back.

OpenQuake's continuous fragility function (``format="continuous" shape="logncdf"``) is given by
the mean m and standard deviation s of the IM at which the limit state is reached, in the
IM's own units (g for PGA and SA, cm/s for PGV), not by the median θ and dispersion β of
ln IM.  For a lognormal IM (OpenQuake manual, "Fragility models"; any text on the lognormal
distribution):

    m = θ exp(β²/2),   s = m sqrt(exp(β²) − 1)                                              (1)
    β = sqrt(ln(1 + (s/m)²)),   θ = m / sqrt(1 + (s/m)²)                                    (2)

The limit state is ``overturned``; ``minIML`` and ``maxIML`` bound the IMs at which OpenQuake
evaluates the function, ``noDamageLimit`` the IM below which it is taken as 0 (here the
level at which the fitted probability falls below ``NO_DAMAGE_PROBABILITY``).
"""
import math
import xml.etree.ElementTree as ET
from collections import namedtuple
from pathlib import Path

from ..bodies import G
from ..io.imt import im_dimension, normalize_im, openquake_imt

NAMESPACE = "http://openquake.org/xmlns/nrml/0.5"
LIMIT_STATE = "overturned"
NO_DAMAGE_PROBABILITY = 1e-4  # noDamageLimit: the IM where P(overturn) = this
OQ_FACTOR = {"acceleration": G, "velocity": 0.01}  # SI per OpenQuake unit (g, cm/s)

Lognormal = namedtuple("Lognormal", "im median beta")
Lognormal.__doc__ = """A fragility read from NRML: IM name, median [SI], dispersion."""


def mean_stddev(median, beta):
    """(m, s) of (1): the mean and standard deviation of a lognormal with median θ, β."""
    mean = median * math.exp(0.5 * beta ** 2)
    return mean, mean * math.sqrt(math.expm1(beta ** 2))


def median_beta(mean, stddev):
    """(θ, β) of (2) from the mean and standard deviation."""
    ratio = 1.0 + (stddev / mean) ** 2
    return mean / math.sqrt(ratio), math.sqrt(math.log(ratio))


def fragility_model(functions, im, *, model_id="sweep_risk", description=""):
    """The NRML document (an ``ElementTree``) of lognormal fragilities of overturning.

    ``functions``: (id, median [SI], beta) per body, one ``fragilityFunction`` each, its
    ``minIML`` at ``noDamageLimit`` and its ``maxIML`` at θ exp(4β) (or 2θ for β = 0)."""
    from scipy.special import ndtri

    factor = OQ_FACTOR[im_dimension(im)]
    ET.register_namespace("", NAMESPACE)
    root = ET.Element(f"{{{NAMESPACE}}}nrml")
    model = ET.SubElement(root, f"{{{NAMESPACE}}}fragilityModel", id=model_id,
                          assetCategory="buildings", lossCategory="structural")
    ET.SubElement(model, f"{{{NAMESPACE}}}description").text = \
        description or "overturning of a free-standing rigid body (sweep.risk)"
    ET.SubElement(model, f"{{{NAMESPACE}}}limitStates").text = LIMIT_STATE
    for function_id, median, beta in functions:
        theta = median / factor
        mean, stddev = mean_stddev(theta, beta)
        no_damage = theta * math.exp(beta * ndtri(NO_DAMAGE_PROBABILITY))
        max_iml = theta * math.exp(4.0 * beta) if beta > 0 else 2.0 * theta
        function = ET.SubElement(model, f"{{{NAMESPACE}}}fragilityFunction",
                                 id=str(function_id), format="continuous", shape="logncdf")
        ET.SubElement(function, f"{{{NAMESPACE}}}imls", imt=openquake_imt(im),
                      noDamageLimit=f"{no_damage:.8g}", minIML=f"{no_damage:.8g}",
                      maxIML=f"{max_iml:.8g}")
        ET.SubElement(function, f"{{{NAMESPACE}}}params", ls=LIMIT_STATE, mean=f"{mean:.12g}",
                      stddev=f"{stddev:.12g}")
    ET.indent(root)
    return ET.ElementTree(root)


def write_fragility_model(path, functions, im, **kwargs):
    """Write :func:`fragility_model` to ``path`` atomically; the path."""
    from ..io.files import replacing

    with replacing(path) as tmp:
        fragility_model(functions, im, **kwargs).write(tmp, encoding="UTF-8",
                                                       xml_declaration=True)
    return Path(path)


def read_fragility_model(path, limit_state=LIMIT_STATE):
    """The :class:`Lognormal` of every continuous logncdf function's ``limit_state``, by the
    function's id."""
    ns = {"n": NAMESPACE}
    root = ET.parse(path).getroot()
    found = {}
    for function in root.iterfind(".//n:fragilityFunction", ns):
        if function.get("format") != "continuous" or function.get("shape") != "logncdf":
            continue
        im = normalize_im(function.find("n:imls", ns).get("imt"))
        for params in function.iterfind("n:params", ns):
            if params.get("ls") == limit_state:
                median, beta = median_beta(float(params.get("mean")),
                                           float(params.get("stddev")))
                found[function.get("id")] = Lognormal(im, median * OQ_FACTOR[im_dimension(im)],
                                                      beta)
    if not found:
        raise ValueError(f"{path}: no continuous logncdf function of limit state "
                         f"{limit_state!r}")
    return found
