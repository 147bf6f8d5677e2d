"""Results carry what the CLI shows: its tables (the same bytes as the CLI's CSV), its units, its figures
(matplotlib or gnuplot), log decrements against the library's, option names in Python's words, and files
written and read back."""
import json
import os
import subprocess

import numpy as np
import pytest

import gyrokit as gk
from scenes import three_disk_in_rad_s

DATA = os.environ.get("GYROKIT_DATA", os.path.join(os.path.dirname(__file__), "..", "..", "data"))
CLI = os.environ.get("GYROKIT_CLI")
SCENE_RPM = os.path.join(DATA, "three_disk_rotor.toml")
EPS = np.finfo(float).eps


SCENE = three_disk_in_rad_s(SCENE_RPM)


def cli(*args):
    if not CLI:
        pytest.skip("GYROKIT_CLI not set")
    return subprocess.run([CLI, *args], check=True, capture_output=True, text=True).stdout


@pytest.fixture(scope="module")
def scene():
    return gk.load_scene(SCENE)


@pytest.fixture(scope="module")
def diagram(scene):
    return gk.campbell(scene, unit="rpm")


def test_the_campbell_table_is_the_clis_csv_byte_for_byte(tmp_path, diagram):
    path = diagram.save(tmp_path / "campbell.csv", table="campbell")
    assert open(path).read() == cli("campbell", SCENE, "--units", "rpm", "--format", "csv")
    assert [t.key for t in diagram.tables] == ["summary", "campbell", "critical_speeds", "heavily_damped_crossings"]


def test_units_per_call_scale_speeds_and_frequencies_only(scene, diagram):
    rad = gk.campbell(scene, unit="rad/s")
    f = 30.0 / np.pi
    np.testing.assert_allclose(diagram.speeds, rad.speeds * f, rtol=2 * EPS, atol=0)
    np.testing.assert_allclose(diagram.frequencies, rad.frequencies * f, rtol=2 * EPS, atol=0)
    np.testing.assert_array_equal(diagram.eigenvalues, rad.eigenvalues)   # 1/s in every unit, as the CLI
    hz = gk.critical_speeds(scene, unit="Hz")
    assert hz.tables[0].columns[0] == "speed_hz"
    np.testing.assert_allclose(hz.speeds, gk.critical_speeds(scene, unit="rad/s").speeds / (2 * np.pi), rtol=2 * EPS,
                               atol=0)
    # Speeds given in the call's unit: 3000 rpm is 100 pi rad/s.
    e = gk.eig(scene, 3000.0, unit="rpm")
    assert e.speed == pytest.approx(3000.0, rel=4 * EPS)
    ref = gk.eig(scene, 100 * np.pi, unit="rad/s")
    # The speeds differ by the rounding of rpm -> rad/s (an ulp): within the two error bounds.
    assert np.all(np.abs(e.eigenvalues - ref.eigenvalues) <= e.error_bounds + ref.error_bounds)
    with pytest.raises(gk.InputError, match="unit = 'rps' is unknown; allowed: rad/s, Hz, rpm"):
        gk.campbell(scene, unit="rps")


def test_a_scene_in_rpm_gives_rpm_unless_a_call_names_a_unit():
    # The scene's [speeds] are in rpm: every result is, as the CLI's (resolve_request decides for both).
    scene = gk.load_scene(SCENE_RPM)
    assert scene.speed_unit == "rpm"
    for result in (gk.campbell(scene), gk.critical_speeds(scene), gk.stability(scene), gk.eig(scene, 3000.0),
                   gk.modes(scene, 3000.0), gk.response(scene, peaks=False, stability_check=False)):
        assert result.unit == "rpm"
    c = gk.critical_speeds(scene)
    assert c.tables[0].columns[0] == "speed_rpm"
    assert cli("critical", SCENE_RPM, "--format", "csv").splitlines()[0].startswith("speed_rpm,")
    np.testing.assert_allclose(c.speeds, gk.critical_speeds(scene, unit="rad/s").speeds * 30 / np.pi, rtol=4 * EPS)
    # Speeds given by the call are in that unit too: 3000 rpm.
    assert gk.eig(scene, 3000.0).speed == pytest.approx(3000.0, rel=4 * EPS)
    assert gk.campbell(scene, speeds=[0.0, 6000.0]).speeds[-1] == pytest.approx(6000.0, rel=4 * EPS)


def test_log_decrements_and_damping_ratios_equal_the_librarys(diagram):
    t = diagram.table("campbell")
    rows = {(r[t.columns.index("speed_rpm")], r[t.columns.index("mode")]): r for r in t.rows}
    checked = 0
    for i, w in enumerate(diagram.speeds):
        for b, branch in enumerate(diagram.branches):
            r = rows.get((w, int(branch)))
            if r is None or np.isnan(diagram.log_decrements[i, b]):
                continue
            # numpy's -2 pi Re/Im against Mode::log_decrement: a few roundings apart.
            assert diagram.log_decrements[i, b] == pytest.approx(r[t.columns.index("log_dec")], rel=8 * EPS, abs=0)
            assert diagram.damping_ratios[i, b] == pytest.approx(r[t.columns.index("damping_ratio")], rel=8 * EPS)
            checked += 1
    assert checked > 100


def test_log_decrements_of_real_eigenvalues_are_the_clis_infinities():
    # Mode::log_decrement: a decaying real eigenvalue +inf, a growing one -inf, zero 0; no point: NaN.
    lam = np.array([-3.0 + 0j, 2.0 + 0j, 0j, complex(np.nan, np.nan), -1.0 + 2.0j])
    d = gk._log_dec(lam)
    assert d[0] == np.inf and d[1] == -np.inf and d[2] == 0.0 and np.isnan(d[3])
    assert d[4] == pytest.approx(np.pi, rel=2 * EPS)


def test_notes_and_tables_name_options_in_pythons_words(diagram):
    summary = str(diagram.tables[0])
    assert "modes = 0 judges every mode" in summary and "--modes" not in summary and "--rows" not in summary
    assert "all rows: result.table('campbell')" in summary
    assert any("modes = 0" in n for n in diagram.notes)
    assert "rpm" in diagram.notes[-1]   # the diagnostics speak the call's unit
    text = cli("campbell", SCENE)
    assert "--modes 0 judges every mode" in text and "(all rows: --rows, or --format csv|json)" in text


def test_tables_saved_and_loaded_json_exact_csv_to_its_digits(tmp_path, diagram):
    diagram.save(tmp_path / "all.json")
    loaded = gk.load_tables(tmp_path / "all.json")
    assert [t.key for t in loaded] == [t.key for t in diagram.tables]
    for a, b in zip(loaded, diagram.tables):
        assert a.columns == b.columns and a.rows == b.rows   # JSON keeps every bit
    diagram.save(tmp_path / "critical.csv", table="critical_speeds")
    (c,) = gk.load_tables(tmp_path / "critical.csv")
    ref = diagram.table("critical_speeds")
    assert c.columns == ref.columns
    for x, y in zip(sum(c.rows, []), sum(ref.rows, [])):
        if isinstance(y, float):
            assert x == pytest.approx(y, rel=1e-11)   # %.12g
        else:
            assert x == y
    diagram.save(tmp_path / "summary.txt", table="summary")
    assert open(tmp_path / "summary.txt").read() == str(diagram.tables[0])
    with pytest.raises(gk.InputError, match="allowed: .json, .csv, .txt"):
        diagram.save(tmp_path / "x.xlsx")
    with pytest.raises(gk.InputError, match="table 'nope'; allowed: summary, campbell"):
        diagram.save(tmp_path / "x.csv", table="nope")


def test_figures_are_the_clis_drawn_by_matplotlib_or_gnuplot(tmp_path, scene, diagram):
    pytest.importorskip("matplotlib")
    import matplotlib
    import matplotlib.figure
    matplotlib.use("Agg")
    fig = diagram.plot()
    assert len(fig.axes) == 2   # frequencies with the 1x line, damping ratio below
    assert fig.axes[0].get_ylabel() == "frequency [rpm]"
    diagram.plot(tmp_path / "campbell.png")   # gnuplot, as --plot
    cli("campbell", SCENE, "--units", "rpm", "--plot", str(tmp_path / "cli.png"))
    assert os.path.getsize(tmp_path / "campbell.png") > 1000 and os.path.getsize(tmp_path / "cli.png") > 1000
    shapes = gk.modes(scene, 600.0, modes=3)
    labels = [line.get_label() for line in shapes.plot().axes[0].lines]
    assert "disks" in labels and "bearings" in labels   # marked on the axis, as the CLI draws them
    # One mode alone, or a chosen few: the CLI's figure of `gyrokit modes --mode 2` (one line per mode per panel).
    every = shapes.plot()
    alone = shapes.plot(mode=2)
    pair = shapes.plot(mode=[1, 3])
    shape_lines = lambda fig: [l for l in fig.axes[0].lines if l.get_label().startswith("mode")]
    assert len(shape_lines(every)) == 3 and len(shape_lines(alone)) == 1 and len(shape_lines(pair)) == 2
    assert shape_lines(alone)[0].get_label().startswith("mode 2")
    with pytest.raises(gk.InputError, match="mode = 4; allowed: 1, 2, 3"):
        shapes.plot(mode=4)
    with pytest.raises(gk.InputError, match="mode = 1.5; allowed"):
        shapes.plot(mode=1.5)
    assert len(shape_lines(shapes.plot(mode=np.int64(2)))) == 1   # a NumPy whole number is one
    for bad in (np.True_, True, "2", [], [1, "x"]):
        with pytest.raises(gk.InputError, match="allowed"):
            shapes.plot(mode=bad)
    with pytest.raises(gk.InputError, match="allowed: one of 1, 2, 3"):
        shapes.plot_orbits([2, 3])
    shapes.plot(tmp_path / "mode2.svg", mode=2)   # gnuplot, as --mode 2 --plot
    assert "<svg" in open(tmp_path / "mode2.svg").read()
    orbits = shapes.plot_orbits(2)
    assert isinstance(orbits, matplotlib.figure.Figure)   # a Figure, as every plot() returns
    ax = orbits.axes[0]
    pairs = sum(1 for k in range(len(shapes.orbits["mode"]))
                if shapes.orbits["mode"][k] == 2 and shapes.orbits["unit"][k] == "m")
    assert len(ax.lines) == pairs + 1   # an ellipse per node, the axis
    # x and y on one scale: the same limits and the same box side, so an orbit keeps its shape.
    assert ax.get_ylim() == ax.get_zlim()
    aspect = ax.get_box_aspect()
    assert aspect[1] == pytest.approx(aspect[2], rel=1e-12)
    r = gk.response(scene, np.linspace(0.0, 1500.0, 16), dofs=["x12", "y12"])
    assert r.table("response").columns[:2] == ["speed_rad_s", "dof"]
    r.plot_polar(tmp_path / "polar.svg")
    assert "<svg" in open(tmp_path / "polar.svg").read()
    assert ">500 rad/s<" in open(tmp_path / "polar.svg").read()   # speed marks along the curve (gnuplot)
    marks = [t.get_text() for t in r.plot_polar().axes[0].texts]   # and with matplotlib
    assert "500 rad/s" in marks and all(m.endswith(" rad/s") for m in marks)
    with pytest.raises(gk.InputError, match="axes: 1 given; allowed: one per panel"):
        diagram.plot(axes=[fig.axes[0]])


def test_frf_static_map_and_summary_carry_the_clis_tables(tmp_path, scene):
    f = gk.frf(scene, 600.0, "y12", np.array([0.0, 400.0, 800.0, 1200.0]))
    assert open(f.save(tmp_path / "frf.csv")).read() == cli(
        "frf", SCENE, "--input", "y12", "--speed", "600", "--frequencies", "0:1200:4", "--format", "csv")
    s = gk.static(scene)
    s.save(tmp_path / "static.json")
    assert json.load(open(tmp_path / "static.json")) == json.loads(cli("static", SCENE, "--format", "json"))
    m = gk.critical_speed_map(scene, stiffness=[1e7, 1e8], modes=2, unit="rpm")
    assert open(m.save(tmp_path / "map.csv")).read() == cli(
        "critical-map", SCENE, "--stiffness", "1e7:1e8:2", "--modes", "2", "--units", "rpm", "--format", "csv")
    text = cli("model", SCENE)
    summary = gk.summary(scene)
    assert str(summary) in text   # the CLI heads it with the scene's path
    pytest.importorskip("matplotlib")
    import matplotlib
    matplotlib.use("Agg")
    for result in (s, m, summary, f):
        assert result.plot().axes
    f.plot_polar(tmp_path / "frf_polar.png")
    assert os.path.getsize(tmp_path / "frf_polar.png") > 1000


def test_a_transient_run_carries_the_clis_table_and_pictures(tmp_path, scene):
    r = gk.transient(scene, 600.0, duration=0.05, start="steady")
    assert open(r.save(tmp_path / "run.csv")).read() == cli(
        "transient", SCENE, "--speed", "600", "--duration", "0.05", "--start", "steady", "--format", "csv")
    r.plot(tmp_path / "orbit.png")
    r.plot_waterfall(tmp_path / "waterfall.svg")
    assert os.path.getsize(tmp_path / "orbit.png") > 1000 and "<svg" in open(tmp_path / "waterfall.svg").read()


def test_response_is_the_clis_study(tmp_path, scene):
    # One study (lib/gyrokit/study/response_study.hpp): the same curve, refined peaks and summary as the CLI.
    args = ("response", SCENE, "--speeds", "0:1500:16", "--dofs", "x12,y12")
    r = gk.response(scene, np.linspace(0.0, 1500.0, 16), dofs=["x12", "y12"], extrema=True)
    assert [t.key for t in r.tables] == ["response", "response_maxima", "response_peaks"]
    assert open(r.save(tmp_path / "curve.csv")).read() == cli(*args, "--format", "csv")   # the curve by default
    assert open(r.save(tmp_path / "peaks.csv", table="response_peaks")).read() == cli(
        *args, "--extrema", "--format", "csv")
    assert str(r.table("response_maxima")).strip() == cli(*args).strip()
    # The grid maxima are not what the summary reports: a peak refined between grid speeds is higher.
    top = r.table("response_maxima").column("max_amplitude")
    assert all(m > a for m, a in zip(top, r.amplitude.max(axis=0)))
    quick = gk.response(scene, np.linspace(0.0, 1500.0, 16), dofs=["x12", "y12"], stability_check=False, peaks=False)
    np.testing.assert_array_equal(quick.amplitudes, r.amplitudes)
    assert [t.key for t in quick.tables] == ["response"]
    with pytest.raises(gk.InputError, match="dofs: empty"):
        gk.response(scene, [100.0], dofs=[])


def test_probes_at_any_angle_read_x_cos_plus_y_sin_as_the_cli(tmp_path, scene):
    speeds = np.linspace(0.0, 1500.0, 16)
    xy = gk.response(scene, speeds, dofs=["x12", "y12"])
    p = gk.response(scene, speeds, probes=[(12, 0), (12, 90), (12, 30)])
    assert p.dofs == ["12@0", "12@90", "12@30"]
    np.testing.assert_array_equal(p.amplitudes[:, 0], xy.amplitudes[:, 0])   # 0 and 90 degrees: exact
    np.testing.assert_array_equal(p.amplitudes[:, 1], xy.amplitudes[:, 1])
    c, s = np.cos(np.pi / 6), np.sin(np.pi / 6)
    ref = c * xy.amplitudes[:, 0] + s * xy.amplitudes[:, 1]
    assert np.all(np.abs(p.amplitudes[:, 2] - ref) <= 4 * EPS * (np.abs(xy.amplitudes[:, 0]) + np.abs(xy.amplitudes[:, 1])))
    f = gk.frf(scene, 600.0, "y12", np.array([0.0, 600.0, 1200.0]), probes=[(12, 90), (12, -45)])
    assert open(f.save(tmp_path / "frf.csv")).read() == cli(
        "frf", SCENE, "--input", "y12", "--speed", "600", "--frequencies", "0:1200:3", "--probes", "12@90,12@-45",
        "--format", "csv")
    with pytest.raises(gk.InputError, match=r"probes\[0\]: node 99 does not exist; allowed: 0 to 24"):
        gk.response(scene, speeds, probes=[(99, 0)])
    with pytest.raises(gk.InputError, match="dofs and probes: allowed: one of them"):
        gk.frf(scene, 600.0, "y12", [0.0], dofs=["x12"], probes=[(12, 0)])


def _pinned(tmp_path, unit, scale):
    path = tmp_path / f"pinned_{unit}.toml"
    path.write_text(f"""[model]
type = "fe_rotor"
material = "steel"
length_unit = "{unit}"
[[model.shaft]]
length = {1.0 * scale}
elements = 4
outer_diameter = {0.05 * scale}
[[model.disk]]
z = {0.5 * scale}
outer_diameter = {0.2 * scale}
width = {0.03 * scale}
unbalance = 1e-4
[[model.support]]
z = 0
[[model.support]]
z = {1.0 * scale}
""")
    return gk.load_scene(str(path))


def test_an_mm_scene_prints_lengths_in_mm_and_keeps_arrays_si(tmp_path):
    m, mm = _pinned(tmp_path, "m", 1.0), _pinned(tmp_path, "mm", 1000.0)
    assert (m.length_unit, mm.length_unit) == ("m", "mm")
    speeds = np.linspace(100.0, 1000.0, 4)
    a, b = gk.response(m, speeds, dofs=["x2", "y2"]), gk.response(mm, speeds, dofs=["x2", "y2"])
    # The mm scene's inputs differ from the m scene's by the rounding of 1e-3: a few ulp in the results.
    np.testing.assert_allclose(b.amplitude, a.amplitude, rtol=1e-12)        # arrays: SI in both
    ta, tb = a.table("response"), b.table("response")
    assert set(tb.column("unit")) == {"mm"} and set(ta.column("unit")) == {"m"}
    np.testing.assert_allclose(tb.column("amplitude"), 1000.0 * np.array(ta.column("amplitude")), rtol=1e-12)
    f = gk.frf(mm, 300.0, "y2", [100.0, 400.0])
    assert set(f.table("frf").column("unit")) == {"mm/N"}
    tr = gk.transient(mm, 300.0, duration=0.2, node=2, start="steady").table("transient")
    assert set(tr.column("unit")) == {"mm"}
    peaks = np.array(tr.column("peak")) / np.array(tr.column("steady"))
    assert np.all(np.abs(peaks - 1.0) < 0.01)   # started steady: the peaks are the steady amplitude, both in mm
    rows = {r[0]: (r[1], r[2]) for r in gk.summary(mm).tables[0].rows}
    assert rows["disk1_z"] == (pytest.approx(500.0, rel=1e-12), "mm")
