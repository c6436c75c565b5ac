"""NIfTI files of boxrecon as nibabel (Debian python3-nibabel) reads them: the grid, the affine
(sform and qform, with their codes) and the values of `resample -o x.nii[.gz]` against the NRRD
of the same command, --type, and a .hdr/.img pair nibabel writes read back by boxrecon."""
import json
import os

import numpy as np
import pytest

import boxgen
from conftest import cli_error, run

nib = pytest.importorskip("nibabel")


@pytest.fixture
def ml_file(tmp_path):
    path = str(tmp_path / "ml.nrrd")
    run("boxrecon", "sample", "--function", "ml", "--n", "9", "-o", path)
    return path


@pytest.mark.parametrize("name", ["g.nii", "g.nii.gz"])
def test_resample_nifti_matches_the_nrrd_in_nibabel(tmp_path, ml_file, name):
    args = ["resample", "--filter", "m7", "--volume", ml_file, "--n", "6", "--precision", "float",
            "--min", "-0.9", "-0.8", "-0.7", "--max", "0.6", "0.7", "0.9"]
    run("boxrecon", *args, "-o", str(tmp_path / "g.nrrd"))
    run("boxrecon", *args, "-o", str(tmp_path / name))
    grid = boxgen.read_volume(str(tmp_path / "g.nrrd"))
    image = nib.load(str(tmp_path / name))
    assert image.header.get_data_dtype() == np.float32
    data = np.asarray(image.dataobj)
    assert data.shape == (6, 6, 6)
    # boxgen's samples are (coset, i, j, k), nibabel's (i, j, k).
    np.testing.assert_array_equal(data, grid.samples[0].astype(np.float32))
    step = 1.5 / 5, 1.5 / 5, 1.6 / 5
    expected = np.diag([*step, 1.0])
    expected[:3, 3] = (-0.9, -0.8, -0.7)
    np.testing.assert_allclose(image.affine, expected, atol=1e-6)
    # sample's volume is tied to no patient: sform code 2, qform code 0, as nibabel writes a
    # new image (its quaternion still the same affine).
    sform, sform_code = image.header.get_sform(coded=True)
    assert (int(sform_code), int(image.header["qform_code"])) == (2, 0)
    np.testing.assert_allclose(image.header.get_qform(), sform, atol=1e-6)


def test_type_int16_is_rounded_in_nibabel(tmp_path, ml_file):
    args = ["resample", "--filter", "m7", "--volume", ml_file, "--n", "5", "--precision", "double"]
    run("boxrecon", *args, "-o", str(tmp_path / "d.nrrd"))
    run("boxrecon", *args, "-o", str(tmp_path / "i.nii.gz"), "--type", "int16")
    image = nib.load(str(tmp_path / "i.nii.gz"))
    assert image.header.get_data_dtype() == np.int16
    grid = boxgen.read_volume(str(tmp_path / "d.nrrd"))
    expected = np.rint(grid.samples[0])
    np.testing.assert_array_equal(np.asarray(image.dataobj), expected)


def test_nibabel_pair_and_oblique_nrrd_names(tmp_path):
    """A NIfTI .hdr/.img pair nibabel writes reads in boxrecon from either name."""
    data = np.arange(6 * 7 * 8, dtype=np.int16).reshape(6, 7, 8)
    affine = np.diag([0.9, 0.9, 3.0, 1.0])
    affine[:3, 3] = (-2, 1, 4)
    nib.save(nib.Nifti1Pair(data, affine), str(tmp_path / "pair.hdr"))
    assert os.path.exists(tmp_path / "pair.img")
    # subsample onto a Cartesian grid of the same spacing: reads the pair (any read error is one
    # line and a non-zero exit, which run() turns into a failure).
    for name in ("pair.hdr", "pair.img"):
        run("boxrecon", "subsample", "--volume", str(tmp_path / name), "--lattice", "cartesian",
            "--spacing", "3", "--prefilter", "none", "-o", str(tmp_path / "s.nii"))
        assert nib.load(str(tmp_path / "s.nii")).shape[0] >= 1


def test_output_name_without_a_writer_is_refused(tmp_path, ml_file):
    out = tmp_path / "g.mha"
    message = cli_error("boxrecon", "resample", "--filter", "m7", "--volume", ml_file, "-o",
                        str(out))
    assert "no writer knows its extension" in message
    assert not out.exists()


def linear_image(tmp_path, name):
    """float64 samples of a linear function of the world point on an anisotropic grid with a
    reversed y axis, saved by nibabel; returns (path, the function)."""
    affine = np.diag([0.9, -0.9, 3.0, 1.0])
    affine[:3, 3] = (-5.0, 8.0, 1.5)
    f = lambda p: 2.0 + 0.3 * p[..., 0] - 0.1 * p[..., 1] + 0.05 * p[..., 2]
    index = np.stack(np.meshgrid(*(np.arange(s) for s in (12, 11, 9)), indexing="ij"), -1)
    world = index @ affine[:3, :3].T + affine[:3, 3]
    path = tmp_path / name
    nib.save(nib.Nifti1Image(f(world), affine), str(path))
    return path, f


def test_resample_like_reproduces_the_image_on_its_own_grid(tmp_path):
    """--like IMAGE: the output has that image's grid (nibabel's canonical affine and shape), and
    tricubic with interp reproduces the samples there."""
    source, _ = linear_image(tmp_path, "src.nii.gz")
    out = tmp_path / "like.nii.gz"
    run("boxrecon", "resample", "--filter", "tricubic", "--prefilter", "interp", "--volume",
        str(source), "--like", str(source), "--type", "float64", "-o", str(out))
    canonical = nib.as_closest_canonical(nib.load(str(source)))
    image = nib.load(str(out))
    assert image.shape == canonical.shape
    np.testing.assert_allclose(image.affine, canonical.affine, atol=1e-6)
    np.testing.assert_allclose(image.get_fdata(), canonical.get_fdata(), atol=1e-9)


def test_resample_size_and_spacing_grids(tmp_path):
    """--size NX NY NZ and --spacing (one value or three) over --min/--max: the grid nibabel reads,
    and the spline's values there (tricubic reproduces a linear function; strict boundary, a box
    inside the volume)."""
    source, f = linear_image(tmp_path, "src.nii")
    lo, hi = (-2.0, 0.0, 6.0), (3.0, 4.0, 19.5)
    common = ["resample", "--filter", "tricubic", "--boundary", "strict", "--volume", str(source),
              "--min", *map(str, lo), "--max", *map(str, hi), "--type", "float64"]
    cases = [(["--size", "4", "6", "10"], (4, 6, 10), [(hi[a] - lo[a]) / (n - 1)
                                                        for a, n in enumerate((4, 6, 10))]),
             (["--spacing", "0.5"], (11, 9, 28), [0.5, 0.5, 0.5]),
             (["--spacing", "1", "0.8", "4.5"], (6, 6, 4), [1.0, 0.8, 4.5])]
    for args, shape, steps in cases:
        out = tmp_path / "g.nii"
        run("boxrecon", *common, *args, "-o", str(out))
        image = nib.load(str(out))
        assert image.shape == shape, args
        expected = np.diag([*steps, 1.0])
        expected[:3, 3] = lo
        np.testing.assert_allclose(image.affine, expected, atol=1e-6)
        index = np.stack(np.meshgrid(*(np.arange(s) for s in shape), indexing="ij"), -1)
        world = index @ image.affine[:3, :3].T + image.affine[:3, 3]
        np.testing.assert_allclose(image.get_fdata(), f(world), atol=1e-5)


def test_compare_mask_file(tmp_path):
    """compare --mask FILE: the errors over the voxels where a uint8 mask nibabel writes (on the
    reference's grid, with its reversed axis) is not 0: the count and RMS of the error volume
    there (nibabel reads both files)."""
    rng = np.random.default_rng(7)
    affine = np.diag([0.9, -0.9, 3.0, 1.0])
    affine[:3, 3] = (-5.0, 8.0, 1.5)
    data = rng.normal(size=(10, 9, 8))
    nib.save(nib.Nifti1Image(data, affine), str(tmp_path / "ref.nii"))
    mask = np.zeros((10, 9, 8), dtype=np.uint8)
    mask[2:7, 1:5, 3:8] = 1
    mask[0, 0, 0] = 3
    nib.save(nib.Nifti1Image(mask, affine), str(tmp_path / "mask.nii.gz"))
    code, out, err = run("boxrecon", "compare", "--reference", str(tmp_path / "ref.nii"),
                         "--volume", str(tmp_path / "ref.nii"), "--filter", "tricubic", "--mask",
                         str(tmp_path / "mask.nii.gz"), "--error-volume",
                         str(tmp_path / "e.nii"), "--json")
    result = json.loads(out)
    errors = nib.as_closest_canonical(nib.load(str(tmp_path / "e.nii"))).get_fdata()
    inside = nib.as_closest_canonical(nib.load(str(tmp_path / "mask.nii.gz"))).get_fdata() != 0
    assert result["region"]["points"] == data.size  # mirror: every voxel is compared
    assert result["mask"]["points"] == int(inside.sum()) == 5 * 4 * 5 + 1
    np.testing.assert_allclose(result["mask"]["rms"], np.sqrt(np.mean(errors[inside] ** 2)),
                               rtol=1e-6)
    assert result["mask"]["rms"] != result["region"]["rms"]
    np.testing.assert_allclose(result["mask"]["max"], np.abs(errors[inside]).max(), rtol=1e-6)


def test_compare_mask_refusals(tmp_path):
    affine = np.diag([1.0, 1.0, 2.0, 1.0])
    data = np.random.default_rng(1).normal(size=(6, 6, 6))
    nib.save(nib.Nifti1Image(data, affine), str(tmp_path / "ref.nii"))
    nib.save(nib.Nifti1Image(np.ones((6, 6, 5), np.uint8), affine), str(tmp_path / "small.nii"))
    shifted = affine.copy()
    shifted[0, 3] = 0.5
    nib.save(nib.Nifti1Image(np.ones((6, 6, 6), np.uint8), shifted), str(tmp_path / "moved.nii"))
    nib.save(nib.Nifti1Image(np.zeros((6, 6, 6), np.uint8), affine), str(tmp_path / "empty.nii"))
    common = ["compare", "--reference", str(tmp_path / "ref.nii"), "--volume",
              str(tmp_path / "ref.nii"), "--filter", "tricubic", "--mask"]
    for name, says in [("small.nii", "not on the reference's grid"),
                       ("moved.nii", "not on the reference's grid"),
                       ("empty.nii", "the mask is empty")]:
        assert says in cli_error("boxrecon", *common, str(tmp_path / name))
