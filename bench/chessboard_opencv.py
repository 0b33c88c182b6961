#!/usr/bin/env python3
"""OpenCV peer for the robocal chessboard benchmark (issue 14).

Usage: python3 bench/chessboard_opencv.py DIR [KIND]
(KIND: one of fronto, steep, blurred, uneven; all when absent)
DIR holds the PNGs and truth.csv written by
`cargo run --release -p robocal-calib --example chessboard_bench`.
Runs cv2.findChessboardCorners (9x6, default flags ADAPTIVE_THRESH |
NORMALIZE_IMAGE) then cv2.cornerSubPix (criteria EPS+COUNT 40 / 0.001) on one
thread, once per cornerSubPix window (5,5) and (11,11), and prints per kind:
boards detected, corners matched to the truth in OpenCV's order, wrong ones
(> 3 px: a wrong identity; `flipped` counts boards whose order is the truth's
half turn), RMS and worst error, CPU ms per image, in the Rust bench's format.
"""
import csv
import sys
import time
from collections import defaultdict

import cv2
import numpy as np

WRONG_ID_PX = 3.0
KINDS = ["fronto", "steep", "blurred", "uneven"]
PATTERN = (9, 6)


def main():
    folder = sys.argv[1]
    kinds = [sys.argv[2]] if len(sys.argv) > 2 else KINDS
    cv2.setNumThreads(1)
    truth = defaultdict(dict)
    with open(f"{folder}/truth.csv") as f:
        for r in csv.DictReader(f):
            truth[r["image"]][int(r["id"])] = (float(r["x"]), float(r["y"]))
    crit = (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_COUNT, 40, 0.001)
    for win in [(5, 5), (11, 11)]:
        print(f"OpenCV {cv2.__version__} findChessboardCorners + cornerSubPix{win}, {folder}")
        for kind in kinds:
            names = sorted(n for n in truth if n.startswith(kind + "_"))
            boards = found = wrong = flipped = 0
            sq, worst, cpu = 0.0, 0.0, 0.0
            for name in names:
                gray = cv2.imread(f"{folder}/{name}", cv2.IMREAD_GRAYSCALE)
                t = np.array([truth[name][i] for i in range(len(truth[name]))])
                c0 = time.thread_time()
                ok, corners = cv2.findChessboardCorners(gray, PATTERN)
                if ok:
                    corners = cv2.cornerSubPix(gray, corners, win, (-1, -1), crit)
                cpu += time.thread_time() - c0
                if not ok:
                    continue
                boards += 1
                c = corners.reshape(-1, 2)
                e = np.hypot(*(c - t).T)
                if np.median(e) > WRONG_ID_PX and np.median(np.hypot(*(c[::-1] - t).T)) < WRONG_ID_PX:
                    flipped += 1
                    e = np.hypot(*(c[::-1] - t).T)
                for v in e:
                    if v > WRONG_ID_PX:
                        wrong += 1
                        continue
                    found += 1
                    sq += v * v
                    worst = max(worst, float(v))
            n = max(len(names), 1)
            print(f"{kind:8} boards {boards}/{len(names)}, corners {found}, wrong {wrong} (flipped boards {flipped}), "
                  f"RMS {np.sqrt(sq / max(found, 1)):.4f} px, worst {worst:.3f} px, {1000.0 * cpu / n:.1f} ms/image (CPU)")


if __name__ == "__main__":
    main()
