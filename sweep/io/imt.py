"""Names of intensity measures (``pga``, ``pgv``, ``sa(T)``), their dimension, OpenQuake's names.

T is the period in s; OpenQuake writes ``PGA``, ``SA(0.3)``, the USGS ``SA0P3``."""
import re

from ..bodies import G

IM_PATTERN = re.compile(r"^(pga|pgv|sa\((\d+(?:\.\d*)?|\.\d+)\))$")
SI_UNITS = {"acceleration": "m s-2", "velocity": "m s-1"}


def im_dimension(im):
    """``"acceleration"`` for pga and sa(T), ``"velocity"`` for pgv."""
    return "velocity" if im == "pgv" else "acceleration"


def display_scale(units):
    """(factor, label) that show an IM of CF ``units`` in g (accelerations) or cm/s
    (velocities): the value shown is the SI value / factor."""
    return (G, "g") if units == SI_UNITS["acceleration"] else (0.01, "cm/s")


def normalize_im(text):
    """The IM name as this package writes it (``pga``, ``pgv``, ``sa(0.3)``) from OpenQuake's
    ``PGA``, ``SA(0.3)`` or the USGS's ``SA0P3``; ValueError if none of these."""
    raw = str(text).strip()
    usgs = re.fullmatch(r"SA(\d+)P(\d+)", raw, re.IGNORECASE)
    if usgs:
        raw = f"sa({usgs.group(1)}.{usgs.group(2)})"
    name = raw.lower().replace(" ", "")
    match = IM_PATTERN.match(name)
    if not match:
        raise ValueError(f"unknown intensity measure {text!r}; expected pga, pgv or sa(T), "
                         "T the period in s")
    if match.group(2) is not None:
        return f"sa({float(match.group(2)):g})"
    return name


def openquake_imt(im):
    """OpenQuake's IMT name of an IM: ``PGA``, ``PGV``, ``SA(0.3)``."""
    return im.upper() if not im.startswith("sa(") else f"SA({im[3:-1]})"
