"""Bad arguments raise ValueError or TypeError, with boxrecon's or boxgen's one-line message where
the CLI has the same mistake; nothing crashes the interpreter."""
import subprocess
import sys
import textwrap

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
        boxgen.Filter("m7").evaluate(boxgen.read_volume(bcc), [[0, 0, 0]], prefilter="q3opt")
    same_message(e, "boxrecon", "eval", "--filter", "m7", "--prefilter", "q3opt", "--volume", bcc,
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
    """set_threads(66000) then an evaluation crashed the interpreter, and 33000
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


def test_memory_failures_are_memory_errors():
    """Points whose float64 copy cannot be allocated raised "ValueError: cannot
    create a pybind11::array_t from a nullptr"; now NumPy's MemoryError, naming the size. Run in a
    child under an address-space limit 1 GiB above what it has mapped."""
    script = textwrap.dedent("""
        import resource
        import numpy as np
        import boxgen
        volume, m7 = boxgen.sample("ml", 6), boxgen.Filter("m7")
        points = np.zeros((100_000_000, 3), dtype=np.float32)  # 1.2 GB; float64 needs 2.4 GB
        with open("/proc/self/status") as status:
            mapped = next(int(l.split()[1]) for l in status if l.startswith("VmSize:")) * 1024
        resource.setrlimit(resource.RLIMIT_AS, (mapped + (1 << 30), mapped + (1 << 30)))
        try:
            m7.evaluate(volume, points)
        except Exception as e:
            print(type(e).__name__, e)
        """)
    p = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    assert p.stdout.startswith("MemoryError"), p.stdout
    assert "nullptr" not in p.stdout, p.stdout


def test_read_volume_gives_the_lattice_asked_for(tmp_path):
    """read_volume(path, lattice='fcc') on a BCC file returned a BCC volume."""
    path = str(tmp_path / "bcc.nrrd")
    boxgen.write_volume(path, boxgen.sample("ml", 6))
    with pytest.raises(ValueError, match="holds a BCC volume, not the FCC lattice asked for"):
        boxgen.read_volume(path, lattice="fcc")
    assert boxgen.read_volume(path, lattice="bcc").lattice == "bcc"


@pytest.mark.parametrize("call", ["evaluate", "resample"])
def test_ctrl_c_interrupts_a_long_call(call):
    """SIGINT during a long evaluation raised KeyboardInterrupt only when the
    work had ended. The child times the call uninterrupted (T), then sends itself SIGINT 0.3 s into
    the same call: KeyboardInterrupt must come well before T (before the fix it came after T)."""
    script = textwrap.dedent("""
        import os, signal, threading, time
        import numpy as np
        import boxgen
        boxgen.set_threads(1)
        volume, m12 = boxgen.sample("ml", 24), boxgen.Filter("m12")
        rng = np.random.default_rng(1)
        def work(size, points):
            if "CALL" == "evaluate":
                m12.evaluate(volume, points, hessian=True)
            else:
                boxgen.resample(volume, m12, shape=round(size ** (1 / 3)))
        def timed(size, points):
            start = time.monotonic()
            work(size, points)
            return time.monotonic() - start
        # A call of about 3 s on this machine (at most 12 million points, 1.3 GB).
        size = min(12_000_000, int(1_000_000 * 3 / max(timed(10**6, rng.uniform(-.5, .5, (10**6, 3))), 1e-3)))
        points = rng.uniform(-0.5, 0.5, (size, 3))  # made before the calls: only the call is timed
        full = timed(size, points)
        threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
        start = time.monotonic()
        try:
            work(size, points)
            print("finished", full)
        except KeyboardInterrupt:
            print("interrupted", full, time.monotonic() - start)
        """).replace("CALL", call)
    p = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr
    words = p.stdout.split()
    assert words[0] == "interrupted", p.stdout
    full, interrupted_after = float(words[1]), float(words[2])
    # Before the fix the interrupt came when the call ended (after `full`), which fails the check
    # below whenever full > 0.45 s; 0.6 s leaves a margin on a fast machine (the 12 M cap).
    assert full > 0.6, f"the call is too short to tell ({full:.2f} s): {p.stdout}"
    assert interrupted_after < 0.3 + full / 3, p.stdout
