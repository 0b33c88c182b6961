#!/usr/bin/env python3
"""OpenCV peer for the robocal detector benchmark (issue 3).

Usage: opencv_circles.py DIR [COLS ROWS]
DIR holds PNGs and truth.csv (image,row,col,x,y: true centre images). Runs
cv2.findCirclesGrid (symmetric grid, default SimpleBlobDetector) on one core,
matches each found centre to the nearest true centre (OpenCV's ordering is
only defined up to symmetry) and prints detection rate, RMS/max error and
speed in the same format as the Rust bench.
"""
import csv
import sys
import time
from collections import defaultdict

import cv2
import numpy as np

MATCH_PX = 1.0  # a found centre further than this from every truth is wrong


def main():
    folder = sys.argv[1]
    cols = int(sys.argv[2]) if len(sys.argv) > 2 else 9
    rows = int(sys.argv[3]) if len(sys.argv) > 3 else 9
    cv2.setNumThreads(1)
    truth = defaultdict(list)
    with open(f"{folder}/truth.csv") as f:
        for r in csv.DictReader(f):
            truth[r["image"]].append((float(r["x"]), float(r["y"])))
    found, seconds, cpu, sq, n, worst, pixels = 0, 0.0, 0.0, 0.0, 0, 0.0, 0
    for name, pts in sorted(truth.items()):
        gray = cv2.imread(f"{folder}/{name}", cv2.IMREAD_GRAYSCALE)
        pixels += gray.size
        start, cpu0 = time.perf_counter(), time.thread_time()
        ok, centres = cv2.findCirclesGrid(gray, (cols, rows), flags=cv2.CALIB_CB_SYMMETRIC_GRID)
        cpu += time.thread_time() - cpu0
        seconds += time.perf_counter() - start
        if not ok:
            continue
        t = np.array(pts)
        c = centres.reshape(-1, 2)
        d = np.linalg.norm(c[:, None, :] - t[None, :, :], axis=2)
        nearest = d.argmin(axis=1)
        err = d[np.arange(len(c)), nearest]
        if len(set(nearest)) != len(t) or err.max() > MATCH_PX:
            continue
        found += 1
        sq += float((err ** 2).sum())
        n += len(err)
        worst = max(worst, float(err.max()))
    views = len(truth)
    print(f"opencv {cv2.__version__} findCirclesGrid: {views} views")
    print(f"  detected: {found}/{views} ({100.0 * found / max(views, 1):.1f} %)")
    if n:
        print(f"  centre error: RMS {np.sqrt(sq / n):.4f} px, max {worst:.4f} px over {n} dots")
    print(f"  speed: {1e3 * cpu / max(views, 1):.2f} ms/image CPU, "
          f"{pixels * 1e-6 / max(cpu, 1e-12):.1f} MP/s (one core); "
          f"wall {1e3 * seconds / max(views, 1):.2f} ms/image")


if __name__ == "__main__":
    main()
