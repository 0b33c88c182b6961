#!/usr/bin/env python3
"""OpenCV's peer for the Aubo i10 held-out benchmark (calib example
`aubo_heldout`): leave one configuration group out, on the other five
groups run cv2.calibrateCamera, cv2.calibrateHandEye (Park) with the
authors' nominal DH kinematics, place the board in the base, and predict
the held-out group's corners (cv2.projectPoints). Prints the pooled RMS
over all 24 photos for two board placements: the mean of the training
photos' board poses, and the board pose refined on the training corners
by least squares (scipy) with the hand–eye held.

Usage (opencv-python-headless < 5, whose Python binding has
calibrateHandEye, numpy and scipy from PyPI):
    python3 bench/aubo_heldout_opencv.py
Reads the same corners as the Rust example:
calib/tests/data/aubo_i10_hkclr/derived_opencv5/corners_findChessboardCorners.csv
"""
import collections
import os

import cv2
import numpy as np

ROOT = os.path.join(os.path.dirname(__file__), "..", "calib/tests/data/aubo_i10_hkclr")
PER_ROW, SQUARE_MM = 11, 10.0
IMAGE_SIZE = (2400, 1800)
# (d mm, a mm, alpha deg, theta offset deg): the authors' standard DH.
DH = [(163.2, 0.0, 90.0, 0.0), (0.0, 647.0, 180.0, 90.0), (0.0, 600.5, 180.0, 0.0),
      (201.3, 0.0, -90.0, -90.0), (102.5, 0.0, 90.0, 0.0), (94.0, 0.0, 0.0, 0.0)]


def fk(q):
    t = np.eye(4)
    for (d, a, alpha, off), qi in zip(DH, q):
        th, al = qi + np.radians(off), np.radians(alpha)
        ct, st, ca, sa = np.cos(th), np.sin(th), np.cos(al), np.sin(al)
        t = t @ np.array([[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st],
                          [0, sa, ca, d], [0, 0, 0, 1]])
    return t


def photos():
    corners = collections.OrderedDict()
    with open(os.path.join(ROOT, "derived_opencv5/corners_findChessboardCorners.csv")) as f:
        next(f)
        for line in f:
            name, i, x, y = line.strip().split(",")
            corners.setdefault(name, []).append((int(i), float(x), float(y)))
    out = []
    for g in range(1, 7):
        with open(os.path.join(ROOT, f"joints/group{g}.txt")) as f:
            lines = [l for l in f.read().splitlines() if l.strip()]
        names = sorted(n for n in corners if n.startswith(f"group{g}/"))
        for name, line in zip(names, lines):
            pts = corners[name]
            obj = np.array([[(i % PER_ROW) * SQUARE_MM, (i // PER_ROW) * SQUARE_MM, 0.0]
                            for i, _, _ in pts], np.float32)
            img = np.array([[x, y] for _, x, y in pts], np.float32)
            out.append((g - 1, np.array([float(v) for v in line.split(",")]), obj, img))
    return out


def mean_pose(poses):
    r = sum(p[:3, :3] for p in poses)
    u, _, vt = np.linalg.svd(r)
    m = np.eye(4)
    m[:3, :3] = u @ np.diag([1, 1, np.linalg.det(u @ vt)]) @ vt
    m[:3, 3] = np.mean([p[:3, 3] for p in poses], axis=0)
    return m


def project(q, x, base_to_board, obj, k, dist):
    cam_to_board = np.linalg.inv(fk(q) @ x) @ base_to_board
    rv, _ = cv2.Rodrigues(cam_to_board[:3, :3])
    pred, _ = cv2.projectPoints(obj, rv, cam_to_board[:3, 3], k, dist)
    return pred.reshape(-1, 2)


def refine_board(start, train, x, k, dist):
    """The board pose minimising the training corners' reprojection error."""
    from scipy.optimize import least_squares

    def pose(v):
        m = np.eye(4)
        m[:3, :3] = cv2.Rodrigues(v[:3])[0] @ start[:3, :3]
        m[:3, 3] = start[:3, 3] + v[3:]
        return m

    def residuals(v):
        b = pose(v)
        return np.concatenate([(project(q, x, b, obj, k, dist) - img).ravel()
                               for _, q, obj, img in train])

    return pose(least_squares(residuals, np.zeros(6)).x)


def main():
    data = photos()
    assert len(data) == 24
    for refined in (False, True):
        rms = held_out(data, refined)
        how = "board refined on the training corners" if refined else "board as the training mean"
        print(f"OpenCV calibrateHandEye (Park), nominal DH, {how}: held-out corner RMS {rms:.3f} px"
              f" (6 folds, 24 photos pooled; OpenCV {cv2.__version__})")


def held_out(data, refined):
    total, count = 0.0, 0
    for held in range(6):
        train = [d for d in data if d[0] != held]
        test = [d for d in data if d[0] == held]
        rms, k, dist, rvecs, tvecs = cv2.calibrateCamera(
            [d[2] for d in train], [d[3] for d in train], IMAGE_SIZE, None, None)
        grip = [fk(d[1]) for d in train]
        r_cam, t_cam = cv2.calibrateHandEye(
            [g[:3, :3] for g in grip], [g[:3, 3] for g in grip],
            [cv2.Rodrigues(r)[0] for r in rvecs], list(tvecs),
            method=cv2.CALIB_HAND_EYE_PARK)
        x = np.eye(4)
        x[:3, :3], x[:3, 3] = r_cam, t_cam.ravel()
        boards = []
        for g, r, t in zip(grip, rvecs, tvecs):
            c = np.eye(4)
            c[:3, :3], c[:3, 3] = cv2.Rodrigues(r)[0], t.ravel()
            boards.append(g @ x @ c)
        base_to_board = mean_pose(boards)
        if refined:
            base_to_board = refine_board(base_to_board, train, x, k, dist)
        for _, q, obj, img in test:
            total += float(np.sum((project(q, x, base_to_board, obj, k, dist) - img) ** 2))
            count += len(img)
    return np.sqrt(total / count)


if __name__ == "__main__":
    main()
