"""One study behind every front end: for each rotor scene of data/ and each analysis, the CLI's JSON output and
the Python result's tables (saved as JSON, full precision) are the same rows, bit for bit, and so are the notes
and warnings (the CLI's stderr, Python's `notes` and `warnings`). The screening's critical speed and
instability onset are the same study's (test_gyrokit.py: test_screening_judges_the_critical_speeds_...), and so
are its critical speed, instability onset and largest response on an FE rotor (below)."""
import glob
import json
import tomllib
import os
import subprocess
import warnings

import numpy as np
import pytest

import gyrokit as gk

CLI = os.environ.get("GYROKIT_CLI")
DATA = os.environ["GYROKIT_DATA"]

# The rotor scenes (gyrostat, fe_rotor, matrices) of data/, but the 100,000-DOF one (docs/large_models.md).
SCENES = sorted(p for p in glob.glob(os.path.join(DATA, "*.toml")) + [os.path.join(DATA, "ross_rotor_example",
                                                                                   "scene.toml")]
                if os.path.basename(p) != "fe_rotor_100k.toml"
                and tomllib.load(open(p, "rb")).get("model", {}).get("type") in ("gyrostat", "fe_rotor", "matrices"))

# The analysis, its Python call and extra CLI arguments, and which of Python's tables the CLI's JSON holds
# (the CLI lists the critical speeds and the heavily damped crossings as one table).
ANALYSES = {
    "eig": (lambda s, w: gk.eig(s, w), lambda s, w: ["--speed", repr(w)], ["eigenvalues"]),
    "modes": (lambda s, w: gk.modes(s, w), lambda s, w: ["--speed", repr(w)], ["mode_orbits"]),
    "campbell": (lambda s, w: gk.campbell(s), lambda s, w: [], ["campbell"]),
    "critical": (lambda s, w: gk.critical_speeds(s), lambda s, w: [], ["critical_speeds", "heavily_damped_crossings"]),
    "stability": (lambda s, w: gk.stability(s), lambda s, w: [], ["stability_changes"]),
    "response": (lambda s, w: gk.response(s, peaks=False), lambda s, w: [], ["response"]),   # JSON: the curve
    # Three speeds, 0 to the top: what was checked and the losses (the scenes where the refinements
    # of three-speed brackets are quick: a fluid-film rotor's take 6-30 s there).
    "pervasive": (lambda s, w: gk.pervasive(s, [0.0, w, 2.0 * w]), lambda s, w: ["--speeds", f"0:{2.0 * w!r}:3"],
                  ["pervasive_summary", "pervasive_damping"]),
    # A unit force at the first DOF, at half the top speed, over the scene's [speeds] grid.
    "frf": (lambda s, w: gk.frf(s, w, s.system.dof_names[0]),
            lambda s, w: ["--speed", repr(w), "--input", s.system.dof_names[0]], ["frf"]),
    # 20 revolutions at half the top speed, from rest (an InputError, the same in both, without an unbalance).
    "transient": (lambda s, w: gk.transient(s, w, duration=_revolutions(s, w, 20)),
                  lambda s, w: ["--speed", repr(w), "--duration", repr(_revolutions(s, w, 20))], ["transient"]),
    # FE rotors (an InputError, the same in both, for the other models).
    "static": (lambda s, w: gk.static(s), lambda s, w: [], ["deflection", "static", "reactions", "internal_forces"]),
    "critical-map": (lambda s, w: gk.critical_speed_map(s), lambda s, w: [], ["critical_map", "bearing_curves"]),
}
PER_RAD_S = {"rad/s": 1.0, "Hz": 0.5 / np.pi, "rpm": 30.0 / np.pi}
PERVASIVE_SCENES = {"centrifuge.toml", "friswell_5_9_1.toml", "scene.toml", "three_disk_rotor.toml", "drive_train.toml",
                    "fe_rotor.toml"}


def _revolutions(scene, w, n):
    """The time of n revolutions at the speed w in the scene's units, s."""
    return 2.0 * np.pi * n * PER_RAD_S[scene.speed_unit] / w


if not CLI:
    pytest.skip("GYROKIT_CLI not set", allow_module_level=True)


def cli(*args):
    return subprocess.run([CLI, *args, "--format", "json"], check=True, capture_output=True, text=True)


@pytest.mark.parametrize("analysis", list(ANALYSES))
@pytest.mark.parametrize("path", SCENES, ids=lambda p: os.path.relpath(p, DATA))
def test_the_cli_and_python_give_the_same_rows_and_notes(tmp_path, path, analysis):
    scene = gk.load_scene(path)
    if scene.speeds is None or len(scene.speeds) == 0:
        pytest.skip("no [speeds] in the scene")
    if analysis == "pervasive" and os.path.basename(path) not in PERVASIVE_SCENES:
        pytest.skip("pervasive: the scenes quick on three speeds only")
    call, args, keys = ANALYSES[analysis]
    # The one-speed analyses at half the top speed, in the scene's [speeds] units (both front ends' default).
    per_rad_s = PER_RAD_S[scene.speed_unit]
    w = float(np.max(scene.speeds)) / 2.0 * per_rad_s
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")   # the unstable ranges: compared below as the result's `warnings`
            result = call(scene, w)
    except (gk.InputError, gk.SolverError) as e:
        # Bad input (a solver's failure) is the same error in both, with the CLI's exit status 2 (3).
        bad = subprocess.run([CLI, analysis, path, *args(scene, w), "--format", "json"], capture_output=True,
                             text=True)
        status, word = (2, "error") if isinstance(e, gk.InputError) else (3, "solver error")
        assert bad.returncode == status and f"{word}: {e}" in bad.stderr.splitlines()
        return
    run = cli(analysis, path, *args(scene, w))
    tables = json.load(open(result.save(tmp_path / "result.json")))
    printed = json.loads(run.stdout)
    if isinstance(printed, dict):   # several tables: each by its key
        assert printed == {key: tables[key] for key in keys if key in tables}
    else:
        assert printed == [row for key in keys for row in tables.get(key, [])]
    lines = run.stderr.splitlines()
    # Each front end names the options in its own words (the library marks them): --modes 0, modes = 0.
    words = {"--modes 0": "modes = 0", "--f-cut": "f_cut =", "--rigid-body lists": "result.rigid_body lists"}
    spelled = []
    for x in lines:
        for flag, keyword in words.items():
            x = x.replace(flag, keyword)
        spelled.append(x)
    notes = getattr(result, "notes", None)
    if notes is not None:
        assert [f"note: {n}" for n in notes] == [x for x in spelled if x.startswith("note: ")]
    warned = getattr(result, "warnings", None)
    if warned is not None:
        assert [f"warning: {n}" for n in warned] == [x for x in spelled if x.startswith("warning: ")]


FLUID_SCENES = sorted(glob.glob(os.path.join(DATA, "fluid_N*.toml")))


@pytest.mark.parametrize("fill", [None, (0.05, 0.55, 11)])
@pytest.mark.parametrize("path", FLUID_SCENES, ids=os.path.basename)
def test_the_fluid_study_is_the_same_in_both(tmp_path, path, fill):
    # gyrokit fluid and gyrokit.fluid run one study (fluid_study): the same tables, bit for bit, and notes.
    scene = gk.load_scene(path)
    R = float(tomllib.load(open(path, "rb"))["model"]["R"])
    args = []
    if fill is not None:
        lo, hi, n = fill[0] * R / 0.6, fill[1] * R / 0.6, fill[2]   # inside 0 < R0 < R
        args = ["--fill", f"{lo!r}:{hi!r}:{n}"]
        # The CLI's FROM:TO:N points (from + (to - from) i / (N - 1), the last one TO), so that both solve alike.
        result = gk.fluid(scene, fill=[lo + (hi - lo) * i / (n - 1) for i in range(n - 1)] + [hi])
    else:
        result = gk.fluid(scene)
    run = cli("fluid", path, *args)
    tables = json.load(open(result.save(tmp_path / "fluid.json")))
    printed = json.loads(run.stdout)
    if isinstance(printed, dict):
        assert printed == {key: tables[key] for key in printed}
    else:
        assert len(tables) == 1 and printed == next(iter(tables.values()))
    assert [f"note: {n}" for n in result.notes] == [x for x in run.stderr.splitlines() if x.startswith("note: ")]


BALANCER_SCENES = sorted(glob.glob(os.path.join(DATA, "balancer_*.toml")) +
                         glob.glob(os.path.join(DATA, "sommerfeld_*.toml")))


@pytest.mark.parametrize("path", BALANCER_SCENES, ids=os.path.basename)
@pytest.mark.parametrize("analysis", ["balancer", "sommerfeld"])
def test_the_balancer_studies_are_the_same_in_both(tmp_path, path, analysis):
    # gyrokit balancer / sommerfeld and gyrokit.balancer / sommerfeld run one study each (balancer_study,
    # sommerfeld_study): every table, bit for bit; a scene one of them refuses, the same error in both.
    call = {"balancer": gk.balancer, "sommerfeld": gk.sommerfeld}[analysis]
    try:
        result = call(path)
    except gk.InputError as e:
        bad = subprocess.run([CLI, analysis, path, "--format", "json"], capture_output=True, text=True)
        assert bad.returncode == 2 and f"error: {e}" in bad.stderr.splitlines()
        return
    printed = json.loads(cli(analysis, path).stdout)
    assert printed == json.load(open(result.save(tmp_path / "result.json")))


def _points(lo, hi, n):
    """The library's grid FROM:TO:N (SpeedRange::points): lo + (hi - lo) i / (n - 1), the last one hi."""
    return [lo + (hi - lo) * i / (n - 1) for i in range(n - 1)] + [hi]


def test_screening_judges_with_the_quantities_of_the_studies(tmp_path):
    # One design of data/fe_rotor.toml (the first disk's mass as given) screened for separation, stability
    # and response: the screening's critical speed, instability onset and largest response are those of
    # gk.critical_speeds, gk.stability and gk.response on the same scene over each criterion's speeds (the
    # separation scan 0 to 1.05 (1 + margin) x the top operating speed in 121 speeds, the stability scan 0 to
    # up_to in `count` speeds, the response the operating speeds: grids built as the library builds them).
    # Tolerance: the result file's 12 digits.
    sweep = tmp_path / "sweep.toml"
    sweep.write_text(f"""scene = "{os.path.join(DATA, 'fe_rotor.toml')}"
units = "rad/s"
[[parameter]]
name = "model.disk[0].mass"
values = [33.657]
[operating]
from = 100.0
to = 300.0
count = 21
[criteria.separation]
margin_percent = 5.0
[criteria.stability]
up_to = 400.0
count = 41
[criteria.response]
max_amplitude = 1e-3
dofs = ["x8", "y8"]
""")
    r = gk.screen(str(sweep), jobs=1)
    q = {k: v[0] for k, v in r.quantities.items()}
    scene = gk.load_scene(os.path.join(DATA, "fe_rotor.toml"))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")   # the response's unstable range: the stability criterion's concern
        critical = gk.critical_speeds(scene, _points(0.0, 300.0 * (1.0 + 5.0 / 100.0) * 1.05, 121))
        stability = gk.stability(scene, _points(0.0, 400.0, 41))
        response = gk.response(scene, _points(100.0, 300.0, 21), dofs=["x8", "y8"])
    assert min(abs(critical.speeds - q["critical_speed_rad_s"])) <= 1e-11 * q["critical_speed_rad_s"]
    onset = min(w for w, up in zip(stability.speeds, stability.becomes_unstable) if up)
    assert q["instability_onset_rad_s"] == pytest.approx(onset, rel=1e-11)
    peaks = response.table("response_maxima")
    largest = max(peaks.rows, key=lambda row: row[peaks.columns.index("max_amplitude")])
    assert q["max_amplitude"] == pytest.approx(largest[peaks.columns.index("max_amplitude")], rel=1e-11)
    assert q["max_amplitude_speed_rad_s"] == pytest.approx(largest[peaks.columns.index("speed_rad_s")], rel=1e-11)
    assert r.verdict[0] == "fail" and "stability: mode" in r.reason[0] and "response:" in r.reason[0]
