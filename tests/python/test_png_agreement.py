"""scripts/png_agreement.py, the pixel comparison docs/gpu.md uses for the CPU and GL pictures:
its counts on pictures with known edits, written here with each of PNG's five row filters, and
on boxrecon's own PNGs (libpng's choice of filters); one line for bad input."""
import os
import struct
import subprocess
import sys
import zlib

from conftest import run

SCRIPT = os.path.join(os.path.dirname(__file__), "../../scripts/png_agreement.py")


def agreement(a, b):
    p = subprocess.run([sys.executable, SCRIPT, a, b], capture_output=True, text=True)
    return p.returncode, p.stdout.strip(), p.stderr.strip()


def filtered(kind, line, prev):
    """A row of RGB bytes under PNG filter `kind` (0 None, 1 Sub, 2 Up, 3 Average, 4 Paeth)."""
    out = bytearray()
    for i, x in enumerate(line):
        left = line[i - 3] if i >= 3 else 0
        up, corner = prev[i], prev[i - 3] if i >= 3 else 0
        p = left + up - corner
        paeth = min((abs(p - left), 0, left), (abs(p - up), 1, up), (abs(p - corner), 2, corner))[2]
        predictor = (0, left, up, (left + up) // 2, paeth)[kind]
        out.append((x - predictor) & 255)
    return bytes(out)


def write_png(path, width, height, pixels, kind=0):
    """An 8-bit RGB PNG, every row under filter `kind` (pixels: bytes, row by row)."""
    rows = [pixels[3 * width * y:3 * width * (y + 1)] for y in range(height)]
    raw = b"".join(bytes([kind]) + filtered(kind, row, rows[y - 1] if y else bytes(3 * width))
                   for y, row in enumerate(rows))

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def test_known_edits_are_counted_under_every_filter(tmp_path):
    base = bytes((7 * i) % 251 for i in range(3 * 5 * 4))
    edited = bytearray(base)
    edited[3 * 2 + 1] = (edited[3 * 2 + 1] + 2) % 256  # pixel 2: within 3/255
    edited[3 * 7] = (edited[3 * 7] + 40) % 256  # pixel 7: beyond, by 40
    for kind in range(5):
        a, b = str(tmp_path / f"a{kind}.png"), str(tmp_path / f"b{kind}.png")
        write_png(a, 5, 4, base, kind)
        write_png(b, 5, 4, bytes(edited), (kind + 1) % 5)
        assert agreement(a, b) == (
            0, "1 of 20 pixels differ by more than 3/255, 18 identical, worst 40/255", ""), kind


def test_boxrecons_filtered_pngs_decode(tmp_path):
    # The same picture compares identical, and another shading of the same surface differs.
    normal, curvature = str(tmp_path / "n.png"), str(tmp_path / "c.png")
    for path, shading in ((normal, "normal"), (curvature, "curvature")):
        run("boxrecon", "render", "--function", "ml", "--n", "12", "--width", "24", "--height", "20",
            "--shading", shading, "-o", path)
    assert agreement(normal, normal) == (
        0, "0 of 480 pixels differ by more than 3/255, 480 identical, worst 0/255", "")
    code, out, _ = agreement(normal, curvature)
    assert code == 0 and not out.startswith("0 of 480")


def test_bad_input_is_one_line(tmp_path):
    (tmp_path / "not.png").write_text("text")
    write_png(tmp_path / "small.png", 2, 2, bytes(12))
    write_png(tmp_path / "large.png", 3, 2, bytes(18))
    for a, b, message in ((tmp_path / "not.png", tmp_path / "small.png", "is not a PNG"),
                          (tmp_path / "small.png", tmp_path / "large.png", "sizes differ")):
        code, out, err = agreement(str(a), str(b))
        assert code == 1 and out == "" and len(err.split("\n")) == 1 and message in err, err
