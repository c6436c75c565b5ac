#!/usr/bin/python3
"""How good can a FIR prefilter on shells 0..3 be on Marschner-Lobb, and which objective gets
there? docs/design.md §18.

For M7 and M8 on BCC (200000 random points, the sampling of scripts/optimised_prefilter_error.py):
every symmetric prefilter on the shells of qfir:3 that keeps the filter's approximation order is
q = qfir:3 + t1 n1 + t2 n2 (the orbit weights whose sum is 1 and whose second moment cancels the
filter's; n1, n2 span the orbit weights with both sums zero).

1. The bound (N = 41): the reconstruction is linear in q, so its RMS error over the points is a
   quadratic in (t1, t2), minimised exactly here: the best such FIR for this test function and
   these points, a bound below which no prefilter on these 27 taps goes (tuned to the test, so a
   bound, not a prefilter to ship). Printed beside qfir:3 and the runtime's interp.
2. Candidate objectives (`--candidates`): each defined by the filter and lattice alone, each a
   quadratic in t minimised in double on a 48^3 midpoint grid of [-pi, pi)^3 (the BCC Brillouin
   zone four times over; the rhombic dodecahedron |w_i| + |w_j| <= pi where the integrand is not
   periodic). Their RMS on Marschner-Lobb at N = 33, 41, 57 and on the smooth function of
   optimised_prefilter_error.py at N = 41, beside qfir:3 and interp.

Usage: PYTHONPATH=build/python /usr/bin/python3 scripts/fir_limit.py [--candidates]
"""
import sys
from fractions import Fraction

import numpy as np

import boxgen
import optimised_prefilter_error as sampling
from optimised_prefilter_error import POINTS, convolve, marschner_lobb, samples, smooth, volume


def orbits(offsets):
    """The offsets grouped by the signed permutations of the axes (M7's and M8's symmetry)."""
    groups = {}
    for o in offsets:
        groups.setdefault(tuple(sorted(abs(x) for x in o)), []).append(tuple(o))
    return list(groups.values())


def family(name):
    """qfir:3's orbits, its orbit weights and the two directions n1, n2 that keep the order."""
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
    return groups, np.array([fir[g[0]] for g in groups]), null


def rms(flt, groups, orbit_weights, v, points, exact):
    taps = {j: w for g, w in zip(groups, orbit_weights) for j in g}
    return np.sqrt(np.mean((flt.evaluate(volume(convolve(v, taps)), points) - exact) ** 2))


def bound():
    points = np.random.default_rng(7).uniform(-1, 1, (POINTS, 3))
    v, exact = samples(marschner_lobb), marschner_lobb(points)
    print("| filter | qfir:3 | best FIR on shells 0..3, order kept (tuned to this test) | interp |")
    print("|---|---|---|---|")
    for name in ("m7", "m8"):
        flt = boxgen.Filter(name)
        groups, weights, null = family(name)
        def reconstruct(orbit_weights):
            taps = {j: w for g, w in zip(groups, orbit_weights) for j in g}
            return flt.evaluate(volume(convolve(v, taps)), points)
        base = reconstruct(weights) - exact
        directions = np.stack([reconstruct(n) for n in null], axis=1)
        t, *_ = np.linalg.lstsq(directions, -base, rcond=None)
        best = np.sqrt(np.mean((base + directions @ t) ** 2))
        interp = flt.evaluate(volume(v), points, prefilter="interp")
        print(f"| {name} | {np.sqrt(np.mean(base ** 2)):.3e} | {best:.3e} | "
              f"{np.sqrt(np.mean((interp - exact) ** 2)):.3e} |", flush=True)


# The frequency grid of the candidates.
GRID = 48
_AXIS = -np.pi + (np.arange(GRID) + 0.5) * 2 * np.pi / GRID
W = np.stack(np.meshgrid(_AXIS, _AXIS, _AXIS, indexing="ij"), -1).reshape(-1, 3)
ZONE = np.all([np.abs(W[:, a]) + np.abs(W[:, b]) <= np.pi for a, b in ((0, 1), (0, 2), (1, 2))],
              axis=0)


def cosine_symbol(points, values):
    """sum_k v(k) e^(-i w.k) for a symmetric v."""
    return np.cos(W @ np.array(points, dtype=float).T) @ np.array(values, dtype=float)


def alias_sums(directions, power, reach=5):
    """sum_k |hat(M^c)(w + 2 pi k)|^power over the dual lattice pi {n : n1 + n2 + n3 even}."""
    out = np.zeros(len(W))
    for n in np.ndindex(2 * reach + 1, 2 * reach + 1, 2 * reach + 1):
        shift = np.array(n) - reach
        if shift.sum() % 2 == 0:
            m = np.prod(np.sinc((W + np.pi * shift) @ directions.T / (2 * np.pi)), axis=1)
            out += np.abs(m) ** power
    return out


def candidate_weights(name):
    """{label: orbit weights}: the minimiser of each objective over qfir:3's family."""
    groups, base, null = family(name)
    analysis = boxgen.analyze(name)
    samples_a = analysis["interpolation_symbol"]["samples"]
    A = cosine_symbol([s["point"] for s in samples_a],
                      [float(Fraction(s["value"])) for s in samples_a])
    directions = np.array(analysis["directions"], dtype=float)
    hat_m = np.prod(np.sinc(W @ directions.T / (2 * np.pi)), axis=1)
    # a = sum_k hat(M^c)^2 (w + 2 pi k) = |det G| times the symbol of the autocorrelation samples.
    a = alias_sums(directions, 2)
    orbit_symbols = np.stack([sum(np.cos(W @ np.array(j, dtype=float)) for j in g)
                              for g in groups], axis=1)

    def minimise(operator, target, weight, where=None):
        """argmin of sum weight |operator q - target|^2 over q = base + null^T t."""
        if where is not None:
            operator, target, weight = operator[where], target[where], weight[where]
        root = np.sqrt(weight)
        t, *_ = np.linalg.lstsq((operator @ null.T) * root[:, None],
                                (target - operator @ base) * root, rcond=None)
        return base + null.T @ t

    aq = A[:, None] * orbit_symbols  # the symbol of M * q per orbit weight
    one = np.ones(len(W))
    # Tikhonov with interp's default: lambda 1e-3, mu = lambda max|A|^2 / max|D|^2, D = 8 delta
    # minus the 8 nearest neighbours (§17), max|D| = 16.
    d = 8 - 8 * np.cos(W[:, 0]) * np.cos(W[:, 1]) * np.cos(W[:, 2])
    mu = 1e-3 * np.max(np.abs(A)) ** 2 / 16 ** 2
    out = {
        "|AQ - 1|^2 (qfir:3 today: residual at white samples)": minimise(aq, one, one),
        "|AQ - 1|^2 |A|^2 (residual, samples M * white)": minimise(aq, one, A ** 2),
        "|AQ - 1|^2 |A|^4 (residual, samples M * M * white)": minimise(aq, one, A ** 4),
        "|AQ - 1|^2 |A|^6 (residual, samples M * M * M * white)": minimise(aq, one, A ** 6),
        "|AQ - 1|^2 a (continuous L2, spline with white coefficients)": minimise(aq, one, a),
        "|AQ - 1|^2 a |A|^2 (continuous L2, spline with coefficients M * white)":
            minimise(aq, one, a * A ** 2),
        "|Q - Q_reg|^2 a (Tikhonov prefilter, lambda 1e-3)":
            minimise(orbit_symbols, A / (A ** 2 + mu * d ** 2), a),
        "error kernel over the zone, a |Q - hat(M)/a|^2 (band-limited white signal)":
            minimise(orbit_symbols, hat_m / a, a, ZONE),
    }
    for power in (1, 2):
        # Continuous L2 error for a stationary signal of spectrum |hat(M)|^(2p): per frequency of
        # the zone |Q|^2 a s_2p - 2 Q s_(2p+1) + s_2p, s_k = sum over aliases of |hat(M)|^k.
        spectrum, cross = alias_sums(directions, 2 * power), alias_sums(directions, 2 * power + 1)
        out[f"continuous L2, stationary signal of spectrum |hat(M)|^{2 * power}"] = \
            minimise(orbit_symbols, cross / (a * spectrum), a * spectrum)
    return groups, out


def candidates():
    densities = (33, 41, 57)
    points = np.random.default_rng(7).uniform(-1, 1, (POINTS, 3))
    print("| objective (min over q) | filter | " +
          " | ".join(f"ML N = {n}" for n in densities) + " | smooth N = 41 |")
    print("|---|---|" + "---|" * (len(densities) + 1))
    for name in ("m7", "m8"):
        flt = boxgen.Filter(name)
        groups, weights = candidate_weights(name)
        table = {label: [] for label in list(weights) + ["interp"]}
        for n, f in [(n, marschner_lobb) for n in densities] + [(41, smooth)]:
            sampling.use_density(n)
            v, exact = sampling.samples(f), f(points)
            for label, w in weights.items():
                table[label].append(rms(flt, groups, w, v, points, exact))
            interp = flt.evaluate(sampling.volume(v), points, prefilter="interp")
            table["interp"].append(np.sqrt(np.mean((interp - exact) ** 2)))
        for label, row in table.items():
            ratios = [f"{x:.3e} ({x / i:.2f})" for x, i in zip(row, table["interp"])]
            print(f"| {label} | {name} | " + " | ".join(ratios) + " |", flush=True)


if __name__ == "__main__":
    if "--candidates" in sys.argv:
        candidates()
    else:
        bound()
