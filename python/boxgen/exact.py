"""boxgen.eval: the exact value of a box spline (or of a partial derivative) at points, as
fractions.Fraction, through the code of `boxgen eval` (docs/python.md)."""
import math
import numbers
from fractions import Fraction

from . import _core


def _coordinate(c):
    """A coordinate as the text `boxgen eval --at` reads: an exact fraction p/q."""
    if isinstance(c, bool) or not isinstance(c, (numbers.Real, str)):
        raise TypeError(f"a coordinate must be an int, a fractions.Fraction, a float or a str, "
                        f"not {type(c).__name__}")
    if isinstance(c, str):
        return c.strip()  # a fraction or a decimal, read exactly by boxgen
    if not isinstance(c, numbers.Rational):
        c = float(c)
        if not math.isfinite(c):
            raise ValueError(f"a coordinate must be finite, got {c}")
        c = Fraction(c)  # the float's exact binary value
    return f"{c.numerator}/{c.denominator}"


def _sequence(value, what):
    """list(value), or TypeError naming what was expected and the type that came."""
    try:
        return list(value)
    except TypeError:
        raise TypeError(f"{what}, not {type(value).__name__}") from None


def _point(p):
    if isinstance(p, str):
        return p
    coordinates = _sequence(p, "a point must be a str 'x y z' or a sequence of coordinates")
    return " ".join(_coordinate(c) for c in coordinates)


def _orders(derivative):
    if derivative is None:
        return ""
    if isinstance(derivative, str):
        return derivative
    orders = _sequence(derivative,
                       "derivative must be a sequence of integer orders or a str 'a b c'")
    for a in orders:
        if isinstance(a, bool) or not isinstance(a, numbers.Integral):
            raise TypeError(f"a derivative order must be an int, not {type(a).__name__}")
    return " ".join(str(int(a)) for a in orders)


def eval(spec, points, derivative=None, lattice=None):  # noqa: A001 (boxgen.eval, as the CLI)
    """The exact value M(x) = |det G| M_Xi(x + c) of the box spline `spec` (a preset name or
    directions "1,1,1; 1,-1,-1; ...") on `lattice` at each point, or of its partial derivative of
    orders `derivative` ((a, b, c) or "a b c"), as fractions.Fraction.

    `points` is one point (a str "x y z" of fractions or decimals, or a sequence of numbers: int,
    Fraction, float at its exact binary value) or a sequence of points (a list, a (n, d) NumPy
    array; each a str or a sequence of coordinates, which may also be str); one point gives one
    Fraction, a sequence of points a list. The values are those of
    `boxgen eval SPEC --at ... --json`, computed by the same code."""
    if isinstance(points, str):
        single, texts = True, [points]
    else:
        try:
            items = list(points)
        except TypeError:
            raise TypeError(f"points must be a point or a sequence of points, not "
                            f"{type(points).__name__}") from None
        single = bool(items) and all(isinstance(c, numbers.Number) for c in items)
        texts = [_point(items)] if single else [_point(p) for p in items]
    if not texts:
        raise ValueError("eval: give at least one point")
    values = [Fraction(v["value"])
              for v in _core._eval_json(spec, texts, _orders(derivative), lattice)]
    return values[0] if single else values
