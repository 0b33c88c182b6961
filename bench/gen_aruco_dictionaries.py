#!/usr/bin/env python3
"""Writes every OpenCV predefined ArUco dictionary to a compact binary file
that robocal-calib embeds with include_bytes! (issue 14).

Usage: python3 bench/gen_aruco_dictionaries.py \
           calib/src/vision/aruco/dictionaries.bin

Format (little-endian):
  b"RCARUCO1", u16 dictionary count, then per dictionary:
  u8 name length, name (ASCII, OpenCV's constant name, e.g. DICT_5X5_100),
  u16 OpenCV enum value, u8 marker size (bits per side),
  u8 maxCorrectionBits, u16 marker count,
  marker count x ceil(size^2 / 8) bytes: the marker's bits in OpenCV's
  rotation 0, row-major, most significant bit first, 1 = white cell.
"""
import struct
import sys

import cv2
import numpy as np

MAGIC = b"RCARUCO1"


def predefined_names():
    """One name per dictionary: OpenCV also exports upper-case aliases
    (DICT_APRILTAG_36H11 for DICT_APRILTAG_36h11); keep the documented
    mixed-case one (robocal matches names case-insensitively)."""
    by_value = {}
    for n in dir(cv2.aruco):
        if n.startswith("DICT_"):
            v = getattr(cv2.aruco, n)
            if v not in by_value or n != n.upper():
                by_value[v] = n
    return [by_value[v] for v in sorted(by_value)]


def marker_bits(d, marker_id):
    """Bits of one marker, rows x cols, from OpenCV's byte list."""
    size = d.markerSize
    bits = cv2.aruco.Dictionary.getBitsFromByteList(d.bytesList[marker_id:marker_id + 1], size)
    return np.asarray(bits, dtype=np.uint8).reshape(size, size)


def main():
    out = sys.argv[1]
    names = predefined_names()
    blob = bytearray(MAGIC)
    blob += struct.pack("<H", len(names))
    for name in names:
        value = getattr(cv2.aruco, name)
        d = cv2.aruco.getPredefinedDictionary(value)
        n = d.bytesList.shape[0]
        blob += struct.pack("<B", len(name)) + name.encode("ascii")
        blob += struct.pack("<HBBH", value, d.markerSize, d.maxCorrectionBits, n)
        for i in range(n):
            blob += np.packbits(marker_bits(d, i).ravel()).tobytes()
        print(f"{name:24s} enum {value:2d} size {d.markerSize} "
              f"maxCorrectionBits {d.maxCorrectionBits} markers {n}")
    with open(out, "wb") as f:
        f.write(blob)
    print(f"wrote {len(blob)} bytes to {out} (OpenCV {cv2.__version__})")


if __name__ == "__main__":
    main()
