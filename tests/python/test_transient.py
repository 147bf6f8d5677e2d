"""gk.transient against the CLI (the same run, the same envelope), its keywords' errors, and the example of
docs/transient.md."""
import csv
import io
import os
import re
import subprocess

import numpy as np
import pytest

import gyrokit as gk
from scenes import three_disk_in_rad_s

DATA = os.environ.get("GYROKIT_DATA", os.path.join(os.path.dirname(__file__), "..", "..", "data"))
# Speeds below are in rad/s, the unit of this copy's [speeds] (the scene's own are in rpm).
SCENE = three_disk_in_rad_s(os.path.join(DATA, "three_disk_rotor.toml"))


def cli(*args):
    return subprocess.run([os.environ["GYROKIT_CLI"], "transient", SCENE, *args], capture_output=True, text=True,
                          check=True).stdout


def test_a_run_up_matches_the_cli_step_by_step_and_window_by_window(tmp_path):
    r = gk.transient(gk.load_scene(SCENE), run_up=(1000, 6000), acceleration=20000, unit="rpm", node=12)
    assert r.dofs == ["x12", "y12"] and r.unit == "rpm"
    history = tmp_path / "h.csv"
    out = cli("--run-up", "1000:6000", "--acceleration", "20000", "--units", "rpm", "--node", "12", "--format", "csv",
              "--out", str(history))
    rows = list(csv.DictReader(open(history)))
    assert len(rows) == len(r.t) == r.stats["steps"] + 1
    for row, n in zip(rows[::97], range(0, len(rows), 97)):
        assert float(row["time_s"]) == pytest.approx(r.t[n], rel=1e-11, abs=1e-15)
        assert float(row["speed_rpm"]) == pytest.approx(r.speed[n], rel=1e-11)
        for k, name in enumerate(r.dofs):   # CSV prints 12 digits: within them
            assert float(row[name]) == pytest.approx(r.z[n, k], rel=1e-10, abs=1e-10 * np.abs(r.z).max())
    windows = list(csv.DictReader(io.StringIO(out)))
    frame = r.to_pandas("envelope")
    assert len(windows) == len(frame) > 0
    for w, (_, p) in zip(windows, frame.iterrows()):
        assert w["dof"] == p["dof"] and int(w["revolution"]) == p["revolution"]
        assert float(w["peak"]) == pytest.approx(p["peak"], rel=1e-10)
        assert float(w["steady"]) == pytest.approx(p["steady"], rel=1e-10)
        assert float(w["speed_rpm"]) == pytest.approx(p["speed"], rel=1e-10)
    assert r.speed[0] == pytest.approx(1000.0) and r.speed[-1] == pytest.approx(6000.0)


def test_a_steady_start_stays_on_the_steady_response_and_the_waterfall_reads_it():
    r = gk.transient(gk.load_scene(SCENE), 600.0, duration=0.2, start="steady")
    # Newmark's period error (w dt)^2 / 12 = 0.3 % moves the response by about 1 % here (see docs/transient.md).
    assert np.allclose(r.envelope["peak"], r.envelope["steady"], rtol=0.02)
    w = r.waterfall("x12", windows=5, frequencies=301)
    assert w["frequencies"][200] == pytest.approx(600.0)
    assert np.all(np.argmax(w["amplitude"], axis=1) == 200)
    assert w["amplitude"][:, 200] == pytest.approx(r.envelope["steady"][0, 0], rel=0.02)
    assert r.notes[0].startswith("Newmark average acceleration")
    with pytest.raises(gk.InputError, match="waterfall dof 'zz': allowed: a recorded DOF"):
        r.waterfall("zz")
    with pytest.raises(gk.InputError, match="waterfall dof -1: allowed: a column 0 to"):
        r.waterfall(-1)


def test_bad_keywords_name_themselves_the_value_and_the_range():
    scene = gk.load_scene(SCENE)
    with pytest.raises(gk.InputError, match=r"dt = -1 s: allowed: \(0, 0.001309\] s"):
        gk.transient(scene, 600.0, dt=-1)
    with pytest.raises(gk.InputError, match="dt = 0 s: allowed: a finite time step > 0"):
        gk.transient(scene, 600.0, dt=0)
    with pytest.raises(gk.InputError, match=r"acceleration = -5 rpm/s with a run-up from 0 to 15000 rpm: allowed: a "
                                            r"finite number > 0"):
        gk.transient(scene, run_up=(0, 15000), acceleration=-5, unit="rpm")
    with pytest.raises(gk.InputError, match=r"allowed: at most max_steps = 2000000 \(up to 50000000\)"):
        gk.transient(scene, 600.0, duration=1e5)
    with pytest.raises(gk.InputError, match=r"no speed: allowed: speed \(a constant speed\), or run_up \(from, to\) with acceleration$"):
        gk.transient(scene)
    with pytest.raises(gk.InputError, match="run_up needs acceleration"):
        gk.transient(scene, run_up=(0, 100))
    with pytest.raises(gk.InputError, match="start = 'hot'"):
        gk.transient(scene, 600.0, start="hot")
    with pytest.raises(gk.InputError, match="dofs 'x99': 'x99' is not a DOF of the model"):
        gk.transient(scene, 600.0, dofs=["x99"])
    with pytest.raises(gk.InputError, match="unit = 'rps'"):
        gk.transient(scene, 600.0, unit="rps")


def test_the_docs_example_runs():
    root = os.path.dirname(os.path.abspath(DATA))
    block = re.findall(r"```python\n(.*?)```", open(os.path.join(root, "docs", "transient.md")).read(), re.S)[0]
    import matplotlib
    matplotlib.use("Agg")
    cwd = os.getcwd()
    os.chdir(root)
    try:
        exec(compile(block, "docs/transient.md", "exec"), {"gk": gk, "np": np})
    finally:
        os.chdir(cwd)
