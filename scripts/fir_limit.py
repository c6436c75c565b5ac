#!/usr/bin/python3
"""How good can a FIR prefilter on shells 0..3 be on Marschner-Lobb? docs/design.md §18.

For M7 and M8 on BCC (N = 41, 200000 random points, the sampling of
scripts/optimised_prefilter_error.py): every symmetric prefilter on the shells of qfir:3 that
keeps the filter's approximation order is q = qfir:3 + t1 n1 + t2 n2 (the orbit weights whose
sum is 1 and whose second moment cancels the filter's; n1, n2 span the orbit weights with both
sums zero). The reconstruction is linear in q, so its RMS error over the points is a quadratic in
(t1, t2), minimised exactly here: the best such FIR for this test function and these points, a
bound below which no prefilter on these 27 taps goes (it is tuned to the test, so it is a bound,
not a prefilter to ship). Printed beside qfir:3 and the runtime's interp.

Usage: PYTHONPATH=build/python /usr/bin/python3 scripts/fir_limit.py
"""
from fractions import Fraction

import numpy as np

import boxgen
from optimised_prefilter_error import POINTS, convolve, marschner_lobb, samples, volume


def orbits(offsets):
    """The offsets grouped by the signed permutations of the axes (M7's and M8's symmetry)."""
    groups = {}
    for o in offsets:
        groups.setdefault(tuple(sorted(abs(x) for x in o)), []).append(tuple(o))
    return list(groups.values())


def main():
    points = np.random.default_rng(7).uniform(-1, 1, (POINTS, 3))
    v, exact = samples(marschner_lobb), marschner_lobb(points)
    print("| filter | qfir:3 | best FIR on shells 0..3, order kept (tuned to this test) | interp |")
    print("|---|---|---|---|")
    for name in ("m7", "m8"):
        flt = boxgen.Filter(name)
        fir = {tuple(w["offset"]): float(Fraction(w["weight"]))
               for w in boxgen.prefilter(name, prefilter="qfir:3")["weights"]}
        groups = orbits(fir)
        # qfir:3 has one weight per orbit (the generator's unknowns are the filter's symmetry
        # orbits): the orbits here are the filter's.
        assert all(fir[j] == fir[g[0]] for g in groups for j in g)
        # Per orbit: its size and second moment sum_j j_x^2; the order-4 conditions fix
        # sum_o size_o w_o and sum_o moment_o w_o (symmetry leaves no other condition below 4).
        constraints = np.array([[len(g) for g in groups],
                                [sum(j[0] ** 2 for j in g) for g in groups]], dtype=float)
        null = np.linalg.svd(constraints)[2][2:]  # orbit weights keeping both sums
        def reconstruct(orbit_weights):
            taps = {j: w for g, w in zip(groups, orbit_weights) for j in g}
            return flt.evaluate(volume(convolve(v, taps)), points)
        base = reconstruct([fir[g[0]] for g in groups]) - exact
        directions = np.stack([reconstruct(n) for n in null], axis=1)
        t, *_ = np.linalg.lstsq(directions, -base, rcond=None)
        best = np.sqrt(np.mean((base + directions @ t) ** 2))
        interp = flt.evaluate(volume(v), points, prefilter="interp")
        print(f"| {name} | {np.sqrt(np.mean(base ** 2)):.3e} | {best:.3e} | "
              f"{np.sqrt(np.mean((interp - exact) ** 2)):.3e} |", flush=True)


if __name__ == "__main__":
    main()
