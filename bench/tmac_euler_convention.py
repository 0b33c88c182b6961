"""Which Euler convention the Leica T-Mac's rx, ry, rz
follow in the Landgraf 2021 UR10 data, from the hand-eye files (not in the
repository: calibration_handeye.csv of Series B and D, controller flange pose
as x, y, z in metres and a quaternion, plus the T-Mac's x, y, z mm and
rx, ry, rz deg).

    python3 -m venv .venv && .venv/bin/pip install numpy scipy
    .venv/bin/python bench/tmac_euler_convention.py DIR

The finding and its figures: docs/decisions/0030-tmac-euler-convention.md.

DIR holds Series_B/ and Series_D/. Two tests per convention (12 axis
sequences x extrinsic/intrinsic x angles in file order or by axis name x
as is/inverse):
1. relative-motion angles: angle(F_i^T F_j) = angle(M_i^T M_j) (AX = XB);
   blind to inversion and to conventions equal up to constant rotations;
2. W from the positions alone (M_i = W F_i X, translation part), then the
   best constant X rotation: the rotation residual of each convention.
"""
import sys
import numpy as np
from scipy.optimize import least_squares
from scipy.spatial.transform import Rotation as Rot

TAIT_BRYAN = ["XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX"]
PROPER = ["XYX", "XZX", "YXY", "YZY", "ZXZ", "ZYZ"]


def load(path):
    lines = open(path).read().strip().splitlines()
    head = lines[0].split(";")
    rows = [[float(x.strip().strip("\x00").replace(",", ".")) for x in l.split(";")]
            for l in lines[1:] if l.strip()]
    return {k: i for i, k in enumerate(head)}, np.array(rows)


def angle_deg(r):
    return np.degrees(np.arccos(np.clip((np.trace(r) - 1) / 2, -1, 1)))


def conventions():
    for seq in TAIT_BRYAN + PROPER:
        for intrinsic in (False, True):
            s = seq if intrinsic else seq.lower()
            perms = [None]
            if seq in TAIT_BRYAN and seq != "XYZ":
                perms.append(["XYZ".index(c) for c in seq])
            for perm in perms:
                for inverse in (False, True):
                    name = s + ("(by axis)" if perm else "") + (" inv" if inverse else "")
                    yield name, s, perm, inverse


def rotations(angles, s, perm, inverse):
    r = Rot.from_euler(s, angles if perm is None else angles[:, perm], degrees=True).as_matrix()
    return np.transpose(r, (0, 2, 1)) if inverse else r


def chordal_mean(ms):
    u, _, vt = np.linalg.svd(sum(ms))
    return u @ np.diag([1, 1, np.linalg.det(u @ vt)]) @ vt


def main(root):
    for series in "BD":
        h, v = load(f"{root}/Series_{series}/calibration_handeye.csv")
        rf = Rot.from_quat(v[:, [h[f"flange_q{c}"] for c in "xyzw"]]).as_matrix()
        tf = v[:, [h[f"flange_{c}"] for c in "xyz"]] * 1000
        pm = v[:, [h[f"measurement_{c}"] for c in "xyz"]]
        ang = v[:, [h[f"measurement_r{c}"] for c in "xyz"]]
        n = len(v)
        pairs = [(i, j) for i in range(n) for j in range(i + 1, n)]
        flange_rel = np.array([angle_deg(rf[i].T @ rf[j]) for i, j in pairs])

        def residual(x):
            w = Rot.from_rotvec(x[:3]).as_matrix()
            return ((rf @ x[6:9] + tf) @ w.T + x[3:6] - pm).ravel()

        c1, c2 = tf.mean(0), pm.mean(0)
        u, _, vt = np.linalg.svd((tf - c1).T @ (pm - c2))
        r0 = vt.T @ np.diag([1, 1, np.linalg.det(vt.T @ u.T)]) @ u.T
        fits = [least_squares(residual, np.r_[Rot.from_matrix(r0).as_rotvec(), c2 - r0 @ c1, z])
                for z in ([0, 0, 109], [109, 0, 0])]
        sol = min(fits, key=lambda s: s.cost)
        w = Rot.from_rotvec(sol.x[:3]).as_matrix()
        res = residual(sol.x).reshape(-1, 3)
        print(f"Series {series}: {n} rows; tool point in flange {np.round(sol.x[6:9], 2)} mm, "
              f"position rms {np.sqrt((res ** 2).sum(1).mean()):.3f} mm")
        out = []
        for name, s, perm, inverse in conventions():
            rm = rotations(ang, s, perm, inverse)
            rel = np.array([angle_deg(rm[i].T @ rm[j]) for i, j in pairs]) - flange_rel
            x = chordal_mean([rf[i].T @ w.T @ rm[i] for i in range(n)])
            e = np.array([angle_deg(rm[i].T @ w @ rf[i] @ x) for i in range(n)])
            out.append((np.sqrt(np.mean(e ** 2)), e.max(), np.sqrt(np.mean(rel ** 2)), name, x))
        out.sort(key=lambda o: o[0])
        print("  convention              W-fixed rotation rms / max (deg)   relative-angle rms (deg)")
        for o in out[:6]:
            print(f"  {o[3]:22s} {o[0]:8.4f} / {o[1]:8.4f}              {o[2]:.4f}")
        print("  tool rotation in flange (rotvec, deg):",
              np.round(np.degrees(Rot.from_matrix(out[0][4]).as_rotvec()), 2))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: tmac_euler_convention.py DIR  (DIR holds Series_B/ and Series_D/)")
    main(sys.argv[1])
