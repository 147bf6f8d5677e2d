"""The Python module against the C++ command-line tool on the example scenes, closed
forms, and its errors. Run by ctest (test python_module) with PYTHONPATH=build/python,
GYROKIT_CLI (the gyrokit binary) and GYROKIT_DATA (data/)."""
import csv
import io
import os
import re
import subprocess
import threading

import numpy as np
import pytest
import scipy.sparse as sp

import gyrokit as gk

CLI = os.environ["GYROKIT_CLI"]
DATA = os.environ["GYROKIT_DATA"]
# The CLI's CSV has 12 significant digits: agreement to rounding is 1e-10 relative.
RTOL = 1e-10


def cli(*args):
    out = subprocess.run([CLI, *args, "--format", "csv"], check=True, capture_output=True, text=True).stdout
    return list(csv.DictReader(io.StringIO(out)))


def scene(name):
    return os.path.join(DATA, name)


def test_eig_matches_the_cli():
    s = gk.load_scene(scene("centrifuge.toml"))
    ev = gk.eig(s, speed=20.0)
    rows = cli("eig", scene("centrifuge.toml"), "--speed", "20")
    assert len(rows) == len(ev.eigenvalues) == 6
    for k, r in enumerate(rows):
        assert ev.eigenvalues[k] == pytest.approx(complex(float(r["re_1_s"]), float(r["im_rad_s"])), rel=RTOL)
        assert ev.whirl[k] == r["whirl"]
    assert ev.eigenvalues.dtype == np.complex128
    assert ev.backward_errors.max() < 1e-14
    assert ev.vectors.shape == (6, 6)
    assert ev.method == "scaled QZ"


def test_eig_with_a_mode_count_gives_the_k_lowest_on_the_dense_solver_too():
    # One meaning of modes = K at one speed: the K lowest by frequency, dense or sparse (spectrum_study).
    path = scene("three_disk_rotor.toml")
    s = gk.load_scene(path)
    every = gk.eig(s, 300.0, modes=0)
    six = gk.eig(s, 300.0, modes=6)
    assert len(every.eigenvalues) > 6 and len(six.eigenvalues) == 6
    # The six lowest by frequency (those that vibrate first), as a Campbell diagram's six lowest.
    np.testing.assert_array_equal(six.eigenvalues, every.eigenvalues[:6])
    f = every.eigenvalues.imag
    assert np.all(np.diff(f[f > 0]) >= 0) and np.all(f[:6] > 0)
    assert any("the 6 lowest by frequency of the dense solver's" in n and "modes = 0 lists all" in n
               for n in six.notes)
    rows = cli("eig", path, "--speed", "300", "--modes", "6")
    assert [complex(float(r["re_1_s"]), float(r["im_rad_s"])) for r in rows] == pytest.approx(list(six.eigenvalues),
                                                                                             rel=RTOL)
    # A sparse window holds the six nearest its target 0 instead: the real eigenvalue of an overdamped
    # branch nearer 0 than a vibrating mode takes that mode's place.
    sparse = gk.eig(s, 300.0, modes=6, solver="sparse")
    assert np.sum(sparse.eigenvalues.imag == 0) >= 1
    for lam in sparse.eigenvalues[sparse.eigenvalues.imag > 0]:
        assert np.min(np.abs(every.eigenvalues - lam)) <= 1e-8 * abs(lam)


def test_campbell_matches_the_cli():
    s = gk.load_scene(scene("centrifuge.toml"))
    cd = gk.campbell(s, speeds=np.linspace(0, 60, 241), modes=6)
    assert cd.eigenvalues.shape == (len(cd.speeds), len(cd.branches))
    rows = cli("campbell", scene("centrifuge.toml"), "--speeds", "0:60:241", "--modes", "6")
    got = {(round(float(r["speed_rad_s"]), 9), int(r["mode"])): complex(float(r["re_1_s"]), float(r["im_rad_s"])) for r in rows}
    n = 0
    for i, w in enumerate(cd.speeds):
        for b, branch in enumerate(cd.branches):
            lam = cd.eigenvalues[i, b]
            if np.isnan(lam.real):
                continue
            assert lam == pytest.approx(got[(round(w, 9), int(branch))], rel=RTOL, abs=1e-12)
            n += 1
    assert n == len(rows)
    df_rows = cd.to_pandas() if _has("pandas") else None
    if df_rows is not None:
        assert len(df_rows) == len(rows)


def test_critical_speeds_match_the_cli():
    s = gk.load_scene(scene("centrifuge.toml"))
    cs = gk.critical_speeds(s, speeds=np.linspace(0, 60, 241))
    rows = cli("critical", scene("centrifuge.toml"), "--speeds", "0:60:241")
    assert len(rows) == len(cs.speeds) == 5
    for k, r in enumerate(rows):
        assert cs.speeds[k] == pytest.approx(float(r["speed_rad_s"]), rel=RTOL)
        # the crossing's bound: Im lambda - k w known to its sharp bound, over its slope
        assert 0 < cs.bounds[k] < 1e-9 * cs.speeds[k]
        assert cs.whirl[k] == r["whirl"]
        assert cs.harmonic[k] == int(r["harmonic"])


def test_stability_and_sparse_solver_on_the_fe_scene_match_the_cli():
    s = gk.load_scene(scene("fe_rotor.toml"))
    st = gk.stability(s)   # the scene's speeds, modes and solver choice
    rows = cli("stability", scene("fe_rotor.toml"))
    assert len(rows) == len(st.speeds) >= 1
    for k, r in enumerate(rows):
        # each threshold within its bound (the real part's error bound over its slope)
        assert abs(st.speeds[k] - float(r["speed_rad_s"])) <= st.bounds[k] + float(r["bound_rad_s"])
        assert 0 < st.bounds[k] < 1e-4 * st.speeds[k]
        assert st.becomes_unstable[k] == (r["change"] == "unstable")
    ev = gk.eig(s, 500.0, solver="sparse", modes=4, target=400.0)
    rows = cli("eig", scene("fe_rotor.toml"), "--speed", "500", "--solver", "sparse", "--modes", "4", "--target", "400")
    assert len(rows) == 4
    for k, r in enumerate(rows):
        assert ev.eigenvalues[k] == pytest.approx(complex(float(r["re_1_s"]), float(r["im_rad_s"])), rel=1e-9)
    assert ev.method == "ARPACK shift-invert"


def jeffcott_with_disk():
    m, Id, Ip, k, kt = 5.0, 0.02, 0.04, 2e5, 4e3
    M = np.diag([m, m, Id, Id])
    K = np.diag([k, k, kt, kt])
    G = np.zeros((4, 4))
    G[2, 3], G[3, 2] = Ip, -Ip
    w = 100.0
    root = np.sqrt(Ip**2 * w**2 + 4 * Id * kt)
    expected = [np.sqrt(k / m), np.sqrt(k / m), (root - Ip * w) / (2 * Id), (root + Ip * w) / (2 * Id)]
    return M, K, G, w, expected


def test_system_from_numpy_and_scipy_matrices_closed_form():
    M, K, G, w, expected = jeffcott_with_disk()
    for system in (gk.System(M=M, K=K, G=G), gk.System(M=sp.csc_matrix(M), K=sp.csr_matrix(K), G=sp.coo_matrix(G))):
        ev = gk.eig(system, w)
        np.testing.assert_allclose(ev.eigenvalues.imag, expected, rtol=1e-12)
        assert ev.whirl[2:] == ["backward", "forward"]
    s = gk.System(M=M, K=K, G=G, dof_names=["x", "y", "tx", "ty"])
    assert s.size == 4 and s.dof_names == ["x", "y", "tx", "ty"]
    assert sp.issparse(s.M) and s.M.nnz == 4


def test_a_dof_of_1e20_beside_kilograms_keeps_its_mode():
    # omega = sqrt(k / m) for each DOF; the 4.47e9 rad/s one is a mode, within its bound.
    m, k = np.array([5.0, 5.0, 0.02, 0.02]), np.array([1.0, 1e20, 1.0, 1.0])
    ev = gk.eig(gk.System(M=np.diag(m), K=np.diag(k)), speed=0.0)
    expected = np.sort(np.sqrt(k / m))
    assert len(ev.frequencies) == 4 and ev.notes == []
    assert np.all(np.abs(ev.eigenvalues - 1j * expected) <= ev.error_bounds)
    with pytest.raises(gk.SolverError, match="M is invertible"):
        gk.eig(gk.System(M=np.diag(m), K=np.diag(k)), speed=0.0, method="state")


def test_damping_components_and_unbalance():
    M, K, G, w, _ = jeffcott_with_disk()
    s = gk.System(M=M, K=K, G=G, damping={"bearings": np.diag([40.0, 40.0, 0, 0])},
                  unbalance=np.array([1e-4, -1e-4j, 0, 0]))
    assert s.damping_names == ["bearings"]
    ev = gk.eig(s, w)
    assert np.all(ev.eigenvalues.real < 0) or np.any(np.isclose(ev.eigenvalues.real, 0, atol=1e-9))


def test_bad_input_raises_gyrokit_errors():
    M, K, G, w, _ = jeffcott_with_disk()
    with pytest.raises(gk.InputError, match="matrix K is 3x3, expected 4x4"):
        gk.System(M=M, K=np.eye(3))
    bad = K.copy()
    bad[0, 0] = np.nan
    with pytest.raises(gk.InputError, match="NaN"):
        gk.System(M=M, K=bad)
    with pytest.raises(gk.InputError, match="not symmetric"):
        gk.System(M=M + np.triu(np.ones((4, 4)), 1), K=K)
    s = gk.System(M=M, K=K, G=G)
    with pytest.raises(gk.InputError, match="modes"):
        gk.campbell(s, [0.0, 1.0], modes=-1)
    with pytest.raises(gk.InputError, match="speeds"):
        gk.campbell(s, [0.0, -1.0])
    with pytest.raises(gk.InputError, match="speed"):
        gk.eig(s, float("nan"))
    with pytest.raises(gk.InputError, match="allowed: auto, dense, sparse"):
        gk.eig(s, 1.0, solver="qr")
    with pytest.raises(gk.InputError, match="not found"):
        gk.load_scene(os.path.join(DATA, "no_such_scene.toml"))
    assert issubclass(gk.InputError, gk.Error) and issubclass(gk.SolverError, gk.Error)


def test_threads_release_the_interpreter():
    s = gk.load_scene(scene("fe_rotor.toml"))
    speeds = np.linspace(0, 2000, 21)
    ref = gk.campbell(s, speeds, solver="sparse", modes=4).eigenvalues
    out = [None, None]

    def run(k):
        out[k] = gk.campbell(s, speeds, solver="sparse", modes=4).eigenvalues

    threads = [threading.Thread(target=run, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for o in out:
        np.testing.assert_allclose(o, ref, rtol=1e-10)


def _has(module):
    try:
        __import__(module)
        return True
    except ImportError:
        return False


def test_screen_gives_the_verdicts_of_the_cli():
    sweep = scene("screen_centrifuge.toml")
    r = gk.screen(sweep, jobs=2)
    rows = cli("screen", sweep)
    assert len(rows) == len(r.verdict) == 24
    for k, row in enumerate(rows):
        assert r.verdict[k] == row["verdict"]
        assert ";".join(r.failed[k]) == row["failed"]
        for q, values in r.quantities.items():
            assert (np.isnan(values[k]) and row[q] == "") or values[k] == pytest.approx(float(row[q]), rel=1e-11)
    # The same designs given as a list of dicts, with progress reported after each.
    designs = [{"model.c_G": float(row["model.c_G"]), "model.d_G": float(row["model.d_G"])} for row in rows[::5]]
    calls = []
    listed = gk.screen(sweep, designs, jobs=2, progress=lambda done, total: calls.append((done, total)))
    assert listed.verdict == [row["verdict"] for row in rows[::5]]
    assert calls[-1] == (len(designs), len(designs)) and len(calls) == len(designs)
    np.testing.assert_array_equal(listed.parameters["model.c_G"], [d["model.c_G"] for d in designs])
    if _has("matplotlib"):   # the safe region: a Figure, as every plot() returns
        import matplotlib
        import matplotlib.figure
        matplotlib.use("Agg")
        assert isinstance(r.plot(), matplotlib.figure.Figure)


def test_screen_varies_elements_by_path_in_the_cli_and_python_alike():
    # Bearing stiffness (a tied parameter: both bearings, kxx and kyy) x mid-section diameter, 3 x 3.
    sweep = scene("screen_three_disk.toml")
    r = gk.screen(sweep, jobs=2)
    rows = cli("screen", sweep, "--jobs", "2")
    assert len(rows) == len(r.verdict) == 9
    assert list(r.parameters) == ["k_bearing", "model.shaft[2].outer_diameter"]
    for k, row in enumerate(rows):
        assert r.verdict[k] == row["verdict"] and r.reason[k] == row["reason"]
        for q, values in r.quantities.items():
            assert (np.isnan(values[k]) and row[q] == "") or values[k] == float(row[q])
    # Each swept value changes the rotor: no two designs give the same critical speed.
    assert len(set(r.quantities["critical_speed_rpm"])) == 9


def test_screen_log_decrement_and_probes_as_in_the_cli(tmp_path):
    # The stability margin and named probes: numbers, the probe column (text) and verdicts as the CLI writes them,
    # from the threaded run and from an executor.
    sweep = tmp_path / "probes.toml"
    sweep.write_text(f"""scene = "{os.path.abspath(scene('centrifuge.toml'))}"
[[parameter]]
name = "model.d_G"
values = [0.0, 4.0, 10.0]
[operating]
from = 24.0
to = 50.0
count = 14
[criteria.stability]
up_to = 60.0
count = 31
min_log_dec = 0.01
[criteria.response]
max_amplitude = 2.58e-3
probes = [{{ name = "NE", dof_x = "x", dof_y = "y", angle = 45.0 }}, {{ name = "NW", dof_x = "x", dof_y = "y", angle = 135.0 }}]
""")
    r = gk.screen(str(sweep), jobs=2)
    rows = cli("screen", str(sweep))
    assert list(r.quantities) == ["instability_onset_rad_s", "min_log_dec", "min_log_dec_speed_rad_s", "max_amplitude",
                                  "max_amplitude_speed_rad_s"]
    assert list(r.labels) == ["max_amplitude_probe"]
    assert len(rows) == len(r.verdict) == 3
    for k, row in enumerate(rows):
        assert r.verdict[k] == row["verdict"] and r.reason[k] == row["reason"]
        assert r.labels["max_amplitude_probe"][k] == row["max_amplitude_probe"]
        for q, values in r.quantities.items():
            assert (np.isnan(values[k]) and row[q] == "") or values[k] == float(row[q])
    # The undamped cage (d_G = 0) misses both: the least log decrement and the response limit.
    assert r.verdict == ["fail", "pass", "pass"] and r.failed[0] == ["stability", "response"]
    if _has("pandas"):
        assert list(r.to_pandas()["max_amplitude_probe"]) == r.labels["max_amplitude_probe"]
    from concurrent.futures import ThreadPoolExecutor
    with ThreadPoolExecutor(max_workers=2) as pool:
        pooled = gk.screen(str(sweep), executor=pool)
    assert pooled.labels == r.labels and pooled.verdict == r.verdict


def test_screen_refuses_bad_designs():
    sweep = scene("screen_centrifuge.toml")
    with pytest.raises(gk.InputError, match="differ"):
        gk.screen(sweep, [{"model.c_G": 200.0}, {"model.d_G": 1.0}])
    with pytest.raises(gk.InputError, match="not accepted by the scene"):
        gk.screen(sweep, [{"model.c_X": 200.0}])
    with pytest.raises(gk.InputError, match="not a finite number"):
        gk.screen(sweep, [{"model.c_G": float("nan")}])
    # A design the scene refuses among accepted ones is an error row (as in gyrokit screen); a parameter no
    # design makes acceptable is bad input.
    mixed = gk.screen(sweep, [{"model.c_G": -5.0}, {"model.c_G": 300.0}])
    assert mixed.verdict[0] == "error" and "invalid parameters" in mixed.reason[0]
    assert mixed.verdict[1] in ("pass", "fail")
    with pytest.raises(gk.InputError, match="c_G = -5"):
        gk.screen(sweep, [{"model.c_G": -5.0}])


def test_the_tour_in_docs_python_md_runs():
    import re
    import matplotlib
    matplotlib.use("Agg")
    root = os.path.dirname(os.path.abspath(DATA))
    text = open(os.path.join(root, "docs", "python.md")).read()
    tour = text[text.index("## A five-minute tour"):text.index("## API reference")]
    blocks = re.findall(r"```python\n(.*?)```", tour, re.S)
    assert len(blocks) == 4
    cwd = os.getcwd()
    os.chdir(root)
    try:
        namespace = {}
        for block in blocks:
            exec(compile(block, "docs/python.md", "exec"), namespace)
    finally:
        os.chdir(cwd)
    assert len(namespace["df"]) == 30 and set(namespace["df"].verdict) <= {"pass", "fail", "error"}


def test_pervasive_and_response_match_the_cli():
    s = gk.load_scene(scene("centrifuge.toml"))
    p = gk.pervasive(s)
    rows = cli("pervasive", scene("centrifuge.toml"))
    assert len(rows) == len(p.speeds) >= 1
    for k, r in enumerate(rows):
        assert p.damping[k] == r["damping"] and p.mode[k] == int(r["mode"]) and p.whirl[k] == r["whirl"]
        assert p.speeds[k] == pytest.approx(float(r["speed_rad_s"]), rel=RTOL)
    f = gk.load_scene(scene("fe_rotor.toml"))
    # The CLI's stability check of the response runs in Python too: the same warning, as a RuntimeWarning.
    with pytest.warns(RuntimeWarning, match="mode 2 is unstable from"):
        resp = gk.response(f, np.linspace(10, 600, 3), dofs=["x12", "y12"])
    err = subprocess.run([CLI, "response", scene("fe_rotor.toml"), "--speeds", "10:600:3", "--dofs", "x12,y12"],
                         check=True, capture_output=True, text=True).stderr
    assert resp.warnings and [f"warning: {w}" for w in resp.warnings] == \
        [line for line in err.splitlines() if line.startswith("warning: ")]
    rows = cli("response", scene("fe_rotor.toml"), "--speeds", "10:600:3", "--dofs", "x12,y12")
    assert len(rows) == resp.amplitude.size
    for k, r in enumerate(rows):
        i, j = divmod(k, 2)
        assert r["dof"] == resp.dofs[j]
        assert resp.amplitude[i, j] == pytest.approx(float(r["amplitude"]), rel=RTOL)
        assert resp.phase[i, j] == pytest.approx(float(r["phase_deg"]), rel=1e-9, abs=1e-9)
    with pytest.raises(gk.InputError, match="not a DOF"):
        gk.response(f, [100.0], dofs=["x99"])


def test_models_from_keywords_equal_their_scenes():
    keys = dict(A_G=2.0, B_G=2.0, A_R=0.09, C_R=0.10, m=8.0, s=0.25, eps=1.0e-3, c_G=306.862, c_T=2112.19,
                c_R=74.1333, d_G=4.0, d_T=5.0, d_R=0.02)
    made = gk.gyrostat(**keys)
    read = gk.load_scene(scene("centrifuge.toml"))
    w = np.linspace(0, 60, 241)
    # The same analysis on both (the scene's [analysis] modes = 6): the same numbers.
    np.testing.assert_array_equal(gk.critical_speeds(made, w, modes=6).speeds, gk.critical_speeds(read, w).speeds)
    with pytest.raises(gk.InputError, match=r"A_G = -1: out of range; allowed: a finite number > 0"):
        gk.gyrostat(**{**keys, "A_G": -1.0})
    with pytest.raises(gk.InputError, match="unknown key"):
        gk.gyrostat(**keys, c_X=1.0)
    rotor = gk.fe_rotor(E=211e9, poisson=0.3, density=7810,
                        shaft=[dict(length=1.5, elements=24, outer_diameter=0.05)],
                        disk=[dict(z=0.5, mass=33.657, Id=0.17831, Ip=0.32985, unbalance=1e-4),
                              dict(z=1.0, mass=33.657, Id=0.17831, Ip=0.32985)],
                        bearing=[dict(z=0.0, table="bearings/drive_end.csv"),
                                 dict(z=1.5, table="bearings/non_drive_end.csv")],
                        directory=DATA, analysis=dict(modes=6))
    assert rotor.system.size == 100
    a = gk.eig(rotor, 700.0, solver="dense").eigenvalues
    b = gk.eig(gk.load_scene(scene("fe_rotor.toml")), 700.0, solver="dense").eigenvalues
    np.testing.assert_allclose(a, b, rtol=1e-13)
    # 6 DOFs per node, a cone, a coupling, a pedestal and a table written as arrays.
    train = gk.fe_rotor(material="steel", dofs_per_node=6, length_unit="mm",
                        shaft=[dict(length=600, elements=6, outer_diameter=50, outer_diameter_end=40),
                               dict(type="coupling", length=50, k_lateral=1e6, k_bending=1e4, k_axial=1e8,
                                    k_torsion=2e4, mass=1.5),
                               dict(length=300, elements=3, outer_diameter=40)],
                        disk=[dict(z=300, outer_diameter=250, width=40)],
                        pedestal=[dict(z=0, mass=20, k=5e7)],
                        bearing=[dict(z=0, speeds=[0, 1000], k=[3e7, 3.5e7], c=[200, 250]),
                                 dict(z=950, k=2e7, c=300, kzz=1e8)])
    assert train.system.size == 6 * 11 + 2
    assert "tz5" in train.system.dof_names and "px0" in train.system.dof_names
    # The same description, torsion alone: one DOF per node, the block of the 6-DOF model.
    full = gk.load_scene(scene("drive_train.toml"))
    torsion = gk.load_scene(scene("drive_train.toml"), motion="torsional")
    idx = [i for i, n in enumerate(full.system.dof_names) if n.startswith("tz")]
    assert torsion.system.dof_names == [full.system.dof_names[i] for i in idx]
    np.testing.assert_array_equal(torsion.system.K.toarray(), full.system.K.toarray()[np.ix_(idx, idx)])
    with pytest.raises(gk.InputError, match="fe_rotor"):
        gk.load_scene(scene("centrifuge.toml"), motion="torsional")


def test_balancer_and_sommerfeld_match_the_cli():
    b = gk.balancer(scene("balancer_table1.toml"))
    rows = cli("balancer", scene("balancer_table1.toml"))
    assert len(rows) == len(b.state) >= 4
    for k, r in enumerate(rows):
        assert b.state[k] == r["state"] and b.range[k] == r["range"]
        assert b.stable[k] == (r["stable"] == "true") and b.stable_eigen[k] == (r["stable_eigen"] == "true")
        assert b.max_real_eigenvalue[k] == pytest.approx(float(r["max_re_lambda_1_s"]), rel=RTOL, abs=1e-12)
        assert b.alpha_deg[k][0] == pytest.approx(float(r["alpha1_deg"]), rel=RTOL)
    verdicts = cli("balancer", scene("balancer_table1.toml"), "--table", "balancing_ranges")
    assert len(verdicts) == len(b.ranges) == 4
    for r, v in zip(b.ranges, verdicts):
        assert r["range"] == v["range"] and r["balances"] == (v["balances"] == "true")
        assert (", ".join(r["stable_compensating"]) or "none") == v["stable_compensating"]
    assert [r["balances"] for r in b.ranges] == [False, True, False, True]   # Tabelle 1
    s = gk.sommerfeld(scene("sommerfeld_rotor.toml"))
    text = subprocess.run([CLI, "sommerfeld", scene("sommerfeld_rotor.toml")], check=True, capture_output=True,
                          text=True).stdout
    summary = dict(line.split()[:2] for line in text.splitlines()
                   if line.split()[:1] and line.split()[0] in ("jump_up", "jump_down", "limit_speed_estimate"))
    assert s.has_jump
    assert s.jump_up == pytest.approx(float(summary["jump_up"]), rel=1e-5)         # the table prints 6 digits
    assert s.jump_down == pytest.approx(float(summary["jump_down"]), rel=1e-5)
    assert s.limit_speed_estimate == pytest.approx(float(summary["limit_speed_estimate"]), rel=1e-5)


def test_large_sparse_system_round_trips_through_scipy():
    rotor = gk.fe_rotor(E=211e9, poisson=0.3, density=7810,
                        shaft=[dict(length=1.5, elements=768, outer_diameter=0.05)],
                        disk=[dict(z=0.5, mass=33.657, Id=0.17831, Ip=0.32985)],
                        bearing=[dict(z=0.0, k=1e7, c=400.0), dict(z=1.5, k=1e7, c=400.0)])
    s = rotor.system
    assert s.size == 3076 and sp.issparse(s.M) and s.M.nnz < 20 * s.size   # sparse out, never dense
    again = gk.System(M=s.M, K=s.K, G=s.G, damping={"bearings": s.damping_matrix(0.0)},
                      dof_names=s.dof_names, whirl_pairs=s.whirl_pairs)
    a = gk.eig(rotor, 300.0, modes=4)        # auto: sparse above 200 DOFs
    b = gk.eig(again, 300.0, modes=4)
    assert a.method == b.method == "ARPACK shift-invert"
    np.testing.assert_allclose(b.eigenvalues, a.eigenvalues, rtol=1e-10)


def test_fluid_rotor_from_keywords_and_bad_arguments():
    keys = dict(R=0.6, R0=0.4, a=0.5, l=2.5, rho=1000.0, nu=1.0e-6, c1=6.0e8, c2=2.0e8, c11=3.0e6, m0=400.0,
                I0=133.0, J0=75.0, e=1.0e-4, modes=5)
    made = gk.fluid_rotor(**keys)
    read = gk.load_scene(scene("fluid_N1.toml"))
    assert made.system.size == read.system.size
    np.testing.assert_array_equal(gk.eig(made, 50.0).eigenvalues, gk.eig(read, 50.0).eigenvalues)
    M, K, G, w, _ = jeffcott_with_disk()
    with pytest.raises(gk.InputError, match="2-D"):
        gk.System(M=np.ones(4), K=K)
    with pytest.raises(gk.InputError, match="unbalance has 3 entries"):
        gk.System(M=M, K=K, unbalance=np.ones(3))
    with pytest.raises(gk.InputError, match="jobs = -2: allowed"):
        gk.campbell(gk.System(M=M, K=K), [0.0, 1.0], jobs=-2)
    # The library's option fields in Python's keywords (lanczos, not lanczos_vectors);
    # more jobs than cores: capped, with a warning (the CLI's note).
    with pytest.raises(gk.InputError, match=r"^lanczos = 3: must exceed"):
        gk.eig(gk.load_scene(scene("fe_rotor.toml")), 0.0, solver="sparse", modes=6, lanczos=3)
    with pytest.warns(RuntimeWarning, match="jobs = 100000 capped to the"):
        gk.campbell(gk.System(M=M, K=K), [0.0, 1.0], jobs=100000)
    with pytest.raises(gk.InputError, match="finite number"):
        gk.gyrostat(A_G=float("inf"))
    assert "Campbell diagram" in gk.campbell.__doc__


def test_exported_rotor_rigid_body_modes_apart_and_eigenvalues_as_the_cli():
    # data/ross_rotor_example: 42 DOFs from another package, singular K (free axial and torsional
    # motion), no damping. Rigid-body eigenvalues are listed apart, never as modes.
    s = gk.load_scene(scene("ross_rotor_example/scene.toml"))
    ev = gk.eig(s, 500.0, modes=0)
    rows = cli("eig", scene("ross_rotor_example/scene.toml"), "--speed", "500", "--modes", "0")
    assert len(ev.eigenvalues) == len(rows) == 40
    # The scene's [analysis] modes = 6: its six lowest, as the CLI's eig without --modes.
    assert len(gk.eig(s, 500.0).eigenvalues) == len(cli("eig", scene("ross_rotor_example/scene.toml"), "--speed",
                                                        "500")) == 6
    assert len(ev.rigid_body) == 4 and np.all(np.abs(ev.rigid_body) < 1e-6 * 500)
    for k, r in enumerate(rows):
        assert ev.frequencies[k] == pytest.approx(float(r["frequency_rad_s"]), rel=RTOL)
        assert ev.whirl[k] == r["whirl"]
    assert ev.backward_errors.max() < 1e-14
    assert set(ev.stability) == {"neutral"}   # undamped: never unstable by rounding
    cd = gk.campbell(s, np.linspace(0, 1000, 21), modes=6)
    assert cd.rigid_body == 4 and len(cd.branches) >= 6


def test_mode_shapes_match_the_cli_and_the_eigenvectors():
    s = gk.load_scene(scene("fe_rotor.toml"))
    ms = gk.modes(s, 100.0, modes=4)
    assert ms.numbers == [1, 2, 3, 4]
    rows = cli("modes", scene("fe_rotor.toml"), "--speed", "100", "--modes", "4")
    assert len(rows) == len(ms.orbits["pair"])
    for k, r in enumerate(rows):
        assert ms.orbits["pair"][k] == r["pair"]
        assert ms.orbits["whirl"][k] == r["whirl"]
        assert ms.orbits["major"][k] == pytest.approx(float(r["major"]), rel=RTOL, abs=1e-14)
        assert np.degrees(ms.orbits["angle"][k]) == pytest.approx(float(r["angle_deg"]), rel=RTOL, abs=1e-9)
    # Each shape is the eigenvector eig returns, scaled to 1 at its reference DOF (MAC = 1).
    ev = gk.eig(s, 100.0)
    for j, lam in enumerate(ms.eigenvalues):
        x, v = ms.shapes[:, j], ev.vectors[:, j]
        assert x[ms.dof_names.index(ms.reference[j])] == pytest.approx(1.0, abs=1e-14)
        assert lam == pytest.approx(ev.eigenvalues[j], rel=1e-12)
        assert abs(np.vdot(x, v)) ** 2 / (np.vdot(x, x).real * np.vdot(v, v).real) == pytest.approx(1.0, abs=1e-12)
    frame = ms.to_pandas()
    assert list(frame.columns)[:3] == ["mode", "pair", "unit"]


def test_malformed_matrices_and_whirl_pairs_are_refused_not_cast():
    import warnings
    M, K = np.eye(4), 100.0 * np.eye(4)
    with pytest.raises(gk.InputError, match="K: has complex entries"):
        gk.System(M=M, K=K * (1 + 1j))
    with pytest.raises(gk.InputError, match="D: has complex entries"):
        gk.System(M=M, K=K, D=sp.csc_matrix(np.eye(4) * 1j))
    with warnings.catch_warnings():
        warnings.simplefilter("error")   # a complex matrix with zero imaginary parts is its real part, silently
        s = gk.System(M=M, K=K.astype(complex))
    assert gk.eig(s, 0.0).frequencies[0] == pytest.approx(10.0, rel=1e-12)
    # A CSC matrix whose index arrays are wrong is refused (it was read as is: a segfault).
    bad = sp.csc_matrix(M)
    bad.indices[0] = 99
    with pytest.raises(gk.InputError, match="M: not a valid sparse matrix"):
        gk.System(M=bad, K=K)
    bad = sp.csc_matrix(M)
    bad.indptr[1] = 9
    with pytest.raises(gk.InputError, match="M: not a valid sparse matrix"):
        gk.System(M=bad, K=K)
    # Unsorted indices and duplicates are summed, as SciPy means them.
    dup = sp.csc_matrix((np.array([0.5, 0.5, 1.0, 1.0, 1.0]), np.array([0, 0, 1, 2, 3]), np.array([0, 2, 3, 4, 5])),
                        shape=(4, 4))
    assert gk.eig(gk.System(M=dup, K=K), 0.0).frequencies[0] == pytest.approx(10.0, rel=1e-12)
    with pytest.raises(gk.InputError, match="in whirl pairs"):
        gk.System(M=M, K=K, whirl_pairs=[[0, 1], [1, 0]])


def test_deep_toml_and_special_files_are_refused(tmp_path):
    deep = tmp_path / "deep.toml"
    deep.write_text("[" + ".".join(["x"] * 50000) + "]\n")
    with pytest.raises(gk.InputError, match="more than 64 levels deep"):
        gk.load_scene(str(deep))
    with pytest.raises(gk.InputError, match="is not a regular file"):
        gk.load_scene("/dev/zero")


_INTERRUPTED_CALL = r"""
import os, signal, sys, threading, time
import gyrokit as gk
sc = gk.load_scene(sys.argv[1])
threading.Timer(1.0, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
t = time.time()
try:
    gk.campbell(sc, modes=0, jobs=int(sys.argv[2]))   # every mode: about two minutes
    print("finished")
except KeyboardInterrupt:
    print("interrupted after", time.time() - t)
me = str(os.getpid())
def parent(p):   # a process that ends while the list is read has no parent to count
    try:
        return open(f"/proc/{p}/stat").read().rsplit(")", 1)[1].split()[1]
    except OSError:
        return None
kids = [p for p in os.listdir("/proc") if p.isdigit() and parent(p) == me]
print("children", len(kids))
"""


@pytest.mark.parametrize("jobs", [1, 2])
def test_ctrl_c_stops_a_long_call(jobs):
    # Before, a campbell ignored Ctrl-C until it ended (238 s): now SIGINT stops it at
    # the next speed, as KeyboardInterrupt, with no worker left behind.
    import sys
    r = subprocess.run([sys.executable, "-c", _INTERRUPTED_CALL, scene("three_disk_rotor_journal.toml"), str(jobs)],
                       capture_output=True, text=True, timeout=120, env=dict(os.environ))
    assert r.returncode == 0, r.stderr
    lines = r.stdout.split("\n")
    assert lines[0].startswith("interrupted after"), r.stdout
    assert float(lines[0].split()[-1]) < 20.0
    assert "children 0" in r.stdout


def test_interrupt_is_cleared_after_a_call():
    # The SIGINT handler is Python's again after the call: a later Ctrl-C is a plain KeyboardInterrupt.
    import signal
    before = signal.getsignal(signal.SIGINT)
    gk.campbell(gk.load_scene(scene("centrifuge.toml")), speeds=np.linspace(0, 100, 5))
    assert signal.getsignal(signal.SIGINT) is before
    with pytest.raises(KeyboardInterrupt):
        os.kill(os.getpid(), signal.SIGINT)
        for _ in range(1000):
            pass


@pytest.mark.parametrize("name", ["fe_rotor.toml", "three_disk_rotor_journal.toml", "ross_rotor_example/scene.toml", "compressor.toml"])
def test_the_cli_and_python_run_one_study_with_the_same_notes(name):
    # One pipeline (the library's study layer) behind both: the same critical speeds and the same notes and
    # warnings, the CLI's on stderr, Python's in the result.
    c = gk.critical_speeds(gk.load_scene(scene(name)))
    run = subprocess.run([CLI, "critical", scene(name), "--format", "csv"], check=True, capture_output=True, text=True)
    rows = list(csv.DictReader(io.StringIO(run.stdout)))
    # Both in the scene's [speeds] units (rpm where the scene says so, else rad/s).
    assert c.unit == gk.load_scene(scene(name)).speed_unit
    column = {"rad/s": "speed_rad_s", "Hz": "speed_hz", "rpm": "speed_rpm"}[c.unit]
    assert [float(r[column]) for r in rows] == pytest.approx(list(c.speeds), rel=RTOL)
    # Each front end names the options in its own words (the library marks them): --modes 0, modes = 0.
    lines = run.stderr.replace("--modes 0", "modes = 0").splitlines()
    assert [f"note: {n}" for n in c.notes] == [x for x in lines if x.startswith("note: ")]
    assert [f"warning: {w}" for w in c.warnings] == [x for x in lines if x.startswith("warning: ")]


def test_screening_judges_the_critical_speeds_the_cli_and_python_find():
    # The separation criterion runs the same study (the library's study layer) on the design's scene,
    # over 0 to 1.05 (1 + margin) x the top operating speed in 121 speeds: design 3 of the three-disk
    # family (bearings 2e7 N/m, mid-section 90 mm) equals Python and the CLI on that scene and grid. (With
    # bearings of 1e7 N/m both crossings are heavily damped, AF 2.0 and 1.4: `critical` calls them not
    # critical, and the separation criterion needs no margin from them.)
    # Tolerance: the screening row prints 12 digits, and the crossing's eigenvalue error bound is
    # about 3e-7 rad/s (1e-9 of it); the roots themselves are refined to 1e-13.
    ov = {"model.bearing[*].kxx": 2e7, "model.bearing[*].kyy": 2e7, "model.shaft[2].outer_diameter": 0.09}
    r = gk.screen(scene("screen_three_disk.toml"), designs=[{"k_bearing": 2e7, "model.shaft[2].outer_diameter": 0.09}],
                  jobs=1)
    screened = r.quantities["critical_speed_rpm"][0]
    assert "branch 2" in r.reason[0]
    top = 12000 * 1.15 * 1.05
    c = gk.critical_speeds(gk.load_scene(scene("three_disk_rotor.toml"), overrides=ov), np.linspace(0, top, 121),
                           unit="rpm")
    assert c.speeds[list(c.branch).index(2)] == pytest.approx(screened, rel=1e-9)
    edited = os.path.join(os.environ.get("TMPDIR", "/tmp"), f"design0_{os.getpid()}.toml")
    with open(edited, "w") as f:
        f.write(gk.load_scene(scene("three_disk_rotor.toml"), overrides=ov).to_toml())
    try:
        run = subprocess.run([CLI, "critical", edited, "--units", "rpm", "--speeds", f"0:{top}:121", "--format", "csv"],
                             check=True, capture_output=True, text=True)
    finally:
        os.remove(edited)
    rows = [r for r in csv.DictReader(io.StringIO(run.stdout)) if r["mode"] == "2"]
    assert float(rows[0]["speed_rpm"]) == pytest.approx(screened, rel=1e-9)


def _rows(r):
    return list(zip(r.design, r.verdict, r.reason, *[list(v) for v in r.quantities.values()]))


def test_screen_on_a_process_pool_and_a_dask_cluster_gives_the_threaded_rows():
    from concurrent.futures import ProcessPoolExecutor
    sweep = scene("screen_centrifuge.toml")
    threaded = gk.screen(sweep, jobs=2)
    with ProcessPoolExecutor(max_workers=2) as pool:
        pooled = gk.screen(sweep, executor=pool)
    assert pooled.columns == threaded.columns
    np.testing.assert_array_equal(pooled.design, threaded.design)
    assert pooled.verdict == threaded.verdict and pooled.reason == threaded.reason
    for q in threaded.quantities:
        np.testing.assert_array_equal(pooled.quantities[q], threaded.quantities[q])
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        on_dask = gk.screen(sweep, executor=client.get_executor())
    assert on_dask.verdict == threaded.verdict and on_dask.reason == threaded.reason
    for q in threaded.quantities:
        np.testing.assert_array_equal(on_dask.quantities[q], threaded.quantities[q])


class _KillsDesign:
    """An executor whose worker process dies while it runs design `index` (a node lost mid-run)."""

    def __init__(self, pool, index):
        self.pool, self.index = pool, index

    def submit(self, fn, *args, **kwargs):
        if args[-1] == self.index:
            return self.pool.submit(os._exit, 9)
        return self.pool.submit(fn, *args, **kwargs)


def _same_or_reported(r, threaded):
    """Every design is the threaded run's row or an error row naming the failed task; none is missing."""
    assert len(r.verdict) == len(threaded.verdict)
    np.testing.assert_array_equal(r.design, np.arange(len(threaded.verdict)))
    for k in range(len(threaded.verdict)):
        assert (r.verdict[k], r.reason[k]) == (threaded.verdict[k], threaded.reason[k]) or \
            (r.verdict[k] == "error" and "task failed" in r.reason[k])


def test_a_worker_killed_mid_run_leaves_its_designs_reported_not_lost():
    # A process pool whose worker dies is broken: the retry is refused, the designs are error rows.
    from concurrent.futures import ProcessPoolExecutor
    sweep = scene("screen_centrifuge.toml")
    threaded = gk.screen(sweep, jobs=2)
    with ProcessPoolExecutor(max_workers=2) as pool:
        r = gk.screen(sweep, executor=_KillsDesign(pool, 5))
    assert len(threaded.verdict) == 24
    assert r.verdict[5] == "error" and "task failed 2 times" in r.reason[5]
    assert "BrokenProcessPool" in r.reason[5]
    _same_or_reported(r, threaded)
    with ProcessPoolExecutor(max_workers=2) as pool:
        with pytest.raises(gk.InputError, match="retries"):
            gk.screen(sweep, executor=pool, retries=-1)


def test_a_dask_worker_killed_mid_run_is_replaced_and_nothing_is_lost():
    # A real worker process killed (SIGKILL) after the first design came back: Dask's nanny restarts
    # it and the scheduler reruns its tasks (and the results it held): every row is the threaded one.
    distributed = pytest.importorskip("distributed")
    import signal
    sweep = scene("screen_centrifuge.toml")
    threaded = gk.screen(sweep, jobs=2)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        pids = list(client.run(os.getpid).values())
        killed = []

        def kill_one(done, total):
            if not killed:
                os.kill(pids[0], signal.SIGKILL)
                killed.append(pids[0])
        r = gk.screen(sweep, executor=client.get_executor(), progress=kill_one)
        assert pids[0] not in client.run(os.getpid).values()
    assert killed
    assert r.verdict == threaded.verdict and r.reason == threaded.reason
    for q in threaded.quantities:
        np.testing.assert_array_equal(r.quantities[q], threaded.quantities[q])


def test_a_design_that_kills_every_dask_worker_it_runs_on_is_reported():
    # With no failures allowed per task, Dask gives up on the task that killed its worker (KilledWorker)
    # and on the others that worker held; the retry reruns those on the restarted workers and reports
    # design 5, which kills its worker each time, as an error row.
    distributed = pytest.importorskip("distributed")
    import dask
    sweep = scene("screen_centrifuge.toml")
    threaded = gk.screen(sweep, jobs=2)
    with dask.config.set({"distributed.scheduler.allowed-failures": 0}), \
            distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        r = gk.screen(sweep, executor=_KillsDesign(client.get_executor(), 5), retries=2)
    assert r.verdict[5] == "error" and "task failed 3 times" in r.reason[5] and "KilledWorker" in r.reason[5]
    assert [k for k in range(24) if r.verdict[k] == "error"] == [5]
    _same_or_reported(r, threaded)


def test_screen_of_given_designs_on_an_executor_equals_the_threaded_run():
    # Designs given as dicts, one of them refused by the scene: the same rows, the refused one an error row.
    from concurrent.futures import ThreadPoolExecutor
    sweep = scene("screen_centrifuge.toml")
    designs = [{"model.c_G": -5.0}, {"model.c_G": 300.0}, {"model.c_G": 550.0}]
    threaded = gk.screen(sweep, designs, jobs=2)
    with ThreadPoolExecutor(max_workers=2) as pool:
        pooled = gk.screen(sweep, designs, executor=pool)
    assert pooled.verdict == threaded.verdict and pooled.reason == threaded.reason
    assert pooled.verdict[0] == "error"
    np.testing.assert_array_equal(pooled.design, [0, 1, 2])


def test_response_takes_speeds_in_any_order():
    # The stability check behind the response tracks over the sorted distinct speeds.
    f = gk.load_scene(scene("centrifuge.toml"))
    down = gk.response(f, [40.0, 30.0, 30.0, 20.0])
    up = gk.response(f, [20.0, 30.0, 40.0])
    np.testing.assert_allclose(down.amplitude[[3, 1, 0]], up.amplitude, rtol=1e-12)


# --- Files a result writes: the library's one output guard --------------------------------

def _copied_scene(tmp_path):
    import shutil
    src = os.path.join(DATA, "ross_rotor_example")
    dst = tmp_path / "ross"
    shutil.copytree(src, dst)
    return dst


def test_save_and_plot_refuse_the_inputs_of_the_result_through_links(tmp_path):
    # save() and plot(path) go through the output layer with the scene's files as the run's
    # inputs: the scene, a matrix it names, a symbolic and a hard link to one are refused,
    # and nothing is written.
    folder = _copied_scene(tmp_path)
    sc = gk.load_scene(str(folder / "scene.toml"))
    assert str(folder / "M.mtx") in sc.inputs and str(folder / "scene.toml") in sc.inputs
    r = gk.critical_speeds(sc)
    before = {p: open(p, "rb").read() for p in sc.inputs}
    os.symlink(folder / "scene.toml", tmp_path / "link.csv")
    os.link(folder / "M.mtx", tmp_path / "hard.svg")
    os.symlink(folder / "K.mtx", tmp_path / "k.json")
    for target in [tmp_path / "link.csv", tmp_path / "k.json"]:   # save() takes .csv, .json, .txt
        with pytest.raises(gk.InputError, match="input of this run"):
            r.save(str(target))
    with pytest.raises(gk.InputError, match="input of this run"):
        gk.campbell(sc, speeds=np.linspace(0, 100, 5)).plot(str(tmp_path / "hard.svg"))
    assert {p: open(p, "rb").read() for p in sc.inputs} == before
    assert os.path.islink(tmp_path / "link.csv")
    # A new file is written, whole.
    r.save(str(tmp_path / "speeds.csv"))
    assert open(tmp_path / "speeds.csv").read().startswith("speed")


def test_a_scene_named_by_a_bare_file_name_reads_its_matrices_from_the_working_folder(tmp_path):
    folder = _copied_scene(tmp_path)
    here = os.getcwd()
    try:
        os.chdir(folder)
        sc = gk.load_scene("scene.toml")
    finally:
        os.chdir(here)
    assert sc.system.size == 42


def test_malformed_systems_are_refused_with_the_key_named():
    M = np.diag([-1.0, -1.0])
    K = np.eye(2)
    with pytest.raises(gk.InputError, match="M has the diagonal entry -1 at DOF 0.*positive semidefinite"):
        gk.System(M=M, K=K)
    with pytest.raises(gk.InputError, match="whirl_pairs = .*allowed: pairs of whole-number DOF indices"):
        gk.System(M=np.eye(2), K=K, whirl_pairs=[[0.0, 1.5]])


_INTERRUPTED_FRF = r"""
import os, signal, sys, threading, time
import numpy as np
import gyrokit as gk
sc = gk.load_scene(sys.argv[1])
threading.Timer(1.0, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
t = time.time()
try:
    gk.frf(sc, 100.0, "y3", np.linspace(1, 3000, 400000))   # minutes without Ctrl-C
    print("finished")
except KeyboardInterrupt:
    print("interrupted after", time.time() - t)
"""


def test_ctrl_c_stops_a_frequency_response():
    import sys
    r = subprocess.run([sys.executable, "-c", _INTERRUPTED_FRF, scene("three_disk_rotor.toml")],
                       capture_output=True, text=True, timeout=120, env=dict(os.environ))
    assert r.returncode == 0, r.stderr
    assert r.stdout.startswith("interrupted after"), r.stdout
    assert float(r.stdout.split()[2]) < 20.0


def test_a_sweep_parameter_named_as_a_result_column_is_refused_before_the_study(tmp_path):
    sweep = tmp_path / "sweep.toml"
    sweep.write_text(f"""scene = "{os.path.abspath(scene("centrifuge.toml"))}"
[[parameter]]
name = "verdict"
paths = ["model.c_G"]
values = [150.0, 300.0]
[operating]
from = 24.0
to = 50.0
[criteria.separation]
margin_percent = 15.0
""")
    with pytest.raises(gk.InputError, match="parameter name 'verdict' is also the name of a result column"):
        gk.screen(str(sweep))


def _every_result(tmp_path):
    """One result of each analysis of the module, with the scene (or scene file) it was computed from."""
    import shutil
    for name in ["three_disk_rotor.toml", "centrifuge.toml", "screen_centrifuge.toml", "balancer_bild7.toml",
                 "sommerfeld_rotor.toml", "fluid_N2.toml"]:
        shutil.copy(os.path.join(DATA, name), tmp_path / name)
    rotor = gk.load_scene(str(tmp_path / "three_disk_rotor.toml"))
    filled = gk.load_scene(str(tmp_path / "fluid_N2.toml"))
    speeds = np.linspace(0, 1000, 6)
    return [
        (rotor, gk.eig(rotor, 100.0)), (rotor, gk.modes(rotor, 100.0)), (rotor, gk.campbell(rotor, speeds)),
        (rotor, gk.critical_speeds(rotor, speeds)), (rotor, gk.stability(rotor, speeds)),
        (rotor, gk.pervasive(rotor, speeds)), (rotor, gk.response(rotor, speeds)),
        (rotor, gk.frf(rotor, 100.0, "y3", np.linspace(10, 1000, 5))), (rotor, gk.static(rotor)),
        (rotor, gk.critical_speed_map(rotor, stiffness=[1e6, 1e7, 1e8])), (rotor, gk.summary(rotor)),
        (rotor, gk.level1(rotor, intervals=4)),
        (rotor, gk.api_unbalance(rotor, speeds=41)), (rotor, gk.mesh_convergence(rotor)),
        (rotor, gk.transient(rotor, 100.0, node=3, duration=0.02, unit="rad/s")),
        (filled, gk.fluid(filled)),
        (str(tmp_path / "screen_centrifuge.toml"), gk.screen(str(tmp_path / "screen_centrifuge.toml"),
                                                             [{"model.c_G": 150.0}])),
        (str(tmp_path / "balancer_bild7.toml"), gk.balancer(str(tmp_path / "balancer_bild7.toml"))),
        (str(tmp_path / "sommerfeld_rotor.toml"), gk.sommerfeld(str(tmp_path / "sommerfeld_rotor.toml"))),
        (str(tmp_path / "balancer_bild7.toml"), gk.balancer(str(tmp_path / "balancer_bild7.toml"), simulate=True,
                                                           duration=0.2)),
        (str(tmp_path / "sommerfeld_rotor.toml"), gk.sommerfeld(str(tmp_path / "sommerfeld_rotor.toml"), runup=True,
                                                                max_speed=50.0)),
    ]


def test_every_result_method_that_writes_a_file_refuses_its_inputs(tmp_path):
    # Every method of every result class that takes a `path` (found by inspection, not listed
    # here) is pointed at a symbolic link and a hard link to the file the result was computed
    # from: InputError, and the file is unchanged. Every result class of the module is covered.
    import inspect
    results = _every_result(tmp_path)
    covered = {type(r) for _, r in results}
    classes = {getattr(gk, n) for n in gk.__all__ if inspect.isclass(getattr(gk, n)) and
               issubclass(getattr(gk, n), gk._Result) and getattr(gk, n) is not gk._Result}
    assert classes <= covered, f"results without a recipe here: {classes - covered}"
    checked = 0
    for source, result in results:
        src = source.path if isinstance(source, gk.Scene) else source
        before = open(src, "rb").read()
        for name, method in inspect.getmembers(result, inspect.ismethod):
            if name.startswith("_") or "path" not in inspect.signature(method).parameters:
                continue
            ext = ".csv" if name == "save" else ".svg"
            for i, make in enumerate([os.symlink, os.link]):
                target = tmp_path / f"{type(result).__name__}_{name}_{i}{ext}"
                make(src, target)
                with pytest.raises(gk.InputError) as refused:
                    method(str(target))
                if re.search(r"has no (figure|tables to save)", str(refused.value)):
                    continue   # this result writes nothing by this method
                assert "input of this run" in str(refused.value)
                checked += 1
        assert open(src, "rb").read() == before
    assert checked >= 2 * len(results)


def test_f_cut_in_the_callers_unit_as_the_clis_and_from_the_scene(tmp_path):
    path = scene("three_disk_rotor.toml")
    s = gk.load_scene(path)
    assert s.f_cut is None
    wide = gk.critical_speeds(s, unit="Hz")
    # A cut-off of 100 Hz leaves out the modes that stay above it; the same as --f-cut 100 --units Hz.
    cut = gk.critical_speeds(s, unit="Hz", f_cut=100.0)
    rows = cli("critical", path, "--units", "Hz", "--f-cut", "100")
    assert len(rows) == len(cut.speeds) < len(wide.speeds)
    for k, r in enumerate(rows):
        assert cut.speeds[k] == pytest.approx(float(r["speed_hz"]), rel=RTOL)
    # The scene key (rad/s) gives the same.
    text = open(path).read().replace("\n[", "\n[analysis]\nf_cut = %r\n\n[" % (200.0 * np.pi), 1)
    written = tmp_path / "cut.toml"
    written.write_text(text)
    keyed = gk.load_scene(str(written))
    assert keyed.f_cut == pytest.approx(200.0 * np.pi)
    assert list(gk.critical_speeds(keyed, unit="Hz").speeds) == pytest.approx(list(cut.speeds), rel=RTOL)
    with pytest.raises(gk.InputError, match="f_cut"):
        gk.stability(s, f_cut=0.0)


def test_campbell_gives_the_judged_modes_beyond_the_k_shown():
    s = gk.load_scene(scene("fe_rotor.toml"))
    c = gk.campbell(s, modes=1)
    assert list(c.branches) == [1]
    assert c.judged_eigenvalues.shape == (len(c.speeds), len(c.judged_branches))
    assert list(c.judged_branches) == list(range(2, 2 + len(c.judged_branches)))
    # Every branch the critical speeds name is shown or judged.
    cs = gk.critical_speeds(s, modes=1)
    assert set(int(b) for b in cs.branch) <= {1} | set(int(b) for b in c.judged_branches)
    # Mode 4 is unstable from 1100 rad/s on (the CLI's summary): its judged eigenvalues say so.
    k = list(c.judged_branches).index(4)
    top = c.judged_eigenvalues[-1, k]
    assert top.real > 0 and top.imag > 0
    assert any("mode 4 is unstable" in w for w in c.warnings)
