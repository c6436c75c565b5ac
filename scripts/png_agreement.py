#!/usr/bin/python3
"""How far two PNG pictures of the same size differ, per pixel: the largest difference of any
channel, counted as identical (0), within 3/255 and beyond. boxrecon render writes 8-bit RGB
PNGs; docs/gpu.md compares its CPU and GL pictures with this (no image library needed).

Usage: scripts/png_agreement.py A.png B.png
Prints one line: "<beyond> of <pixels> pixels differ by more than 3/255, <identical> identical,
worst <d>/255". Exit 1 with one line on stderr for a file that is not an 8-bit RGB PNG or
pictures of different sizes."""
import struct
import sys
import zlib


def read_rgb(path):
    """(width, height, rows): the rows of an 8-bit RGB, non-interlaced PNG as bytes."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(f"{path} is not a PNG")
    at, header, chunks = 8, None, []
    while at + 8 <= len(data):
        length, kind = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8:at + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            chunks.append(body)
        at += 12 + length
    if header is None or header[2:5] != (8, 2, 0) or header[6] != 0:
        raise ValueError(f"{path} is not an 8-bit RGB non-interlaced PNG")
    width, height = header[0], header[1]
    raw = zlib.decompress(b"".join(chunks))
    stride, rows, prev = 3 * width, [], bytearray(3 * width)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):  # undo the PNG filter of the row (types 0-4)
            left = line[i - 3] if i >= 3 else 0
            up, corner = prev[i], prev[i - 3] if i >= 3 else 0
            if kind == 1:
                line[i] = (line[i] + left) & 255
            elif kind == 2:
                line[i] = (line[i] + up) & 255
            elif kind == 3:
                line[i] = (line[i] + (left + up) // 2) & 255
            elif kind == 4:
                p = left + up - corner
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - corner)
                line[i] = (line[i] + (left if pa <= pb and pa <= pc else up if pb <= pc else corner)) & 255
            elif kind != 0:
                raise ValueError(f"{path} has an unknown PNG filter {kind}")
        rows.append(bytes(line))
        prev = line
    return width, height, rows


def main(argv):
    if len(argv) != 3:
        print("usage: png_agreement.py A.png B.png", file=sys.stderr)
        return 1
    try:
        a, b = read_rgb(argv[1]), read_rgb(argv[2])
    except (OSError, ValueError, zlib.error) as e:
        print(f"png_agreement: {e}", file=sys.stderr)
        return 1
    if a[:2] != b[:2]:
        print(f"png_agreement: the pictures' sizes differ ({a[0]} x {a[1]}, {b[0]} x {b[1]})",
              file=sys.stderr)
        return 1
    beyond = identical = worst = 0
    for ra, rb in zip(a[2], b[2]):
        for i in range(0, len(ra), 3):
            d = max(abs(ra[i + c] - rb[i + c]) for c in range(3))
            beyond += d > 3
            identical += d == 0
            worst = max(worst, d)
    print(f"{beyond} of {a[0] * a[1]} pixels differ by more than 3/255, {identical} identical, "
          f"worst {worst}/255")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
