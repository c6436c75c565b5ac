"""Oblique affines (a scanner's tilted slices): `boxrecon resample` reads a NIfTI volume whose
affine is not axis-aligned, reconstructs it in its own index space, and maps each output world
point through the inverse of that affine, as scipy.ndimage.affine_transform does with the matrix
inv(A_in) A_out. nibabel (Debian python3-nibabel) writes the files and reads the outputs back;
scipy (Debian python3-scipy) gives the independent values."""
import numpy as np
import pytest

from conftest import cli_error, run

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
    affine back (sform and qform, codes > 0), and tricubic with interp reproduces the samples."""
    source, a_in, data = oblique_volume
    out = tmp_path / "self.nii"
    run("boxrecon", "resample", "--filter", "tricubic", "--prefilter", "interp", "--volume",
        str(source), "--like", str(source), "--type", "float64", "-o", str(out))
    image = nib.load(str(out))
    np.testing.assert_allclose(image.affine, a_in, atol=1e-5)
    sform, sform_code = image.header.get_sform(coded=True)
    qform, qform_code = image.header.get_qform(coded=True)
    assert int(sform_code) > 0 and int(qform_code) > 0
    np.testing.assert_allclose(qform, sform, atol=1e-5)
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
    """One line, no file: an oblique output grid into NRRD, a --like grid that leaves the volume; commands that do not map through the affine still refuse
    an oblique volume, naming its affine."""
    source, a_in, data = oblique_volume
    out = tmp_path / "o.nrrd"
    message = cli_error("boxrecon", "resample", "--filter", "tricubic", "--volume", str(source),
                        "-o", str(out))
    assert "write it as NIfTI" in message and not out.exists()
    out = tmp_path / "o.nii"
    far, _ = target_grid(tmp_path, "far.nii", 3 * np.eye(3), a_in, data.shape, shape=(20, 20, 20))
    message = cli_error("boxrecon", "resample", "--filter", "tricubic", "--volume", str(source),
                        "--like", str(far), "-o", str(out))
    assert "leaves the region" in message and not out.exists()
    message = cli_error("boxrecon", "compare", "--volume", str(source), "--reference",
                        str(source), "--filter", "tricubic")
    assert "oblique" in message


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
