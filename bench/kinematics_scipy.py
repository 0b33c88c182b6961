"""Peer benchmark for issue 5: the same pose-level identification (same
model, start, free parameters, whitened residuals) as robocal's, solved by
scipy.optimize.least_squares, timed in the same run.

    pip install numpy scipy
    python3 bench/kinematics_scipy.py [preset]

Runs the Rust example `kinematics_export` (which prints the Rust timings
and writes the problem), then solves it with scipy ('lm' = MINPACK
Levenberg-Marquardt, and 'trf'), 2-point finite-difference Jacobian.
"""
import json, os, subprocess, sys, time
import numpy as np
from scipy.optimize import least_squares
from scipy.spatial.transform import Rotation

PRESET = sys.argv[1] if len(sys.argv) > 1 else "irb2400"
OUT = "/tmp/robocal_kinematics_problem.json"
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
subprocess.run(["cargo", "run", "-q", "-p", "robocal-calib", "--example", "kinematics_export",
                "--", OUT, PRESET], check=True, cwd=ROOT)
doc = json.load(open(OUT))
joints = doc["joints"]
B0 = np.array(doc["world_to_base"]); T0 = np.array(doc["flange_to_tool"])
free = np.array(doc["free"]); n_all = 4 * len(joints) + 12
meas = doc["measurements"]
Q = [np.array(m["q"]) for m in meas]
M = [np.array(m["pose"]) for m in meas]
W = [np.array(m["w"]) for m in meas]

Qa = np.array(Q); Ma = np.array(M); Wa = np.array(W)  # (n,6), (n,4,4), (n,6,6)

def rz(t):  # batched over poses
    c, s = np.cos(t), np.sin(t); T = np.zeros(t.shape + (4, 4))
    T[..., 0, 0] = c; T[..., 0, 1] = -s; T[..., 1, 0] = s; T[..., 1, 1] = c; T[..., 2, 2] = 1; T[..., 3, 3] = 1
    return T
def rx(t):
    c, s = np.cos(t), np.sin(t); return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1.0]])
def ry(t):
    c, s = np.cos(t), np.sin(t); return np.array([[c, 0, s, 0], [0, 1, 0, 0], [-s, 0, c, 0], [0, 0, 0, 1.0]])
def tr(x, y, z):
    T = np.eye(4); T[:3, 3] = (x, y, z); return T
def left(T, d):
    out = T.copy(); out[:3, 3] += d[:3]
    out[:3, :3] = Rotation.from_rotvec(d[3:]).as_matrix() @ T[:3, :3]; return out

def residuals(xf):
    """Vectorised over poses: one batched 4x4 product per link."""
    x = np.zeros(n_all); x[free] = xf
    base = left(B0, x[4 * len(joints):4 * len(joints) + 6]); tool = left(T0, x[-6:])
    T = np.broadcast_to(base, (len(Q), 4, 4))
    for i, j in enumerate(joints):
        p = x[4 * i:4 * i + 4]
        th = Qa[:, i] + j["theta_offset_rad"] + p[0]
        if j["convention"] == "dh":
            fixed = tr(0, 0, j["d_mm"] + p[2]) @ tr(j["a_mm"] + p[1], 0, 0) @ rx(j["alpha_rad"] + p[3])
        else:
            fixed = tr(j["a_mm"] + p[1], 0, 0) @ rx(j["alpha_rad"] + p[3]) @ ry(j["beta_rad"] + p[2])
        T = T @ rz(th) @ fixed
    T = T @ tool
    dp = Ma[:, :3, 3] - T[:, :3, 3]
    dr = Rotation.from_matrix(Ma[:, :3, :3] @ np.transpose(T[:, :3, :3], (0, 2, 1))).as_rotvec()
    e = np.concatenate([dp, dr], axis=1)
    return np.einsum("nij,nj->ni", Wa, e).ravel()

x0 = np.zeros(len(free))
for method in ["lm", "trf"]:
    best = np.inf
    for _ in range(3):
        t = time.perf_counter()
        sol = least_squares(residuals, x0, method=method, x_scale="jac", xtol=1e-12, ftol=1e-12, gtol=1e-12)
        best = min(best, time.perf_counter() - t)
    print(f"scipy least_squares({method!r}) {PRESET}: {len(meas)} poses, {len(free)} free parameters: "
          f"{best:.4f} s, cost {np.sum(sol.fun ** 2):.6f}, {sol.nfev} evaluations "
          f"(rust pose-level LM alone {doc['rust']['fit_s']:.4f} s, cost {doc['rust']['fit_cost']:.6f})")
