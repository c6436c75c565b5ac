#!/usr/bin/python3
"""The optimised prefilters q2opt on Marschner-Lobb and a smooth function, beside q1 and q2: the
table of docs/analysis.md ("Optimised free parameters").

The runtime does not take q1opt/q2opt yet, so every prefilter here is applied the same way: the
taps of `boxgen.prefilter(f, prefilter=NAME)` convolved with the BCC samples in numpy, then
reconstruction with prefilter none (for q2 the script checks that this equals the runtime's
prefilter q2). BCC with N = 41 samples per coset and axis over [-1,1]^3 and 14 coset cells of
margin; RMS error over 200000 uniform random points of [-1,1]^3 (numpy's default_rng(7)).

Usage: PYTHONPATH=build/python /usr/bin/python3 scripts/optimised_prefilter_error.py
"""
from fractions import Fraction

import numpy as np

import boxgen

N, MARGIN, POINTS = 41, 14, 200000
FM, ALPHA = 6.0, 0.25  # Marschner-Lobb, as runtime/test_functions.h


def marschner_lobb(p):
    x, y, z = p[:, 0], p[:, 1], p[:, 2]
    r = np.hypot(x, y)
    return (1 - np.sin(np.pi * z / 2) + ALPHA * (1 + np.cos(2 * np.pi * FM * np.cos(np.pi * r / 2)))) \
        / (2 * (1 + ALPHA))


def smooth(p):
    return np.sin(1.3 * p[:, 0] + 0.4) * np.cos(0.9 * p[:, 1] - 0.2) * np.exp(0.5 * p[:, 2])


def use_density(n):
    """Sample with n points per coset and axis over [-1,1]^3 (scripts/fir_limit.py varies it)."""
    global N, H, SIZE, ORIGIN  # pylint: disable=global-statement
    N = n
    H = 1.0 / (N - 1)  # lattice unit: BCC point j = 2 i + c at -1 + H (2 i + c)
    SIZE = N + 2 * MARGIN
    ORIGIN = (-1 - 2 * H * MARGIN,) * 3


use_density(N)


def samples(f):
    """(2, SIZE, SIZE, SIZE): coset c holds f at -1 + H (2 (i - MARGIN) + c)."""
    i = np.arange(SIZE) - MARGIN
    a, b, c = np.meshgrid(i, i, i, indexing='ij')
    v = np.zeros((2, SIZE, SIZE, SIZE))
    for coset in range(2):
        p = np.stack([-1 + H * (2 * a + coset), -1 + H * (2 * b + coset), -1 + H * (2 * c + coset)],
                     -1).reshape(-1, 3)
        v[coset] = f(p).reshape(SIZE, SIZE, SIZE)
    return v


def convolve(v, taps):
    """(v * q)(j) = sum_o q(o) v(j - o) on the two cosets; the faces (zero beyond) lie in the
    margin, outside the evaluated cube."""
    out = np.zeros_like(v)
    for coset in range(2):
        for offset, weight in taps.items():
            shift = np.array([coset - o for o in offset])  # (j - o) - 2 i = coset - o
            source = shift[0] % 2
            step = (shift - source) // 2
            dst, src = [], []
            for axis in range(3):
                lo, hi = max(0, -step[axis]), min(SIZE, SIZE - step[axis])
                dst.append(slice(lo, hi))
                src.append(slice(lo + step[axis], hi + step[axis]))
            out[coset][tuple(dst)] += weight * v[source][tuple(src)]
    return out


def taps(filter_name, prefilter):
    d = boxgen.prefilter(filter_name, prefilter=prefilter)
    return {tuple(w["offset"]): float(Fraction(w["weight"])) for w in d["weights"]}


def volume(v):
    return boxgen.Volume(np.ascontiguousarray(v), lattice="bcc", spacing=H, origin=ORIGIN)


def main():
    points = np.random.default_rng(7).uniform(-1, 1, (POINTS, 3))
    print("| function | filter | q1 | q2 | q2opt |")
    print("|---|---|---|---|---|")
    for label, f in (("Marschner-Lobb", marschner_lobb), ("smooth", smooth)):
        v, exact = samples(f), f(points)
        for name in ("m7", "m8", "m12"):
            flt = boxgen.Filter(name)
            rms = {}
            for prefilter in ("q1", "q2", "q2opt"):
                value = flt.evaluate(volume(convolve(v, taps(name, prefilter))), points)
                rms[prefilter] = np.sqrt(np.mean((value - exact) ** 2))
            runtime = flt.evaluate(volume(v), points, prefilter="q2")
            # The numpy route equals the runtime's own q2.
            assert abs(np.sqrt(np.mean((runtime - exact) ** 2)) / rms["q2"] - 1) < 1e-9
            print(f"| {label} | {name} | {rms['q1']:.3e} | {rms['q2']:.3e} | {rms['q2opt']:.3e} |",
                  flush=True)


if __name__ == "__main__":
    main()
