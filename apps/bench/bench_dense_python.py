"""Every mode of a large dense model at one speed: gyrokit against numpy's eig of the state matrix.

The model is data/three_disk_rotor.toml with every shaft section in 12 times as many elements
(288 elements, 1156 DOFs; --quick: 3 times, 292 DOFs). At one speed numpy.linalg.eig solves the
state matrix [[0, I], [-M^-1 K, -M^-1 (C + w G)]] (eigenvalues and right vectors, the usual
script), and gyrokit.eig solves the same model with every mode in four ways: the default
(`method="auto"`: the state matrix below, kept where every pair is verified and vouched for,
else the scaled QZ; the row names the path it took), the state matrix (`method="state"`: the DOF- and time-scaled state matrix by LAPACK dgeev, then every pair
refined and given its left vector on the quadratic itself by one sparse LU near it), the scaled
QZ (`method="qz"`, LAPACK dggev3) and the classic QZ (`qz-classic`, dggev).

Rows: the wall time (best of --repeat runs), the ratio to numpy's time of the same sitting, the
eigenvalues returned (upper half plane), the largest backward error, the pairs above 1e-10 (not
verified: must be 0), the pairs gyrokit vouches for (error bound <= 1e-6 of the modulus), and
`max_rel_dev`: the largest distance from a gyrokit eigenvalue to the nearest numpy eigenvalue,
relative to its modulus, over the modes below 10 times the top speed (the program exits 1 where
that exceeds 1e-6 or a pair is not verified).

    PYTHONPATH=build/python /usr/bin/python3 apps/bench/bench_dense_python.py [--quick] [--repeat 2]
"""
import argparse
import os
import re
import tempfile
import time

import numpy as np

import gyrokit as gk

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "..", "data")


def refined_scene(factor, directory):
    text = open(os.path.join(DATA, "three_disk_rotor.toml")).read()
    text = re.sub(r"elements = (\d+)", lambda m: "elements = %d" % round(int(m.group(1)) * factor), text)
    path = os.path.join(directory, "three_disk_refined.toml")
    with open(path, "w") as f:
        f.write(text)
    return path


def best_of(repeat, f):
    best, result = float("inf"), None
    for _ in range(repeat):
        t = time.perf_counter()
        result = f()
        best = min(best, time.perf_counter() - t)
    return best, result


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeat", type=int, default=2, help="runs per path; the best time counts")
    ap.add_argument("--quick", action="store_true", help="a 292-DOF model, one run (the ctest smoke run)")
    a = ap.parse_args()
    repeat = 1 if a.quick else max(1, a.repeat)
    with tempfile.TemporaryDirectory() as tmp:
        sc = gk.load_scene(refined_scene(3 if a.quick else 12, tmp))
    s = sc.system
    w = float(np.max(sc.speeds))
    M, K, G = s.M.toarray(), s.K.toarray(), s.G.toarray()
    C = s.damping_matrix(w).toarray() + w * G
    n = M.shape[0]

    def numpy_eig():
        Minv = np.linalg.inv(M)
        A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ K, -Minv @ C]])
        return np.linalg.eig(A)[0]

    t_ref, reference = best_of(repeat, numpy_eig)
    rows = [("numpy.linalg.eig, state matrix", t_ref, 1.0, int(np.sum(reference.imag >= 0)), float("nan"), 0, 0, 0.0)]
    failed = False
    paths = (("gyrokit, default (auto)", None), ("gyrokit, state", "state"), ("gyrokit, qz", "qz"),
             ("gyrokit, qz-classic", "qz-classic"))
    for label, method in paths:
        kw = {} if method is None else {"method": method}
        t, r = best_of(repeat, lambda: gk.eig(s, w, solver="dense", modes=0, **kw))
        if method is None:
            label += ": " + r.method
        lam = r.eigenvalues
        low = np.abs(lam) <= 10.0 * w
        dev = max((np.min(np.abs(reference - l)) / abs(l) for l in lam[low]), default=0.0)
        unverified = int(np.sum(~(r.backward_errors <= 1e-10)))
        vouched = int(np.sum(r.error_bounds <= 1e-6 * np.abs(lam)))
        failed = failed or dev > 1e-6 or unverified > 0
        rows.append((label, t, t / t_ref, len(lam), float(np.max(r.backward_errors)), unverified, vouched, dev))
    print(f"model: three_disk_rotor refined, {n} DOFs, speed {w:g} rad/s")
    head = ("path", "seconds", "time_vs_numpy", "eigenvalues", "max_backward_error", "unverified", "vouched",
            "max_rel_dev")
    print("  ".join(head))
    for r in rows:
        print(f"{r[0]}  {r[1]:.3f}  {r[2]:.2f}  {r[3]}  {r[4]:.1e}  {r[5]}  {r[6]}  {r[7]:.1e}")
    if failed:
        raise SystemExit("a gyrokit pair is not verified, or has no numpy eigenvalue within 1e-6 relative")


if __name__ == "__main__":
    main()
