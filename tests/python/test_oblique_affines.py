"""Oblique affines (a scanner's tilted slices): `boxrecon resample` reads a NIfTI volume whose
affine is not axis-aligned, reconstructs it in its own index space, and maps each output world
point through the inverse of that affine, as scipy.ndimage.affine_transform does with the matrix
inv(A_in) A_out. nibabel (Debian python3-nibabel) writes the files and reads the outputs back;
scipy (Debian python3-scipy) gives the independent values."""
import numpy as np
import pytest

from conftest import cli_error, run
from test_output_frames import nrrd_affine, nrrd_floats, nrrd_header

nib = pytest.importorskip("nibabel")
ndimage = pytest.importorskip("scipy.ndimage")


def rotation(axis, degrees):
    """The rotation by `degrees` about `axis` (Rodrigues' formula)."""
    k = np.asarray(axis, dtype=float)
    k /= np.linalg.norm(k)
    t = np.radians(degrees)
    cross = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(t) * cross + (1 - np.cos(t)) * cross @ cross


def affine(linear, translation):
    a = np.eye(4)
    a[:3, :3] = linear
    a[:3, 3] = translation
    return a


@pytest.fixture
def oblique_volume(tmp_path):
    """An int16 volume of smooth data plus noise on a grid tilted by 25 degrees about (1, 2, 3)
    with anisotropic voxels (1.1 x 0.9 x 1.3 mm), written by nibabel; returns (path, affine as
    nibabel reads it back, data)."""
    rng = np.random.default_rng(33)
    shape = (26, 24, 22)
    index = np.stack(np.meshgrid(*(np.arange(s) for s in shape), indexing="ij"), -1)
    smooth = 400 * np.sin(index[..., 0] / 4.0) * np.cos(index[..., 1] / 5.0) + 30 * index[..., 2]
    data = (smooth + rng.integers(-50, 50, shape)).astype(np.int16)
    a = affine(rotation((1, 2, 3), 25) @ np.diag([1.1, 0.9, 1.3]), (-12.0, 4.0, 7.5))
    path = tmp_path / "oblique.nii.gz"
    nib.save(nib.Nifti1Image(data, a), str(path))
    image = nib.load(str(path))  # the affine as stored (float32 in the header)
    return path, image.affine, np.asarray(image.dataobj).astype(np.float64)


def target_grid(tmp_path, name, linear, source_affine, source_shape, shape=(9, 8, 7)):
    """An image of `shape` with the linear part `linear`, centred on the source volume's centre,
    written by nibabel; returns (path, its affine as stored)."""
    centre = source_affine[:3, :3] @ ((np.asarray(source_shape) - 1) / 2) + source_affine[:3, 3]
    translation = centre - linear @ ((np.asarray(shape) - 1) / 2)
    path = tmp_path / name
    nib.save(nib.Nifti1Image(np.zeros(shape, np.float32), affine(linear, translation)), str(path))
    return path, nib.load(str(path)).affine


def scipy_values(data, source_affine, target_affine, shape, prefilter):
    m = np.linalg.inv(source_affine) @ target_affine
    return ndimage.affine_transform(data, m[:3, :3], offset=m[:3, 3], output_shape=shape, order=3,
                                    prefilter=prefilter, mode="mirror")


@pytest.mark.parametrize("target", ["axis-aligned", "oblique"])
@pytest.mark.parametrize("prefilter", ["none", "interp"])
def test_resample_like_matches_scipy_affine_transform(tmp_path, oblique_volume, target, prefilter):
    """Tricubic (the cubic B-spline) without a prefilter equals affine_transform(order=3,
    prefilter=False); with interp (the spline through the samples) it equals
    affine_transform(order=3, prefilter=True); mirror boundary in both. The grid of --like is
    axis-aligned, or oblique with another rotation; its affine and shape are the output's."""
    source, a_in, data = oblique_volume
    linear = (np.diag([1.2, 1.0, 0.8]) if target == "axis-aligned"
              else rotation((-2, 1, 0.5), 40) @ np.diag([1.2, 1.0, 0.8]))
    like, a_out = target_grid(tmp_path, "like.nii", linear, a_in, data.shape)
    out = tmp_path / "out.nii.gz"
    run("boxrecon", "resample", "--filter", "tricubic", "--prefilter", prefilter, "--volume",
        str(source), "--like", str(like), "--type", "float64", "-o", str(out))
    image = nib.load(str(out))
    assert image.shape == (9, 8, 7)
    np.testing.assert_allclose(image.affine, a_out, atol=1e-5)
    expected = scipy_values(data, a_in, a_out, (9, 8, 7), prefilter == "interp")
    # Both evaluate the same spline at the same index points (inv(A_in) A_out in double): the
    # difference is rounding, far below 1e-9 of the data's range (about 1300).
    np.testing.assert_allclose(image.get_fdata(), expected, rtol=0, atol=1e-9 * np.ptp(data))
    assert np.ptp(expected) > 100  # the grid crosses the data's structure


def test_resample_onto_its_own_oblique_grid(tmp_path, oblique_volume):
    """Without --like the output stays on the volume's tilted axes: nibabel reads the file's own
    affine back (sform and qform, with the input's codes), and tricubic with interp reproduces
    the samples."""
    source, a_in, data = oblique_volume
    out = tmp_path / "self.nii"
    run("boxrecon", "resample", "--filter", "tricubic", "--prefilter", "interp", "--volume",
        str(source), "--like", str(source), "--type", "float64", "-o", str(out))
    image = nib.load(str(out))
    np.testing.assert_allclose(image.affine, a_in, atol=1e-5)
    sform, sform_code = image.header.get_sform(coded=True)
    # The input's own codes (nibabel wrote it: sform 2, qform 0), claimed again; the qform is
    # written all the same and gives the same affine.
    source_header = nib.load(str(source)).header
    assert int(sform_code) == int(source_header["sform_code"]) > 0
    assert int(image.header["qform_code"]) == int(source_header["qform_code"])
    np.testing.assert_allclose(image.header.get_qform(), sform, atol=1e-5)
    np.testing.assert_allclose(image.get_fdata(), data, atol=1e-8)
    # --size over the default box, on the volume's own axes: in the volume's index space the
    # output's axes are the volume's (a diagonal map with positive steps) and its box spans the
    # samples (the strict boundary's region: the stencil inside the volume).
    run("boxrecon", "resample", "--filter", "tricubic", "--boundary", "strict", "--volume",
        str(source), "--size", "6", "5", "4", "--type", "float64", "-o", str(out))
    image = nib.load(str(out))
    assert image.shape == (6, 5, 4)
    to_index = np.linalg.inv(a_in) @ image.affine
    steps = np.diag(to_index[:3, :3])
    np.testing.assert_allclose(to_index[:3, :3], np.diag(steps), atol=1e-5)
    assert np.all(steps > 0)
    first, last = to_index[:3, 3], to_index[:3, 3] + steps * [5, 4, 3]
    assert np.all(first >= 0.99) and np.all(first <= 1.01)
    assert np.all(last >= np.asarray(data.shape) - 2.01) and np.all(last < np.asarray(data.shape) - 1)
    # Into NRRD: the same grid, its affine as oblique space directions.
    nrrd = tmp_path / "self.nrrd"
    run("boxrecon", "resample", "--filter", "tricubic", "--boundary", "strict", "--volume",
        str(source), "--size", "6", "5", "4", "--type", "float32", "-o", str(nrrd))
    fields = nrrd_header(nrrd)
    assert fields["space"] == "right-anterior-superior"
    np.testing.assert_allclose(nrrd_affine(fields), image.affine, atol=1e-5)
    np.testing.assert_allclose(nrrd_floats(nrrd, fields), image.get_fdata(), rtol=0, atol=1e-3)


def test_world_box_of_an_oblique_volume(tmp_path, oblique_volume):
    """--min/--max are world coordinates: the output is axis-aligned in the world (its affine the
    box's grid), with scipy's values at those world points; NRRD can hold it."""
    source, a_in, data = oblique_volume
    centre = a_in[:3, :3] @ ((np.asarray(data.shape) - 1) / 2) + a_in[:3, 3]
    lo, hi = centre - 4, centre + 4
    out = tmp_path / "box.nrrd"
    run("boxrecon", "resample", "--filter", "tricubic", "--volume", str(source), "--min",
        *map(str, lo), "--max", *map(str, hi), "--size", "5", "6", "7", "-o", str(out))
    run("boxrecon", "resample", "--filter", "tricubic", "--volume", str(source), "--min",
        *map(str, lo), "--max", *map(str, hi), "--size", "5", "6", "7", "--type", "float64",
        "-o", str(tmp_path / "box.nii"))
    image = nib.load(str(tmp_path / "box.nii"))
    a_out = affine(np.diag((hi - lo) / [4, 5, 6]), lo)
    np.testing.assert_allclose(image.affine, a_out, atol=1e-5)
    expected = scipy_values(data, a_in, a_out, (5, 6, 7), False)
    np.testing.assert_allclose(image.get_fdata(), expected, rtol=0, atol=1e-9 * np.ptp(data))
    assert out.exists()


def test_oblique_refusals(tmp_path, oblique_volume):
    """One line, no file: a --like grid that leaves the volume."""
    source, a_in, data = oblique_volume
    out = tmp_path / "o.nii"
    far, _ = target_grid(tmp_path, "far.nii", 3 * np.eye(3), a_in, data.shape, shape=(20, 20, 20))
    message = cli_error("boxrecon", "resample", "--filter", "tricubic", "--volume", str(source),
                        "--like", str(far), "-o", str(out))
    assert "leaves the region" in message and not out.exists()


def test_python_resample_affine_and_like_match_scipy(tmp_path, oblique_volume):
    """boxgen.resample(volume, filter, affine=A, shape=S): the spline at the world points
    A (i, j, k, 1), oblique or not; like=FILE: that image's grid (its shape and affine). An
    axis-aligned anisotropic volume, tricubic without a prefilter, against affine_transform with
    inv(A_volume) A (order=3, prefilter=False)."""
    boxgen = pytest.importorskip("boxgen")
    _, _, data = oblique_volume
    a_vol = affine(np.diag([1.1, 0.9, 1.3]), (-12.0, 4.0, 7.5))
    volume = boxgen.Volume(data[None], lattice="cartesian", affine=a_vol)
    tricubic = boxgen.Filter("tricubic")
    linear = rotation((-2, 1, 0.5), 40) @ np.diag([1.2, 1.0, 0.8])
    like, a_out = target_grid(tmp_path, "like.nii.gz", linear, a_vol, data.shape)
    expected = scipy_values(data, a_vol, a_out, (9, 8, 7), False)
    tolerance = 1e-9 * np.ptp(data)
    got = boxgen.resample(volume, tricubic, affine=a_out, shape=(9, 8, 7))
    assert got.shape == (9, 8, 7)
    np.testing.assert_allclose(got, expected, rtol=0, atol=tolerance)
    np.testing.assert_allclose(boxgen.resample(volume, tricubic, like=str(like)), expected, rtol=0,
                               atol=tolerance)
    # Interp (the spline through the samples) with the mirror boundary: scipy's prefilter=True.
    np.testing.assert_allclose(boxgen.resample(volume, tricubic, "interp", like=like),
                               scipy_values(data, a_vol, a_out, (9, 8, 7), True), rtol=0,
                               atol=10 * tolerance)
    with pytest.raises(ValueError, match="one of"):
        boxgen.resample(volume, tricubic, lo=(0, 0, 0), hi=(1, 1, 1), affine=a_out)
    with pytest.raises(ValueError, match="like or shape"):
        boxgen.resample(volume, tricubic, like=str(like), shape=4)
    with pytest.raises(ValueError, match="last row"):
        boxgen.resample(volume, tricubic, affine=np.ones((4, 4)), shape=4)
    with pytest.raises(ValueError, match="leaves the region"):
        boxgen.resample(volume, tricubic, affine=affine(5 * np.eye(3), a_vol[:3, 3]), shape=20)


def test_python_oblique_volume_reads_resamples_and_writes(tmp_path, oblique_volume):
    """boxgen.read_volume of a tilted NIfTI keeps its affine (Volume.frame, as boxrecon keeps it):
    its samples as stored, its positions affine @ (i, j, k, 1); resample onto another image's
    grid (like=, affine=) or a world box (lo, hi) equals affine_transform with inv(A_in) A_out;
    Volume(affine=) of the same affine is the same volume; write_volume writes NIfTI that nibabel
    reads back with that affine, and NRRD with oblique space directions; pickling keeps the
    frame."""
    import pickle

    boxgen = pytest.importorskip("boxgen")
    source, a_in, data = oblique_volume
    v = boxgen.read_volume(str(source))
    assert v.frame is not None and "oblique" in repr(v)
    np.testing.assert_allclose(v.affine, a_in, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(v.samples[0], data)
    np.testing.assert_allclose(v.spacings, [1.1, 0.9, 1.3], rtol=1e-6)
    np.testing.assert_allclose(v.origin, a_in[:3, 3], rtol=0, atol=1e-12)
    ijk = np.array([3, 5, 7])
    index = ijk[0] + data.shape[0] * (ijk[1] + data.shape[1] * ijk[2])
    np.testing.assert_allclose(v.positions()[index], (a_in @ [*ijk, 1])[:3], rtol=0, atol=1e-12)

    tricubic = boxgen.Filter("tricubic")
    tolerance = 1e-9 * np.ptp(data)
    like, a_out = target_grid(tmp_path, "like.nii", rotation((-2, 1, 0.5), 40) @
                              np.diag([1.2, 1.0, 0.8]), a_in, data.shape)
    for prefilter in ("none", "interp"):
        expected = scipy_values(data, a_in, a_out, (9, 8, 7), prefilter == "interp")
        got = boxgen.resample(v, tricubic, prefilter, like=like)
        np.testing.assert_allclose(got, expected, rtol=0, atol=tolerance)
        np.testing.assert_allclose(boxgen.resample(v, tricubic, prefilter, affine=a_out,
                                                   shape=(9, 8, 7)), expected, rtol=0,
                                   atol=tolerance)
    # The CLI's file of the same resampling (boxrecon resample --like).
    out = tmp_path / "cli.nii"
    run("boxrecon", "resample", "--filter", "tricubic", "--volume", str(source), "--like",
        str(like), "--type", "float64", "-o", str(out))
    np.testing.assert_allclose(boxgen.resample(v, tricubic, like=like),
                               nib.load(str(out)).get_fdata(), rtol=0, atol=tolerance)
    # A world box: the output axis-aligned in the world.
    centre = a_in[:3, :3] @ ((np.asarray(data.shape) - 1) / 2) + a_in[:3, 3]
    lo, hi = centre - 4, centre + 4
    np.testing.assert_allclose(
        boxgen.resample(v, tricubic, lo=lo, hi=hi, shape=(5, 6, 7)),
        scipy_values(data, a_in, affine(np.diag((hi - lo) / [4, 5, 6]), lo), (5, 6, 7), False),
        rtol=0, atol=tolerance)

    # Volume(affine=) of the file's affine: the same frame and spacings, the same values.
    w = boxgen.Volume(data[None], lattice="cartesian", affine=a_in)
    np.testing.assert_array_equal(w.frame, v.frame)
    assert w.spacings == v.spacings
    np.testing.assert_array_equal(boxgen.resample(w, tricubic, like=like),
                                  boxgen.resample(v, tricubic, like=like))

    again = pickle.loads(pickle.dumps(v))
    np.testing.assert_array_equal(again.frame, v.frame)
    np.testing.assert_array_equal(again.affine, v.affine)
    np.testing.assert_array_equal(boxgen.resample(again, tricubic, like=like),
                                  boxgen.resample(v, tricubic, like=like))

    written = tmp_path / "written.nii.gz"
    boxgen.write_volume(str(written), v, type="int16")
    image = nib.load(str(written))
    np.testing.assert_allclose(image.affine, a_in, atol=1e-5)  # float32 in the header
    np.testing.assert_array_equal(np.asarray(image.dataobj), data)
    back = boxgen.read_volume(str(written))
    np.testing.assert_allclose(back.frame, v.frame, atol=1e-6)
    # NRRD holds the affine as oblique space directions (double precision).
    nrrd = tmp_path / "written.nrrd"
    boxgen.write_volume(str(nrrd), v)
    back = boxgen.read_volume(str(nrrd))
    np.testing.assert_allclose(back.affine, v.affine, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(back.samples, v.samples)

    # Without a grid, an oblique volume's output grid is not guessed.
    with pytest.raises(ValueError, match="the volume is oblique: give the output grid"):
        boxgen.resample(v, tricubic)
    # Lattice volumes are axis-aligned: an oblique volume goes onto a Cartesian grid first.
    with pytest.raises(ValueError, match="resamples onto Cartesian grids only"):
        boxgen.resample(v, tricubic, lattice="bcc", spacing=1.0)


def test_python_dask_resample_of_an_oblique_volume(oblique_volume, tmp_path):
    """boxgen.dask.resample of an oblique volume equals boxgen.resample bit for bit, and refuses
    the default grid as boxgen.resample does."""
    boxgen = pytest.importorskip("boxgen")
    bdask = pytest.importorskip("boxgen.dask")
    source, a_in, data = oblique_volume
    v = boxgen.read_volume(str(source))
    tricubic = boxgen.Filter("tricubic")
    like, _ = target_grid(tmp_path, "like.nii", np.diag([1.2, 1.0, 0.8]), a_in, data.shape)
    lazy = bdask.resample(v, tricubic, "q1", like=str(like), chunks=4)
    np.testing.assert_array_equal(lazy.compute(scheduler="threads"),
                                  boxgen.resample(v, tricubic, "q1", like=str(like)))
    with pytest.raises(ValueError, match="the volume is oblique"):
        bdask.resample(v, tricubic)


def quadratic_on_a_tilted_grid(tmp_path):
    """f(w) = w.Q w + b.w + 3 sampled (float64) at the world points of a 14 x 13 x 12 grid tilted
    by 30 degrees about (2, -1, 1) with voxels 0.8 x 1.1 x 0.95, written by nibabel; returns
    (path, affine, f, gradient, Hessian) with the world gradient and Hessian known exactly."""
    q = np.array([[0.3, 0.1, -0.2], [0.1, -0.4, 0.05], [-0.2, 0.05, 0.25]])
    b = np.array([0.7, -1.3, 0.4])

    def f(w):
        return np.einsum("ni,ij,nj->n", w, q, w) + w @ b + 3

    a = affine(rotation((2, -1, 1), 30) @ np.diag([0.8, 1.1, 0.95]), (5.0, -2.0, 1.5))
    shape = (14, 13, 12)
    index = np.stack(np.meshgrid(*(np.arange(s) for s in shape), indexing="ij"), -1)
    world = index.reshape(-1, 3) @ a[:3, :3].T + a[:3, 3]
    path = tmp_path / "quadratic.nii"
    nib.save(nib.Nifti1Image(f(world).reshape(shape), a), str(path))
    a = nib.load(str(path)).affine  # as stored: the samples are f at the stored grid's points
    world = index.reshape(-1, 3) @ a[:3, :3].T + a[:3, 3]
    nib.save(nib.Nifti1Image(f(world).reshape(shape), a), str(path))
    return path, a, f, (lambda w: 2 * w @ q + b), 2 * q


def test_eval_of_an_oblique_volume_maps_derivatives_to_world(tmp_path):
    """boxrecon eval and Filter.evaluate on a tilted grid: a world point maps through the inverse
    affine, the gradient back as A^-T g, the Hessian as A^-T H A^-1. Tricubic with its q1
    prefilter reproduces the quadratic exactly away from the boundary (approximation order 4), so
    the world value, gradient and Hessian are f's own, up to rounding."""
    boxgen = pytest.importorskip("boxgen")
    path, a, f, gradient, hessian = quadratic_on_a_tilted_grid(tmp_path)
    rng = np.random.default_rng(7)
    index = 4.5 + 2 * rng.random((40, 3))  # the prefilter's and spline's stencils inside
    points = index @ a[:3, :3].T + a[:3, 3]
    points_file = tmp_path / "points.txt"
    points_file.write_text("".join(f"{x!r} {y!r} {z!r}\n" for x, y, z in points))
    _, out, _ = run("boxrecon", "eval", "--filter", "tricubic", "--prefilter", "q1", "--volume",
                    str(path), "--points", str(points_file), "--gradient", "--hessian")
    got = np.loadtxt(out.splitlines())
    # Rounding only (measured 1.4e-14, 8.9e-15, 1.3e-14; values up to 26).
    np.testing.assert_allclose(got[:, 0], f(points), rtol=0, atol=1e-12)
    np.testing.assert_allclose(got[:, 1:4], gradient(points), rtol=0, atol=1e-12)
    h = hessian[[0, 0, 0, 1, 1, 2], [0, 1, 2, 1, 2, 2]]  # xx xy xz yy yz zz
    np.testing.assert_allclose(got[:, 4:], np.tile(h, (len(points), 1)), rtol=0, atol=1e-12)
    # The map matters: in the volume's own frame (its axes R) the gradient R^T g is not g.
    frame = a[:3, :3] / np.linalg.norm(a[:3, :3], axis=0)
    assert np.abs(gradient(points) @ frame - gradient(points)).max() > 0.1

    v = boxgen.read_volume(str(path))
    values, gradients, hessians = boxgen.Filter("tricubic").evaluate(v, points, "q1",
                                                                     hessian=True)
    # The same path as boxrecon eval: its printed values (%.17g) bit for bit.
    np.testing.assert_array_equal(values, got[:, 0])
    np.testing.assert_array_equal(gradients, got[:, 1:4])
    np.testing.assert_array_equal(hessians, got[:, 4:])


def test_oblique_nrrd_reads_as_the_nifti_of_the_same_affine(tmp_path, oblique_volume):
    """A Cartesian NRRD with oblique space directions (as 3D Slicer writes tilted scans) reads as
    an oblique volume in Python and in boxrecon resample and eval: the same frame as the NIfTI
    file of the same affine, so the same values bit for bit."""
    boxgen = pytest.importorskip("boxgen")
    source, a_in, data = oblique_volume
    path = tmp_path / "oblique.nrrd"
    vectors = " ".join("({!r},{!r},{!r})".format(*a_in[:3, c]) for c in range(3))
    header = ("NRRD0004\ntype: double\ndimension: 3\nspace: right-anterior-superior\n"
              f"sizes: {' '.join(map(str, data.shape))}\nspace directions: {vectors}\n"
              "kinds: domain domain domain\nendian: little\nencoding: raw\n"
              "space origin: ({!r},{!r},{!r})\n\n".format(*a_in[:3, 3]))
    path.write_bytes(header.encode() + data.astype("<f8").tobytes(order="F"))
    v, w = boxgen.read_volume(str(path)), boxgen.read_volume(str(source))
    np.testing.assert_array_equal(v.frame, w.frame)
    np.testing.assert_array_equal(v.affine, w.affine)
    np.testing.assert_array_equal(v.samples, w.samples)
    tricubic = boxgen.Filter("tricubic")
    like, _ = target_grid(tmp_path, "like.nii", np.diag([1.2, 1.0, 0.8]), a_in, data.shape)
    np.testing.assert_array_equal(boxgen.resample(v, tricubic, like=like),
                                  boxgen.resample(w, tricubic, like=like))
    outs = []
    for volume in (path, source):
        out = tmp_path / f"from-{volume.suffix}.nii"
        run("boxrecon", "resample", "--filter", "tricubic", "--volume", str(volume), "--like",
            str(like), "--type", "float64", "-o", str(out))
        outs.append(nib.load(str(out)).get_fdata())
    np.testing.assert_array_equal(outs[0], outs[1])
    # Singular directions: one line.
    path.write_bytes(header.replace(vectors, "(1,0,0) (2,0,0) (0,0,1)").encode() +
                     data.astype("<f8").tobytes(order="F"))
    with pytest.raises(ValueError, match="space directions is singular"):
        boxgen.read_volume(str(path))


def test_compare_maps_reference_points_between_frames(tmp_path):
    """boxrecon compare with an oblique reference, an oblique volume, or both: each reference grid
    point maps from the reference's frame to the volume's. A quadratic sampled on a tilted grid
    (the reference) and on an axis-aligned grid around it (the volume), or the other way round:
    tricubic with q1 reproduces it, so the errors are float rounding (the command reads floats),
    and the points compared are exactly the reference points whose world position lies in the
    volume's box (counted here from the affines)."""
    tilted, a, f, _, _ = quadratic_on_a_tilted_grid(tmp_path)
    shape = (14, 13, 12)
    corners = np.array([[i, j, k, 1] for i in (0, shape[0] - 1) for j in (0, shape[1] - 1)
                        for k in (0, shape[2] - 1)]) @ a.T
    lo, hi = corners[:, :3].min(0) - 3, corners[:, :3].max(0) + 3  # the stencils inside
    n = np.ceil((hi - lo) / 0.7).astype(int) + 1
    aligned_affine = affine(np.diag([0.7] * 3), lo)
    grid = np.stack(np.meshgrid(*(np.arange(m) for m in n), indexing="ij"), -1).reshape(-1, 3)
    aligned = tmp_path / "aligned.nii"
    nib.save(nib.Nifti1Image(f(grid * 0.7 + lo).reshape(tuple(n)), aligned_affine), str(aligned))
    aligned_affine = nib.load(str(aligned)).affine
    assert np.allclose(aligned_affine[:3, 3], lo)  # float32 header: lo itself, near enough

    def compare(reference, volume, *more):
        _, out, _ = run("boxrecon", "compare", "--reference", str(reference), "--volume",
                        str(volume), "--filter", "tricubic", "--prefilter", "q1", "--json", *more)
        import json
        return json.loads(out)["region"]

    # Oblique reference, axis-aligned volume: its box (mirror boundary: the sampled box) holds
    # the whole tilted grid.
    region = compare(tilted, aligned)
    assert region["points"] == np.prod(shape)
    assert region["max"] < 1e-4 * 26
    # Axis-aligned reference, oblique volume: the reference points inside the tilted grid's box
    # (in its own frame: index 0 .. n - 1 on each axis, up to rounding at the faces).
    # Near the tilted grid's faces the mirror boundary bends the quadratic; 3 voxels in, it is f.
    error = tmp_path / "aligned-error.nii"
    region = compare(aligned, tilted, "--error-volume", str(error))
    # The region the filter reconstructs (with the mirror extension: beyond the samples), in the
    # tilted volume's own frame; points within 1e-4 of its faces may go either way (compare reads
    # floats: its box is pulled in by 16 float ulps).
    boxgen = pytest.importorskip("boxgen")
    tricubic, v = boxgen.Filter("tricubic"), boxgen.read_volume(str(tilted))
    box_lo, box_hi = map(np.asarray, tricubic.default_box(tricubic.prefilter_volume(v, "q1")))
    world = np.c_[grid, np.ones(len(grid))] @ aligned_affine.T
    in_frame = (world @ np.linalg.inv(v.frame).T)[:, :3]
    inside = np.all((in_frame >= box_lo) & (in_frame <= box_hi), 1)
    near_face = np.any(np.minimum(np.abs(in_frame - box_lo), np.abs(in_frame - box_hi)) < 1e-4, 1)
    assert abs(region["points"] - inside.sum()) <= near_face.sum()
    index = (world @ np.linalg.inv(a).T)[:, :3]
    errors = nib.load(str(error)).get_fdata().reshape(-1)  # [i, j, k] as `grid`
    interior = np.all((index >= 3) & (index <= np.asarray(shape) - 4), 1)
    assert interior.sum() > 100
    assert np.abs(errors[interior]).max() < 1e-4 * 26
    assert np.all(errors[~inside & ~near_face] == 0)  # not compared: 0 in the error volume
    # The same oblique frame on both sides, and the error volume on the oblique reference's grid.
    error = tmp_path / "error.nii.gz"
    region = compare(tilted, tilted, "--error-volume", str(error))
    assert region["points"] == np.prod(shape)
    image = nib.load(str(error))
    np.testing.assert_allclose(image.affine, a, atol=1e-5)
    assert np.abs(image.get_fdata()[3:-3, 3:-3, 3:-3]).max() < 1e-4 * 26
    # One line, no file: an oblique reference's error volume into NRRD, a world box.
    out = tmp_path / "error.nrrd"
    message = cli_error("boxrecon", "compare", "--reference", str(tilted), "--volume",
                        str(aligned), "--filter", "tricubic", "--error-volume", str(out))
    assert "write --error-volume as NIfTI" in message and not out.exists()
    message = cli_error("boxrecon", "compare", "--reference", str(tilted), "--volume",
                        str(aligned), "--filter", "tricubic", "--box", "0", "1")
    assert "world coordinates" in message
