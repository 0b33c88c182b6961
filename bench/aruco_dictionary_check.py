#!/usr/bin/env python3
"""Compares every marker of every OpenCV predefined dictionary with robocal's
embedded copy (issue 14): the marker image OpenCV draws
(generateImageMarker, one pixel per bit) against robocal's bits.

Usage:
  cargo run -p robocal-calib --example aruco_dictionary_dump > /tmp/aruco_dump.txt
  python3 bench/aruco_dictionary_check.py /tmp/aruco_dump.txt
"""
import sys

import cv2


def main():
    ours = {}
    for line in open(sys.argv[1]):
        name, i, size, bits = line.split()
        ours[(name.upper(), int(i))] = (int(size), bits)
    names = {}
    for n in dir(cv2.aruco):
        if n.startswith("DICT_"):
            names.setdefault(getattr(cv2.aruco, n), n)
    checked = mismatched = missing = 0
    for value, name in sorted(names.items()):
        d = cv2.aruco.getPredefinedDictionary(value)
        n = d.bytesList.shape[0]
        for i in range(n):
            img = cv2.aruco.generateImageMarker(d, i, d.markerSize + 2)
            bits = "".join("1" if v > 127 else "0" for v in img[1:-1, 1:-1].ravel())
            got = ours.get((name.upper(), i))
            checked += 1
            if got is None:
                missing += 1
            elif got != (d.markerSize, bits):
                mismatched += 1
                print("MISMATCH", name, i, got, bits)
    extra = len(ours) - (checked - missing)
    print(f"OpenCV {cv2.__version__}: {len(names)} dictionaries, {checked} markers checked, "
          f"{mismatched} mismatched, {missing} missing, {extra} extra in robocal")
    sys.exit(1 if mismatched or missing or extra else 0)


if __name__ == "__main__":
    main()
