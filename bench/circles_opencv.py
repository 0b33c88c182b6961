#!/usr/bin/env python3
"""OpenCV peer for the robocal circle-grid benchmark (issue 14).

Usage: python3 bench/circles_opencv.py DIR
DIR holds asymmetric_4x11/ and symmetric_9x7/, each with PNGs and truth.csv
(image,row,col,x,y,visible) written by
`cargo run --release -p robocal-calib --example circles_bench`.
Runs cv2.findCirclesGrid (default SimpleBlobDetector; patternSize (4, 11)
with CALIB_CB_ASYMMETRIC_GRID, (9, 7) with CALIB_CB_SYMMETRIC_GRID) on one
thread. OpenCV's ordering of a symmetric grid is defined only up to the
grid's symmetry, so every found centre is matched to its nearest true
centre; a view counts as read when all centres match distinct truths within
1 px. Prints per board and kind the Rust bench's figures.
"""
import csv
import sys
import time
from collections import defaultdict

import cv2
import numpy as np

WRONG_ID_PX = 1.0
KINDS = ["fronto", "steep", "partial", "blurred", "uneven"]
BOARDS = [
    ("asymmetric_4x11", (4, 11), cv2.CALIB_CB_ASYMMETRIC_GRID),
    ("symmetric_9x7", (9, 7), cv2.CALIB_CB_SYMMETRIC_GRID),
]


def main():
    root = sys.argv[1]
    cv2.setNumThreads(1)
    print(f"OpenCV {cv2.__version__} findCirclesGrid, {root}")
    for name, size, flags in BOARDS:
        folder = f"{root}/{name}"
        truth = defaultdict(list)
        with open(f"{folder}/truth.csv") as f:
            for r in csv.DictReader(f):
                truth[r["image"]].append((float(r["x"]), float(r["y"]), r["visible"] == "1"))
        print(name)
        for kind in KINDS:
            names = sorted(n for n in truth if n.startswith(kind + "_"))
            read = wrong = found = visible = 0
            sq, worst, cpu = 0.0, 0.0, 0.0
            for img in names:
                gray = cv2.imread(f"{folder}/{img}", cv2.IMREAD_GRAYSCALE)
                t = np.array([(x, y) for x, y, _ in truth[img]])
                visible += sum(1 for p in truth[img] if p[2])
                c0 = time.thread_time()
                ok, centres = cv2.findCirclesGrid(gray, size, flags=flags)
                cpu += time.thread_time() - c0
                if not ok:
                    continue
                c = centres.reshape(-1, 2)
                d = np.linalg.norm(c[:, None, :] - t[None, :, :], axis=2)
                nearest = d.argmin(axis=1)
                err = d[np.arange(len(c)), nearest]
                if len(set(nearest)) != len(c) or err.max() > WRONG_ID_PX:
                    wrong += 1
                    continue
                read += 1
                found += len(c)
                sq += float((err ** 2).sum())
                worst = max(worst, float(err.max()))
            n = max(len(names), 1)
            print(f"  {kind:8} views {read}/{len(names)}, wrong {wrong}, dots {found}/{visible}, "
                  f"RMS {np.sqrt(sq / max(found, 1)):.4f} px, worst {worst:.4f} px, "
                  f"{1000.0 * cpu / n:.1f} ms/image (CPU)")


if __name__ == "__main__":
    main()
