"""boxgen.eval, emit and bbform against `boxgen eval/emit/bbform` (the same code, the same input)."""
import json
import os
from fractions import Fraction

import numpy as np
import pytest

import boxgen
from conftest import cli_error, run

CUSTOM = "1,0,0; 0,1,0; 0,0,1; 1,1,1"
PLANAR = "1,0; 0,1; 1,1; 1,-1"
# On a lattice given by the rows of G (its directions must be lattice points).
STRETCHED, ROWS = "2,0,0; 0,1,0; 0,0,1; 2,1,1", "2,0,0; 0,1,0; 0,0,1"


def cli_eval(spec, *points, derivative=None, lattice=None):
    args = ["eval", spec]
    for p in points:
        args += ["--at", p]
    if derivative:
        args += ["--derivative", derivative]
    if lattice:
        args += ["--lattice", lattice]
    return [Fraction(v["value"]) for v in json.loads(run("boxgen", *args, "--json")[1])]


def test_eval_equals_the_cli_at_every_kind_of_point():
    third = [Fraction(1, 3), Fraction(1, 5), Fraction(-1, 7)]
    expected = cli_eval("m7", "1/3 1/5 -1/7", "0.25 0 -0.5", "0 0 0")
    assert boxgen.eval("m7", third) == expected[0]  # one point: one Fraction
    assert isinstance(boxgen.eval("m7", third), Fraction)
    assert boxgen.eval("m7", "1/3 1/5 -1/7") == expected[0]
    # A sequence of numbers is one point; anything else a sequence of points, whose coordinates
    # may be text too.
    assert boxgen.eval("m7", [["1/3", "0.2", Fraction(-1, 7)]]) == expected[:1]
    # Several points: a list; floats at their exact binary value (0.25 and -0.5 are exact).
    assert boxgen.eval("m7", [third, [0.25, 0, -0.5], (0, 0, 0)]) == expected
    assert boxgen.eval("m7", np.array([[0.25, 0.0, -0.5], [0.0, 0.0, 0.0]])) == expected[1:]
    assert boxgen.eval("m7", ["1/3 1/5 -1/7", "0 0 0"]) == [expected[0], expected[2]]
    tenth = Fraction(0.1)  # not 1/10
    assert boxgen.eval("m7", [0.1, 0, 0]) == cli_eval(
        "m7", f"{tenth.numerator}/{tenth.denominator} 0 0")[0]
    assert boxgen.eval("m7", [0.1, 0, 0]) != boxgen.eval("m7", "0.1 0 0")


def test_eval_of_derivatives_and_lattices_equals_the_cli():
    assert boxgen.eval("m7", "1/3 1/5 -1/7", derivative=(1, 0, 2)) == cli_eval(
        "m7", "1/3 1/5 -1/7", derivative="1 0 2")[0]
    assert boxgen.eval("m7", "1/3 1/5 -1/7", derivative="0 1 0") == cli_eval(
        "m7", "1/3 1/5 -1/7", derivative="0 1 0")[0]
    assert boxgen.eval(STRETCHED, "1/3 1/5 -1/7", lattice=ROWS) == cli_eval(
        STRETCHED, "1/3 1/5 -1/7", lattice=ROWS)[0]


def test_eval_is_exact():
    # The Courant hat (three directions on Z^2) peaks at 1 at its centre, and the box [e1 e2]
    # is 1 inside the centred unit square and 0 outside it; derived independently by hand.
    assert boxgen.eval("hex3", "0 0") == 1
    assert boxgen.eval("1,0; 0,1", [[Fraction(1, 3), Fraction(-2, 5)], ["0.6", "0"]]) == [1, 0]
    # The hat is linear on each triangle: half-way to a vertex of its support it is 1/2.
    assert boxgen.eval("hex3", [Fraction(1, 2), 0]) == Fraction(1, 2)


def test_bbform_equals_the_cli():
    assert boxgen.bbform(PLANAR) == json.loads(run("boxgen", "bbform", PLANAR, "--json")[1])
    assert boxgen.bbform("hex3", region=0) == json.loads(
        run("boxgen", "bbform", "hex3", "--region", "0", "--json")[1])
    assert boxgen.bbform(STRETCHED, lattice=ROWS) == json.loads(
        run("boxgen", "bbform", STRETCHED, "--lattice", ROWS, "--json")[1])


@pytest.mark.parametrize("options", [[], ["--target", "glsl", "--precision", "double"],
                                     ["--target", "cuda"], ["--strategy", "monomial"]])
def test_emit_returns_what_the_cli_writes(tmp_path, options):
    run("boxgen", "emit", CUSTOM, "--lattice", "cartesian", "--name", "mine", "--out",
        str(tmp_path), *options)
    written = {name: open(tmp_path / name, encoding="utf-8", newline="").read()
               for name in os.listdir(tmp_path)}
    kwargs = dict(zip([o.lstrip("-") for o in options[0::2]], options[1::2]))
    assert boxgen.emit(CUSTOM, "mine", lattice="cartesian", **kwargs) == written
    assert written  # the comparison compared something


def test_emit_with_shells_equals_the_cli(tmp_path):
    run("boxgen", "emit", "m7", "--name", "m7s", "--shells", "0,1", "--out", str(tmp_path))
    files = boxgen.emit("m7", "m7s", shells=[0, 1])
    assert sorted(files) == sorted(os.listdir(tmp_path))
    for name, text in files.items():
        assert text == (tmp_path / name).read_text(encoding="utf-8")


def test_bad_input_is_a_value_error_with_the_clis_message():
    cases = [
        (lambda: boxgen.eval("m7", "0 0"), ("eval", "m7", "--at", "0 0")),
        (lambda: boxgen.eval("m7", [0, 0, 0], derivative=(1, -1, 0)),
         ("eval", "m7", "--at", "0/1 0/1 0/1", "--derivative", "1 -1 0")),
        (lambda: boxgen.eval("nonsense", "0 0 0"), ("eval", "nonsense", "--at", "0 0 0")),
        (lambda: boxgen.eval("m7", "1/0 0 0"), ("eval", "m7", "--at", "1/0 0 0")),
        (lambda: boxgen.emit(CUSTOM, "bad name"), ("emit", CUSTOM, "--name", "bad name", "--out",
                                                   "/nonexistent-boxgen-dir")),
        (lambda: boxgen.emit(CUSTOM, "fine", target="java"),
         ("emit", CUSTOM, "--name", "fine", "--target", "java", "--out", "/nonexistent-boxgen-dir")),
        (lambda: boxgen.bbform(PLANAR, region=99), ("bbform", PLANAR, "--region", "99")),
    ]
    for call, cli_args in cases:
        with pytest.raises(ValueError) as e:
            call()
        assert str(e.value) == cli_error("boxgen", *cli_args), cli_args


def test_wrong_types_and_values_are_refused():
    with pytest.raises(ValueError, match="at least one point"):
        boxgen.eval("m7", [])
    with pytest.raises(ValueError, match="finite"):
        boxgen.eval("m7", [0, 0, float("nan")])
    with pytest.raises(TypeError, match="coordinate"):
        boxgen.eval("m7", [[0, True, 0]])
    with pytest.raises(TypeError, match="point"):
        boxgen.eval("m7", [object()])
    with pytest.raises(TypeError, match="points"):
        boxgen.eval("m7", 3)
    with pytest.raises(TypeError, match="derivative order"):
        boxgen.eval("m7", "0 0 0", derivative=(1.0, 0, 0))
    with pytest.raises(TypeError):
        boxgen.emit(CUSTOM, 3)
    with pytest.raises(TypeError):
        boxgen.bbform(PLANAR, region=1.5)
