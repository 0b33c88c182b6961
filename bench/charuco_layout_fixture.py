#!/usr/bin/env python3
"""Exports OpenCV's ChArUco board layouts (both the >=4.6 layout and the
legacy one) as a JSON fixture plus a few small board renderings, for the
robocal-calib layout tests (issue 14).

Usage: python3 bench/charuco_layout_fixture.py calib/tests/data/charuco

Writes layouts.json: per board, the marker ids, their four object corners
(OpenCV's order: top-left, top-right, bottom-right, bottom-left) and the
chessboard inner corners, in millimetres; and board_<cols>x<rows>_<dict>_<layout>.png
rendered by CharucoBoard.generateImage with an exact pixel scale.
"""
import json
import os
import sys

import cv2
import numpy as np

BOARDS = [
    # cols, rows, square_mm, marker_mm, dictionary
    (5, 4, 10.0, 7.0, "DICT_4X4_50"),
    (6, 5, 10.0, 7.0, "DICT_5X5_100"),
    (7, 6, 20.0, 15.0, "DICT_6X6_250"),
    (3, 8, 10.0, 8.0, "DICT_APRILTAG_36h11"),
    (4, 3, 10.0, 5.0, "DICT_ARUCO_ORIGINAL"),
]
# Renderings: (cols, rows, dictionary, square px, marker px); marker px is a
# multiple of (bits + 2) so every bit is a whole number of pixels.
RENDERS = [
    (5, 4, "DICT_4X4_50", 64, 48),
    (6, 5, "DICT_5X5_100", 70, 49),
]


def board(cols, rows, square, marker, dict_name, legacy):
    d = cv2.aruco.getPredefinedDictionary(getattr(cv2.aruco, dict_name))
    b = cv2.aruco.CharucoBoard((cols, rows), square, marker, d)
    b.setLegacyPattern(legacy)
    return b


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    layouts = []
    for cols, rows, sq, mk, name in BOARDS:
        for legacy in (False, True):
            b = board(cols, rows, sq, mk, name, legacy)
            layouts.append({
                "squares": [cols, rows],
                "square_mm": sq,
                "marker_mm": mk,
                "dictionary": name,
                "legacy_layout": legacy,
                "marker_ids": [int(i) for i in b.getIds().ravel()],
                "marker_corners_mm": [np.asarray(c)[:, :2].round(9).tolist() for c in b.getObjPoints()],
                "chessboard_corners_mm": np.asarray(b.getChessboardCorners())[:, :2].round(9).tolist(),
            })
    with open(os.path.join(out, "layouts.json"), "w") as f:
        json.dump({"opencv_version": cv2.__version__, "boards": layouts}, f, indent=None)
        f.write("\n")
    for cols, rows, name, sq_px, mk_px in RENDERS:
        for legacy in (False, True):
            b = board(cols, rows, float(sq_px), float(mk_px), name, legacy)
            img = b.generateImage((cols * sq_px, rows * sq_px), marginSize=0, borderBits=1)
            tag = "legacy" if legacy else "current"
            path = os.path.join(out, f"board_{cols}x{rows}_{name}_{tag}.png")
            cv2.imwrite(path, img)
            print("wrote", path, img.shape)
    print(f"wrote {len(layouts)} layouts (OpenCV {cv2.__version__})")


if __name__ == "__main__":
    main()
