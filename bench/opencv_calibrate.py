#!/usr/bin/env python3
"""Time cv2.calibrateCamera on the points a robocal example wrote (issue 4).

Input CSV (header): view,row,col,x_mm,y_mm,z_mm,u_px,v_px; argv: path width height repeats.
Prints one JSON object: per model, the median wall time and the result.
Needs opencv-python-headless and numpy (pip install opencv-python-headless numpy).
"""
import json
import sys
import time

import cv2
import numpy as np


def main():
    path, width, height = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    repeats = int(sys.argv[4]) if len(sys.argv) > 4 else 3
    data = np.loadtxt(path, delimiter=",", skiprows=1)
    views = sorted(set(data[:, 0].astype(int)))
    obj = [data[data[:, 0] == v][:, 3:6].astype(np.float32) for v in views]
    img = [data[data[:, 0] == v][:, 6:8].astype(np.float32) for v in views]
    cv2.setNumThreads(1)
    out = {"opencv": cv2.__version__, "views": len(views), "points": int(data.shape[0])}
    for name, flags in [("k1k2p1p2", cv2.CALIB_FIX_K3), ("k1k2p1p2k3", 0)]:
        times = []
        cpu0 = time.process_time()
        for _ in range(repeats):
            t0 = time.perf_counter()
            rms, k, dist, _, _ = cv2.calibrateCamera(obj, img, (width, height), None, None, flags=flags)
            times.append(time.perf_counter() - t0)
        cpu = (time.process_time() - cpu0) / repeats
        out[name] = {
            "seconds_median": float(np.median(times)),
            "cpu_seconds_mean": cpu,
            "rms_px": float(rms),
            "fx": float(k[0, 0]),
            "fy": float(k[1, 1]),
            "cx": float(k[0, 2]),
            "cy": float(k[1, 2]),
            "dist": [float(d) for d in dist.ravel()],
        }
    print(json.dumps(out))


if __name__ == "__main__":
    main()
