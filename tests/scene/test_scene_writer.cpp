// Scenes written back: every FE rotor of data/ read, written and read again gives the
// same matrices bit for bit (the writer prints each number in its shortest round-trip
// form), the same bearings and settings; a model built in code equals its scene.
#include <gyrokit/core/error.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/scene/scene_writer.hpp>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

using namespace gyrokit;

namespace {

std::string data(const std::string& name) { return std::string(GYROKIT_DATA_DIR) + "/" + name; }

bool same(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& b) {
    return a.rows() == b.rows() && a.cols() == b.cols() && Eigen::MatrixXd(a) == Eigen::MatrixXd(b);
}

// Two scenes describe the same model and analysis. The unbalance phases go through
// degrees (rad -> deg -> rad: two correctly rounded products and quotients), so the
// unbalance vector agrees within 4 ulp of each entry's magnitude, not bit for bit.
void check_same(const Scene& a, const Scene& b) {
    const GyroscopicSystem &s = a.system, &t = b.system;
    CHECK(same(s.M, t.M));
    CHECK(same(s.K, t.K));
    CHECK(same(s.G, t.G));
    CHECK(same(s.N, t.N));
    REQUIRE(s.damping.size() == t.damping.size());
    for (std::size_t i = 0; i < s.damping.size(); ++i) {
        CHECK(s.damping[i].name == t.damping[i].name);
        CHECK(same(s.damping[i].D, t.damping[i].D));
    }
    REQUIRE(s.unbalance.size() == t.unbalance.size());
    for (Eigen::Index i = 0; i < s.unbalance.size(); ++i)
        CHECK(std::abs(s.unbalance(i) - t.unbalance(i)) <= 4 * 2.3e-16 * std::abs(s.unbalance(i)));
    CHECK(s.dofs.names == t.dofs.names);
    CHECK(s.whirl_pairs == t.whirl_pairs);
    REQUIRE(s.bearings.size() == t.bearings.size());
    for (std::size_t i = 0; i < s.bearings.size(); ++i) {
        const BearingTable &p = s.bearings[i], &q = t.bearings[i];
        CHECK(p.name == q.name);
        CHECK(p.dof_x == q.dof_x);
        CHECK(p.dof_y == q.dof_y);
        CHECK(p.pedestal_x == q.pedestal_x);
        CHECK(p.speeds == q.speeds);
        // Coefficients over the table and beyond it (a fluid film's are computed at any speed).
        for (double w : {0.0, 100.0, 523.6, 1000.0, 2500.0}) {
            CHECK(p.at(w).K == q.at(w).K);
            CHECK(p.at(w).C == q.at(w).C);
        }
    }
    CHECK(a.title == b.title);
    CHECK(a.solver.kind == b.solver.kind);
    CHECK(a.solver.modes == b.solver.modes);
    CHECK(a.analysis.harmonics == b.analysis.harmonics);
    CHECK(a.solver.target == b.solver.target);
    CHECK(a.solver.target_order == b.solver.target_order);
    CHECK(a.analysis.f_cut == b.analysis.f_cut);
    REQUIRE(a.speeds.has_value() == b.speeds.has_value());
    if (a.speeds) {
        CHECK(a.speeds->from == b.speeds->from);
        CHECK(a.speeds->to == b.speeds->to);
        CHECK(a.speeds->count == b.speeds->count);
        CHECK(a.speed_unit.name == b.speed_unit.name);
        CHECK(a.speed_points() == b.speed_points());
    }
}

}  // namespace

TEST_CASE("scene writer: every FE rotor of data/ reads back to the same matrices, bearings and settings") {
    for (const char* name : {"fe_rotor.toml", "three_disk_rotor.toml", "three_disk_rotor_journal.toml",
                             "compressor.toml", "compressor336.toml", "drive_train.toml", "friswell_5_9_1.toml"}) {
        INFO(name);
        const Scene a = load_scene(data(name));
        const std::string text = scene_text(a);
        const Scene b = parse_scene(text, "written", "/nonexistent");   // tables by absolute path
        check_same(a, b);
        // Another motion of the same description: the writer keeps the description, not the mesh.
        if (std::string(name) == "drive_train.toml")
            for (const char* motion : {"torsional", "axial", "all"}) {
                const Scene m = load_scene(data(name), {}, motion);
                check_same(m, parse_scene(scene_text(m), "written", "."));
            }
    }
}

TEST_CASE("scene writer: a rotor built in code equals its hand-written scene") {
    const std::string hand = R"(
title = "two-disk rotor"
[model]
type = "fe_rotor"
E = 2.1e11
density = 7800
poisson = 0.3
[[model.shaft]]
length = 0.6
elements = 6
outer_diameter = 0.05
[[model.shaft]]
length = 0.4
elements = 2
outer_diameter = 0.06
outer_diameter_end = 0.04
inner_diameter = 0.01
[[model.disk]]
z = 0.3
outer_diameter = 0.3
width = 0.04
unbalance = 1e-4
phase = 90
[[model.bearing]]
z = 0.0
kxx = 2e7
kyy = 1.5e7
c = 3e3
[[model.bearing]]
z = 1.0
speeds = [0, 1000]
k = [1e7, 2e7]
c = [1e3, 2e3]
[[model.support]]
z = 0.6
type = "pinned"
[speeds]
from = 0
to = 1500
count = 31
units = "rad/s"
[analysis]
modes = 8
harmonics = [1, 2]
f_cut = 2500
)";
    const Scene a = parse_scene(hand, "hand", ".");

    RotorModel m;
    RotorSection s1;
    s1.shape.length = 0.6;
    s1.shape.outer_diameter = 0.05;
    s1.shape.youngs_modulus = 2.1e11;
    s1.shape.density = 7800;
    s1.elements = 6;
    RotorSection s2 = s1;
    s2.shape.length = 0.4;
    s2.shape.outer_diameter = 0.06;
    s2.shape.outer_diameter_end = 0.04;
    s2.shape.inner_diameter = 0.01;
    s2.elements = 2;
    m.sections = {s1, s2};
    RotorDisk d;
    d.z = 0.3;
    d.geometry = DiskGeometry{0.3, 0.0, 0.04, 7800};
    d.disk.unbalance = 1e-4;
    d.disk.unbalance_phase = 90 * std::acos(-1.0) / 180;
    m.disks = {d};
    RotorBearing b0;
    b0.constant.kxx = 2e7;
    b0.constant.kyy = 1.5e7;
    b0.constant.cxx = b0.constant.cyy = 3e3;
    RotorBearing b1;
    b1.z = 1.0;
    b1.kind = RotorBearing::Kind::table;
    b1.table.speeds = {0, 1000};
    b1.table.rows.resize(2);
    b1.table.rows[0].K = Eigen::Matrix2d::Identity() * 1e7;
    b1.table.rows[0].C = Eigen::Matrix2d::Identity() * 1e3;
    b1.table.rows[1].K = Eigen::Matrix2d::Identity() * 2e7;
    b1.table.rows[1].C = Eigen::Matrix2d::Identity() * 2e3;
    m.bearings = {b0, b1};
    RotorSupport sup;
    sup.z = 0.6;
    m.supports = {sup};
    Scene c = rotor_scene(m, "two-disk rotor");
    c.speeds = SpeedRange{0, 1500, 31};
    c.solver.modes = 8;
    c.analysis.harmonics = {1, 2};
    c.analysis.f_cut = 2500;
    check_same(a, c);
    check_same(a, parse_scene(scene_text(c), "written", "."));

    const std::string path = (std::filesystem::temp_directory_path() / "gyrokit_written_scene.toml").string();
    write_scene(c, path);
    check_same(a, load_scene(path));
    std::filesystem::remove(path);
}

TEST_CASE("scene writer: what a scene cannot say is refused with the item named") {
    RotorModel m;
    RotorSection s;
    s.shape.length = 1;
    s.shape.outer_diameter = 0.05;
    s.shape.youngs_modulus = 2e11;
    s.shape.density = 7800;
    s.elements = 4;
    m.sections = {s};
    RotorSupport x_only;
    x_only.z = 0.5;
    x_only.hold.y = false;
    m.supports = {x_only};
    const Scene sc = rotor_scene(m);
    CHECK_THROWS_WITH(scene_text(sc), Catch::Contains("support 1: holds x = true, y = false") &&
                                          Catch::Contains("allowed in a scene: pinned"));
    Scene in_code;
    CHECK_THROWS_WITH(scene_text(in_code), Catch::Contains("a [model] of type matrices built in code cannot be written"));
    // Positions that are not nodes name the item in a model built in code.
    m.supports[0].z = 0.3;
    CHECK_THROWS_WITH(rotor_scene(m), Catch::Contains("support 1 z = 0.3 m is not a node of the mesh") &&
                                          Catch::Contains("the nearest is 0.25"));
    CHECK_THROWS_WITH(write_scene(load_scene(data("fe_rotor.toml")), "/nonexistent-dir/x.toml"),
                      Catch::Contains("/nonexistent-dir/x.toml: the folder '/nonexistent-dir' does not exist"));
}

TEST_CASE("scenes of other models are written as read: overrides applied, file names absolute", "[scene]") {
    // The gyrostat (with an override), a liquid-filled rotor and exported matrices (relative
    // Matrix Market names): written from another folder and read back, the same system.
    const std::vector<std::pair<std::string, std::map<std::string, double>>> cases = {
        {"centrifuge.toml", {{"model.c_G", 400.0}}}, {"fluid_N1.toml", {}}, {"ross_rotor_example/scene.toml", {}}};
    for (const auto& [name, overrides] : cases) {
        INFO(name);
        const Scene a = load_scene(data(name), overrides);
        const Scene b = parse_scene(scene_text(a), "written", "/");
        CHECK(b.model_type() == a.model_type());
        CHECK(Eigen::MatrixXd(SparseMatrix(b.system.M)) == Eigen::MatrixXd(SparseMatrix(a.system.M)));
        CHECK(Eigen::MatrixXd(SparseMatrix(b.system.K)) == Eigen::MatrixXd(SparseMatrix(a.system.K)));
        CHECK(Eigen::MatrixXd(b.system.damping_matrix(30.0)) == Eigen::MatrixXd(a.system.damping_matrix(30.0)));
        CHECK(b.system.dofs.names == a.system.dofs.names);
        CHECK(b.speeds.has_value() == a.speeds.has_value());
        CHECK(b.solver.modes == a.solver.modes);
    }
}

TEST_CASE("a scene document keeps strings that only happen to name a file: type, DOF names", "[scene]") {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / ("gyrokit_document_" + std::to_string(std::rand()));
    fs::create_directories(dir);
    for (const char* f : {"M.mtx", "K.mtx", "C.mtx", "G.mtx", "u.mtx", "scene.toml"})
        fs::copy_file(data(std::string("ross_rotor_example/") + f), dir / f);
    std::ofstream(dir / "matrices") << "";   // files named like the model type and a DOF
    std::ofstream(dir / "x0") << "";
    const Scene a = load_scene((dir / "scene.toml").string());
    const Scene b = parse_scene(scene_text(a), "written", "/");
    CHECK(b.model_type() == "matrices");
    CHECK(b.system.dofs.names == a.system.dofs.names);
    CHECK(Eigen::MatrixXd(SparseMatrix(b.system.K)) == Eigen::MatrixXd(SparseMatrix(a.system.K)));
    fs::remove_all(dir);
}

TEST_CASE("a gyrostat or liquid-filled rotor built from its parameters is written from them and reads back equal",
          "[scene]") {
    // Every data/ scene of these models: its parameters, made into a scene in code, written
    // and read back, give the read scene's matrices bit for bit and its settings.
    for (const char* name : {"centrifuge.toml", "fluid_N1.toml"}) {
        INFO(name);
        const Scene read = load_scene(data(name));
        Scene made = read.gyrostat() ? model_scene(*read.gyrostat(), read.title) : model_scene(*read.fluid(), read.title);
        made.solver = read.solver;
        made.analysis = read.analysis;
        made.speeds = read.speeds;
        made.speed_unit = read.speed_unit;
        check_same(made, read);
        const std::string text = scene_text(made);
        CHECK(text.find(read.gyrostat() ? "type = \"gyrostat\"" : "type = \"fluid_rotor\"") != std::string::npos);
        check_same(parse_scene(text, "written"), read);
    }
    // Each model's parameters are checked in code as the reader checks the keys.
    GyrostatParameters g = *load_scene(data("centrifuge.toml")).gyrostat();
    g.c_T = -1.0;
    CHECK_THROWS_WITH(model_scene(g, "g"), "g: c_T = -1: out of range; allowed: a finite number > 0 (N/m)");
    g.rigid_shaft = true;   // c_T then unused
    const Scene rigid = model_scene(g, "g");
    CHECK(rigid.system.size() == 2);   // only the cage tilts alpha, beta (eq. 12)
    CHECK(parse_scene(scene_text(rigid), "back").system.size() == 2);
    g.rigid_housing = true;
    CHECK_THROWS_WITH(model_scene(g, "g"), Catch::Contains("leaves no degree of freedom"));
    FluidRotorParameters f = *load_scene(data("fluid_N1.toml")).fluid();
    f.R0 = f.R;
    CHECK_THROWS_WITH(model_scene(f, "f"), Catch::Contains("f: R0 = 0.6 is not below R = 0.6"));
}

TEST_CASE("scene writer: a scene in mm is written back in mm, every length as it was given") {
    // Lengths of up to 15 significant digits, none of them exact in binary, in every length key
    // the writer has (shaft, cone, disk, film and its band, support, pedestal, [api]).
    const std::string text = R"(
[model]
type = "fe_rotor"
length_unit = "mm"
material = "steel"
[[model.shaft]]
length = 333.333333333333
elements = 3
outer_diameter = 63.5
inner_diameter = 12.7
[[model.shaft]]
length = 466.666666666667
elements = 4
outer_diameter = 63.5
outer_diameter_end = 50.8
[[model.disk]]
z = 333.333333333333
outer_diameter = 304.8
inner_diameter = 63.5
width = 25.4
[[model.bearing]]
type = "fluid_film"
z = 0.0
diameter = 63.5
length = 31.75
clearance = 0.0762
clearance_min = 0.0635
clearance_max = 0.0889
viscosity = 0.018
load = "auto"
[[model.bearing]]
z = 800.0
kxx = 1.3e8
kyy = 1.1e8
[[model.support]]
z = 800.0
type = "pinned"
[[model.pedestal]]
z = 800.0
mass = 40.0
k = 3e8
[api]
machine = "centrifugal"
mcs = 1200
station = 333.333333333333
[[api.stage]]
z = 333.333333333333
power = 1.5e6
diameter = 304.8
width = 12.7
density_ratio = 1.4
[[api.clearance]]
z = 333.333333333333
clearance = 0.381
[speeds]
from = 0
to = 1200
count = 5
)";
    const Scene a = parse_scene(text, "inches.toml", ".");
    const std::string written = scene_text(a);
    INFO(written);
    CHECK(written.find("length_unit = \"mm\"") != std::string::npos);
    for (const char* line : {"length = 333.333333333333\n", "length = 466.666666666667\n", "outer_diameter = 63.5\n",
                             "inner_diameter = 12.7\n", "outer_diameter_end = 50.8\n", "z = 333.333333333333\n",
                             "outer_diameter = 304.8\n", "width = 25.4\n", "diameter = 63.5\n", "length = 31.75\n",
                             "clearance = 0.0762\n", "clearance_min = 0.0635\n", "clearance_max = 0.0889\n",
                             "z = 800.0\n", "station = 333.333333333333\n", "diameter = 304.8\n", "width = 12.7\n",
                             "clearance = 0.381\n"})
        CHECK(written.find(line) != std::string::npos);
    const Scene b = parse_scene(written, "written", ".");
    check_same(a, b);
    // Written again, the same text: the unit is kept, nothing drifts.
    CHECK(scene_text(b) == written);
    REQUIRE(b.api.has_value());
    CHECK(b.api->station == a.api->station);
    CHECK(b.api->stages.at(0).diameter == a.api->stages.at(0).diameter);
    CHECK(b.api->clearances.at(0).clearance == a.api->clearances.at(0).clearance);
    // A length no scene in mm gave (0.1 + 0.2 m, set in code) still reads back bit for bit.
    RotorModel m = *a.rotor_model();
    m.sections.at(0).shape.inner_diameter = 0.1 / 7.0;
    m.disks.at(0).geometry->width = 0.1 + 0.2;
    m.bearings.at(0).film.clearance = 0.0762e-3 * (1.0 + 1.0 / 3.0e3);
    const Scene c = rotor_scene(m, "code");
    const Scene d = parse_scene(scene_text(c), "written", ".");
    CHECK(d.rotor_model()->sections.at(0).shape.inner_diameter == 0.1 / 7.0);
    CHECK(d.rotor_model()->disks.at(0).geometry->width == 0.1 + 0.2);
    CHECK(d.rotor_model()->bearings.at(0).film.clearance == 0.0762e-3 * (1.0 + 1.0 / 3.0e3));
    check_same(c, d);
}
