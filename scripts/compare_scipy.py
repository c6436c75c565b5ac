#!/usr/bin/python3
"""boxgen's reconstructions of Marschner-Lobb beside scipy's Cartesian spline interpolation at
equal sample counts: the tables of docs/analysis.md ("Against scipy"). boxgen's rows are M8 and M7
with every prefilter (q1, q2, q2opt, qfir:3, interp), M12 with interp, and the tricubic B-spline
with interp on scipy's own grid.

For N in 33, 41, 57: BCC with N samples per coset and axis over [-1,1]^3 (N^3 + (N-1)^3 samples
inside the cube, `boxrecon error --n N`), against a Cartesian grid of M^3 samples over [-1,1]^3,
M the integer whose cube is nearest that count. scipy.ndimage.map_coordinates interpolates the
Cartesian samples with cubic (order=3) and quintic (order=5) B-splines (prefilter=True,
mode='mirror'), sampled with 10 samples of margin beyond the cube; boxgen's rows come from
`boxrecon error --json` (its own margin, which it reports). RMS error over 200000 uniform random
points of [-1,1]^3: numpy's default_rng(1) for scipy, boxrecon's seed 1 for boxgen (different
points: the RMS of 200000 points varies by about 0.3% between point sets).

Usage: /usr/bin/python3 scripts/compare_scipy.py [path/to/boxrecon] [--json]
(Debian's python3 with python3-scipy; boxrecon defaults to build/apps/boxrecon.)
"""
import json
import os
import subprocess
import sys

import numpy as np
import scipy
import scipy.ndimage as ndimage

POINTS = 200000
DENSITIES = (33, 41, 57)
MARGIN = 10  # Cartesian samples beyond the cube for scipy
FM, ALPHA = 6.0, 0.25  # Marschner-Lobb, as runtime/test_functions.h


def marschner_lobb(x, y, z):
    r = np.hypot(x, y)
    return (1 - np.sin(np.pi * z / 2) + ALPHA * (1 + np.cos(2 * np.pi * FM * np.cos(np.pi * r / 2)))) \
        / (2 * (1 + ALPHA))


def cartesian_size(n):
    """M whose M^3 is nearest the BCC samples inside [-1,1]^3, N^3 + (N-1)^3."""
    count = n ** 3 + (n - 1) ** 3
    m = round(count ** (1 / 3))
    return min((m - 1, m, m + 1), key=lambda k: abs(k ** 3 - count))


def scipy_rms(m, order, points, exact):
    h = 2 / (m - 1)
    g = -1 + h * np.arange(-MARGIN, m + MARGIN)
    x, y, z = np.meshgrid(g, g, g, indexing="ij")
    samples = marschner_lobb(x, y, z)
    coordinates = (points.T + 1) / h + MARGIN
    values = ndimage.map_coordinates(samples, coordinates, order=order, prefilter=True,
                                     mode="mirror")
    return float(np.sqrt(np.mean((values - exact) ** 2)))


def boxrecon_error(boxrecon, n, filter_name, prefilter):
    out = subprocess.run([boxrecon, "error", "--function", "ml", "--n", str(n), "--filter",
                          filter_name, "--prefilter", prefilter, "--points", str(POINTS), "--json",
                          "--quiet"], check=True, capture_output=True, text=True).stdout
    return json.loads(out)


# boxgen's BCC rows: every prefilter of M8 and M7 (quasi-interpolation Q^I, Q^II and Q^II with
# optimised free parameters; the FIR interpolation prefilter on shells 0..3; interpolation, exact
# for M8 and regularised for M7), and M12's interpolation.
BOXGEN_ROWS = [(f, q) for f in ("m8", "m7") for q in ("q1", "q2", "q2opt", "qfir:3", "interp")] + \
    [("m12", "interp")]


def e3(x):
    """1.763e-2, as the docs write numbers."""
    mantissa, exponent = f"{x:.3e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def main():
    args = [a for a in sys.argv[1:] if a != "--json"]
    boxrecon = args[0] if args else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..",
                                                 "build", "apps", "boxrecon")
    rng = np.random.default_rng(1)
    points = rng.uniform(-1, 1, (POINTS, 3))
    exact = marschner_lobb(points[:, 0], points[:, 1], points[:, 2])
    rows = []
    for n in DENSITIES:
        m = cartesian_size(n)
        row = {"n": n, "bcc_samples_in_cube": n ** 3 + (n - 1) ** 3, "m": m,
               "cartesian_samples": m ** 3,
               "scipy_cubic": scipy_rms(m, 3, points, exact),
               "scipy_quintic": scipy_rms(m, 5, points, exact)}
        tricubic = boxrecon_error(boxrecon, m, "tricubic", "interp")
        row["boxgen_tricubic_interp"] = tricubic["rms"]
        for f, q in BOXGEN_ROWS:
            r = boxrecon_error(boxrecon, n, f, q)
            row[f"boxgen_{f}_{q}"] = r["rms"]
            row[f"boxgen_{f}_{q}_samples"] = r["samples"]
            if "interpolation" in r:
                row[f"boxgen_{f}_{q}_lambda"] = r["interpolation"]["lambda"]
        rows.append(row)
    if "--json" in sys.argv:
        print(json.dumps({"scipy": scipy.__version__, "points": POINTS, "rows": rows}, indent=2))
        return
    print(f"Marschner-Lobb RMS error, {POINTS} random points of [-1,1]^3; scipy "
          f"{scipy.__version__}")
    print()
    print("| N | BCC samples in the cube | Cartesian M^3 |")
    print("|---|---|---|")
    for r in rows:
        print(f"| {r['n']} | {r['bcc_samples_in_cube']} | {r['m']}^3 = {r['cartesian_samples']} |")
    print()
    print("| reconstruction | " + " | ".join(f"N = {r['n']}" for r in rows) + " | " +
          " | ".join(f"/ scipy cubic, N = {r['n']}" for r in rows) + " |")
    print("|---" * (1 + 2 * len(rows)) + "|")
    labelled = [("scipy cubic (Cartesian)", "scipy_cubic"),
                ("scipy quintic (Cartesian)", "scipy_quintic"),
                ("boxgen tricubic interp (Cartesian)", "boxgen_tricubic_interp")] + \
        [(f"boxgen {f} {q} (BCC)", f"boxgen_{f}_{q}") for f, q in BOXGEN_ROWS]
    for label, key in labelled:
        print(f"| {label} | " + " | ".join(e3(r[key]) for r in rows) + " | " +
              " | ".join(f"{r[key] / r['scipy_cubic']:.3f}" for r in rows) + " |")


if __name__ == "__main__":
    main()
