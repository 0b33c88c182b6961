#!/usr/bin/env python3
"""OpenCV reference corners for the Aubo i10 chessboard photos (issue 14).

Usage: python3 bench/aubo_opencv_corners.py
Runs findChessboardCorners (11x8) + cornerSubPix((11,11), EPS+COUNT 30/0.001),
as the authors' scripts do, on calib/tests/data/aubo_i10_hkclr/images, writes
derived_opencv5/corners_findChessboardCorners.csv (group/file, OpenCV corner
index, x, y) and prints calibrateCamera's intrinsics and RMS on all 24.
"""
import glob
import os

import cv2
import numpy as np

ROOT = "calib/tests/data/aubo_i10_hkclr"
PATTERN = (11, 8)
SQUARE_MM = 10.0


def main():
    files = sorted(glob.glob(f"{ROOT}/images/*/*.png"))
    crit = (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_COUNT, 30, 0.001)
    objp = np.zeros((PATTERN[0] * PATTERN[1], 3), np.float32)
    objp[:, :2] = np.mgrid[0:PATTERN[0], 0:PATTERN[1]].T.reshape(-1, 2) * SQUARE_MM
    rows, obj, img = ["image,id,x,y"], [], []
    for f in files:
        gray = cv2.imread(f, cv2.IMREAD_GRAYSCALE)
        ok, c = cv2.findChessboardCorners(gray, PATTERN)
        assert ok, f
        c = cv2.cornerSubPix(gray, c, (11, 11), (-1, -1), crit)
        name = "/".join(f.split("/")[-2:])
        for i, (x, y) in enumerate(c.reshape(-1, 2)):
            rows.append(f"{name},{i},{x:.4f},{y:.4f}")
        obj.append(objp)
        img.append(c)
    os.makedirs(f"{ROOT}/derived_opencv5", exist_ok=True)
    with open(f"{ROOT}/derived_opencv5/corners_findChessboardCorners.csv", "w") as out:
        out.write("\n".join(rows) + "\n")
    rms, k, d, _, _ = cv2.calibrateCamera(obj, img, gray.shape[::-1], None, None)
    print(f"OpenCV {cv2.__version__}: {len(files)} images, RMS {rms:.4f} px")
    print("fx fy cx cy", k[0, 0], k[1, 1], k[0, 2], k[1, 2])
    print("dist", d.ravel())


if __name__ == "__main__":
    main()
