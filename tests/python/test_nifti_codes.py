"""A NIfTI's own qform and sform codes (1 scanner, 3 Talairach, 4 MNI, ...) are claimed again by
the NIfTI files written from it, as nibabel keeps a header's codes: boxrecon resample (on a grid of
its own, or on --like's, whose codes it then takes), subsample and compare --error-volume, and
Python's write_volume of a volume read_volume read. Inputs are written by nibabel (Debian
python3-nibabel) and, byte by byte, by the test itself; outputs are read by nibabel."""
import pickle
import struct

import numpy as np
import pytest

import boxgen
from conftest import run

nib = pytest.importorskip("nibabel")

AFFINE = np.array([[2.0, 0, 0, -10], [0, 2, 0, -12], [0, 0, 2, -8], [0, 0, 0, 1]])


def ramp():
    """12^3 int16 voxels, a ramp along x."""
    return (np.arange(12, dtype=np.int16)[:, None, None] * 10 + np.zeros((12, 12, 12), np.int16))


def nibabel_nifti(path, qform_code, sform_code):
    """The ramp, written by nibabel with these codes (the affine in both forms)."""
    image = nib.Nifti1Image(ramp(), AFFINE)
    image.set_qform(AFFINE, code=qform_code)
    image.set_sform(AFFINE, code=sform_code)
    nib.save(image, str(path))
    return path


def handmade_nifti(path, qform_code, sform_code):
    """The ramp as a NIfTI-1 file written byte by byte (little-endian): the 348-byte header with
    the affine as sform rows and as a qform (identity rotation, pixdim 2, qoffset the origin),
    four zero extension bytes, the int16 data from byte 352."""
    header = bytearray(348)
    struct.pack_into("<i", header, 0, 348)                       # sizeof_hdr
    struct.pack_into("<8h", header, 40, 3, 12, 12, 12, 1, 1, 1, 1)  # dim
    struct.pack_into("<hh", header, 70, 4, 16)                   # datatype int16, bitpix
    struct.pack_into("<8f", header, 76, 1, 2, 2, 2, 1, 1, 1, 1)  # pixdim: qfac 1, 2 mm voxels
    struct.pack_into("<3f", header, 108, 352, 1, 0)              # vox_offset, scl_slope, inter
    struct.pack_into("<hh", header, 252, qform_code, sform_code)
    struct.pack_into("<6f", header, 256, 0, 0, 0, *AFFINE[:3, 3])  # quatern_bcd, qoffset_xyz
    for row in range(3):
        struct.pack_into("<4f", header, 280 + 16 * row, *AFFINE[row])
    header[344:348] = b"n+1\0"
    with open(path, "wb") as f:
        f.write(bytes(header) + bytes(4) + ramp().astype("<i2").tobytes(order="F"))
    return path


def codes(path):
    header = nib.load(str(path)).header
    return int(header["qform_code"]), int(header["sform_code"])


@pytest.mark.parametrize("write", [nibabel_nifti, handmade_nifti])
def test_boxrecon_outputs_claim_the_codes_of_their_nifti(tmp_path, write):
    source = write(tmp_path / "in.nii", 1, 4)  # scanner qform, MNI sform
    assert codes(source) == (1, 4)
    np.testing.assert_array_equal(nib.load(str(source)).get_fdata(), ramp())
    outputs = {
        "like.nii.gz": ("resample", "--filter", "tricubic", "--volume", str(source), "--like",
                        str(source)),
        "size.nii": ("resample", "--filter", "tricubic", "--volume", str(source), "--size", "5",
                     "6", "7"),
        "sub.nii.gz": ("subsample", "--volume", str(source), "--lattice", "cartesian",
                       "--fraction", "0.5"),
    }
    for name, args in outputs.items():
        run("boxrecon", *args, "-o", str(tmp_path / name))
        assert codes(tmp_path / name) == (1, 4), name
    # The error volume lies on the reference's grid and claims its codes.
    bcc = tmp_path / "bcc.nrrd"
    run("boxrecon", "subsample", "--volume", str(source), "--lattice", "bcc", "--fraction", "0.5",
        "-o", str(bcc))
    run("boxrecon", "compare", "--reference", str(source), "--volume", str(bcc), "--filter", "m7",
        "--error-volume", str(tmp_path / "err.nii"))
    assert codes(tmp_path / "err.nii") == (1, 4)
    np.testing.assert_array_equal(nib.load(str(tmp_path / "err.nii")).affine, AFFINE)


def test_codes_follow_the_grid_the_output_takes(tmp_path):
    volume = nibabel_nifti(tmp_path / "scanner.nii.gz", 1, 1)
    # On --like's grid the output claims --like's codes (as nilearn's resample_to_img keeps the
    # target's header): here a sform-only Talairach image, qform code 0 kept.
    talairach = handmade_nifti(tmp_path / "talairach.nii", 0, 3)
    assert codes(talairach) == (0, 3)
    run("boxrecon", "resample", "--filter", "tricubic", "--volume", str(volume), "--like",
        str(talairach), "-o", str(tmp_path / "out.nii"))
    assert codes(tmp_path / "out.nii") == (0, 3)
    # A --like NRRD has no codes: the volume's are kept.
    run("boxrecon", "resample", "--filter", "tricubic", "--volume", str(volume), "--n", "6",
        "-o", str(tmp_path / "grid.nrrd"))
    run("boxrecon", "resample", "--filter", "tricubic", "--volume", str(volume), "--like",
        str(tmp_path / "grid.nrrd"), "-o", str(tmp_path / "on_nrrd.nii"))
    assert codes(tmp_path / "on_nrrd.nii") == (1, 1)
    # A qform-only file: its code goes to the sform too, so that the exact affine is coded.
    qform_only = handmade_nifti(tmp_path / "q.nii", 1, 0)
    run("boxrecon", "resample", "--filter", "tricubic", "--volume", str(qform_only), "--like",
        str(qform_only), "-o", str(tmp_path / "q_out.nii"))
    assert codes(tmp_path / "q_out.nii") == (1, 1)
    # A code NIfTI does not define placed the world all the same: "aligned" (2).
    odd = handmade_nifti(tmp_path / "odd.nii", 1, 9)
    run("boxrecon", "resample", "--filter", "tricubic", "--volume", str(odd), "--like", str(odd),
        "-o", str(tmp_path / "odd_out.nii"))
    assert codes(tmp_path / "odd_out.nii") == (1, 2)
    # Through a NRRD (which has no codes) the world stays a patient's: aligned in both.
    run("boxrecon", "resample", "--filter", "tricubic", "--volume", str(tmp_path / "grid.nrrd"),
        "--n", "6", "-o", str(tmp_path / "from_nrrd.nii"))
    assert codes(tmp_path / "from_nrrd.nii") == (2, 2)


@pytest.mark.parametrize("write", [nibabel_nifti, handmade_nifti])
def test_python_write_volume_claims_the_codes_read(tmp_path, write):
    volume = boxgen.read_volume(str(write(tmp_path / "in.nii", 1, 4)))
    assert volume.nifti_codes == (1, 4)
    boxgen.write_volume(str(tmp_path / "out.nii.gz"), volume)
    assert codes(tmp_path / "out.nii.gz") == (1, 4)
    np.testing.assert_array_equal(nib.load(str(tmp_path / "out.nii.gz")).affine, AFFINE)
    again = pickle.loads(pickle.dumps(volume))
    assert again.nifti_codes == (1, 4)
    boxgen.write_volume(str(tmp_path / "pickled.nii"), again)
    assert codes(tmp_path / "pickled.nii") == (1, 4)
    # A NRRD has no codes: read back, its volume has none, and its NIfTI is aligned (2, 2).
    boxgen.write_volume(str(tmp_path / "out.nrrd"), volume)
    from_nrrd = boxgen.read_volume(str(tmp_path / "out.nrrd"))
    assert from_nrrd.nifti_codes == (0, 0)
    boxgen.write_volume(str(tmp_path / "from_nrrd.nii"), from_nrrd)
    assert codes(tmp_path / "from_nrrd.nii") == (2, 2)


def test_python_volumes_take_codes(tmp_path):
    data = ramp().astype(np.float64)[None]
    made = boxgen.Volume(data, lattice="cartesian", affine=AFFINE, anatomical="RAS",
                         nifti_codes=(1, 3))
    assert made.nifti_codes == (1, 3)
    boxgen.write_volume(str(tmp_path / "made.nii"), made)
    assert codes(tmp_path / "made.nii") == (1, 3)
    # Without: an array's world is no patient's (sform aligned, qform unknown), as nibabel writes.
    plain = boxgen.Volume(data, lattice="cartesian", affine=AFFINE)
    assert plain.nifti_codes == (0, 0)
    boxgen.write_volume(str(tmp_path / "plain.nii"), plain)
    assert codes(tmp_path / "plain.nii") == (0, 2)
    for bad in [(6, 1), (-1, 2)]:
        with pytest.raises(ValueError, match="nifti_codes must be"):
            boxgen.Volume(data, lattice="cartesian", affine=AFFINE, nifti_codes=bad)
