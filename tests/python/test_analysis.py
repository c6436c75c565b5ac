"""boxgen.analyze, pieces, prefilter, metrics, kernel, spectrum against `boxgen ... --json`."""
import json

import numpy as np
import pytest

import boxgen
from conftest import cli_error, run

# Small matrices: each derivation takes well under a second.
CUSTOM = "1,0,0; 0,1,0; 0,0,1; 1,1,1"
PLANAR = "1,0; 0,1; 1,1; 1,-1"


def cli_json(*args):
    return json.loads(run("boxgen", *args, "--json")[1])


def plain(x):
    """NumPy arrays as lists, recursively, to compare with parsed JSON."""
    if isinstance(x, dict):
        return {k: plain(v) for k, v in x.items()}
    if isinstance(x, np.ndarray):
        return x.tolist()
    return x


def without_timings(a):
    a = dict(a)
    for key in ("derivation_seconds", "seconds", "checks"):
        a.pop(key, None)
    return a


def test_analyze_equals_cli():
    py = boxgen.analyze(CUSTOM, lattice="cartesian")
    cli = cli_json("analyze", CUSTOM, "--lattice", "cartesian")
    assert without_timings(py) == without_timings(cli)
    assert py["degree"] == 1 and py["checks"]["integral_is_one"] is True


def test_pieces_equals_cli():
    assert boxgen.pieces(PLANAR) == cli_json("pieces", PLANAR)
    assert boxgen.pieces(PLANAR, of="filter", region="all") == cli_json(
        "pieces", PLANAR, "--of", "filter", "--region", "all")


def test_prefilter_equals_cli():
    py = boxgen.prefilter("m7", "0,1")
    assert py == cli_json("prefilter", "m7", "--shells", "0,1")
    assert boxgen.prefilter("m7", [0, 1]) == py
    # The paper's Table 1: Q^I of M7 is 5/3 at the centre and -1/12 on the first shell.
    weights = {tuple(w["offset"]): w["weight"] for w in py["weights"]}
    assert weights[(0, 0, 0)] == "5/3"


def test_optimised_prefilter_equals_cli():
    # q2opt: one free parameter of M8's Q^II shells chosen by the integrated error kernel.
    py = boxgen.prefilter("m8", prefilter="q2opt")
    assert py == cli_json("prefilter", "m8", "--prefilter", "q2opt")
    assert py["exact"] is False and len(py["optimisation"]["parameters"]) == 1
    o = py["optimisation"]
    assert o["integrated_error_kernel"] < o["integrated_error_kernel_at_zero"]


def test_metrics_equals_cli():
    # 2-D matrices: the 3-D quadratures take seconds.
    py = boxgen.metrics([PLANAR, "1,0; 0,1; 1,1"])
    assert py == cli_json("metrics", PLANAR, "1,0; 0,1; 1,1")
    assert boxgen.metrics(PLANAR, lattice="cartesian") == cli_json("metrics", PLANAR, "--lattice",
                                                                   "cartesian")


def test_specs_with_lattices_and_labels_equal_cli():
    # SPEC@LATTICE and labels as on the command line: directions of the checkerboard lattice
    # {x + y even} (rows of G "1,1; 1,-1") on it and on Z^2.
    spec = "1,1; 1,-1; 2,0; 0,2"
    on_checkerboard = spec + "@1,1; 1,-1"
    py = boxgen.metrics([spec, on_checkerboard], labels=["Z2", "D2"])
    assert py == cli_json("metrics", spec, on_checkerboard, "--label", "Z2", "--label", "D2")
    assert py["Z2"]["lattice"] == "cartesian" and py["D2"]["lattice"] != "cartesian"
    line = boxgen.spectrum(["fcc6", "fcc6@cartesian"], line="1,1,1", w=[0, 1], labels=["a", "b"])
    assert plain(line) == cli_json("spectrum", "fcc6", "fcc6@cartesian", "--line", "1,1,1", "--w",
                                   "0,1", "--label", "a", "--label", "b")
    with pytest.raises(ValueError) as e:
        boxgen.metrics([PLANAR], labels=["a", "b"])
    assert str(e.value) == cli_error("boxgen", "metrics", PLANAR, "--label", "a", "--label", "b")


def test_kernel_equals_cli_with_arrays():
    py = boxgen.kernel("m7", prefilter="q1", w=[0.5, 1, 2])
    assert isinstance(py["w"], np.ndarray) and isinstance(py["E"], np.ndarray)
    assert plain(py) == cli_json("kernel", "m7", "--prefilter", "q1", "--w", "0.5,1,2")
    many = boxgen.kernel(["m7", "m8"], w_from=0.1, w_to=1, steps=5)
    assert plain(many) == cli_json("kernel", "m7", "m8", "--from", "0.1", "--to", "1", "--steps",
                                   "5")
    assert isinstance(many["m8"]["E"], np.ndarray) and many["m8"]["E"].shape == (5,)


def test_equal_density_equals_cli():
    py = boxgen.kernel(["m8", "fcc6@fcc"], prefilter="q1", w=[0.5, 1], equal_density=True)
    assert plain(py) == cli_json("kernel", "m8", "fcc6@fcc", "--prefilter", "q1", "--w", "0.5,1",
                                 "--equal-density")
    line = boxgen.spectrum(["m8", "fcc6@fcc"], line="1,1,1", w=[1], equal_density=True)
    assert plain(line) == cli_json("spectrum", "m8", "fcc6@fcc", "--line", "1,1,1", "--w", "1",
                                   "--equal-density")
    m = boxgen.metrics(["m8"], equal_density=True)
    assert plain(m) == cli_json("metrics", "m8", "--equal-density")


def test_spectrum_equals_cli_with_arrays():
    py = boxgen.spectrum(["m7", "m8"], line="1,1,1", steps=9, w_from=0, w_to=4)
    cli = cli_json("spectrum", "m7", "m8", "--line", "1,1,1", "--steps", "9", "--from", "0",
                   "--to", "4")
    assert plain(py) == cli
    assert py["m7"]["magnitude"][0] == 1.0  # psi_hat(0) = 1: the filter integrates to 1


def test_analysis_errors_are_the_cli_messages():
    with pytest.raises(ValueError) as e:
        boxgen.analyze("1,2,3; nonsense")
    assert str(e.value) == cli_error("boxgen", "analyze", "1,2,3; nonsense")
    with pytest.raises(ValueError) as e:
        boxgen.prefilter("m7", "0,7,x")
    assert str(e.value) == cli_error("boxgen", "prefilter", "m7", "--shells", "0,7,x")
    with pytest.raises(ValueError) as e:
        boxgen.kernel("m7", prefilter="q9", w=[1])
    assert str(e.value) == cli_error("boxgen", "kernel", "m7", "--prefilter", "q9", "--w", "1")
    with pytest.raises(ValueError):
        boxgen.metrics([])
    with pytest.raises(TypeError):
        boxgen.metrics(7)
