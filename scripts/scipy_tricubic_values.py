#!/usr/bin/python3
"""Writes tests/runtime/data/scipy_tricubic.txt: scipy's cubic B-spline interpolation
(scipy.ndimage.map_coordinates, order=3, prefilter=True, mode='mirror') of a small volume at
points all over its sampled box, for the test that boxgen's tricubic `interp` equals it
(tests/runtime/interpolation_test.cpp).

The volume is v[i, j, k] = ((7 i + 13 j + 29 k) mod 17) / 16 on the grid 0 <= i < 12,
0 <= j < 10, 0 <= k < 9 (x = i, y = j, z = k, spacing 1): exact in binary, so that the test
builds the same samples. The points are uniform in the box [0, 11] x [0, 9] x [0, 8] (seed 36),
then 8 points on its faces and corners.

scipy 1.10's 'mirror' is the whole-sample mirror (d c b | a b c d | c b a) for the prefilter (its
causal and anti-causal recursions start from the mirror-symmetric boundary values) and for the
evaluation, the extension boxgen's `--boundary mirror` applies (runtime/boundary.h).

Run with Debian's python3 (python3-scipy): /usr/bin/python3 scripts/scipy_tricubic_values.py
"""
import os
import sys

import numpy as np
import scipy
import scipy.ndimage as ndimage

SIZES = (12, 10, 9)


def volume():
    i, j, k = np.meshgrid(*(np.arange(n) for n in SIZES), indexing="ij")
    return ((7 * i + 13 * j + 29 * k) % 17) / 16.0


def points():
    rng = np.random.default_rng(36)
    hi = np.array(SIZES, dtype=float) - 1
    p = rng.uniform(0, 1, (400, 3)) * hi
    corners = np.array([[0, 0, 0], hi, [0, hi[1], 0], [hi[0], 0, hi[2]],
                        [0.5, 0, 4], [hi[0], 3.25, 2], [5, hi[1], 0.75], [2.5, 7, hi[2]]])
    return np.vstack([p, corners])


def main():
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "runtime",
                       "data", "scipy_tricubic.txt")
    if len(sys.argv) > 1:
        out = sys.argv[1]
    p = points()
    v = ndimage.map_coordinates(volume(), p.T, order=3, prefilter=True, mode="mirror")
    with open(out, "w") as f:
        f.write(f"# scipy {scipy.__version__} map_coordinates(order=3, prefilter=True, "
                f"mode='mirror'); written by scripts/scipy_tricubic_values.py\n")
        f.write("# x y z value\n")
        for q, value in zip(p, v):
            f.write(f"{q[0]:.17g} {q[1]:.17g} {q[2]:.17g} {value:.17g}\n")


if __name__ == "__main__":
    main()
