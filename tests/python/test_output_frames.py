"""The files boxrecon writes keep the anatomical frame of the volume they came from: a NRRD output
of resample, subsample or compare --error-volume has the input's `space` (right-anterior-superior
for NIfTI, the NRRD's own for a NRRD), so that `slice` of that file alone shows the orientation
letters; a NIfTI output is in RAS (NIfTI's world) also when the input was an LPS NRRD. The NRRD
headers are parsed here by hand and the NIfTI files read by nibabel (Debian python3-nibabel), so
the geometry is checked independently of boxrecon's readers."""
import re

import numpy as np
import pytest

from conftest import cli_error, run

nib = pytest.importorskip("nibabel")

RAS_LETTERS = "orientation: left L, right R, bottom P, top A (RAS world)"
LPS_LETTERS = "orientation: left R, right L, bottom A, top P (LPS world)"


def nrrd_header(path):
    """The fields of a NRRD header ("key: value" lines up to the blank line), by hand."""
    with open(path, "rb") as f:
        text = f.read().split(b"\n\n", 1)[0].decode("ascii")
    fields = {}
    for line in text.split("\n")[1:]:
        if ": " in line and not line.startswith("#"):
            key, value = line.split(": ", 1)
            fields[key] = value
    return fields


def nrrd_affine(fields):
    """The 4x4 affine of a 3-D NRRD's space directions and origin (columns: the directions)."""
    vectors = [[float(x) for x in v.split(",")]
               for v in re.findall(r"\(([^)]*)\)", fields["space directions"])]
    origin = [float(x) for x in re.findall(r"\(([^)]*)\)", fields["space origin"])[0].split(",")]
    affine = np.eye(4)
    affine[:3, :3] = np.array(vectors).T
    affine[:3, 3] = origin
    return affine


def nrrd_floats(path, fields):
    """The raw little-endian float samples of a 3-D NRRD, indexed [i, j, k]."""
    assert fields["type"] == "float" and fields["encoding"] == "raw", fields
    sizes = [int(s) for s in fields["sizes"].split()]
    with open(path, "rb") as f:
        data = f.read().split(b"\n\n", 1)[1]
    return np.frombuffer(data, dtype="<f4").reshape(sizes[::-1]).transpose(2, 1, 0)


def orientation(*args):
    """The orientation line `boxrecon slice ARGS` prints (its second line)."""
    _, out, _ = run("boxrecon", "slice", *args)
    return out.strip().split("\n")[1]


@pytest.fixture
def ras_nifti(tmp_path):
    """A RAS NIfTI written by nibabel: 12^3 int16 voxels of 2 mm, a ramp along x."""
    data = (np.arange(12, dtype=np.int16)[:, None, None] * 10 + np.zeros((12, 12, 12), np.int16))
    affine = np.diag([2.0, 2.0, 2.0, 1.0])
    affine[:3, 3] = (-10, -12, -8)
    path = tmp_path / "ras.nii.gz"
    nib.save(nib.Nifti1Image(data, affine), str(path))
    return path, affine


def test_nrrd_outputs_of_a_nifti_keep_its_ras_frame(tmp_path, ras_nifti):
    nifti, affine = ras_nifti
    # resample onto the image's own grid: the NRRD's geometry is the NIfTI's, in RAS, and its
    # values are those of the same resample written as NIfTI (read by nibabel).
    out = tmp_path / "grid.nrrd"
    for name in ("grid.nrrd", "grid.nii.gz"):
        run("boxrecon", "resample", "--filter", "tricubic", "--volume", str(nifti), "--like",
            str(nifti), "--precision", "float", "-o", str(tmp_path / name))
    fields = nrrd_header(out)
    assert fields["space"] == "right-anterior-superior", fields
    np.testing.assert_array_equal(nrrd_affine(fields), affine)
    written = nib.load(str(tmp_path / "grid.nii.gz"))
    np.testing.assert_array_equal(written.affine, affine)
    # The codes of the input (nibabel wrote it: sform 2, qform 0), claimed again.
    source_header = nib.load(str(nifti)).header
    assert (int(written.header["sform_code"]), int(written.header["qform_code"])) == \
        (int(source_header["sform_code"]), int(source_header["qform_code"])) == (2, 0)
    np.testing.assert_array_equal(nrrd_floats(out, fields), np.asarray(written.dataobj))
    assert orientation("--reference", str(out), "--at", "0", "-o", str(tmp_path / "r.png")) \
        == RAS_LETTERS

    # subsample onto BCC: `slice` of the BCC file alone shows the letters.
    bcc = tmp_path / "bcc.nrrd"
    run("boxrecon", "subsample", "--volume", str(nifti), "--lattice", "bcc", "--fraction", "0.5",
        "-o", str(bcc))
    assert nrrd_header(bcc)["space"] == "right-anterior-superior"
    assert orientation("--volume", str(bcc), "--filter", "m7", "--at", "0", "-o",
                       str(tmp_path / "b.png")) == RAS_LETTERS
    # resample of the BCC file keeps the frame again (a second generation).
    run("boxrecon", "resample", "--filter", "m7", "--volume", str(bcc), "--n", "6", "-o",
        str(tmp_path / "again.nrrd"))
    assert nrrd_header(tmp_path / "again.nrrd")["space"] == "right-anterior-superior"

    # compare's error volume lies on the reference's grid, in its frame.
    run("boxrecon", "compare", "--reference", str(nifti), "--volume", str(bcc), "--filter", "m7",
        "--error-volume", str(tmp_path / "err.nrrd"))
    fields = nrrd_header(tmp_path / "err.nrrd")
    assert fields["space"] == "right-anterior-superior"
    np.testing.assert_array_equal(nrrd_affine(fields), affine)


def test_an_lps_nrrd_stays_lps_and_becomes_ras_in_nifti(tmp_path):
    # DICOM's LPS space: +x points left, +y posterior. A ramp along x, brightest at i = 9.
    ramp = np.broadcast_to(np.arange(10, dtype=np.float32)[:, None, None], (10, 10, 10))
    lps = tmp_path / "lps.nrrd"
    with open(lps, "wb") as f:
        f.write(b"NRRD0004\ntype: float\ndimension: 3\nspace: left-posterior-superior\n"
                b"sizes: 10 10 10\nspace directions: (1.5,0,0) (0,1.5,0) (0,0,1.5)\n"
                b"space origin: (3,-4,5)\nendian: little\nencoding: raw\n\n")
        f.write(np.ascontiguousarray(ramp.transpose(2, 1, 0)).astype("<f4").tobytes())
    lps_affine = np.diag([1.5, 1.5, 1.5, 1.0])
    lps_affine[:3, 3] = (3, -4, 5)
    for name in ("out.nrrd", "out.nii.gz"):
        run("boxrecon", "resample", "--filter", "tricubic", "--volume", str(lps), "--like",
            str(lps), "--precision", "float", "-o", str(tmp_path / name))
    fields = nrrd_header(tmp_path / "out.nrrd")
    assert fields["space"] == "left-posterior-superior", fields
    np.testing.assert_array_equal(nrrd_affine(fields), lps_affine)
    assert orientation("--reference", str(tmp_path / "out.nrrd"), "--at", "10", "-o",
                       str(tmp_path / "s.png")) == LPS_LETTERS
    # NIfTI's world is RAS: x and y change sign, and every voxel keeps its place in the patient
    # (the same values at the same RAS points as the NRRD's at the same LPS points).
    written = nib.load(str(tmp_path / "out.nii.gz"))
    np.testing.assert_array_equal(written.affine, np.diag([-1.0, -1.0, 1.0, 1.0]) @ lps_affine)
    assert (int(written.header["sform_code"]), int(written.header["qform_code"])) == (2, 2)
    np.testing.assert_array_equal(np.asarray(written.dataobj),
                                  nrrd_floats(tmp_path / "out.nrrd", fields))


def test_python_volumes_keep_the_anatomical_frame(tmp_path, ras_nifti):
    """boxgen.read_volume records the world's anatomical frame (Volume.anatomical) and
    write_volume converts it as boxrecon does: an LPS NRRD written as NIfTI is the CLI's file
    byte for byte (x and y mirrored into RAS), as NRRD it stays LPS; RAS for NIfTI, None for a
    frameless world; Volume(anatomical=), pickling, prefilter_volume and resample(lattice=) keep
    it."""
    import pickle

    boxgen = pytest.importorskip("boxgen")
    lps = tmp_path / "lps.nrrd"
    with open(lps, "wb") as f:
        f.write(b"NRRD0004\ntype: float\ndimension: 3\nspace: left-posterior-superior\n"
                b"sizes: 8 9 10\nspace directions: (1.5,0,0) (0,1.25,0) (0,0,2)\n"
                b"space origin: (3,-4,5)\nendian: little\nencoding: raw\n\n")
        f.write(np.arange(720, dtype="<f4").tobytes())
    v = boxgen.read_volume(str(lps))
    assert v.anatomical == "LPS"
    cli = tmp_path / "cli.nii"  # the CLI's NIfTI of the same samples (--like itself, interp)
    run("boxrecon", "resample", "--filter", "tricubic", "--prefilter", "interp", "--volume",
        str(lps), "--like", str(lps), "--precision", "float", "-o", str(tmp_path / "cli.nrrd"))
    run("boxrecon", "resample", "--filter", "tricubic", "--prefilter", "interp", "--volume",
        str(lps), "--like", str(lps), "--precision", "float", "-o", str(cli))
    resampled = boxgen.read_volume(str(tmp_path / "cli.nrrd"))
    assert resampled.anatomical == "LPS"
    boxgen.write_volume(str(tmp_path / "py.nii"), resampled)
    assert (tmp_path / "py.nii").read_bytes() == cli.read_bytes()
    image = nib.load(str(tmp_path / "py.nii"))
    np.testing.assert_array_equal(image.affine, np.diag([-1.0, -1.0, 1.0, 1.0]) @ v.affine)
    assert (int(image.header["sform_code"]), int(image.header["qform_code"])) == (2, 2)
    boxgen.write_volume(str(tmp_path / "py.nrrd"), v)
    fields = nrrd_header(tmp_path / "py.nrrd")
    assert fields["space"] == "left-posterior-superior"
    np.testing.assert_array_equal(nrrd_affine(fields), v.affine)

    assert boxgen.read_volume(str(ras_nifti[0])).anatomical == "RAS"
    assert pickle.loads(pickle.dumps(v)).anatomical == "LPS"
    tricubic = boxgen.Filter("tricubic")
    assert tricubic.prefilter_volume(v, "q1").anatomical == "LPS"
    assert boxgen.resample(v, tricubic, lattice="bcc", spacing=2.0).anatomical == "LPS"

    # A volume of arrays has no frame unless given one; given LPS, NIfTI mirrors x and y.
    plain = boxgen.Volume(v.samples.copy(), lattice="cartesian", spacing=(1.5, 1.25, 2),
                          origin=(3, -4, 5))
    assert plain.anatomical is None
    tagged = boxgen.Volume(v.samples.copy(), lattice="cartesian", spacing=(1.5, 1.25, 2),
                           origin=(3, -4, 5), anatomical="LPS")
    boxgen.write_volume(str(tmp_path / "tagged.nii"), tagged)
    np.testing.assert_array_equal(nib.load(str(tmp_path / "tagged.nii")).affine, image.affine)
    boxgen.write_volume(str(tmp_path / "plain.nii"), plain)
    np.testing.assert_array_equal(nib.load(str(tmp_path / "plain.nii")).affine, v.affine)
    with pytest.raises(ValueError, match="anatomical must be"):
        boxgen.Volume(v.samples.copy(), lattice="cartesian", anatomical="XYZ")


def test_a_like_image_in_another_frame_is_refused(tmp_path, ras_nifti):
    nifti, _ = ras_nifti
    lps = tmp_path / "lps.nrrd"
    with open(lps, "wb") as f:
        f.write(b"NRRD0004\ntype: float\ndimension: 3\nspace: left-posterior-superior\n"
                b"sizes: 8 8 8\nspace directions: (1,0,0) (0,1,0) (0,0,1)\n"
                b"space origin: (0,0,0)\nendian: little\nencoding: raw\n\n")
        f.write(np.zeros(512, "<f4").tobytes())
    out = tmp_path / "out.nrrd"
    message = cli_error("boxrecon", "resample", "--filter", "tricubic", "--volume", str(lps),
                        "--like", str(nifti), "-o", str(out))
    assert "LPS" in message and "RAS" in message, message
    assert not out.exists()


def test_a_volume_without_a_frame_stays_without_one(tmp_path):
    run("boxrecon", "sample", "--function", "ml", "--n", "8", "--lattice", "cartesian", "-o",
        str(tmp_path / "v.nrrd"))
    run("boxrecon", "resample", "--filter", "tricubic", "--volume", str(tmp_path / "v.nrrd"),
        "--n", "4", "-o", str(tmp_path / "r.nrrd"))
    assert nrrd_header(tmp_path / "r.nrrd")["space"] == "3D-right-handed"
    # Into NIfTI: the affine as the sform (code 2, aligned) and a qform of code 0, as nibabel
    # writes Nifti1Image(data, affine): no reader takes it for a scanner's anatomical qform, and
    # nibabel's affine is still the grid's (both codes 0 would lose it to pixdim alone).
    run("boxrecon", "resample", "--filter", "tricubic", "--volume", str(tmp_path / "v.nrrd"),
        "--n", "4", "-o", str(tmp_path / "r.nii"))
    written = nib.load(str(tmp_path / "r.nii"))
    assert (int(written.header["sform_code"]), int(written.header["qform_code"])) == (2, 0)
    np.testing.assert_allclose(written.affine, nrrd_affine(nrrd_header(tmp_path / "r.nrrd")),
                               rtol=0, atol=1e-6)
