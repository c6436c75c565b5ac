"""boxrecon resample's progress on a terminal (issue 33): after 2 s, percentages on stderr, the
same file as without a terminal (where stderr stays empty) or with --quiet. The terminal is the
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
