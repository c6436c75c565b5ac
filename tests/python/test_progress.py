"""boxrecon's progress on a terminal: after 2 s, percentages (resample, subsample, compare) and the
prefilter's stage on stderr; the same files as without a terminal (where stderr stays empty) or
with --quiet. The terminal is the
pseudo-terminal of util-linux's `script` (Debian's bsdutils, always installed)."""
import os
import shutil
import subprocess

import pytest

from conftest import BIN, run

SCRIPT = shutil.which("script")


@pytest.mark.skipif(SCRIPT is None, reason="no script(1) for a pseudo-terminal")
def test_resample_progress_on_a_terminal_only(tmp_path):
    volume = str(tmp_path / "c.nrrd")
    run("boxrecon", "sample", "--function", "cubic", "--lattice", "cartesian", "--n", "17", "-o",
        volume)
    # BOXGEN_PROGRESS_AFTER=0: progress at once (else after 2 s), whatever the machine's speed.
    args = ["resample", "--filter", "tricubic", "--volume", volume, "--n", "64", "--precision",
            "float"]
    boxrecon = os.path.join(BIN, "boxrecon")
    command = " ".join(["BOXGEN_PROGRESS_AFTER=0", boxrecon, *args, "-o",
                        str(tmp_path / "tty.nrrd")])
    tty = subprocess.run([SCRIPT, "-qec", command, "/dev/null"], capture_output=True, text=True,
                         timeout=600)
    assert tty.returncode == 0, tty.stdout
    assert "resampling 100%" in tty.stdout  # script passes the terminal's output on stdout
    _, out, err = run("boxrecon", *args, "-o", str(tmp_path / "plain.nrrd"))
    assert out == "" and err == ""
    with open(tmp_path / "tty.nrrd", "rb") as a, open(tmp_path / "plain.nrrd", "rb") as b:
        assert a.read() == b.read()
    quiet = subprocess.run([SCRIPT, "-qec", command.replace("-o ", "--quiet -o "), "/dev/null"],
                           capture_output=True, text=True, timeout=600)
    assert quiet.returncode == 0 and "resampling" not in quiet.stdout


def _on_a_terminal(args):
    """boxrecon ARGS on the pseudo-terminal of script(1), progress at once: (exit, what it showed)."""
    boxrecon = os.path.join(BIN, "boxrecon")
    command = " ".join(["BOXGEN_PROGRESS_AFTER=0", boxrecon, *args])
    tty = subprocess.run([SCRIPT, "-qec", command, "/dev/null"], capture_output=True, text=True,
                         timeout=600)
    return tty.returncode, tty.stdout


@pytest.mark.skipif(SCRIPT is None, reason="no script(1) for a pseudo-terminal")
def test_subsample_compare_and_prefilter_show_progress_on_a_terminal_only(tmp_path):
    """subsample and compare count their work as resample does; the prefilter, which counts no
    steps, shows its stage and how long it took. Off a terminal, or with --quiet, nothing shows,
    and the outputs are the same."""
    volume = str(tmp_path / "c.nrrd")
    run("boxrecon", "sample", "--function", "cubic", "--lattice", "cartesian", "--n", "17", "-o",
        volume)
    subsample = ["subsample", "--volume", volume, "--lattice", "bcc", "--fraction", "0.5",
                 "--prefilter", "interp"]
    code, shown = _on_a_terminal([*subsample, "-o", str(tmp_path / "tty.nrrd")])
    assert code == 0, shown
    assert "subsampling 100%" in shown
    assert "prefilter interp (mirror boundary) ... done (" in shown
    _, out, err = run("boxrecon", *subsample, "-o", str(tmp_path / "plain.nrrd"))
    assert err == ""
    with open(tmp_path / "tty.nrrd", "rb") as a, open(tmp_path / "plain.nrrd", "rb") as b:
        assert a.read() == b.read()
    code, shown = _on_a_terminal([*subsample, "--quiet", "-o", str(tmp_path / "quiet.nrrd")])
    assert code == 0 and "subsampling" not in shown and "prefilter" not in shown, shown

    compare = ["compare", "--reference", volume, "--volume", str(tmp_path / "plain.nrrd"),
               "--filter", "m8", "--prefilter", "q1"]
    code, shown = _on_a_terminal(compare)
    assert code == 0, shown
    assert "comparing 100%" in shown
    assert "prefilter q1 (mirror boundary) ... done (" in shown
    _, plain, err = run("boxrecon", *compare)
    assert err == ""
    assert plain.replace("\r\n", "\n") in shown.replace("\r\n", "\n")  # the same report
    code, shown = _on_a_terminal([*compare, "--quiet"])
    assert code == 0 and "comparing" not in shown and "prefilter" not in shown, shown
