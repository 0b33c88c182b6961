#!/usr/bin/env python3
"""OpenCV peer for the robocal ChArUco benchmark (issue 14).

Usage: python3 bench/charuco_opencv.py DIR [KIND]
DIR holds the PNGs and truth.csv written by
`cargo run --release -p robocal-calib --example charuco_bench`.
Runs cv2.aruco.CharucoDetector (default parameters, which refine the corners
with cornerSubPix) on one thread, matches corners to truth by id and prints
per kind: corners found / visible, wrong ids, RMS and worst error, CPU ms per
image, in the Rust bench's format.
"""
import csv
import sys
import time
from collections import defaultdict

import cv2
import numpy as np

WRONG_ID_PX = 3.0
KINDS = ["fronto", "steep", "partial", "blurred", "uneven"]


def main():
    folder = sys.argv[1]
    cv2.setNumThreads(1)
    d = cv2.aruco.getPredefinedDictionary(cv2.aruco.DICT_5X5_100)
    board = cv2.aruco.CharucoBoard((9, 7), 30.0, 22.0, d)
    detector = cv2.aruco.CharucoDetector(board)
    truth = defaultdict(dict)
    with open(f"{folder}/truth.csv") as f:
        for r in csv.DictReader(f):
            truth[r["image"]][int(r["id"])] = (float(r["x"]), float(r["y"]), r["visible"] == "1")
    print(f"OpenCV {cv2.__version__} CharucoDetector, {folder}")
    kinds = KINDS if len(sys.argv) < 3 else [sys.argv[2]]
    for kind in kinds:
        names = sorted(n for n in truth if n.startswith(kind + "_"))
        found = visible = wrong = 0
        sq, worst, cpu = 0.0, 0.0, 0.0
        for name in names:
            gray = cv2.imread(f"{folder}/{name}", cv2.IMREAD_GRAYSCALE)
            t = truth[name]
            visible += sum(1 for v in t.values() if v[2])
            c0 = time.thread_time()
            corners, ids, _, _ = detector.detectBoard(gray)
            cpu += time.thread_time() - c0
            if ids is None:
                continue
            for (x, y), i in zip(corners.reshape(-1, 2), ids.ravel()):
                tx, ty, _ = t[int(i)]
                e = float(np.hypot(x - tx, y - ty))
                if e > WRONG_ID_PX:
                    wrong += 1
                    continue
                found += 1
                sq += e * e
                worst = max(worst, e)
        n = max(len(names), 1)
        print(f"{kind:8} corners {found}/{visible} ({100.0 * found / max(visible, 1):.1f} %), "
              f"wrong {wrong}, RMS {np.sqrt(sq / max(found, 1)):.3f} px, worst {worst:.3f} px, "
              f"{1000.0 * cpu / n:.1f} ms/image (CPU)")


if __name__ == "__main__":
    main()
