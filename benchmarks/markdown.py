"""Markdown tables and number formats of the benchmark report, and atomic file writing."""
import math
from collections import namedtuple

from sweep.io.files import write_atomic


Section = namedtuple("Section", "text targets")
Section.__doc__ = """What a benchmark section gives: its Markdown ``text`` and its ``targets``,
rows (target, measured, met) that the report also gathers in one table at its top."""


def table(header, rows):
    """A Markdown table: header cells, then rows of cells (converted with str)."""
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(cell) for cell in row) + " |" for row in rows]
    return "\n".join(lines)


def sci(x, digits=1):
    """1.2e-08; a dash for None or NaN."""
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "–"
    return f"{x:.{digits}e}"


def ms(seconds):
    """A CPU or wall time in milliseconds with three significant digits (1.00, 0.0355,
    650, 12345)."""
    if seconds is None or math.isnan(seconds):
        return "–"
    value = 1e3 * seconds
    if value <= 0.0:
        return "0"
    decimals = max(0, 2 - math.floor(math.log10(value)))
    return f"{value:.{decimals}f}"


def verdict(met):
    """yes / **no** / – (not measured)."""
    return "–" if met is None else ("yes" if met else "**no**")


def write_text(path, text):
    """Write a text file atomically (temporary file in the same folder, then rename)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    write_atomic(path, lambda f: f.write(text.encode()))


def write_figure(path, fig, dpi=130):
    """Save a matplotlib figure as PNG atomically."""
    path.parent.mkdir(parents=True, exist_ok=True)
    write_atomic(path, lambda f: fig.savefig(f, format="png", dpi=dpi))
