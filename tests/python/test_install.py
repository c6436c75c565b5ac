"""`cmake --install` puts the package where Debian's python3 finds it under the prefix."""
import os
import subprocess
import sys

BUILD = os.environ.get("BOXGEN_BUILD_DIR", os.path.join(os.path.dirname(__file__), "../../build"))


def test_installed_package_imports(tmp_path):
    prefix = tmp_path / "prefix"
    subprocess.run(["cmake", "--install", BUILD, "--prefix", str(prefix), "--component", "python"],
                   check=True, capture_output=True)
    version = f"python{sys.version_info.major}.{sys.version_info.minor}"
    site = prefix / "lib" / version / "dist-packages"
    assert (site / "boxgen" / "__init__.py").is_file() and (site / "boxgen" / "dask.py").is_file()
    env = dict(os.environ, PYTHONPATH=str(site))
    out = subprocess.run(
        [sys.executable, "-c", "import boxgen, boxgen.dask; print(boxgen.__file__); "
         "print(boxgen.Filter('m7').degree)"],
        check=True, capture_output=True, text=True, env=env, cwd=tmp_path).stdout.split()
    assert out[0].startswith(str(site)) and out[1] == "4"
