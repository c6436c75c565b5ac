"""Bad arguments raise ValueError or TypeError, with boxrecon's or boxgen's one-line message where
the CLI has the same mistake; nothing crashes the interpreter."""
import numpy as np
import pytest

import boxgen
from conftest import cli_error, points_in, run


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    d = tmp_path_factory.mktemp("files")
    bcc, pts = str(d / "bcc.nrrd"), str(d / "p.txt")
    boxgen.write_volume(bcc, boxgen.sample("ml", 5))
    return d, bcc, pts


def same_message(exc, *cli_args):
    assert str(exc.value) == cli_error(*cli_args)


def test_unknown_names(files):
    d, bcc, pts = files
    with open(pts, "w") as f:
        f.write("0 0 0\n")
    with pytest.raises(ValueError) as e:
        boxgen.Filter("m99")
    same_message(e, "boxgen", "analyze", "m99")
    with pytest.raises(ValueError) as e:
        boxgen.Filter("m7").evaluate(boxgen.read_volume(bcc), [[0, 0, 0]], prefilter="q3")
    same_message(e, "boxrecon", "eval", "--filter", "m7", "--prefilter", "q3", "--volume", bcc,
                 "--points", pts)
    with pytest.raises(ValueError) as e:
        boxgen.sample("nope", 5)
    same_message(e, "boxrecon", "sample", "--function", "nope", "--n", "5", "-o", str(d / "x"))
    with pytest.raises(ValueError) as e:
        boxgen.sample("ml", 1)
    same_message(e, "boxrecon", "sample", "--n", "1", "-o", str(d / "x"))
    with pytest.raises(ValueError) as e:
        boxgen.sample("ml", 5, lattice="hexagonal")
    same_message(e, "boxrecon", "sample", "--n", "5", "--lattice", "hexagonal", "-o", str(d / "x"))
    with pytest.raises(ValueError) as e:
        boxgen.read_volume(str(d / "missing.nrrd"), lattice="bcc")
    same_message(e, "boxrecon", "eval", "--filter", "m7", "--volume", str(d / "missing.nrrd"),
                 "--points", pts)
    with pytest.raises(ValueError) as e:
        boxgen.Filter("fcc6", lattice="bcc")
    same_message(e, "boxrecon", "eval", "--filter", "fcc6", "--lattice", "bcc", "--volume", bcc,
                 "--points", pts)


def test_wrong_lattice_and_points_outside(files):
    d, bcc, pts = files
    v = boxgen.read_volume(bcc)
    with open(pts, "w") as f:
        f.write("0 0 0\n")
    with pytest.raises(ValueError) as e:
        boxgen.Filter("fcc6").evaluate(v, [[0, 0, 0]])
    assert "fcc6" in str(e.value) and "bcc" in str(e.value)
    with open(pts, "w") as f:
        f.write("0 0 0\n9 0 0\n")
    with pytest.raises(ValueError) as e:
        boxgen.Filter("m7").evaluate(v, [[0, 0, 0], [9, 0, 0]])
    same_message(e, "boxrecon", "eval", "--filter", "m7", "--volume", bcc, "--points", pts)
    with pytest.raises(ValueError, match="leaves the region"):
        boxgen.resample(v, boxgen.Filter("m7"), None, (-9, 0, 0), (0, 1, 1), 4)


def test_nan_points_and_nonfinite_values(files):
    d, bcc, pts = files
    v = boxgen.read_volume(bcc)
    f = boxgen.Filter("m7")
    with open(pts, "w") as fh:
        fh.write("0 0 0\n0 nan 0\n")
    with pytest.raises(ValueError) as e:
        f.evaluate(v, [[0, 0, 0], [0, np.nan, 0]])
    cli = cli_error("boxrecon", "eval", "--filter", "m7", "--volume", bcc, "--points", pts)
    assert str(e.value) == "points[1]: " + cli.split(": ", 1)[1]  # the CLI names file:line
    with pytest.raises(ValueError, match="not finite"):
        f.evaluate(v, [[np.inf, 0, 0]])
    huge = boxgen.Volume(np.full((2, 8, 8, 8), 1e308), lattice="bcc")
    with pytest.raises(ValueError, match="not finite"):
        f.evaluate(huge, [points_in(f.default_box(huge), 1, np.random.default_rng(1))[0]])
    with pytest.raises(ValueError, match="non-finite|not finite"):
        boxgen.sample(lambda p: np.where(p[:, 0] > 0, np.inf, 0.0), 3)


@pytest.mark.parametrize("points,error", [
    (np.zeros((4, 2)), ValueError), (np.zeros(3), ValueError), (np.zeros((2, 3, 1)), ValueError),
    (np.zeros((2, 3), dtype=complex), TypeError), (np.array([["a", "b", "c"]]), TypeError),
    (np.zeros((2, 3), dtype=bool), TypeError), ([[0, 0, None]], TypeError), ("points", TypeError),
])
def test_wrong_points(files, points, error):
    v = boxgen.read_volume(files[1])
    with pytest.raises(error, match="points"):
        boxgen.Filter("m7").evaluate(v, points)


def test_wrong_arguments_elsewhere(files):
    d, bcc, pts = files
    v = boxgen.read_volume(bcc)
    f = boxgen.Filter("m7")
    assert f.evaluate(v, np.zeros((0, 3))).shape == (0,)
    assert f.evaluate(v, np.zeros((2, 3), dtype=np.int32)).shape == (2,)  # integers are fine
    with pytest.raises(TypeError):
        f.evaluate(np.zeros((2, 4, 4, 4)), [[0, 0, 0]])
    with pytest.raises(TypeError):
        boxgen.resample(v, "m7", None)
    with pytest.raises(ValueError, match="each size must be in 2"):
        boxgen.resample(v, f, None, shape=(1, 4, 4))
    with pytest.raises(ValueError, match="empty or degenerate"):
        boxgen.resample(v, f, None, (0, 0, 0), (0, 1, 1), 4)
    with pytest.raises(ValueError, match="both lo and hi"):
        boxgen.resample(v, f, None, (0, 0, 0))
    with pytest.raises(ValueError, match="three numbers"):
        boxgen.resample(v, f, None, (0, 0), (1, 1), 4)
    with pytest.raises(ValueError, match="coset"):
        boxgen.Volume(np.zeros((3, 4, 4, 4)), lattice="bcc")
    with pytest.raises(TypeError):
        boxgen.Volume(np.zeros((2, 4, 4, 4), dtype=complex))
    with pytest.raises(ValueError):
        boxgen.Volume(np.zeros((2, 4, 4, 4)), spacing=-1)
    with pytest.raises(ValueError) as e:
        boxgen.write_volume(str(d / "no" / "such" / "dir.nrrd"), v)
    assert "no/such" in str(e.value)
    with pytest.raises(ValueError, match="one value per point"):
        boxgen.sample(lambda p: p, 3)
    with pytest.raises(TypeError):
        boxgen.sample(42, 3)


def test_thread_counts_have_an_upper_bound(files, ml_volume):
    """Issue 32, item 11: set_threads(66000) then an evaluation crashed the interpreter, and 33000
    ended it in libgomp's "Thread creation failed"; boxrecon --threads says the same line."""
    d, bcc, pts = files
    for n in (33000, 66000):
        with pytest.raises(ValueError) as e:
            boxgen.set_threads(n)
        assert "threads are more than this process can use: at most" in str(e.value)
        same_message(e, "boxrecon", "--threads", str(n), "eval", "--filter", "m7", "--volume",
                     bcc, "--points", pts)
    boxgen.set_threads(0)
    assert boxgen.Filter("m7").evaluate(ml_volume, [[0, 0, 0]]).shape == (1,)
