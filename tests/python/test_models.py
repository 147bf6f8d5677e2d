"""FE rotors built in Python: equal to their scene files, written back as TOML, pickled, screened."""
import os
import pickle

import numpy as np
import pytest

import gyrokit as gk

DATA = os.environ.get("GYROKIT_DATA", os.path.join(os.path.dirname(__file__), "..", "..", "data"))

# Steel as the library's material table has it (Friswell et al.): E, G = 81.2 GPa, density.
STEEL = dict(E=211e9, poisson=211e9 / (2 * 81.2e9) - 1, density=7810.0)


def three_disk_rotor():
    """data/three_disk_rotor.toml, built in Python."""
    sections = [gk.Section(length=L, elements=n, outer_diameter=d, **STEEL)
                for L, n, d in ((0.1, 2, 0.06), (0.25, 5, 0.09), (0.5, 10, 0.10), (0.25, 5, 0.09), (0.1, 2, 0.06))]
    disks = [gk.Disk(z=0.35, outer_diameter=0.32, inner_diameter=0.10, width=0.05, density=7810.0),
             gk.Disk(z=0.6, outer_diameter=0.40, inner_diameter=0.10, width=0.07, density=7810.0, unbalance=2e-4),
             gk.Disk(z=0.85, outer_diameter=0.32, inner_diameter=0.10, width=0.05, density=7810.0)]
    bearings = [gk.Bearing(z=z, kxx=2e7, kyy=1.5e7, cxx=3e4, cyy=3e4) for z in (0.05, 1.15)]
    return gk.Rotor(sections=sections, disks=disks, bearings=bearings)


def dense(A):
    return A.toarray() if hasattr(A, "toarray") else np.asarray(A)


def assert_same_model(a, b):
    """Bit for bit: the same description gives the same matrices."""
    for name in ("M", "K", "G"):
        assert np.array_equal(dense(getattr(a.system, name)), dense(getattr(b.system, name))), name
    assert np.array_equal(dense(a.system.damping_matrix(0.0)), dense(b.system.damping_matrix(0.0)))
    assert np.array_equal(a.system.unbalance, b.system.unbalance)
    assert a.system.dof_names == b.system.dof_names


def test_a_rotor_built_in_python_equals_its_scene_file():
    built = gk.rotor_scene(three_disk_rotor(), title="three disks")
    assert_same_model(built, gk.load_scene(os.path.join(DATA, "three_disk_rotor.toml")))
    assert built.model_type == "fe_rotor" and built.title == "three disks"
    assert [b.kind for b in built.rotor.bearings] == ["constant", "constant"]


def test_named_materials_give_the_scenes_values_and_sections_read_back_from_their_repr():
    # data/three_disk_rotor.toml names "steel"; the same rotor by material name is the same model bit for bit
    # (by hand with the default poisson 0.3 it would not be: K differs by about 6e-5).
    steel = {m.name: m for m in gk.materials()}["steel"]
    assert (steel.E, steel.density, steel.poisson) == (STEEL["E"], STEEL["density"], STEEL["poisson"])
    by_name = three_disk_rotor()
    by_name = gk.Rotor(sections=[gk.Section(length=s.length, elements=s.elements, outer_diameter=s.outer_diameter,
                                            material="steel") for s in by_name.sections],
                       disks=[gk.Disk(z=d.z, outer_diameter=g[0], inner_diameter=0.10, width=g[1], material=steel,
                                      unbalance=d.unbalance)
                              for d, g in zip(by_name.disks, ((0.32, 0.05), (0.40, 0.07), (0.32, 0.05)))],
                       bearings=by_name.bearings)
    assert_same_model(gk.rotor_scene(by_name), gk.load_scene(os.path.join(DATA, "three_disk_rotor.toml")))
    # A value given wins over its material's, as in a scene.
    assert gk.Section(length=1.0, outer_diameter=0.05, material="aluminium", density=2800.0).density == 2800.0
    # Readable reprs that read back to the same object.
    s = gk.Section(length=0.25, elements=5, outer_diameter=0.09, inner_diameter=0.02, material="titanium")
    assert repr(s) == ("Section(length=0.25, outer_diameter=0.09, inner_diameter=0.02, elements=5, E=113800000000.0, "
                       "density=4430.0, poisson=0.342)")
    back = eval(repr(s), {"Section": gk.Section})
    assert (back.E, back.density, back.poisson, back.inner_diameter) == (s.E, s.density, s.poisson, s.inner_diameter)
    assert repr(gk.coupling(length=0.1, k_lateral=1e7, mass=2.0)) == "coupling(length=0.1, k_lateral=10000000.0, mass=2.0)"
    assert repr(by_name.disks[1]).startswith("Disk(z=0.6, outer_diameter=0.4, inner_diameter=0.1, width=0.07, "
                                             "density=7810.0, unbalance=0.0002")
    assert repr(steel) == "Material(name='steel', E=211000000000.0, density=7810.0, poisson=%r)" % STEEL["poisson"]
    # Phases in degrees read back to the same radians (30, not 29.999999999999996).
    assert repr(gk.Disk(z=0.2, mass=1.0, phase=30.0)) == "Disk(z=0.2, mass=1.0, phase=30.0)"
    for phase in (30.0, 69.0, 75.0, 138.0, 359.9, 1e-3):
        d = gk.Disk(z=0.2, mass=1.0, phase=phase)
        assert repr(eval(repr(d), {"Disk": gk.Disk})) == repr(d)
        assert gk.rotor_scene(gk.Rotor(sections=[gk.Section(length=0.4, elements=2, outer_diameter=0.05,
                                                            material="steel")],
                                       disks=[eval(repr(d), {"Disk": gk.Disk})],
                                       supports=[gk.Support(z=0.0), gk.Support(z=0.4)])).to_toml() == \
            gk.rotor_scene(gk.Rotor(sections=[gk.Section(length=0.4, elements=2, outer_diameter=0.05,
                                                         material="steel")],
                                    disks=[d], supports=[gk.Support(z=0.0), gk.Support(z=0.4)])).to_toml()
    own = gk.Material(name="inconel", E=2.05e11, density=8190.0, poisson=0.284)
    assert gk.Section(length=1.0, outer_diameter=0.05, material=own).poisson == 0.284
    with pytest.raises(gk.InputError, match="material = 'iron' is unknown; allowed: steel, stainless, aluminium"):
        gk.Section(length=1.0, outer_diameter=0.05, material="iron")
    with pytest.raises(gk.InputError, match="E is missing; required: a number > 0, or material"):
        gk.Section(length=1.0, outer_diameter=0.05)
    with pytest.raises(gk.InputError, match="material needs outer_diameter"):
        gk.Disk(z=0.5, mass=3.0, material="steel")
    with pytest.raises(gk.InputError, match="poisson = 0.5: allowed: -1 < poisson < 0.5"):
        gk.Material(name="rubber", E=1e6, density=1100.0, poisson=0.5)
    with pytest.raises(gk.InputError, match="material = 3: allowed: a gyrokit.Material"):
        gk.Section(length=1.0, outer_diameter=0.05, material=3)


def test_a_scene_in_mm_is_written_back_in_mm():
    s = gk.load_scene(os.path.join(DATA, "drive_train.toml"))
    text = s.to_toml()
    assert 'length_unit = "mm"' in text and "\nlength = 800.0\n" in text and "\nouter_diameter = 80.0\n" in text
    assert_same_model(s, gk._core.parse_scene(text, "written", "."))


def test_a_scene_round_trips_through_toml_pickle_and_a_file(tmp_path):
    s = gk.load_scene(os.path.join(DATA, "three_disk_rotor_journal.toml"))
    assert_same_model(s, gk._core.parse_scene(s.to_toml(), "written", "."))
    p = pickle.loads(pickle.dumps(s))
    assert_same_model(s, p)
    assert list(p.speeds) == list(s.speeds) and p.harmonics == s.harmonics and p.modes == s.modes
    s.write(str(tmp_path / "journal.toml"))
    w = gk.load_scene(str(tmp_path / "journal.toml"))
    assert_same_model(s, w)
    # The fluid films' coefficients at speed: the same bearings, not only the same constant matrices.
    for speed in (300.0, 1500.0):
        assert np.array_equal(dense(s.system.damping_matrix(speed)), dense(w.system.damping_matrix(speed)))


def test_rotor_scene_settings_and_bad_input_name_the_item():
    s = gk.rotor_scene(three_disk_rotor(), speeds={"from": 0, "to": 1500, "count": 31},
                       analysis={"modes": 8, "harmonics": [1, 2]})
    assert s.modes == 8 and s.harmonics == [1, 2] and len(s.speeds) == 31
    shaft = [gk.Section(length=1.0, elements=4, outer_diameter=0.05, **STEEL)]
    with pytest.raises(gk.InputError, match=r"bearings\[1\] z = 0.3 m is not a node of the mesh.*nearest is 0.25"):
        gk.rotor_scene(gk.Rotor(sections=shaft, bearings=[gk.Bearing(z=0, k=1e7), gk.Bearing(z=0.3, k=1e7)]))
    with pytest.raises(gk.InputError, match=r"sections\[0\]: outer_diameter = -0.05 is out of range"):
        gk.rotor_scene(gk.Rotor(sections=[gk.Section(length=1.0, outer_diameter=-0.05, **STEEL)]))
    with pytest.raises(gk.InputError, match=r"type = 'fixed'; allowed: pinned, clamped"):
        gk.Support(z=0, type="fixed")
    with pytest.raises(gk.InputError, match=r"density is missing"):
        gk.Section(length=1.0, outer_diameter=0.05, E=2e11)
    with pytest.raises(gk.InputError, match=r"modes = -3"):
        gk.rotor_scene(gk.Rotor(sections=shaft), analysis={"modes": -3})
    with pytest.raises(gk.InputError, match=r"speeds: unknown key 'stop'"):
        gk.rotor_scene(gk.Rotor(sections=shaft), speeds={"from": 0, "stop": 3})


def test_a_gyrostat_built_in_python_pickles_and_screens_as_its_text():
    # Scenes of every model read from a document write back as read: gk.gyrostat(...) travels to
    # executors and screens with scene= like an FE rotor.
    g = gk.gyrostat(A_G=2.0, B_G=2.0, A_R=0.09, C_R=0.1, m=8.0, s=0.25, eps=1e-3, c_G=300.0, c_T=2000.0, c_R=70.0,
                    speeds={"from": 0, "to": 40, "count": 41})
    back = pickle.loads(pickle.dumps(g))
    np.testing.assert_array_equal(back.system.M.toarray(), g.system.M.toarray())
    np.testing.assert_array_equal(back.system.K.toarray(), g.system.K.toarray())
    assert gk.eig(back, 20.0).eigenvalues.tolist() == gk.eig(g, 20.0).eigenvalues.tolist()
    sweep = os.path.join(DATA, "screen_centrifuge.toml")
    by_file = gk.screen(sweep, jobs=1)
    by_scene = gk.screen(sweep, jobs=1, scene=gk.load_scene(os.path.join(DATA, "centrifuge.toml")))
    assert by_scene.verdict == by_file.verdict and by_scene.reason == by_file.reason
    for q in by_file.quantities:
        np.testing.assert_array_equal(by_scene.quantities[q], by_file.quantities[q])


def same_rows(a, b):
    assert a.columns == b.columns and a.verdict == b.verdict and a.reason == b.reason
    for name in a.quantities:
        assert np.array_equal(a.quantities[name], b.quantities[name], equal_nan=True), name
    for name in a.parameters:
        assert np.array_equal(a.parameters[name], b.parameters[name]), name


def test_a_model_built_in_python_screens_as_its_written_scene_file(tmp_path):
    shaft = [gk.Section(length=0.6, elements=6, outer_diameter=0.05, **STEEL)]
    rotor = gk.Rotor(sections=shaft, disks=[gk.Disk(z=0.3, mass=20.0, Id=0.1, Ip=0.2, unbalance=1e-4)],
                     bearings=[gk.Bearing(z=0.0, k=1e7, c=2e3), gk.Bearing(z=0.6, k=1e7, c=2e3)])
    scene = gk.rotor_scene(rotor, title="disk rotor", analysis={"modes": 8})
    criteria = """
[[parameter]]
name = "k"
paths = ["model.bearing[*].kxx", "model.bearing[*].kyy"]
values = [5e6, 1e7, 4e7]

[operating]
from = 50
to = 150
count = 5

[criteria.separation]
margin_percent = 15

[criteria.stability]
up_to = 400
"""
    (tmp_path / "in_code.toml").write_text('title = "bearings"\n' + criteria)
    scene.write(str(tmp_path / "rotor.toml"))
    (tmp_path / "on_file.toml").write_text('title = "bearings"\nscene = "rotor.toml"\n' + criteria)
    given = gk.screen(str(tmp_path / "in_code.toml"), scene=scene, jobs=2)
    filed = gk.screen(str(tmp_path / "on_file.toml"), jobs=2)
    same_rows(given, filed)
    assert len(given.verdict) == 3 and set(given.verdict) <= {"pass", "fail"}
    # Designs given in Python, on an executor: the same rows as threads.
    from concurrent.futures import ThreadPoolExecutor
    designs = [{"k": 1e7}, {"k": 4e7}]
    with ThreadPoolExecutor(2) as pool:
        on_pool = gk.screen(str(tmp_path / "in_code.toml"), designs, scene=scene, executor=pool)
    same_rows(on_pool, gk.screen(str(tmp_path / "in_code.toml"), designs, scene=scene, jobs=1))
    with pytest.raises(gk.InputError, match="scene is missing"):
        gk.screen(str(tmp_path / "in_code.toml"))


def test_the_rotor_example_in_docs_python_md_runs_and_its_scene_file_reads_back(tmp_path):
    import re
    import subprocess
    text = open(os.path.join(os.path.dirname(os.path.abspath(DATA)), "docs", "python.md")).read()
    part = text[text.index("FE rotors built in code"):]
    block = re.findall(r"```python\n(.*?)```", part, re.S)[0]
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        namespace = {"gk": gk}
        exec(compile(block, "docs/python.md", "exec"), namespace)
    finally:
        os.chdir(cwd)
    written = gk.load_scene(str(tmp_path / "pump.toml"))
    assert_same_model(namespace["scene"], written)
    # The CLI reads it as the library wrote it.
    out = subprocess.run([os.environ["GYROKIT_CLI"], "model", str(tmp_path / "pump.toml")], capture_output=True,
                         text=True)
    assert out.returncode == 0, out.stderr


def test_static_matches_the_cli_and_the_docs_example_runs():
    import csv
    import io
    import subprocess
    scene = os.path.join(DATA, "three_disk_rotor_journal.toml")
    s = gk.static(gk.load_scene(scene), loads=[{"node": 12, "fy": -500.0}])
    out = subprocess.run([os.environ["GYROKIT_CLI"], "static", scene, "--load", "12:0:-500", "--format", "csv",
                          "--table", "reactions"], capture_output=True, text=True, check=True).stdout
    rows = list(csv.DictReader(io.StringIO(out)))
    assert [r["reaction"] for r in rows] == list(s.reactions["reaction"]) == ["bearing 1", "bearing 2"]
    for r, fy in zip(rows, s.reactions["fy"]):
        assert float(r["fy_n"]) == pytest.approx(fy, rel=1e-11)   # CSV prints 12 digits
    # The weight and the load, carried half and half by the symmetric rotor's films.
    assert sum(s.reactions["fy"]) == pytest.approx(s.weight + 500.0, rel=1e-12)
    assert s.error_bound < 1e-9 and s.balance_error < 1e-12
    assert len(s.to_pandas("sections")) == 2 * 24
    with pytest.raises(gk.InputError, match=r"loads\[0\]: 'fz'"):
        gk.static(gk.load_scene(scene), loads=[{"node": 1, "fz": 1.0}])
    with pytest.raises(gk.InputError, match="allowed: an fe_rotor model"):
        gk.static(gk.load_scene(os.path.join(DATA, "centrifuge.toml")))
    # The Python block of docs/static.md, run from the repository's root.
    import re
    root = os.path.dirname(os.path.abspath(DATA))
    block = re.findall(r"```python\n(.*?)```", open(os.path.join(root, "docs", "static.md")).read(), re.S)[0]
    import matplotlib
    matplotlib.use("Agg")
    cwd = os.getcwd()
    os.chdir(root)
    try:
        exec(compile(block, "docs/static.md", "exec"), {"gk": gk})
    finally:
        os.chdir(cwd)


def test_critical_speed_map_matches_the_cli():
    import csv
    import io
    import subprocess
    scene = os.path.join(DATA, "three_disk_rotor.toml")
    m = gk.critical_speed_map(gk.load_scene(scene), stiffness=[1e7, 1e8, 1e9], modes=2, unit="rpm")
    out = subprocess.run([os.environ["GYROKIT_CLI"], "critical-map", scene, "--stiffness", "1e7:1e9:3", "--modes", "2",
                          "--units", "rpm", "--format", "csv"], capture_output=True, text=True, check=True).stdout
    rows = list(csv.DictReader(io.StringIO(out)))
    frame = m.to_pandas()
    assert len(rows) == len(frame) == 3 * 4 + 4
    for r, (_, p) in zip(rows, frame.iterrows()):
        assert r["whirl"] == p["whirl"] and int(r["critical"]) == p["critical"]
        assert float(r["speed_rpm"]) == pytest.approx(p["speed"], rel=1e-11)
    assert np.all(np.isinf(m.rigid["stiffness"])) and m.max_backward_error < 1e-12
    with pytest.raises(gk.InputError, match="unit = 'rps'"):
        gk.critical_speed_map(gk.load_scene(scene), unit="rps")
    with pytest.raises(gk.InputError, match="allowed: an fe_rotor model"):
        gk.critical_speed_map(gk.load_scene(os.path.join(DATA, "centrifuge.toml")))


def test_level1_matches_the_cli_and_runs_on_a_rotor_built_in_python():
    import json
    import subprocess
    scene = os.path.join(DATA, "three_disk_rotor.toml")
    l1 = gk.level1(gk.load_scene(scene))
    out = subprocess.run([os.environ["GYROKIT_CLI"], "level1", scene, "--format", "json", "--table", "level1_curve"],
                         capture_output=True, text=True, check=True).stdout
    rows = json.loads(out)
    assert len(rows) == len(l1.q) == 21   # 20 steps, QA among them
    for r, q, d in zip(rows, l1.q, l1.log_decrement):
        assert r["Q_N_m"] == pytest.approx(q, rel=1e-14)
        assert r["log_decrement"] == pytest.approx(d, abs=1e-7)
    assert l1.unit == "rpm" and l1.layout == "between bearings" and not l1.level2_required
    assert l1.q0 is not None and abs(l1.q0 / l1.qa - 3.448) < 1e-3 and l1.q0_bound < 1e-6 * l1.q0
    assert sum(l1.stage_qa) == pytest.approx(l1.qa, rel=1e-14)
    assert l1.csr == pytest.approx(10000 / l1.rigid_critical, rel=1e-12)
    # The same rotor built in Python has no [api]: the machine data come as keywords.
    built = gk.level1(gk.rotor_scene(three_disk_rotor()), mcs=10000 * 2 * np.pi / 60, qa=l1.qa, gas_density=40)
    assert built.q0 == pytest.approx(l1.q0, rel=1e-6)
    assert built.unit == "rad/s" and built.stage_qa == []
    with pytest.raises(gk.InputError, match="mcs ="):
        gk.level1(gk.rotor_scene(three_disk_rotor()), qa=1e6)
    with pytest.raises(gk.InputError, match="Level I needs an FE rotor"):
        gk.level1(gk.load_scene(os.path.join(DATA, "centrifuge.toml")), mcs=10, qa=1)
    with pytest.raises(gk.InputError, match="expected a gyrokit.Scene"):
        gk.level1(scene)


def test_level1_at_both_ends_of_the_films_bands_in_python_and_the_cli(tmp_path):
    import json
    import subprocess
    rotor = three_disk_rotor()
    band = dict(diameter=0.06, length=0.03, clearance=60e-6, viscosity=0.015, clearance_min=50e-6,
                clearance_max=75e-6, viscosity_min=0.011, viscosity_max=0.024)
    rotor = gk.Rotor(sections=rotor.sections, disks=rotor.disks,
                     bearings=[gk.Bearing.fluid_film(z=z, **band) for z in (0.05, 1.15)])
    scene = gk.rotor_scene(rotor)
    l1 = gk.level1(scene, mcs=6000 * 2 * np.pi / 60, qa=2e6, intervals=4)
    assert [s["bearing_set"] for s in l1.bearing_sets] == ["minimum clearance", "maximum clearance"]
    worse = min(l1.bearing_sets, key=lambda s: s["q0"] if s["q0"] is not None else np.inf)
    assert l1.bearing_set == worse["bearing_set"] and l1.q0 == worse["q0"]
    # The two ends are different films: their curves differ.
    assert not np.allclose(l1.bearing_sets[0]["log_decrement"], l1.bearing_sets[1]["log_decrement"])
    assert all(p["orbit_ratio"] < 0.05 for s in l1.bearing_sets for p in s["passed"])
    # The scene written back keeps the bands: the CLI screens the same two ends.
    path = tmp_path / "bands.toml"
    scene.write(str(path))
    assert "clearance_min" in path.read_text()
    out = subprocess.run([os.environ["GYROKIT_CLI"], "level1", str(path), "--mcs", "6000", "--units", "rpm", "--qa",
                          "2e6", "--intervals", "4", "--format", "json", "--table", "level1_curve"],
                         capture_output=True, text=True, check=True).stdout
    rows = json.loads(out)
    for s in l1.bearing_sets:
        mine = [r for r in rows if r["bearing_set"] == s["bearing_set"]]
        assert len(mine) == len(s["q"]) == 6   # 4 steps and QA
        for r, d in zip(mine, s["log_decrement"]):
            assert r["log_decrement"] == pytest.approx(d, abs=1e-7)
    with pytest.raises(gk.InputError, match="clearance_min is given without clearance_max"):
        gk.rotor_scene(gk.Rotor(sections=rotor.sections, disks=rotor.disks,
                                bearings=[gk.Bearing.fluid_film(z=z, diameter=0.06, length=0.03, clearance=60e-6,
                                                                viscosity=0.015, clearance_min=50e-6)
                                          for z in (0.05, 1.15)]))


def test_api_unbalance_matches_the_cli_and_runs_on_a_rotor_built_in_python():
    import json
    import subprocess
    scene = os.path.join(DATA, "three_disk_rotor.toml")
    r = gk.api_unbalance(gk.load_scene(scene))
    out = subprocess.run([os.environ["GYROKIT_CLI"], "api-unbalance", scene, "--format", "json", "--table",
                          "api_unbalance_margins"], capture_output=True, text=True, check=True).stdout
    rows = json.loads(out)
    mine = [(i + 1, k) for i, c in enumerate(r.cases) for k in c["criticals"]]
    assert len(rows) == len(mine) >= 3
    for row, (case, k) in zip(rows, mine):
        assert row["case"] == case
        assert row["speed_rpm"] == pytest.approx(k["speed"], rel=1e-12)
        assert row["met"] == k["met"]
    assert r.verdict == "pass" and r.reasons == [] and r.unit == "rpm"
    assert r.min_speed == pytest.approx(7000) and r.trip_speed == pytest.approx(10500)
    first = r.cases[0]
    assert first["layout"].startswith("first mode") and len(first["loads"]) == 1
    assert first["scc"] == pytest.approx(min(6.0, max(0.5, first["avl"] / first["a1"])), rel=1e-12)
    assert first["curves"].shape == (len(r.speeds), len(r.locations))
    # The same rotor built in Python has no [api]: speeds as keywords, and no clearance to check.
    built = gk.api_unbalance(gk.rotor_scene(three_disk_rotor()), mcs=10000, min_speed=7000, trip_speed=10500,
                             unit="rpm")
    assert [c["layout"] for c in built.cases] == [c["layout"] for c in r.cases]
    assert built.cases[0]["a1"] == pytest.approx(first["a1"], rel=1e-8)
    assert built.verdict == "not judged" and not any(built.clearance)
    with pytest.raises(gk.InputError, match="mcs ="):
        gk.api_unbalance(gk.rotor_scene(three_disk_rotor()))
    with pytest.raises(gk.InputError, match="min_speed = 12000: allowed"):
        gk.api_unbalance(gk.load_scene(scene), min_speed=12000)
    with pytest.raises(gk.InputError, match="need an FE rotor"):
        gk.api_unbalance(gk.load_scene(os.path.join(DATA, "centrifuge.toml")), mcs=10)


def test_mesh_convergence_matches_the_cli():
    import json
    import subprocess
    scene = os.path.join(DATA, "three_disk_rotor.toml")
    m = gk.mesh_convergence(gk.load_scene(scene))
    out = subprocess.run([os.environ["GYROKIT_CLI"], "mesh", scene, "--format", "json", "--table", "mesh_quantities"],
                         capture_output=True, text=True, check=True).stdout
    rows = json.loads(out)
    assert len(rows) == len(m.quantities) * len(m.factors)
    for row in rows:
        q = next(q for q in m.quantities if q["name"] == row["quantity"])
        i = m.factors.index(row["factor"])
        assert row["value_rpm"] == pytest.approx(q["values"][i], rel=1e-12)
    assert m.chosen == 0 and m.section_elements == [2, 5, 10, 5, 2] and m.factors == [1, 2]
    with pytest.raises(gk.InputError, match="tolerance = 0.7"):
        gk.mesh_convergence(gk.load_scene(scene), tolerance=0.7)


def test_frf_matches_the_cli_and_the_docs_example_runs():
    import csv
    import io
    import re
    import subprocess
    scene = os.path.join(DATA, "three_disk_rotor.toml")
    # The scene's [speeds] are in rpm; the example (docs/frf.md) names rad/s.
    r = gk.frf(gk.load_scene(scene), 600.0, "y12", [0.0, 400.0, 800.0, 1200.0], dofs=["y12", "x12"], unit="rad/s")
    assert gk.frf(gk.load_scene(scene), 600.0, "y12", [400.0]).unit == "rpm"
    out = subprocess.run([os.environ["GYROKIT_CLI"], "frf", scene, "--units", "rad/s", "--input", "y12", "--dofs", "y12,x12", "--speed",
                          "600", "--frequencies", "0:1200:4", "--format", "csv"], capture_output=True, text=True,
                         check=True).stdout
    rows = list(csv.DictReader(io.StringIO(out)))
    frame = r.to_pandas()
    assert len(rows) == len(frame) == 8
    for row, (_, p) in zip(rows, frame.iterrows()):
        assert row["dof"] == p["dof"] and row["unit"] == "m/N"
        assert complex(float(row["re"]), float(row["im"])) == pytest.approx(complex(p["re"], p["im"]),
                                                                           rel=1e-11, abs=1e-11 * r.amplitude.max())
    # In rpm: the same response at the same speeds.
    rpm = gk.frf(gk.load_scene(scene), 600.0 * 30 / np.pi, "y12", np.array([400.0]) * 30 / np.pi, unit="rpm")
    assert rpm.H[0, 0] == pytest.approx(r.H[1, 0], rel=1e-12)
    with pytest.raises(gk.InputError, match="input 'y99': not a DOF of the model"):
        gk.frf(gk.load_scene(scene), 600.0, "y99", [100.0])
    with pytest.raises(gk.InputError, match=r"frequencies \(none\): allowed"):   # not a crash in the figure
        gk.frf(gk.load_scene(scene), 600.0, "y12", [])
    root = os.path.dirname(os.path.abspath(DATA))
    block = re.findall(r"```python\n(.*?)```", open(os.path.join(root, "docs", "frf.md")).read(), re.S)[0]
    import matplotlib
    matplotlib.use("Agg")
    cwd = os.getcwd()
    os.chdir(root)
    try:
        exec(compile(block, "docs/frf.md", "exec"), {"gk": gk, "np": np})
    finally:
        os.chdir(cwd)


def test_gyrostat_and_fluid_rotor_parameters_are_objects_that_make_and_write_their_scenes():
    # The parameters are bound types: made from the [model] keys, read back from a scene, and a scene built
    # from them is written from them (no document), reading back to the same matrices bit for bit.
    keys = dict(A_G=2.0, B_G=2.0, A_R=0.09, C_R=0.10, m=8.0, s=0.25, eps=1.0e-3, c_G=306.862, c_T=2112.19,
                c_R=74.1333, d_G=4.0, d_T=5.0, d_R=0.02)
    p = gk.GyrostatParameters(**keys)
    assert p.A_G == 2.0 and p.shaft == "elastic" and p.housing == "elastic"
    assert repr(p).startswith("GyrostatParameters(A_G=2.0, B_G=2.0") and "shaft='elastic'" in repr(p)
    made = gk.gyrostat(p, title="centrifuge", speeds={"from": 0, "to": 60, "count": 241}, analysis={"modes": 6})
    read = gk.load_scene(os.path.join(DATA, "centrifuge.toml"))
    assert read.gyrostat.c_T == p.c_T and made.gyrostat.d_R == p.d_R
    np.testing.assert_array_equal(made.system.M.toarray(), read.system.M.toarray())
    np.testing.assert_array_equal(made.system.K.toarray(), read.system.K.toarray())
    back = gk._core.parse_scene(made.to_toml(), "back", ".")
    assert back.title == "centrifuge" and back.modes == 6
    np.testing.assert_array_equal(back.system.M.toarray(), made.system.M.toarray())
    np.testing.assert_array_equal(back.system.damping_matrix(0.0).toarray(), made.system.damping_matrix(0.0).toarray())
    rigid = gk.gyrostat(**{k: v for k, v in keys.items() if k not in ("c_T", "c_R")}, shaft="rigid")
    assert rigid.system.size == 2 and 'shaft = "rigid"' in rigid.to_toml()
    with pytest.raises(gk.InputError, match=r"shaft = 'soft': allowed: 'elastic' or 'rigid'"):
        gk.GyrostatParameters(shaft="soft")
    with pytest.raises(gk.InputError, match=r"gyrostat: unknown key 'c_X'; allowed: A_G"):
        gk.GyrostatParameters(c_X=1.0)
    with pytest.raises(gk.InputError, match=r"A_G = 'two': allowed: a number"):
        gk.GyrostatParameters(A_G="two")
    with pytest.raises(gk.InputError, match="given together"):
        gk.gyrostat(p, A_G=3.0)
    with pytest.raises(gk.InputError, match=r"c_T = 0: out of range; allowed: a finite number > 0 \(N/m\)"):
        gk.gyrostat(**{**keys, "c_T": 0.0})

    fkeys = dict(R=0.6, R0=0.4, a=0.5, l=2.5, rho=1000.0, nu=1.0e-6, c1=6.0e8, c2=2.0e8, c11=3.0e6, m0=400.0,
                 I0=133.0, J0=75.0, e=1.0e-4, modes=5)
    f = gk.FluidRotorParameters(**fkeys)
    assert f.modes == 5 and "R0=0.4" in repr(f)
    fmade = gk.fluid_rotor(f)
    fread = gk.load_scene(os.path.join(DATA, "fluid_N1.toml"))
    assert fread.fluid_rotor.R == 0.6 and fmade.gyrostat is None and fread.rotor is None
    np.testing.assert_array_equal(gk.eig(fmade, 50.0).eigenvalues, gk.eig(fread, 50.0).eigenvalues)
    fback = pickle.loads(pickle.dumps(fmade))
    np.testing.assert_array_equal(gk.eig(fback, 50.0).eigenvalues, gk.eig(fmade, 50.0).eigenvalues)
    with pytest.raises(gk.InputError, match=r"modes = 1.5: allowed: a whole number"):
        gk.FluidRotorParameters(modes=1.5)
    with pytest.raises(gk.InputError, match=r"R0 = 0.7 is not below R = 0.6"):
        gk.fluid_rotor(**{**fkeys, "R0": 0.7})
    # The example of docs/python.md runs and gives the scene it says.
    import re
    text = open(os.path.join(os.path.dirname(os.path.abspath(DATA)), "docs", "python.md")).read()
    part = text[text.index("Models from keyword parameters"):text.index("FE rotors built in code")]
    namespace = {"gk": gk}
    exec(compile(re.findall(r"```python\n(.*?)```", part, re.S)[0], "docs/python.md", "exec"), namespace)
    np.testing.assert_array_equal(namespace["scene"].system.K.toarray(), read.system.K.toarray())


def test_model_parameters_from_keywords_are_checked_as_the_scene_reader_checks_the_keys():
    keys = dict(A_G=2.0, B_G=2.0, A_R=0.09, C_R=0.10, m=8.0, s=0.25, c_G=306.862, c_T=2112.19, c_R=74.1333)
    # A key without a default is required (s = 0 is a valid value, so a missing s must not become 0).
    with pytest.raises(gk.InputError, match=r"gyrostat: key 's' is missing"):
        gk.gyrostat(**{k: v for k, v in keys.items() if k != "s"})
    # numpy scalars are numbers; a subnormal value is refused (its written scene would not read back).
    made = gk.gyrostat(**{**keys, "m": np.float64(8.0), "A_G": np.int64(2)})
    assert made.gyrostat.m == 8.0 and made.gyrostat.A_G == 2.0
    with pytest.raises(gk.InputError, match=r"d_G = 1e-310: a subnormal number"):
        gk.gyrostat(**keys, d_G=1e-310)
    with pytest.raises(gk.InputError, match=r"A_G = True: allowed: a number"):
        gk.GyrostatParameters(A_G=True)
    # The parameters pickle (they travel with a scene's settings to a pool).
    p = gk.GyrostatParameters(**keys, shaft="elastic")
    assert repr(pickle.loads(pickle.dumps(p))) == repr(p)
    fkeys = dict(R=0.6, R0=0.4, a=0.5, l=2.5, rho=1000.0, c1=6.0e8, c2=2.0e8, c11=3.0e6, m0=400.0, I0=133.0, J0=75.0)
    with pytest.raises(gk.InputError, match=r"fluid_rotor: key 'rho' is missing"):
        gk.fluid_rotor(**{k: v for k, v in fkeys.items() if k != "rho"})
    with pytest.raises(gk.InputError, match=r"tolerance given together with modes"):
        gk.fluid_rotor(**fkeys, modes=5, tolerance=1e-8)
    with pytest.raises(gk.InputError, match=r"modes = 0: out of range"):
        gk.fluid_rotor(**fkeys, modes=0)
    with pytest.raises(gk.InputError, match=r"modes = 4294967296: allowed: a whole number within a C int"):
        gk.FluidRotorParameters(modes=2**32)
    f = gk.fluid_rotor(**fkeys, modes=np.int64(5))
    assert f.fluid_rotor.modes == 5 and f.fluid_rotor.nu == 0.0


def test_report_holds_every_section_and_is_never_written_over_its_scene(tmp_path):
    scene = gk.load_scene(os.path.join(DATA, "three_disk_rotor.toml"))
    r = gk.report(scene, tmp_path / "r.html", mode_shapes=2)
    assert [s["key"] for s in r.sections] == ["model", "map", "campbell", "modes", "stability", "api_unbalance",
                                              "level1"]
    assert r.failed == [] and r.unit == "rpm"
    page = (tmp_path / "r.html").read_text()
    assert page == r.html and "<script" not in page and page.count("<svg ") == sum(s["figures"] for s in r.sections)
    for s in r.sections:
        for key in s["tables"]:
            assert f'id="{key}"' in page
    assert r._repr_html_().startswith("<iframe srcdoc=") and "<script" not in r._repr_html_()
    with pytest.raises(gk.InputError, match="input of this run"):
        r.write(os.path.join(DATA, "three_disk_rotor.toml"))
    with pytest.raises(gk.InputError, match="expected a gyrokit.Scene"):
        gk.report(os.path.join(DATA, "three_disk_rotor.toml"))
