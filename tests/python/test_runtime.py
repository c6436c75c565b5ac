"""boxgen.Volume, Filter, read_volume, write_volume, sample, resample against boxrecon, bit for bit
where boxrecon prints 17 digits, and the Python-side guarantees (no copies, the GIL, threads)."""
import os
import sys
import threading
import time

import numpy as np
import pytest

import boxgen
from conftest import points_in, run


def test_filter_properties_are_the_papers():
    m7 = boxgen.Filter("m7")
    # Kim 2013, Table 1: M7 is a quartic, C^2, approximation order 4, support 120, 30 stencil points.
    assert (m7.name, m7.lattice, m7.degree, m7.continuity, m7.approximation_order) == (
        "m7", "bcc", 4, 2, 4)
    assert (m7.support_volume, m7.stencil_size, m7.linearly_independent) == (120, 30, False)
    assert m7.spec == "1,1,1; 1,-1,-1; -1,1,-1; -1,-1,1; 2,0,0; 0,2,0; 0,0,2"
    offsets, weights = m7.prefilters["q1"]
    assert offsets.shape == (len(weights), 3)
    assert weights[np.all(offsets == 0, axis=1)][0] == pytest.approx(5 / 3, abs=1e-15)
    assert weights.sum() == pytest.approx(1, abs=1e-14)
    fcc = boxgen.Filter("fcc6", lattice="fcc")
    assert (fcc.lattice, fcc.degree) == ("fcc", 3)
    assert sorted(boxgen.filters()) == sorted(["m7", "m8", "m12", "fcc6", "tricubic", "cart7"])


def test_volume_samples_are_a_view(ml_volume, tmp_path):
    v = boxgen.sample("cubic", 5)
    a = v.samples
    assert a.shape == (2,) + tuple(v.sizes) and a.base is not None
    assert not a.flags.owndata
    b = v.samples
    assert np.shares_memory(a, b)  # both views of the one storage
    a[1, 2, 3, 4] = 42.0
    path = str(tmp_path / "v.nrrd")
    boxgen.write_volume(path, v)
    assert boxgen.read_volume(path).samples[1, 2, 3, 4] == 42.0
    del v  # the view keeps the volume alive
    assert a[1, 2, 3, 4] == 42.0


def test_volume_geometry_and_positions():
    v = boxgen.sample("cubic", 5)
    assert v.lattice == "bcc" and v.period == 2
    # N = 5 over [-1, 1]: coset cells of 2/(N-1) = 0.5, h = 0.25; boxrecon's margin of 3 cells.
    assert v.spacing == 0.25 and v.origin == (-2.5, -2.5, -2.5) and v.sizes == [11, 11, 11]
    p = v.positions()
    assert np.array_equal(p[0], [-2.5, -2.5, -2.5]) and np.array_equal(p[1], [-2.25] * 3)
    # Sample (c, i, j, k) at origin + h (2 (i, j, k) + c): the Fortran order of (K, N0, N1, N2).
    assert np.array_equal(p.reshape(11, 11, 11, 2, 3)[4, 3, 2, 1], -2.5 + 0.25 * np.array(
        [2 * 2 + 1, 2 * 3 + 1, 2 * 4 + 1]))


def test_sample_equals_boxrecon_sample(tmp_path):
    path = str(tmp_path / "ml.nrrd")
    run("boxrecon", "sample", "--function", "ml", "--n", "7", "--lattice", "fcc", "-o", path)
    cli = boxgen.read_volume(path)
    py = boxgen.sample("ml", 7, lattice="fcc")
    assert np.array_equal(cli.samples, py.samples)
    assert (cli.lattice, cli.spacing, cli.origin, cli.sizes) == (
        py.lattice, py.spacing, py.origin, py.sizes)


def test_sample_a_callable_once_vectorised():
    calls = []

    def f(points):
        calls.append(points.shape)
        return points[:, 0] - 2 * points[:, 2]

    v = boxgen.sample(f, 5, lattice="cartesian")
    assert len(calls) == 1 and calls[0] == (v.samples.size, 3)
    p = v.positions()
    assert np.array_equal(v.samples.ravel(order="F"), p[:, 0] - 2 * p[:, 2])


def test_volume_from_numpy_and_pickle():
    import pickle
    a = np.arange(2 * 4 * 5 * 6, dtype=np.float32).reshape(2, 4, 5, 6)
    v = boxgen.Volume(a, lattice="bcc", spacing=0.5, origin=(1, 2, 3))
    assert np.array_equal(v.samples, a) and v.sizes == [4, 5, 6] and v.origin == (1.0, 2.0, 3.0)
    w = pickle.loads(pickle.dumps(v))
    assert np.array_equal(w.samples, a) and w.spacing == 0.5 and w.lattice == "bcc"
    f = pickle.loads(pickle.dumps(boxgen.Filter("m8")))
    assert f.name == "m8"


def eval_cli(tmp_path, volume, points, *args):
    vpath, ppath = str(tmp_path / "v.nrrd"), str(tmp_path / "p.txt")
    boxgen.write_volume(vpath, volume)
    np.savetxt(ppath, points, fmt="%.17g")
    out = run("boxrecon", "eval", "--volume", vpath, "--points", ppath, *args)[1]
    return np.array([[float(x) for x in line.split()] for line in out.splitlines()])


@pytest.mark.parametrize("name,lattice,prefilter", [("m7", "bcc", "q2"), ("m12", "bcc", None),
                                                    ("fcc6", "fcc", "q1"),
                                                    ("tricubic", "cartesian", "q2"),
                                                    ("m8", "bcc", "interp"),
                                                    ("m7", "bcc", "interp:0.01"),
                                                    ("fcc6", "fcc", "interp"),
                                                    ("m8", "bcc", "q2opt")])
def test_evaluate_is_boxrecon_eval_bit_for_bit(tmp_path, rng, name, lattice, prefilter):
    f = boxgen.Filter(name)
    v = boxgen.sample("ml", 7, lattice=lattice)
    pv = v if prefilter is None else f.prefilter_volume(v, prefilter)
    points = points_in(f.default_box(pv), 200, rng)
    values, gradients, hessians = f.evaluate(v, points, prefilter=prefilter, hessian=True)
    cli = eval_cli(tmp_path, v, points, "--filter", name, "--prefilter", prefilter or "none",
                   "--gradient", "--hessian")
    assert np.array_equal(cli[:, 0], values)
    assert np.array_equal(cli[:, 1:4], gradients)
    assert np.array_equal(cli[:, 4:], hessians)
    assert np.array_equal(f.evaluate(v, points, prefilter), values)
    vg = f.evaluate(v, points, prefilter, gradient=True)
    assert len(vg) == 2 and np.array_equal(vg[1], gradients)


def test_optimised_prefilters_are_boxgen_prefilters():
    # The runtime's q1opt / q2opt are the generated tables: the weights `boxgen prefilter
    # --prefilter q1opt|q2opt` prints (17 digits), at the same offsets.
    for name in ("m7", "m8", "m12", "fcc6", "tricubic", "cart7"):
        taps = boxgen.Filter(name).prefilters
        for q in ("q1opt", "q2opt"):
            printed = boxgen.prefilter(name, prefilter=q)
            offsets, weights = taps[q]
            expected = {tuple(w["offset"]): float(w["weight"].split("/")[0]) /
                        float((w["weight"].split("/") + ["1"])[1]) for w in printed["weights"]}
            assert {tuple(o): w for o, w in zip(offsets.tolist(), weights.tolist())} == expected


def test_interpolation_passes_through_the_samples_and_reports():
    m8, m7 = boxgen.Filter("m8"), boxgen.Filter("m7")
    v = boxgen.sample("ml", 9)
    positions, samples = v.positions(), v.samples.reshape(-1, order="F")
    assert np.allclose(m8.evaluate(v, positions, "interp"), samples, atol=1e-13, rtol=0)
    report = m8.interpolation(v)
    assert report["lambda"] == 0 and report["residual_max"] < 1e-13
    assert report["symbol_min"] == pytest.approx(0.2, abs=1e-12)
    # m7's symbol vanishes: regularised with lambda 1e-3, a residual it reports, as boxrecon does.
    r7 = m7.interpolation(v)
    assert r7["lambda"] == 1e-3 and 0 < r7["residual_max"] < 0.1
    assert r7["symbol_min"] < 1e-6 * r7["symbol_max"]
    offsets, values = boxgen.Filter("tricubic").lattice_values()
    assert offsets.shape == (27, 3) and values.sum() == pytest.approx(1, abs=1e-15)
    # The boundary: strict refuses a face sample's stencil, mirror (the default) evaluates it.
    corner = v.positions()[:1]
    m8.evaluate(v, corner, "interp")
    with pytest.raises(ValueError):
        m8.evaluate(v, corner, "interp", boundary="strict")
    for bad in ("interp:nan", "interp:-1", "interp:x", "interp:0"):
        with pytest.raises(ValueError):
            m7.evaluate(v, corner, bad)
    with pytest.raises(ValueError):
        m8.evaluate(v, corner, boundary="wrap")


def test_evaluate_reproduces_a_cubic():
    # Q^II and M7 (order 4) reproduce cubics: the spline of the sampled cubic is the cubic.
    f = boxgen.Filter("m7")
    v = boxgen.sample("cubic", 9)
    p = np.array([[0.1, -0.3, 0.7], [0, 0, 0], [-0.9, 0.9, 0.2]])
    x, y, z = p.T
    assert np.allclose(f.evaluate(v, p, "q2"), x**3 - 2 * x * y * z + 3 * y**2 - z + 1,
                       atol=1e-11, rtol=0)


def test_resample_is_the_grid_and_boxrecon_resample(tmp_path, ml_volume):
    f = boxgen.Filter("m7")
    lo, hi, shape = (-0.5, -0.4, -0.3), (0.5, 0.6, 0.2), (5, 4, 3)
    grid = boxgen.resample(ml_volume, f, "q2", lo, hi, shape)
    assert grid.shape == shape
    i, j, k = np.meshgrid(*(np.arange(n) for n in shape), indexing="ij")
    idx = np.stack([i, j, k], axis=-1).reshape(-1, 3)
    lo_, hi_ = np.array(lo), np.array(hi)
    points = lo_ + idx * ((hi_ - lo_) / (np.array(shape) - 1))
    assert np.array_equal(grid.reshape(-1), f.evaluate(ml_volume, points, "q2"))
    # The default box and boxrecon resample's file, bit for bit.
    vpath, gpath = str(tmp_path / "v.nrrd"), str(tmp_path / "g.nrrd")
    boxgen.write_volume(vpath, ml_volume)
    run("boxrecon", "resample", "--filter", "m7", "--prefilter", "q2", "--volume", vpath, "--n",
        "6", "-o", gpath)
    cli = boxgen.read_volume(gpath)
    assert cli.lattice == "cartesian"
    assert np.array_equal(cli.samples[0], boxgen.resample(ml_volume, f, "q2", shape=6))


def test_resample_onto_a_lattice_is_boxrecon_resample_lattice(tmp_path, ml_volume):
    """resample(lattice=L) returns a Volume on L's grid: the NRRD `boxrecon resample --lattice L`
    writes, bit for bit (samples and geometry), at spacing= h, at about shape^3 samples, over a
    box lo..hi, and on the grid of like= a volume file of L; every value is the spline at its
    sample's world position."""
    f = boxgen.Filter("m7")
    vpath = str(tmp_path / "v.nrrd")
    boxgen.write_volume(vpath, ml_volume)

    def cli(name, *args):
        path = str(tmp_path / name)
        run("boxrecon", "resample", "--filter", "m7", "--prefilter", "q1", "--volume", vpath,
            *args, "-o", path)
        return boxgen.read_volume(path), path

    def same(got, want):
        assert isinstance(got, boxgen.Volume)
        assert (got.lattice, got.coset_offsets, got.sizes) == (want.lattice, want.coset_offsets,
                                                               want.sizes)
        assert got.spacings == want.spacings and got.origin == want.origin
        np.testing.assert_array_equal(got.samples, want.samples)

    fcc, fcc_path = cli("fcc.nrrd", "--lattice", "fcc", "--spacing", "0.3")
    got = boxgen.resample(ml_volume, f, "q1", lattice="fcc", spacing=0.3)
    same(got, fcc)
    assert got.lattice == "fcc" and got.samples.shape[0] == 4
    np.testing.assert_array_equal(got.samples.reshape(-1, order="F"),
                                  f.evaluate(ml_volume, got.positions(), "q1"))
    same(boxgen.resample(ml_volume, f, "q1", like=fcc_path, lattice="fcc"), fcc)
    bcc, _ = cli("bcc.nrrd", "--lattice", "bcc", "--n", "6")
    same(boxgen.resample(ml_volume, f, "q1", shape=6, lattice="bcc"), bcc)
    lo, hi = (-0.6, -0.5, -0.4), (0.5, 0.6, 0.3)
    box, _ = cli("box.nrrd", "--lattice", "bcc", "--spacing", "0.2", "--min", *map(str, lo),
                 "--max", *map(str, hi))
    same(boxgen.resample(ml_volume, f, "q1", lo, hi, lattice="bcc", spacing=0.2), box)
    # lattice="cartesian" is the Cartesian grid's array, as without lattice=.
    np.testing.assert_array_equal(boxgen.resample(ml_volume, f, "q1", shape=5, lattice="cartesian"),
                                  boxgen.resample(ml_volume, f, "q1", shape=5))


@pytest.mark.parametrize("kwargs,message", [
    (dict(lattice="fcc", affine=np.eye(4)), "affine= gives a Cartesian grid"),
    (dict(lattice="fcc", shape=(4, 5, 6)), r"about N\^3 samples"),
    (dict(lattice="fcc", shape=6, spacing=0.3), "spacing or shape, not both"),
    (dict(lattice="fcc", spacing=-0.3), "must be finite and > 0"),
    (dict(lattice="fcc", lo=(0, 0, 0)), "both lo and hi"),
    (dict(lattice="fcc", lo=(-9, -9, -9), hi=(9, 9, 9), spacing=0.5), "region"),
    (dict(spacing=0.3), "spacing= is the h of a lattice= output"),
    (dict(lattice="hexagonal"), "lattice"),
])
def test_resample_onto_a_lattice_refusals(ml_volume, kwargs, message):
    with pytest.raises(ValueError, match=message):
        boxgen.resample(ml_volume, boxgen.Filter("m7"), **kwargs)


def test_resample_onto_a_lattice_like_refusals(tmp_path, ml_volume):
    f = boxgen.Filter("m7")
    path = str(tmp_path / "bcc.nrrd")
    boxgen.write_volume(path, ml_volume)
    with pytest.raises(ValueError, match="differs from the lattice of like"):
        boxgen.resample(ml_volume, f, like=path, lattice="fcc")
    with pytest.raises(ValueError, match="like gives the grid"):
        boxgen.resample(ml_volume, f, like=path, lattice="bcc", spacing=0.3)
    with pytest.raises(ValueError, match="lattice='bcc'"):
        boxgen.resample(ml_volume, f, like=path)  # a Cartesian array cannot take a BCC grid


def test_gil_is_released_during_evaluation(ml_volume, rng):
    f = boxgen.Filter("m7")
    points = points_in(f.default_box(ml_volume), 400000, rng)
    count, stop = [0], threading.Event()

    def tick():
        while not stop.is_set():
            count[0] += 1
            time.sleep(0.0001)  # sleeping drops the GIL: the main thread never waits for it

    old = sys.getswitchinterval()
    sys.setswitchinterval(100)  # no forced switches: only a released GIL lets tick() run
    t = threading.Thread(target=tick)
    t.start()
    try:
        while count[0] == 0:
            time.sleep(0.001)
        before = count[0]
        f.evaluate(ml_volume, points, gradient=True)
        during = count[0] - before
    finally:
        stop.set()
        t.join()
        sys.setswitchinterval(old)
    assert during > 0


def test_threads_honour_boxgen_threads(ml_volume, rng, monkeypatch):
    f = boxgen.Filter("m8")
    points = points_in(f.default_box(ml_volume), 5000, rng)
    many = f.evaluate(ml_volume, points)
    monkeypatch.setenv("BOXGEN_THREADS", "1")
    assert boxgen.threads() == 1
    assert np.array_equal(f.evaluate(ml_volume, points), many)
    monkeypatch.setenv("BOXGEN_THREADS", "lots")
    with pytest.raises(ValueError, match="BOXGEN_THREADS must be a positive integer, got 'lots'"):
        f.evaluate(ml_volume, points)
    monkeypatch.setenv("BOXGEN_THREADS", "2")
    boxgen.set_threads(1)
    assert boxgen.threads() == 1
    boxgen.set_threads(0)
    assert boxgen.threads() == 2


# A SPEC no preset has (M7 without its third axis direction): compiled at run time on first use
# and cached (BOXGEN_CACHE_DIR, set by CTest in the build tree), as `boxrecon --filter SPEC`.
SPEC = "1,1,1; 1,-1,-1; -1,1,-1; -1,-1,1; 2,0,0; 0,2,0"


def test_a_spec_filter_compiled_at_run_time(tmp_path, rng):
    import pickle
    f = boxgen.Filter(SPEC, lattice="bcc")
    assert (f.lattice, f.degree, f.approximation_order, f.directions) == ("bcc", 3, 3, 6)
    assert pickle.loads(pickle.dumps(f)).spec == f.spec
    v = boxgen.sample("ml", 7)
    points = rng.uniform(-1, 1, (100, 3))  # boxrecon's margin holds [-1, 1]^3 for the stencil
    values, gradients = f.evaluate(v, points, "q1", gradient=True)
    cli = eval_cli(tmp_path, v, points, "--filter", SPEC, "--lattice", "bcc", "--prefilter", "q1",
                   "--gradient")
    assert np.array_equal(cli[:, 0], values) and np.array_equal(cli[:, 1:], gradients)
    # Order 3 with Q^I: quadratics are reproduced.
    q = boxgen.sample(lambda p: 1 + p[:, 0] * p[:, 1] - 2 * p[:, 2] ** 2, 9)
    x, y, z = points.T
    assert np.allclose(f.evaluate(q, points, "q1"), 1 + x * y - 2 * z**2, atol=1e-11, rtol=0)


def test_a_spec_filter_takes_its_lattice_from_the_volume():
    import pickle
    v = boxgen.sample("ml", 7)  # on BCC
    f = boxgen.Filter(SPEC, volume=v)  # compiled (or cached) above as SPEC on bcc
    assert (f.lattice, f.degree) == ("bcc", 3)
    assert pickle.loads(pickle.dumps(f)).lattice == "bcc"
    points = np.array([[0.1, -0.2, 0.3], [0.5, 0.25, -0.75]])
    assert np.array_equal(f.evaluate(v, points), boxgen.Filter(SPEC, "bcc").evaluate(v, points))
    assert boxgen.Filter(SPEC, lattice="bcc", volume=v).lattice == "bcc"
    # A lattice the volume is not on: refused before anything is derived or compiled.
    with pytest.raises(ValueError, match="^lattice is fcc, but the volume is on the bcc lattice$"):
        boxgen.Filter(SPEC, lattice="fcc", volume=v)
    # A registry name keeps its own lattice (evaluate then checks the volume against it).
    assert boxgen.Filter("m7", volume=v).name == "m7"
    with pytest.raises(ValueError, match="lattice"):
        boxgen.Filter("tricubic", volume=v).evaluate(v, points)
    with pytest.raises(TypeError):
        boxgen.Filter(SPEC, volume="bcc.nrrd")
