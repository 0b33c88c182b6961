#!/usr/bin/env python3
"""Which joint file belongs to the Aubo i10 group-1 photos (issue 14).

Usage: python3 bench/aubo_group1_joints.py [calib/tests/data/aubo_i10_hkclr]
Fits hand-eye X and board-in-base Y by least squares (board corners mapped to the base by F X T)
on groups 2-6 only, with the authors' DH and intrinsics and cv2.solvePnP on OpenCV's corners
(derived_opencv5/), then prints how far each photo's board lands from the groups 2-6 consensus,
once with joints/group1_upstream_head.txt (upstream HEAD) and once with joints/group1.txt (4ceb56a).
"""
import csv, sys
import numpy as np, cv2
D = sys.argv[1] if len(sys.argv) > 1 else "calib/tests/data/aubo_i10_hkclr"
DH=[(163.2,0,90,0),(0,647,180,90),(0,600.5,180,0),(201.3,0,-90,-90),(102.5,0,90,0),(94,0,0,0)]
def fk(q):
    T=np.eye(4)
    for (d,a,al,off),qi in zip(DH,q):
        th=qi+np.radians(off); al=np.radians(al)
        ct,st,ca,sa=np.cos(th),np.sin(th),np.cos(al),np.sin(al)
        T=T@np.array([[ct,-st*ca,st*sa,a*ct],[st,ct*ca,-ct*sa,a*st],[0,sa,ca,d],[0,0,0,1]])
    return T
K=np.array([[2281.69027,0,1407.20528],[0,2280.99962,893.295531],[0,0,1]])
dist=np.array([-7.14967118e-3,-1.69424563e-3,-4.70604299e-5,-2.47795750e-4,4.36516991e-2])
corners={}
for r in csv.DictReader(open(D+"/derived_opencv5/corners_findChessboardCorners.csv")):
    corners.setdefault(r["image"],[]).append((float(r["x"]),float(r["y"])))
obj=np.array([[c*10.0,r*10.0,0] for r in range(8) for c in range(11)])
def joints(path): return [list(map(float,l.split(","))) for l in open(path) if l.strip()]
def run(g1file):
    Fs=[];Ts=[];names=[]
    for g in range(1,7):
        js=joints(g1file if g==1 else f"{D}/joints/group{g}.txt")
        ims=sorted(k for k in corners if k.startswith(f"group{g}/"))
        for n,q in zip(ims,js):
            ok,rv,tv=cv2.solvePnP(obj,np.array(corners[n]),K,dist)
            T=np.eye(4);T[:3,:3]=cv2.Rodrigues(rv)[0];T[:3,3]=tv[:,0]  # board->cam
            Fs.append(fk(q));Ts.append(T);names.append(n)
    # hand-eye from groups 2..6 only
    idx=[i for i,n in enumerate(names) if not n.startswith("group1/")]
    from scipy.optimize import least_squares
    from scipy.spatial.transform import Rotation as Ro
    def mk(p):
        M=np.eye(4);M[:3,:3]=Ro.from_rotvec(p[:3]).as_matrix();M[:3,3]=p[3:];return M
    X0=np.array([0,0,0,42.56,6.81,129.87])
    Y0=Fs[idx[0]]@mk(X0)@Ts[idx[0]]
    P=np.c_[obj,np.ones(len(obj))].T
    def res(p):
        X=mk(p[:6]);Y=mk(p[6:])
        return np.concatenate([((Fs[i]@X@Ts[i]-Y)@P)[:3].ravel() for i in idx])
    y0=np.r_[Ro.from_matrix(Y0[:3,:3]).as_rotvec(),Y0[:3,3]]
    sol=least_squares(res,np.r_[X0,y0])
    X=mk(sol.x[:6]); print("rms point mm %.2f"%np.sqrt(np.mean(sol.fun**2)*3))
    boards=np.array([(Fs[i]@X@Ts[i])[:3,3] for i in range(len(names))])
    cons=np.median(boards[idx],axis=0)
    print("hand-eye t",X[:3,3].round(2))
    for n,b in zip(names,boards):
        print(n[:30],"board dist from consensus of groups 2-6: %.1f mm"%np.linalg.norm(b-cons))
print("== joints/group1_upstream_head.txt (upstream 77ac255)"); run(D+"/joints/group1_upstream_head.txt")
print("== joints/group1.txt (upstream 4ceb56a)"); run(D+"/joints/group1.txt")
