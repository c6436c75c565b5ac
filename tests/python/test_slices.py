"""Readable slices: `boxrecon slice` draws each panel with a title, axis labels, a colour bar and
the orientation letters of the file's world frame, with square pixels on anisotropic voxels and a
default window of the 1st-99th percentiles of the samples; with --reference beside --volume every
panel lies on the reference's grid and shares its window. Checked as properties, not snapshots:
the window against NumPy's percentile of the same data, the panel's size and its bands of grey
against the voxel sizes, the letters for known affines, and panels of a linear function that
line up pixel for pixel. nibabel (Debian python3-nibabel) writes the NIfTI files."""
import os
import re
import sys

import numpy as np
import pytest

from conftest import cli_error, run

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "../../scripts"))
from png_agreement import read_rgb  # noqa: E402  (the project's one PNG reader in Python)

nib = pytest.importorskip("nibabel")

# Where image_png (analysis/gnuplot.cpp) puts panel p's image of W x H pixels drawn Z x Z each:
# columns p (Z W + 200) + 70 onwards, rows 40 onwards; the PNG is panels (Z W + 200) by Z H + 100.
LEFT, TOP, MARGIN_X, MARGIN_Y = 70, 40, 200, 100
PURPLE = (96, 0, 96)  # pixels without a value


def save_nifti(path, data, affine, anatomical=True):
    image = nib.Nifti1Image(data, affine)
    if not anatomical:  # both codes 0: voxels placed by pixdim alone, in no patient frame
        image.set_sform(affine, code=0)
        image.set_qform(affine, code=0)
    nib.save(image, str(path))
    return np.asarray(nib.load(str(path)).dataobj).astype(np.float64)


class Slice:
    """What `boxrecon slice ARGS` printed and drew: lines, w x h pixels per panel drawn zoom x
    zoom each, panels, window (lo, hi), png (width, height, rows)."""

    def __init__(self, *args):
        _, out, _ = run("boxrecon", "slice", *args)
        self.lines = out.strip().split("\n")
        m = re.match(r"(\d+) x (\d+) pixels per panel(?: \(drawn (\d+) x \d+ each\))?, "
                     r"(\d+) panel\(s\).*values \[(\S+), (\S+)\] mapped", self.lines[0])
        assert m, out
        self.w, self.h, self.panels = int(m.group(1)), int(m.group(2)), int(m.group(4))
        self.zoom = int(m.group(3) or 1)
        self.window = (float(m.group(5)), float(m.group(6)))
        self.png = read_rgb(args[args.index("-o") + 1])

    def size(self):
        """The PNG's size as image_png lays it out."""
        return (self.panels * (self.zoom * self.w + MARGIN_X), self.zoom * self.h + MARGIN_Y)

    def at(self, panel, x, y):
        """The colour drawn for pixel (x, y) of a panel (y = 0 the top row), at its centre."""
        z = self.zoom
        px = panel * (z * self.w + MARGIN_X) + LEFT + z * x + z // 2
        row = self.png[2][TOP + z * y + z // 2]
        return tuple(row[3 * px:3 * px + 3])


def test_the_default_window_is_numpys_1st_and_99th_percentile(tmp_path):
    rng = np.random.default_rng(6)
    data = save_nifti(tmp_path / "r.nii.gz", rng.integers(0, 1000, (20, 16, 12)).astype(np.int16),
                      np.diag([0.9, 0.9, 3.0, 1]))
    png = str(tmp_path / "s.png")
    for flags, percent in (([], (1, 99)), (["--percentiles", "5", "95"], (5, 95)),
                           (["--percentiles", "0", "100"], (0, 100))):
        s = Slice("--reference", str(tmp_path / "r.nii.gz"), "--axis", "y", "--at", "4.5", *flags,
                  "-o", png)
        assert s.window == pytest.approx(np.percentile(data, percent), rel=1e-5), flags
    s = Slice("--reference", str(tmp_path / "r.nii.gz"), "--at", "3", "--range", "-5", "7", "-o",
              png)
    assert s.window == (-5, 7)


def test_anisotropic_voxels_get_square_pixels(tmp_path):
    # 0.9 x 0.9 x 3 mm voxels, each z layer k of value 10 k: the y slice is 17.1 mm wide and
    # 33 mm high, at one pixel per 0.9 mm 20 x 38 pixels, each layer 3 / 0.9 = 3.33 rows high.
    k = np.arange(12, dtype=np.float32)
    data = np.broadcast_to(10 * k, (20, 16, 12)).copy()
    save_nifti(tmp_path / "a.nii.gz", data, np.diag([0.9, 0.9, 3.0, 1]))
    s = Slice("--reference", str(tmp_path / "a.nii.gz"), "--axis", "y", "--at", "4.5", "--range",
              "0", "110", "-o", str(tmp_path / "s.png"))
    assert (s.w, s.h) == (20, 38)
    assert (s.h - 1) / (s.w - 1) == pytest.approx(33 / 17.1, abs=1 / (s.w - 1))
    assert s.png[:2] == s.size()
    # Down a column (off the middle, where the letters S and I stand): grey 255 k / 11 from the
    # top layer (k = 11) to the bottom one.
    column = [s.at(0, s.w // 4, y)[0] for y in range(s.h)]
    layers = [round(255 * k / 11) for k in range(11, -1, -1)]
    rows_of = [sum(1 for g in column if abs(g - level) <= 2) for level in layers]
    assert sum(rows_of) == s.h, (rows_of, column)
    inner = rows_of[1:-1]  # the first and last layers are half as high (their voxels' centres
    assert sum(inner) / len(inner) == pytest.approx(3 / 0.9, abs=0.25), rows_of  # on the edges)
    # One pixel per voxel (no aspect correction) would make each layer one row high.
    assert min(inner) >= 3, rows_of


def test_orientation_letters_follow_the_world_frame(tmp_path):
    png = str(tmp_path / "s.png")
    ramp = np.broadcast_to(np.arange(10, dtype=np.float32)[:, None, None], (10, 10, 10)).copy()
    save_nifti(tmp_path / "ras.nii.gz", ramp, np.diag([1.0, 1.0, 1.0, 1]))
    for axis, letters in (("z", "left L, right R, bottom P, top A"),
                          ("y", "left L, right R, bottom I, top S"),
                          ("x", "left P, right A, bottom I, top S")):
        s = Slice("--reference", str(tmp_path / "ras.nii.gz"), "--axis", axis, "--at", "4", "-o",
                  png)
        assert s.lines[1] == f"orientation: {letters} (RAS world)", s.lines
    # x stored flipped (radiological): the world frame and its letters stay; the brightest
    # voxel (i = 9) lies at the smallest world x, on the left (L) side of the image.
    flipped = np.diag([-1.0, 1.0, 1.0, 1])
    flipped[0, 3] = 9
    save_nifti(tmp_path / "flipped.nii.gz", ramp, flipped)
    s = Slice("--reference", str(tmp_path / "flipped.nii.gz"), "--at", "4", "-o", png)
    assert s.lines[1] == "orientation: left L, right R, bottom P, top A (RAS world)"
    assert s.at(0, 0, 5) == (255, 255, 255) and s.at(0, 9, 5) == (0, 0, 0)
    # No qform or sform: no anatomical frame, no letters.
    save_nifti(tmp_path / "plain.nii.gz", ramp, np.diag([1.0, 1.0, 1.0, 1]), anatomical=False)
    s = Slice("--reference", str(tmp_path / "plain.nii.gz"), "--at", "4", "-o", png)
    assert s.lines[1] == "orientation: x to the right, y upwards (the file has no anatomical frame)"
    # A NRRD in DICOM's LPS space: +x points left, +y posterior.
    with open(tmp_path / "lps.nrrd", "wb") as f:
        f.write(b"NRRD0004\ntype: float\ndimension: 3\nspace: left-posterior-superior\n"
                b"sizes: 10 10 10\nspace directions: (1,0,0) (0,1,0) (0,0,1)\n"
                b"space origin: (0,0,0)\nendian: little\nencoding: raw\n\n")
        f.write(np.ascontiguousarray(ramp.transpose(2, 1, 0)).astype("<f4").tobytes())
    s = Slice("--reference", str(tmp_path / "lps.nrrd"), "--at", "4", "-o", png)
    assert s.lines[1] == "orientation: left R, right L, bottom A, top P (LPS world)", s.lines


def test_reconstructions_share_the_references_grid_and_window(tmp_path):
    # A linear function, subsampled onto BCC: M7 and M8 reproduce it without a prefilter, so
    # their panels on the reference's grid repeat the reference's pixel for pixel (two pixels
    # from the faces, where the mirror boundary bends the function).
    i, j, _ = np.meshgrid(*(np.arange(17.0),) * 3, indexing="ij")
    data = save_nifti(tmp_path / "ref.nii.gz", (2 * i + j).astype(np.float32),
                      np.diag([1.0, 1.0, 1.0, 1]))
    run("boxrecon", "subsample", "--volume", str(tmp_path / "ref.nii.gz"), "--lattice", "bcc",
        "--spacing", "1", "-o", str(tmp_path / "bcc.nrrd"))
    s = Slice("--volume", str(tmp_path / "bcc.nrrd"), "--filter", "m7", "--filter", "m8",
              "--reference", str(tmp_path / "ref.nii.gz"), "--at", "8", "-o",
              str(tmp_path / "s.png"))
    assert "3 panel(s), z = 8 in [0, 16] x [0, 16]" in s.lines[0], s.lines
    assert (s.w, s.h) == (17, 17)
    assert s.window == pytest.approx(np.percentile(data, (1, 99)), rel=1e-5)
    assert s.png[:2] == s.size()
    compared = 0
    for y in range(2, s.h - 2):
        for x in range(2, s.w - 2):
            want = s.at(0, x, y)
            for panel in (1, 2):
                got = s.at(panel, x, y)
                if got == PURPLE:
                    continue
                assert max(abs(a - b) for a, b in zip(got, want)) <= 3, (panel, x, y, got, want)
                compared += 1
    assert compared > (s.w - 4) * (s.h - 4)  # more than one panel's worth


def test_without_a_reference_the_window_is_the_volumes(tmp_path):
    # The BCC volume's own samples (every coset; the NRRD boxrecon writes is raw little-endian
    # float, its data the file's last bytes) give the window; its space is the NIfTI's RAS, so
    # the letters stand on the BCC file's slice alone.
    rng = np.random.default_rng(8)
    save_nifti(tmp_path / "ref.nii.gz", rng.normal(100, 30, (12, 12, 12)).astype(np.float32),
               np.eye(4))
    run("boxrecon", "subsample", "--volume", str(tmp_path / "ref.nii.gz"), "--lattice", "bcc",
        "--spacing", "1", "-o", str(tmp_path / "bcc.nrrd"))
    header = open(tmp_path / "bcc.nrrd", "rb").read().split(b"\n\n")[0].decode()
    assert "encoding: raw" in header and "endian: little" in header and "type: float" in header
    sizes = [int(n) for n in re.search(r"sizes: (.*)", header).group(1).split()]
    count = int(np.prod(sizes))
    samples = np.frombuffer(open(tmp_path / "bcc.nrrd", "rb").read()[-4 * count:], "<f4")
    s = Slice("--volume", str(tmp_path / "bcc.nrrd"), "--filter", "m7", "--at", "5.5", "-o",
              str(tmp_path / "s.png"))
    assert "percentiles 1 and 99 of the volume's samples" in s.lines[0]
    assert s.window == pytest.approx(np.percentile(samples, (1, 99)), rel=1e-5)
    assert s.lines[1] == "orientation: left L, right R, bottom P, top A (RAS world)"


def test_bad_window_options_are_one_line_and_write_nothing(tmp_path):
    save_nifti(tmp_path / "r.nii.gz", np.zeros((6, 6, 6), np.float32), np.eye(4))
    ref = str(tmp_path / "r.nii.gz")
    png = str(tmp_path / "s.png")
    for args, said in ((["--percentiles", "50", "10"], "0 <= LO < HI <= 100"),
                       (["--percentiles", "1", "101"], "0 <= LO < HI <= 100"),
                       (["--percentiles", "1", "99", "--range", "0", "1"], "not both"),
                       (["--difference-to", ref], "not both")):
        assert said in cli_error("boxrecon", "slice", "--reference", ref, "--at", "2", *args,
                                 "-o", png)
        assert not os.path.exists(png)
    assert "--percentiles has no effect with --difference-to" in cli_error(
        "boxrecon", "slice", "--volume", ref, "--filter", "tricubic", "--difference-to", ref,
        "--at", "2", "--percentiles", "1", "99", "-o", png)
    assert not os.path.exists(png)
