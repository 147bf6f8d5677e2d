// The DOF set of an FE rotor (lateral, all, axial, torsional) and coupling dampers:
// an axial or torsional model is exactly that block of the full model, and a damped
// coupling between two disks against the closed form.
#include <gyrokit/core/error.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>
#include <gyrokit/reports/reports.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/models/fe_rotor.hpp>

#include "test_helpers.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <complex>

using namespace gyrokit;

namespace {

std::string data(const std::string& name) { return std::string(GYROKIT_DATA_DIR) + "/" + name; }

// The rows/columns of `full` whose DOF names start with `prefix` followed by a digit.
std::vector<int> block(const std::vector<std::string>& names, const std::string& prefix) {
    std::vector<int> idx;
    for (int i = 0; i < static_cast<int>(names.size()); ++i)
        if (names[i].compare(0, prefix.size(), prefix) == 0 &&
            std::isdigit(static_cast<unsigned char>(names[i][prefix.size()])))
            idx.push_back(i);
    return idx;
}

}  // namespace

// At constant speed the axial and torsional bars couple neither to each other nor to
// the lateral motion (they share no matrix entry), so building one of them alone must
// give exactly (bit for bit: the same sums in the same order) that block of the model
// with all six DOFs per node, and the same eigenvalues.
TEST_CASE("fe rotor motion: an axial or torsional model is that block of the 6-DOF model",
          "[fe_rotor][motion][validation]") {
    const Scene all = load_scene(data("drive_train.toml"));
    REQUIRE(all.fe_rotor()->motion == FeMotion::all);
    for (const auto& [motion, prefix] : {std::pair{"axial", "z"}, std::pair{"torsional", "tz"}}) {
        INFO(motion);
        const Scene one = load_scene(data("drive_train.toml"), {}, motion);
        const std::vector<int> idx = block(all.dof_names(), prefix);
        REQUIRE(one.dofs() == static_cast<int>(idx.size()));
        REQUIRE(one.dofs() == all.fe_rotor()->node_count());   // nothing holds z or tz in this train
        for (int i = 0; i < one.dofs(); ++i) CHECK(one.dof_names()[i] == all.dof_names()[idx[i]]);
        const Eigen::MatrixXd M(all.system.M), K(all.system.K), D(all.system.damping_matrix());
        CHECK(Eigen::MatrixXd(one.system.M) == M(idx, idx));
        CHECK(Eigen::MatrixXd(one.system.K) == K(idx, idx));
        CHECK(Eigen::MatrixXd(one.system.damping_matrix()) == D(idx, idx));
        // Nothing gyroscopic, no whirl pairs, no unbalance, no pedestal or speed-dependent bearing.
        CHECK(one.system.G.nonZeros() == 0);
        CHECK(one.system.whirl_pairs.empty());
        CHECK(one.system.unbalance.size() == 0);
        CHECK(one.system.bearings.empty());
        // The rest of the full model does not touch the block: its eigenvalues at any speed
        // contain the block's (to the solvers' rounding).
        const QuadraticSpectrum a = solve_at_speed(all.system, 400.0), b = solve_at_speed(one.system, 400.0);
        // The train turns freely; the thrust bearing holds it axially.
        CHECK(b.rigid_body.size() == (std::string(motion) == "torsional" ? 2u : 0u));
        for (const Mode& m : b.modes) {
            double nearest = 1e300;
            for (const Mode& n : a.modes) nearest = std::min(nearest, std::abs(n.lambda - m.lambda));
            CHECK(nearest <= 1e-9 * std::abs(m.lambda));
        }
    }
    SECTION("the scene keys: motion, dofs_per_node = 1, and a lateral model from the same description") {
        const Scene lateral = load_scene(data("drive_train.toml"), {}, "lateral");
        CHECK(lateral.fe_rotor()->motion == FeMotion::lateral);
        CHECK(lateral.dofs() == 4 * 16 + 2);   // 16 nodes, the pedestal's px, py
        const std::vector<int> idx = [&] {
            std::vector<int> v;
            for (int i = 0; i < all.dofs(); ++i)
                if (all.dof_names()[i][0] != 'z' && all.dof_names()[i].rfind("tz", 0) != 0) v.push_back(i);
            return v;
        }();
        CHECK(Eigen::MatrixXd(lateral.system.M) == Eigen::MatrixXd(all.system.M)(idx, idx));
        CHECK(Eigen::MatrixXd(lateral.system.K) == Eigen::MatrixXd(all.system.K)(idx, idx));
        CHECK(Eigen::MatrixXd(lateral.system.G) == Eigen::MatrixXd(all.system.G)(idx, idx));
        CHECK(Eigen::MatrixXd(lateral.system.damping_matrix()) ==
              Eigen::MatrixXd(all.system.damping_matrix())(idx, idx));
    }
}

TEST_CASE("fe rotor motion: scene keys and bad input", "[fe_rotor][motion]") {
    const std::string head = "[model]\ntype = \"fe_rotor\"\nmaterial = \"steel\"\n";
    const std::string shaft = "[[model.shaft]]\nlength = 1\nelements = 4\nouter_diameter = 0.05\n"
                              "[[model.bearing]]\nz = 0\nk = 1e7\nkzz = 1e8\n[[model.bearing]]\nz = 1\nk = 1e7\n"
                              "[[model.support]]\nz = 1\ntype = \"clamped\"\n";
    SECTION("motion = torsional, or dofs_per_node = 1 with it") {
        for (const char* keys : {"motion = \"torsional\"\n", "motion = \"torsional\"\ndofs_per_node = 1\n"}) {
            const Scene sc = parse_scene(head + keys + shaft, "t.toml");
            CHECK(sc.fe_rotor()->motion == FeMotion::torsional);
            CHECK(sc.dofs() == 4);   // five nodes, the clamped end holds tz4
            CHECK(sc.dof_names() == std::vector<std::string>{"tz0", "tz1", "tz2", "tz3"});
            CHECK(sc.system.dofs.units == std::vector<std::string>(4, "rad"));
        }
        // Axial: the thrust bearing (kzz) acts, its lateral k does not exist here.
        const Scene ax = parse_scene(head + "motion = \"axial\"\n" + shaft, "a.toml");
        std::string no_thrust = shaft;
        no_thrust.replace(no_thrust.find("kzz = 1e8\n"), 10, "");
        const Scene ax0 = parse_scene(head + "motion = \"axial\"\n" + no_thrust, "a0.toml");
        CHECK(ax.dofs() == 4);
        CHECK(ax.system.K.coeff(0, 0) - ax0.system.K.coeff(0, 0) == Approx(1e8).epsilon(1e-12));
        CHECK(ax.system.dofs.units == std::vector<std::string>(4, "m"));
    }
    SECTION("bad input") {
        CHECK_THAT(test::scene_error(head + "dofs_per_node = 1\n" + shaft),
                   Catch::Contains("dofs_per_node = 1") && Catch::Contains("motion = \"axial\" or \"torsional\""));
        CHECK_THAT(test::scene_error(head + "motion = \"torsional\"\ndofs_per_node = 6\n" + shaft),
                   Catch::Contains("dofs_per_node = 6 disagrees with motion = \"torsional\"") &&
                       Catch::Contains("allowed: 1"));
        CHECK_THAT(test::scene_error(head + "motion = \"twist\"\n" + shaft),
                   Catch::Contains("motion = 'twist'") && Catch::Contains("all, axial, lateral, torsional"));
        // Without a motion (lateral by default) the thrust stiffness is refused: it would model
        // nothing; with motion = "lateral" given, the description serves and kzz is not used.
        CHECK_THAT(test::scene_error(head + shaft), Catch::Contains("kzz") && Catch::Contains("dofs_per_node = 6"));
        const Scene lateral = parse_scene(head + "motion = \"lateral\"\n" + shaft, "l.toml");
        CHECK(lateral.dofs() == 4 * 5 - 4);
        // The override applies to FE rotors only.
        REQUIRE_THROWS_AS(load_scene(data("centrifuge.toml"), {}, "torsional"), InputError);
        CHECK_THROWS_WITH(load_scene(data("centrifuge.toml"), {}, "torsional"),
                          Catch::Contains("motion = 'torsional' does not apply to") && Catch::Contains("a [model] of type gyrostat; allowed: a [model] of type fe_rotor"));
    }
}

// Two disks J1, J2 joined by a coupling of torsional stiffness k and damping c, nothing
// else: in the relative angle the pencil J s^2 + c s + k with J = J1 J2 / (J1 + J2), so
// s = (-c +- sqrt(c^2 - 4 J k)) / (2 J), besides the free rotation (s = 0). The same with
// the lateral dampers: x1 - x2 with masses m1, m2 on k_lateral, c_lateral.
TEST_CASE("fe rotor coupling dampers: two disks on a damped coupling against the closed form",
          "[fe_rotor][coupling][validation]") {
    const double J1 = 0.3, J2 = 0.7, kt = 5e4, ct = 12.0, m1 = 20.0, m2 = 30.0, kl = 2e6, cl = 400.0;
    FeRotor r;
    r.motion = FeMotion::all;
    FeShaftElement e;
    e.length = 0.1;
    FeCoupling c;
    c.k_lateral = kl;
    c.c_lateral = cl;
    c.k_bending = 1e3;
    c.c_bending = 3.0;
    c.k_axial = 1e6;
    c.c_axial = 50.0;
    c.k_torsion = kt;
    c.c_torsion = ct;
    e.coupling = c;
    r.elements.push_back(e);
    r.disks.push_back({0, m1, 0.1, J1, 0.0, 0.0});
    r.disks.push_back({1, m2, 0.1, J2, 0.0, 0.0});
    const FeRotorMatrices mats = r.assemble();
    CHECK(mats.D.nonZeros() == 0);   // no bearing: all damping is the coupling's
    const GyroscopicSystem sys = mats.to_system();
    REQUIRE(sys.damping.size() == 1);
    CHECK(sys.damping[0].name == "couplings");
    const auto relative_roots = [](double a, double b, double cc, double k) {
        const double J = a * b / (a + b);
        const std::complex<double> disc = std::sqrt(std::complex<double>(cc * cc - 4 * J * k));
        return std::pair{(-cc + disc) / (2 * J), (-cc - disc) / (2 * J)};
    };
    const QuadraticSpectrum s = solve_at_speed(sys, 0.0);
    const auto present = [&](std::complex<double> root) {
        double nearest = 1e300;
        // Modes are listed once per conjugate pair.
        for (const Mode& m : s.modes)
            nearest = std::min({nearest, std::abs(m.lambda - root), std::abs(m.lambda - std::conj(root))});
        INFO("root " << root << " nearest " << nearest);
        CHECK(nearest <= 1e-10 * std::abs(root));
    };
    const auto [t1, t2] = relative_roots(J1, J2, ct, kt);
    present(t1);
    present(t2);
    const auto [x1, x2] = relative_roots(m1, m2, cl, kl);
    present(x1);
    present(x2);
    const auto [a1, a2] = relative_roots(m1, m2, 50.0, 1e6);   // axial
    present(a1);
    present(a2);
    const auto [b1, b2] = relative_roots(0.1, 0.1, 3.0, 1e3);   // tilt (Id of both disks)
    present(b1);
    present(b2);
    // Bad input: a negative damper.
    r.elements[0].coupling->c_torsion = -1.0;
    CHECK_THROWS_WITH(r.assemble(), Catch::Contains("c_torsion = -1") && Catch::Contains("[0, inf)"));
}

// Response outputs by node (--nodes, --at) are the whirling translations x, y: the axial z
// of a 6-DOF model, also in metres, is no lateral response.
TEST_CASE("fe rotor motion: a node's translations are x and y, not the axial z", "[fe_rotor][motion]") {
    const Scene all = load_scene(data("drive_train.toml"));
    std::vector<std::string> names;
    for (const int i : all.system.node_translations(15)) names.push_back(all.dof_names()[i]);
    CHECK(names == std::vector<std::string>{"x15", "y15"});
    CHECK(all.system.node_dofs(15, "m").size() == 3);   // x15, y15, z15
    // An axial model has no whirl pairs: its z is the node's translation.
    const Scene axial = load_scene(data("drive_train.toml"), {}, "axial");
    REQUIRE(axial.system.node_translations(15).size() == 1);
    CHECK(axial.dof_names()[axial.system.node_translations(15)[0]] == "z15");
}

// The model summary names circulatory forces from cross-coupled bearings (oil films), not
// only a speed-proportional N.
TEST_CASE("model summary: cross-coupled bearing stiffness is circulatory", "[fe_rotor][reports]") {
    const auto circulatory = [](const Scene& sc) {
        const Table t = model_summary(sc);
        for (std::size_t i = 0; i < t.rows(); ++i)
            if (std::get<std::string>(t.row(i)[0]) == "circulatory") return std::get<std::string>(t.row(i)[1]);
        return std::string("missing");
    };
    CHECK(circulatory(load_scene(data("compressor.toml"))) == "yes (cross-coupled stiffness)");
    CHECK(circulatory(load_scene(data("drive_train.toml"))) == "no");
    const std::string text = "[model]\ntype = \"fe_rotor\"\nmaterial = \"steel\"\n[[model.shaft]]\nlength = 1\n"
                             "outer_diameter = 0.05\n[[model.bearing]]\nz = 0\nk = 1e7\nkxy = 2e6\n[[model.bearing]]\n"
                             "z = 1\nk = 1e7\n";
    CHECK(circulatory(parse_scene(text, "cc.toml")) == "yes (cross-coupled stiffness)");
}

// The coupling's lateral damper turns with the shafts: a disk m on a coupling (k, c_i) to
// a clamped stub, with a fixed damper c_e at the disk, is the Jeffcott rotor with internal
// damping, m z'' + (c_e + c_i) z' + (k - i w c_i) z = 0 (z = x + i y): stable below
// w_th = w_n (1 + c_e / c_i), w_n = sqrt(k / m), where the forward mode sits exactly at
// lambda = i w_n, unstable above.
TEST_CASE("fe rotor coupling dampers: internal damping, the Jeffcott threshold w_n (1 + c_e / c_i)",
          "[fe_rotor][coupling][validation]") {
    const double m = 8.0, k = 2e5, ci = 60.0, ce = 25.0;
    FeRotor r;
    FeShaftElement e;
    e.length = 0.05;
    FeCoupling c;
    c.k_lateral = k;
    c.c_lateral = ci;
    c.k_bending = 1e4;   // no bending damper: the tilt pair stays neutral
    e.coupling = c;
    r.elements.push_back(e);
    FeSupport clamp;
    clamp.theta_x = clamp.theta_y = true;
    r.supports.push_back(clamp);
    r.disks.push_back({1, m, 0.02, 0.0, 0.0, 0.0});
    r.bearings.push_back({1, 0, 0, 0, 0, ce, 0, 0, ce});
    const GyroscopicSystem sys = make_system(r);
    REQUIRE(sys.has_circulatory());
    const double wn = std::sqrt(k / m), wth = wn * (1 + ce / ci);
    const auto largest_real = [&](double w) {
        double x = -1e300;
        for (const Mode& mode : solve_at_speed(sys, w).modes)
            if (std::abs(mode.lambda.imag() - wn) < 0.2 * wn) x = std::max(x, mode.lambda.real());
        return x;
    };
    CHECK(largest_real(0.99 * wth) < 0.0);
    CHECK(largest_real(1.01 * wth) > 0.0);
    // Internal damping destabilises the forward whirl (a sign error would pick the backward one).
    for (const Mode& mode : solve_at_speed(sys, 1.01 * wth).modes)
        if (mode.lambda.real() > 0.0) CHECK(mode.whirl == Whirl::Forward);
    double nearest = 1e300;
    for (const Mode& mode : solve_at_speed(sys, wth).modes)
        nearest = std::min(nearest, std::abs(mode.lambda - std::complex<double>(0.0, wn)));
    CHECK(nearest <= 1e-10 * wn);
    // The sparse pencil carries the same term: K + w N.
    const SparsePencil p = r.assemble().at_speed(wth);
    CHECK((Eigen::MatrixXd(p.K) - Eigen::MatrixXd(sys.K) - wth * Eigen::MatrixXd(sys.N)).norm() == 0.0);
}
