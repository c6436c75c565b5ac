"""NIfTI files of boxrecon as nibabel (Debian python3-nibabel) reads them: the grid, the affine
(sform and qform, with their codes) and the values of `resample -o x.nii[.gz]` against the NRRD
of the same command, --type, and a .hdr/.img pair nibabel writes read back by boxrecon."""
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
    sform, sform_code = image.header.get_sform(coded=True)
    qform, qform_code = image.header.get_qform(coded=True)
    assert int(sform_code) > 0 and int(qform_code) > 0
    np.testing.assert_allclose(qform, sform, atol=1e-6)


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
