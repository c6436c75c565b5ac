"""Scanner volumes in Python: read_volume takes NIfTI (.nii, .nii.gz, .hdr/.img
pairs) as well as NRRD, write_volume writes both by the name, and Volume takes three spacings or
an affine (oblique ones: test_oblique_affines.py). The files are written here by nibabel (Debian python3-nibabel) and read
back by it: every expected value comes from nibabel, never from boxgen."""
import pickle
import warnings

import numpy as np
import pytest

import boxgen

nib = pytest.importorskip("nibabel")


def scanner_image(tmp_path, name, maker=None):
    """An anisotropic int16 image with a scale slope and a reversed x axis (0.9 x 0.9 x 3 mm,
    as an MRI series), saved by nibabel under `name`."""
    rng = np.random.default_rng(33)
    data = rng.integers(-300, 300, size=(6, 7, 5)).astype(np.int16)
    affine = np.diag([-0.9, 0.9, 3.0, 1.0])
    affine[:3, 3] = (40.5, -12.0, 7.5)
    image = (maker or nib.Nifti1Image)(data, affine)
    image.header.set_slope_inter(0.5, 10.0)
    path = tmp_path / name
    nib.save(image, str(path))
    return path


@pytest.mark.parametrize("name,maker", [("s.nii", None), ("s.nii.gz", None), ("s.hdr", "pair"),
                                        ("s.img", "pair")])
def test_read_volume_of_nifti_is_nibabels_canonical_image(tmp_path, name, maker):
    written = "s.hdr" if maker else name
    scanner_image(tmp_path, written, nib.Nifti1Pair if maker else None)
    volume = boxgen.read_volume(str(tmp_path / name))
    # boxgen orients every axis positive (the samples reversed along x, the origin moved), as
    # nibabel's closest canonical (RAS+) image does for an axis-aligned affine.
    canonical = nib.as_closest_canonical(nib.load(str(tmp_path / written)))
    assert volume.lattice == "cartesian"
    assert volume.sizes == [6, 7, 5]
    np.testing.assert_array_equal(volume.samples[0], canonical.get_fdata())
    np.testing.assert_allclose(volume.affine, canonical.affine, rtol=0, atol=1e-6)
    np.testing.assert_allclose(volume.spacings, canonical.header.get_zooms(), rtol=1e-6)
    with pytest.raises(ValueError, match="anisotropic.*spacings"):
        _ = volume.spacing


def test_volume_takes_three_spacings_or_an_affine(tmp_path):
    data = np.arange(4 * 5 * 6, dtype=np.float64).reshape(1, 4, 5, 6)
    v = boxgen.Volume(data, lattice="cartesian", spacing=(0.9, 0.9, 3.0), origin=(1, 2, 3))
    assert v.spacings == (0.9, 0.9, 3.0)
    expected = np.diag([0.9, 0.9, 3.0, 1.0])
    expected[:3, 3] = (1, 2, 3)
    np.testing.assert_array_equal(v.affine, expected)
    assert "spacings (0.9, 0.9, 3)" in repr(v)
    # The world position of sample (i, j, k) is affine @ (i, j, k, 1).
    p = v.positions()
    np.testing.assert_allclose(p[1 + 4 * 2 + 20 * 3], (expected @ [1, 2, 3, 1])[:3])
    again = pickle.loads(pickle.dumps(v))
    assert again.spacings == v.spacings and again.origin == v.origin
    np.testing.assert_array_equal(again.samples, v.samples)

    # An affine with a reversed axis: the same world positions and values as nibabel's canonical
    # image of that affine.
    affine = np.diag([0.9, -0.9, 3.0, 1.0])
    affine[:3, 3] = (-4, 6, 0.5)
    w = boxgen.Volume(data, lattice="cartesian", affine=affine)
    canonical = nib.as_closest_canonical(nib.Nifti1Image(data[0], affine))
    np.testing.assert_allclose(w.affine, canonical.affine, atol=1e-12)
    np.testing.assert_array_equal(w.samples[0], canonical.get_fdata())
    # Isotropic volumes keep their one spacing.
    assert boxgen.Volume(data, lattice="cartesian", spacing=np.int64(2)).spacing == 2.0


@pytest.mark.parametrize("kwargs,message", [
    (dict(lattice="cartesian", affine=np.array([[1, 1, 0, 0], [0, 0, 0, 0], [0, 0, 1, 0],
                                                [0, 0, 0, 1.0]])), "singular"),
    (dict(lattice="cartesian", affine=np.array([[0, 1, 0, 0], [0, 0, 0, 0], [0, 0, 1, 0],
                                                [0, 0, 0, 1.0]])), "zero or non-finite column 0"),
    (dict(lattice="cartesian", affine=np.eye(3)), "4 x 4"),
    (dict(lattice="cartesian", affine=np.eye(4), spacing=2.0), "not both"),
    (dict(lattice="cartesian", spacing=(1, 2)), "three numbers"),
    (dict(lattice="cartesian", spacing=(1, 0, 2)), "spacing"),
])
def test_bad_geometry_is_a_value_error(kwargs, message):
    with pytest.raises(ValueError, match=message):
        boxgen.Volume(np.zeros((1, 3, 3, 3)), **kwargs)


def test_non_cartesian_volumes_stay_isotropic():
    with pytest.raises(ValueError, match="only Cartesian volumes may be anisotropic"):
        boxgen.Volume(np.zeros((2, 3, 3, 3)), lattice="bcc", spacing=(1, 1, 2))
    with pytest.raises(ValueError, match="negative step"):
        boxgen.Volume(np.zeros((2, 3, 3, 3)), lattice="bcc", affine=np.diag([-1, 1, 1, 1.0]))
    with pytest.raises(ValueError, match="only a Cartesian volume"):
        boxgen.Volume(np.zeros((2, 3, 3, 3)), lattice="bcc",
                      affine=np.array([[1, 0.2, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]]))


@pytest.mark.parametrize("name", ["w.nii", "w.nii.gz"])
def test_write_volume_nifti_reads_in_nibabel(tmp_path, name):
    rng = np.random.default_rng(5)
    data = rng.normal(size=(1, 5, 6, 7))
    v = boxgen.Volume(data, lattice="cartesian", spacing=(0.9, 0.9, 3.0), origin=(-3, 4, 11))
    boxgen.write_volume(str(tmp_path / name), v)
    image = nib.load(str(tmp_path / name))
    assert image.header.get_data_dtype() == np.float32
    np.testing.assert_array_equal(np.asarray(image.dataobj), data[0].astype(np.float32))
    np.testing.assert_allclose(image.affine, v.affine, rtol=1e-7, atol=1e-6)
    # An array's world is tied to no patient: as nibabel's Nifti1Image(data, affine).
    expected = nib.Nifti1Image(data[0], image.affine).header
    assert int(image.header["sform_code"]) == int(expected["sform_code"]) == 2
    assert int(image.header["qform_code"]) == int(expected["qform_code"]) == 0
    # And boxgen reads its own file back (float32 values, the affine to float32's precision).
    back = boxgen.read_volume(str(tmp_path / name))
    np.testing.assert_array_equal(back.samples, data.astype(np.float32))
    np.testing.assert_allclose(back.affine, v.affine, rtol=1e-7)


def test_write_volume_types_and_nrrd(tmp_path):
    data = np.array([-200.5, -1.5, 0.5, 2.5, 3.7, 130.0, 1e5, -1e5]).reshape(1, 2, 2, 2)
    v = boxgen.Volume(data, lattice="cartesian", spacing=(1, 2, 3))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        boxgen.write_volume(str(tmp_path / "i.nii.gz"), v, type="int16")
    assert [str(w.message) for w in caught] == [
        "2 value(s) beyond the range of int16 were clamped to it"]
    image = nib.load(str(tmp_path / "i.nii.gz"))
    assert image.header.get_data_dtype() == np.int16
    # Rounded to nearest, ties to even (NumPy's rint), clamped to int16.
    expected = np.clip(np.rint(data[0]), -32768, 32767)
    np.testing.assert_array_equal(np.asarray(image.dataobj), expected)
    # NRRD keeps float64 by default, with the three spacings.
    boxgen.write_volume(str(tmp_path / "a.nrrd"), v)
    back = boxgen.read_volume(str(tmp_path / "a.nrrd"))
    np.testing.assert_array_equal(back.samples, data)
    assert back.spacings == (1.0, 2.0, 3.0)


def test_write_volume_refusals_leave_no_file(tmp_path):
    bcc = boxgen.sample("ml", 5)
    for name, message in [("b.nii", "Cartesian grids only"), ("b.mha", "no writer knows"),
                          ("b.hdr", "hdr")]:
        with pytest.raises(ValueError, match=message):
            boxgen.write_volume(str(tmp_path / name), bcc)
        assert not (tmp_path / name).exists()
    with pytest.raises(ValueError, match="int8"):
        boxgen.write_volume(str(tmp_path / "t.nrrd"), bcc, type="int7")
    assert not (tmp_path / "t.nrrd").exists()


def test_anisotropic_volume_reconstructs_in_world_coordinates():
    # A linear function on 0.9 x 0.9 x 3 voxels: the tricubic B-spline reproduces it (centred,
    # no prefilter) at world points only if the three spacings are used.
    spacing, origin = np.array([0.9, 0.9, 3.0]), np.array([-2.0, 1.0, 5.0])
    idx = np.indices((8, 8, 8)).reshape(3, -1).T
    world = origin + idx * spacing
    f = lambda p: 0.5 + 0.1 * p[:, 0] - 0.2 * p[:, 1] + 0.05 * p[:, 2]
    data = f(world).reshape(8, 8, 8)
    v = boxgen.Volume(data[None], lattice="cartesian", spacing=tuple(spacing),
                      origin=tuple(origin))
    points = origin + np.array([[3.3, 3.5, 3.7], [4.1, 2.9, 4.6], [3.0, 4.0, 3.5]]) * spacing
    values = boxgen.Filter("tricubic").evaluate(v, points, boundary="strict")
    np.testing.assert_allclose(values, f(points), atol=1e-12)
