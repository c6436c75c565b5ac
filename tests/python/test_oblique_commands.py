"""subsample, slice and render of oblique volumes (a scanner's tilted slices): each works in the
volume's own frame and maps world points through the inverse of its affine (runtime/affine.h),
so a tilted volume gives what the same function sampled on an axis-aligned grid gives. The NRRD
headers are parsed here by hand, NIfTI files written and read by nibabel (Debian
python3-nibabel)."""
import re

import numpy as np
import pytest

from conftest import cli_error, run
from test_oblique_affines import affine, rotation
from test_output_frames import nrrd_affine, nrrd_header

nib = pytest.importorskip("nibabel")

B = np.array([0.7, -1.3, 0.4])


def linear(w):
    """A linear function of world points: tricubic and m7 (centred box splines) reproduce it."""
    return np.asarray(w) @ B + 3


@pytest.fixture
def tilted_linear(tmp_path):
    """linear() sampled (float64) on a 16 x 15 x 14 grid tilted by 30 degrees about (2, -1, 1),
    voxels 0.8 x 1.1 x 0.95, written by nibabel; returns (path, the affine as stored)."""
    a = affine(rotation((2, -1, 1), 30) @ np.diag([0.8, 1.1, 0.95]), (5.0, -2.0, 1.5))
    shape = (16, 15, 14)
    path = tmp_path / "tilted.nii"
    nib.save(nib.Nifti1Image(np.zeros(shape), a), str(path))
    a = nib.load(str(path)).affine  # as stored (float32): the samples are f at its points
    index = np.stack(np.meshgrid(*(np.arange(s) for s in shape), indexing="ij"), -1)
    world = index.reshape(-1, 3) @ a[:3, :3].T + a[:3, 3]
    nib.save(nib.Nifti1Image(linear(world).reshape(shape), a), str(path))
    return path, a


def inside(a, shape, world, margin):
    """Which world points lie `margin` voxels or more inside the grid of affine a and `shape`."""
    index = (np.asarray(world) - a[:3, 3]) @ np.linalg.inv(a[:3, :3]).T
    return np.all((index >= margin) & (index <= np.asarray(shape) - 1 - margin), axis=1)


def lattice_samples(path):
    """The float samples of a 4-D lattice NRRD, indexed [c, i, j, k], and its header fields."""
    fields = nrrd_header(path)
    assert fields["type"] == "float" and fields["encoding"] == "raw", fields
    sizes = [int(s) for s in fields["sizes"].split()]
    with open(path, "rb") as f:
        data = f.read().split(b"\n\n", 1)[1]
    return np.frombuffer(data, dtype="<f4").reshape(sizes[::-1]).transpose(3, 2, 1, 0), fields


def test_subsample_of_an_oblique_volume_keeps_its_affine(tmp_path, tilted_linear):
    """subsample onto BCC in the volume's own frame: the NRRD's space directions are the affine's
    columns times 2h (oblique), its origin a world point, and every interior sample is f at the
    world point the header gives it; reading the file back (eval, Python) evaluates at the same
    world points. Onto a Cartesian grid: an oblique NRRD and a NIfTI with the same affine."""
    boxgen = pytest.importorskip("boxgen")
    path, a = tilted_linear
    out = tmp_path / "bcc.nrrd"
    run("boxrecon", "subsample", "--volume", str(path), "--lattice", "bcc", "--spacing", "0.7",
        "--filter", "tricubic", "--prefilter", "none", "-o", str(out))
    samples, fields = lattice_samples(out)
    assert fields["space"] == "right-anterior-superior"
    d = nrrd_affine(fields)  # columns 2h times the frame's unit axes
    frame = a[:3, :3] / np.linalg.norm(a[:3, :3], axis=0)
    np.testing.assert_allclose(d[:3, :3], 1.4 * frame, atol=1e-12)
    n = samples.shape[1:]
    index = np.stack(np.meshgrid(*(np.arange(s) for s in n), indexing="ij"), -1)
    world = np.stack([(index + c / 2) @ d[:3, :3].T + d[:3, 3] for c in (0, 1)])  # [c, i, j, k]
    keep = inside(a, (16, 15, 14), world.reshape(-1, 3), 2)
    assert keep.sum() > 100
    # float32 samples of values up to about 20.
    np.testing.assert_allclose(samples.reshape(-1)[keep], linear(world.reshape(-1, 3)[keep]),
                               rtol=0, atol=2e-5)

    # Read back: m7 without a prefilter reproduces linear functions; world points inside.
    rng = np.random.default_rng(3)
    points = (6 + 3 * rng.random((30, 3))) @ a[:3, :3].T + a[:3, 3]
    points_file = tmp_path / "points.txt"
    points_file.write_text("".join(f"{x!r} {y!r} {z!r}\n" for x, y, z in points))
    _, text, _ = run("boxrecon", "eval", "--filter", "m7", "--prefilter", "none", "--volume",
                     str(out), "--points", str(points_file))
    got = np.loadtxt(text.splitlines())
    np.testing.assert_allclose(got, linear(points), rtol=0, atol=1e-4)
    v = boxgen.read_volume(str(out))
    assert v.frame is not None
    positions = v.positions().reshape(n[2], n[1], n[0], 2, 3).transpose(3, 2, 1, 0, 4)
    np.testing.assert_allclose(positions, world, rtol=0, atol=1e-9)
    np.testing.assert_array_equal(v.samples, samples)
    np.testing.assert_allclose(boxgen.Filter("m7").evaluate(v, points, "none"), got,
                               rtol=0, atol=1e-12)

    # Onto a Cartesian grid: the oblique NRRD and the NIfTI hold the same affine and samples.
    nrrd, nii = tmp_path / "cart.nrrd", tmp_path / "cart.nii"
    for name in (nrrd, nii):
        run("boxrecon", "subsample", "--volume", str(path), "--lattice", "cartesian",
            "--spacing", "1.2", "--filter", "tricubic", "--prefilter", "none", "-o", str(name))
    image = nib.load(str(nii))
    np.testing.assert_allclose(nrrd_affine(nrrd_header(nrrd)), image.affine, atol=1e-5)
    np.testing.assert_allclose(image.affine[:3, :3], 1.2 * frame, atol=1e-6)
    np.testing.assert_array_equal(boxgen.read_volume(str(nrrd)).samples[0],
                                  np.asarray(image.dataobj))


def test_resample_onto_a_lattice_of_an_oblique_volume(tmp_path, tilted_linear):
    """resample --lattice bcc of an oblique volume is subsample's grid (its own frame, the affine
    kept); a world box, or an oblique --like lattice volume, is refused in one line."""
    path, _ = tilted_linear
    sub, res = tmp_path / "sub.nrrd", tmp_path / "res.nrrd"
    run("boxrecon", "subsample", "--volume", str(path), "--lattice", "bcc", "--spacing", "0.7",
        "--filter", "tricubic", "--prefilter", "none", "-o", str(sub))
    run("boxrecon", "resample", "--volume", str(path), "--lattice", "bcc", "--spacing", "0.7",
        "--filter", "tricubic", "--prefilter", "none", "--type", "float32", "-o", str(res))
    (got, fields), (expected, expected_fields) = lattice_samples(res), lattice_samples(sub)
    for key in ("sizes", "space", "space directions"):
        assert fields[key] == expected_fields[key]
    np.testing.assert_allclose(nrrd_affine(fields), nrrd_affine(expected_fields), atol=1e-12)
    np.testing.assert_allclose(got, expected, rtol=0, atol=1e-5)  # double and float evaluation
    out = tmp_path / "o.nrrd"
    message = cli_error("boxrecon", "resample", "--volume", str(path), "--lattice", "bcc",
                        "--spacing", "0.7", "--filter", "tricubic", "--box", "5", "6", "-o",
                        str(out))
    assert "oblique" in message and "--box" in message and not out.exists()
    message = cli_error("boxrecon", "resample", "--volume", str(path), "--like", str(sub),
                        "--filter", "tricubic", "-o", str(out))
    assert "oblique bcc volume" in message and not out.exists()


def slice_summary(*args):
    """`boxrecon slice ARGS`: its box on the plane, its window and its orientation line."""
    _, out, _ = run("boxrecon", "slice", *args)
    first, orientation = out.strip().split("\n")[:2]
    numbers = r"\[([-0-9.e+]+), ([-0-9.e+]+)\]"
    box = re.search(numbers + " x " + numbers, first).groups()
    window = re.search("values " + numbers, first).groups()
    return [float(x) for x in box], [float(x) for x in window], orientation


def test_slice_of_an_oblique_volume_is_along_world_axes(tmp_path, tilted_linear):
    """slice maps each pixel's world point into an oblique volume's frame: against an
    axis-aligned reference of the same linear function (--difference-to), tricubic without a
    prefilter differs by float rounding only. An oblique reference's panels cover its world box
    (the axis-aligned box around its grid), with RAS letters."""
    path, a = tilted_linear
    centre = a[:3, :3] @ ((np.array([16, 15, 14]) - 1) / 2) + a[:3, 3]
    ref_affine = affine(np.eye(3), centre - 3)
    index = np.stack(np.meshgrid(*(np.arange(7),) * 3, indexing="ij"), -1).reshape(-1, 3)
    ref = tmp_path / "ref.nii"
    nib.save(nib.Nifti1Image(linear(index + centre - 3).reshape(7, 7, 7), ref_affine), str(ref))
    at = f"{centre[2]:.6f}"
    box, window, orientation = slice_summary(
        "--volume", str(path), "--filter", "tricubic", "--prefilter", "none", "--difference-to",
        str(ref), "--axis", "z", "--at", at, "-o", str(tmp_path / "d.png"))
    np.testing.assert_allclose(box, [centre[0] - 3, centre[0] + 3, centre[1] - 3, centre[1] + 3],
                               rtol=0, atol=1e-4)  # printed to 6 digits
    # +- the largest difference: float rounding (measured 1.4e-6; values -5 to 23), none from
    # the mapping (a wrong one would be off by about |b| = 1.5 per unit).
    assert window[0] == -window[1] and 0 <= window[1] < 1e-4, window
    assert orientation == "orientation: left L, right R, bottom P, top A (RAS world)"

    # The oblique volume as the reference: the world box around its grid.
    corners = np.array([[i, j, k] for i in (0, 15) for j in (0, 14) for k in (0, 13)])
    world = corners @ a[:3, :3].T + a[:3, 3]
    box, _, _ = slice_summary("--reference", str(path), "--axis", "z", "--at", at, "-o",
                              str(tmp_path / "r.png"))
    np.testing.assert_allclose(box, [world[:, 0].min(), world[:, 0].max(), world[:, 1].min(),
                                     world[:, 1].max()], rtol=0, atol=1e-4)
