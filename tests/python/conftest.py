"""Shared fixtures of the Python tests: the programs of the same build (BOXGEN_BIN_DIR, set by
CTest) and small volumes, so that every comparison with the CLI runs in well under a second."""
import os
import subprocess

import numpy as np
import pytest

import boxgen

BIN = os.environ.get("BOXGEN_BIN_DIR", os.path.join(os.path.dirname(__file__), "../../build/apps"))


def run(program, *args, stdin=None, check=True):
    """(returncode, stdout, stderr) of build/apps/<program> args."""
    p = subprocess.run([os.path.join(BIN, program), *args], input=stdin, capture_output=True,
                       text=True)
    if check and p.returncode != 0:
        raise AssertionError(f"{program} {' '.join(args)} failed: {p.stderr}")
    return p.returncode, p.stdout, p.stderr


def cli_error(program, *args):
    """The one-line message the program prints for bad input, without its 'program: error: '."""
    code, out, err = run(program, *args, check=False)
    assert code == 1 and out == "", (code, out, err)
    lines = err.strip().split("\n")
    assert len(lines) == 1, err
    prefix = f"{program}: error: "
    assert lines[0].startswith(prefix), lines[0]
    return lines[0][len(prefix):]


@pytest.fixture(scope="session")
def ml_volume():
    """Marschner-Lobb on BCC, N = 9 (2 x 15^3 samples with boxrecon's margin)."""
    return boxgen.sample("ml", 9)


@pytest.fixture
def rng():
    return np.random.default_rng(20)


def points_in(box, count, rng):
    lo, hi = (np.array(b) for b in box)
    return lo + (hi - lo) * rng.random((count, 3))
