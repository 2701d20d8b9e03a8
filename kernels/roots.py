"""Scalar root finders and a maximiser on an interval, for a compiled function f(x, args).

``brent`` (a bracketed sign change: Brent's zero), ``regula_falsi`` (Illinois' variant, for
a sign change of a smooth rate), ``bisect`` (the first point of an interval where f > 0)
and ``peak_above_zero`` (golden-section search for the largest value, stopping as soon as
one above zero is seen).  Each takes f and returns the compiled solver for it, whose first
argument ``args`` is passed through to f unchanged: ``locate = brent(g)`` once at import,
then ``locate(args, xa, xb, ga, gb, xtol)`` in compiled code.  Used by event location,
the extremes inside a step and rest skipping.
"""
import math

from ._jit import jit_for
from .tolerances import EPS, MAX_BRENT_ITER, MAX_TURN_ITER

INV_PHI = 0.6180339887498949    # 1/golden ratio: the golden-section search's interval ratio


def brent(f):
    """solve(args, xa, xb, fa, fb, xtol): x in [xa, xb] with f(x) = 0, given fa > 0 >= fb,
    by Brent's method (Brent 1973, ch. 4; scipy's brentq): the last iterate, within
    xtol + 4 EPS |x| of the root."""
    def solve(args, xa, xb, fa, fb, xtol):
        a, b, c = xa, xb, xa
        fc = fa
        d = e = b - a
        for _ in range(MAX_BRENT_ITER):
            if fb * fc > 0.0:
                c, fc = a, fa
                d = e = b - a
            if abs(fc) < abs(fb):
                a, b, c = b, c, b
                fa, fb, fc = fb, fc, fb
            tol = 2.0 * EPS * abs(b) + 0.5 * xtol
            m = 0.5 * (c - b)
            if abs(m) <= tol or fb == 0.0:
                break
            if abs(e) >= tol and abs(fa) > abs(fb):
                s = fb / fa
                if a == c:                      # secant
                    p = 2.0 * m * s
                    q = 1.0 - s
                else:                           # inverse quadratic interpolation
                    q = fa / fc
                    r = fb / fc
                    p = s * (2.0 * m * q * (q - r) - (b - a) * (r - 1.0))
                    q = (q - 1.0) * (r - 1.0) * (s - 1.0)
                if p > 0.0:
                    q = -q
                else:
                    p = -p
                if 2.0 * p < min(3.0 * m * q - abs(tol * q), abs(e * q)):
                    e = d
                    d = p / q
                else:                           # bisection
                    d = m
                    e = m
            else:
                d = m
                e = m
            a, fa = b, fb
            if abs(d) > tol:
                b += d
            else:
                b += math.copysign(tol, m)
            fb = f(b, args)
        return b
    return jit_for(solve, "brent", f)


def regula_falsi(f):
    """solve(args, xa, xb, fa, fb, xtol): x in [xa, xb] where f changes sign (fa fb < 0),
    by Illinois' regula falsi: the last point evaluated, when two iterates are within xtol
    or f vanishes there."""
    def solve(args, xa, xb, fa, fb, xtol):
        x_old = 2.0 * xb - xa                   # outside the interval: no first stop
        side = 0
        x = xa
        for _ in range(MAX_TURN_ITER):
            x = (xa * fb - xb * fa) / (fb - fa)
            fx = f(x, args)
            if abs(x - x_old) < xtol or fx == 0.0:
                break
            x_old = x
            if fx * fb > 0.0:
                xb, fb = x, fx
                if side == 1:                   # the same end twice: halve the other's weight
                    fa *= 0.5
                side = 1
            else:
                xa, fa = x, fx
                if side == -1:
                    fb *= 0.5
                side = -1
        return x
    return jit_for(solve, "regula_falsi", f)


def bisect(f):
    """solve(args, xa, xb, xtol): a point in (xa, xb] with f > 0 at most xtol max(1, |x|)
    after the last point with f <= 0 (f(xa) <= 0 < f(xb)), by bisection."""
    def solve(args, xa, xb, xtol):
        while xb - xa > xtol * max(1.0, abs(xb)):
            xm = 0.5 * (xa + xb)
            if xm <= xa or xm >= xb:            # no double between them
                break
            if f(xm, args) > 0.0:
                xb = xm
            else:
                xa = xm
        return xb
    return jit_for(solve, "bisect", f)


def peak_above_zero(f):
    """solve(args, xa, xb, xtol): (x, f(x)) at the largest f on [xa, xb] by golden-section
    search, stopping as soon as f > 0 is seen or the interval is shorter than
    xtol max(1, xb)."""
    def solve(args, xa, xb, xtol):
        x1 = xb - INV_PHI * (xb - xa)
        x2 = xa + INV_PHI * (xb - xa)
        f1 = f(x1, args)
        f2 = f(x2, args)
        while xb - xa > xtol * max(1.0, xb) and f1 <= 0.0 and f2 <= 0.0:
            if f1 > f2:
                xb, x2, f2 = x2, x1, f1
                x1 = xb - INV_PHI * (xb - xa)
                f1 = f(x1, args)
            else:
                xa, x1, f1 = x1, x2, f2
                x2 = xa + INV_PHI * (xb - xa)
                f2 = f(x2, args)
        if f1 >= f2:
            return x1, f1
        return x2, f2
    return jit_for(solve, "peak_above_zero", f)
