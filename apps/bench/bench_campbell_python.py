"""Campbell diagrams from Python against a bare SciPy loop: at every speed, the eigenvalues and
right vectors of the state matrix [[0, I], [-M^-1 K, -M^-1 (C + w G)]] by scipy.linalg.eig (the
loop a ROSS-style script runs), against gyrokit.campbell with its defaults (the modes in range,
tracked, each eigenpair verified), with the 6 lowest modes (modes=6, the ROSS scene's own
setting; on one thread and on two) and with every mode (modes=0).

Rows: per model and path, the wall time (best of --repeat runs), the ratio to the SciPy loop of
the same sitting, the branches gyrokit reports, and `max_rel_dev`: the largest distance from a
gyrokit eigenvalue to the nearest SciPy eigenvalue at the same speed, relative to its modulus
(both solve the same model; differences are rounding, of the order of the eigenvalue's
condition times 1e-16; the program exits 1 above 1e-6).

    PYTHONPATH=build/python /usr/bin/python3 apps/bench/bench_campbell_python.py [--quick] [--repeat 3]
"""
import argparse
import os
import time

import numpy as np
import scipy.linalg as sl

import gyrokit as gk

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "..", "data")

# Models whose matrices do not depend on speed (the state matrix above is then exact).
CASES = [
    ("ross_rotor_example (42 DOFs)", "ross_rotor_example/scene.toml", np.linspace(0.0, 1000.0, 101)),
    ("three_disk_rotor (100 DOFs)", "three_disk_rotor.toml", None),
]


def state_loop(M, K, C, G, speeds):
    n = M.shape[0]
    Minv = np.linalg.inv(M)
    MK, MC, MG = Minv @ K, Minv @ C, Minv @ G
    Z, I = np.zeros((n, n)), np.eye(n)
    out = []
    for w in speeds:
        A = np.block([[Z, I], [-MK, -(MC + w * MG)]])
        out.append(sl.eig(A, right=True)[0])
    return out


def best_of(repeat, f):
    best, result = float("inf"), None
    for _ in range(repeat):
        t = time.perf_counter()
        result = f()
        best = min(best, time.perf_counter() - t)
    return best, result


def max_rel_dev(cd, reference, speeds):
    worst = 0.0
    index = {float(w): k for k, w in enumerate(speeds)}
    for b in range(cd.eigenvalues.shape[1]):
        for k, w in enumerate(cd.speeds):
            lam = cd.eigenvalues[k, b]
            if not np.isfinite(lam) or float(w) not in index:
                continue
            ref = reference[index[float(w)]]
            worst = max(worst, np.min(np.abs(ref - lam)) / max(abs(lam), 1e-300))
    return worst


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeat", type=int, default=3, help="runs per path; the best time counts")
    ap.add_argument("--quick", action="store_true", help="a quarter of the speeds, one run (the ctest smoke run)")
    a = ap.parse_args()
    repeat = 1 if a.quick else max(1, a.repeat)
    rows = []
    for name, path, speeds in CASES:
        sc = gk.load_scene(os.path.join(DATA, path))
        if speeds is None:
            speeds = sc.speeds
        if a.quick:
            speeds = speeds[::4]
        s = sc.system
        M, K, G = s.M.toarray(), s.K.toarray(), s.G.toarray()
        C = s.damping_matrix(0.0).toarray()
        t_ref, reference = best_of(repeat, lambda: state_loop(M, K, C, G, speeds))
        rows.append((name, len(speeds), "scipy.linalg.eig loop", t_ref, 1.0, 2 * M.shape[0], 0.0))
        # The model without its scene's [analysis]: modes=None is then the modes in range.
        for label, modes, jobs in (("gyrokit, modes in range", None, 1), ("gyrokit, 6 lowest modes", 6, 1),
                                   ("gyrokit, 6 lowest modes, 2 threads", 6, 2), ("gyrokit, every mode", 0, 1)):
            # One thread: the work of one core, as the SciPy loop (BLAS serial here); the
            # 2-thread row: the modes of each step corrected on two cores.
            t, cd = best_of(repeat, lambda: gk.campbell(s, speeds=speeds, modes=modes, jobs=jobs))
            rows.append((name, len(speeds), label, t, t_ref / t, cd.eigenvalues.shape[1],
                         max_rel_dev(cd, reference, speeds)))
    head = ("model", "speeds", "path", "seconds", "speedup_vs_scipy", "branches_or_eigenvalues", "max_rel_dev")
    print("  ".join(head))
    for r in rows:
        print(f"{r[0]}  {r[1]}  {r[2]}  {r[3]:.4f}  {r[4]:.2f}  {r[5]}  {r[6]:.1e}")
    # A gyrokit eigenvalue that SciPy does not have (beyond 1e-6 relative, far above rounding
    # of these well-conditioned models) means the two solved different problems.
    if any(r[6] > 1e-6 for r in rows):
        raise SystemExit("a gyrokit eigenvalue has no SciPy eigenvalue within 1e-6 relative")


if __name__ == "__main__":
    main()
