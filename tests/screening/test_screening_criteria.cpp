// The stability margin (min_log_dec) and the response probes of design screening:
// log decrements of Jeffcott rotors against the roots of their characteristic
// equation, probe readings against their definition, probe verdicts against the
// closed-form response, one-line errors for bad entries, and the study identity.
#include <gyrokit/analysis/probe.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/screening/screening.hpp>
#include <gyrokit/study/rotor_study.hpp>

#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <limits>
#include <sstream>

using namespace gyrokit;
namespace fs = std::filesystem;
using cd = std::complex<double>;

namespace {

constexpr double eps = std::numeric_limits<double>::epsilon();
const Eigen::Matrix2d J = (Eigen::Matrix2d() << 0, 1, -1, 0).finished();

struct TempDir {
    fs::path path;
    TempDir() {
        path = fs::temp_directory_path() / ("gyrokit_criteria_" + std::to_string(reinterpret_cast<std::uintptr_t>(this)) +
                                            "_" + std::to_string(std::rand()));
        fs::create_directories(path);
    }
    ~TempDir() { fs::remove_all(path); }
    std::string file(const std::string& name, const std::string& text) const {
        const fs::path p = path / name;
        std::ofstream(p) << text;
        return p.string();
    }
};

std::size_t column(const Sweep& s, const std::string& name) {
    const auto c = result_columns(s);
    const auto it = std::find(c.begin(), c.end(), name);
    REQUIRE(it != c.end());
    return static_cast<std::size_t>(it - c.begin());
}

// Jeffcott rotor, mass m on supports kx, ky with external damping c_e and internal
// damping c_i: m x'' + (c_e + c_i) x' + kx x + c_i w y = m eps w^2 cos(wt), and y alike
// (in r = x + i y, isotropic: m r'' + (c_e + c_i) r' + (k - i c_i w) r = m eps w^2 e^{iwt}).
constexpr double jm = 2.0, jeps = 1e-4;

Scene jeffcott(double kx, double ky, double ce, double ci) {
    Scene sc;
    GyroscopicSystem& g = sc.system;
    g.M = jm * Eigen::Matrix2d::Identity();
    g.K = Eigen::Vector2d(kx, ky).asDiagonal();
    g.damping.push_back({"c_e", ce * Eigen::Matrix2d::Identity()});
    if (ci > 0) {
        g.damping.push_back({"c_i", ci * Eigen::Matrix2d::Identity()});
        g.N = ci * J;
    }
    g.unbalance = Eigen::Vector2cd(jm * jeps, cd(0, -jm * jeps));
    g.dofs.names = {"x", "y"};
    g.dofs.units = {"m", "m"};
    g.whirl_pairs = {{0, 1}};
    return sc;
}

// A sweep of the Jeffcott rotor over one of its values (model.kx, model.ky, model.c_e,
// model.c_i; model.k sets both supports).
Sweep jeffcott_sweep(const std::string& varied, const std::vector<double>& values, double ce = 4.0, double ci = 0.0) {
    Sweep s;
    s.path = "jeffcott sweep";
    s.loader = [=](const std::map<std::string, double>& o) {
        const auto get = [&](const std::string& k, double d) {
            const auto it = o.find(k);
            return it == o.end() ? d : it->second;
        };
        const double k = get("model.k", 5e3);
        return jeffcott(get("model.kx", k), get("model.ky", k), get("model.c_e", ce), get("model.c_i", ci));
    };
    SweepParameter p;
    p.name = varied;
    p.values = values;
    s.parameters = {p};
    return s;
}

// The roots of m l^2 + c l + kc = 0 (kc complex), without cancellation: q = -(c + sqrt(d))/2
// with Re sqrt(d) >= 0, l1 = q/m, l2 = kc/q.
std::array<cd, 2> roots(double m, double c, cd kc) {
    const cd q = -0.5 * (c + std::sqrt(c * c - 4.0 * m * kc));
    return {q / m, kc / q};
}

double log_dec(cd l) { return -2.0 * M_PI * l.real() / std::abs(l.imag()); }

// What the eigenvalue's error bound e allows for -2 pi Re l / |Im l|, to first order:
// 2 pi e (1/|Im l| + |Re l|/Im l^2); the closed form's own rounding (a few eps |l|) added to e.
double log_dec_bound(cd l, double e) {
    const double im = std::abs(l.imag());
    return 2.0 * M_PI * (e + 8.0 * eps * std::abs(l)) * (1.0 / im + std::abs(l.real()) / (im * im));
}

// The largest bound over the oscillating modes the criterion reads: its own study
// (every mode, 0..up_to) on the design's scene.
double largest_log_dec_bound(const Scene& sc, double up_to, int count) {
    StudyOptions so = study_options(sc);
    so.solver.modes = 0;
    so.speeds = SpeedRange{0.0, up_to, count}.points();
    double b = 0.0;
    for (const Branch& br : stability_study(sc.system, so).tracked.diagram.branches)
        for (const BranchPoint& p : br.points)
            if (p.mode.lambda.imag() > 0.0) b = std::max(b, log_dec_bound(p.mode.lambda, p.mode.error_bound));
    REQUIRE(std::isfinite(b));
    return b;
}

}  // namespace

TEST_CASE("probe reading: 0 degrees reads x, 90 degrees y, a circular orbit the same at every angle", "[probe]") {
    Eigen::VectorXcd Z(3);
    Z << cd(0.3, -1.7), cd(-2.2, 0.4), cd(5.0, 5.0);
    const auto reading = [&](double angle, int x = 0, int y = 1) { return probe_amplitude(Probe{"p", x, y, angle}, Z); };
    // Multiples of 90 degrees read one DOF exactly (cos and sin are not rounded there).
    CHECK(reading(0.0) == std::abs(Z(0)));
    CHECK(reading(90.0) == std::abs(Z(1)));
    CHECK(reading(180.0) == std::abs(Z(0)));
    CHECK(reading(-90.0) == std::abs(Z(1)));
    CHECK(reading(360.0) == std::abs(Z(0)));
    CHECK(reading(90.0, 2, 0) == std::abs(Z(0)));
    CHECK(probe_response(Probe{"p", 0, 1, 270.0}, Z) == -Z(1));
    // A line orbit along x: |Z_x cos(angle)|.
    Eigen::VectorXcd line(2);
    line << cd(1e-3, 2e-3), 0.0;
    // A circular forward orbit: Z_y = -i Z_x (x = A cos wt, y = A sin wt), every direction reads |Z_x|.
    Eigen::VectorXcd circle(2);
    circle << cd(1e-3, 2e-3), cd(2e-3, -1e-3);
    for (double angle = -360.0; angle <= 360.0; angle += 7.5) {
        CAPTURE(angle);
        // cos and sin of the rounded argument (|error| <= 2 eps |angle in rad| + eps) and the
        // sum of two complex products (a few eps): 8 eps (1 + |angle in rad|) relative.
        const double tol = 8.0 * eps * (1.0 + std::abs(angle) * M_PI / 180.0);
        const double a = probe_amplitude(Probe{"c", 0, 1, angle}, circle);
        CHECK(std::abs(a - std::abs(circle(0))) <= tol * std::abs(circle(0)));
        const double l = probe_amplitude(Probe{"l", 0, 1, angle}, line);
        CHECK(std::abs(l - std::abs(line(0) * std::cos(angle * M_PI / 180.0))) <= tol * std::abs(line(0)));
    }
    CHECK_THROWS_AS(probe_amplitude(Probe{"p", 0, 3, 0.0}, Z), InputError);
}

TEST_CASE("probe at a node: the node's x and y, errors naming the node and the allowed range", "[probe]") {
    const Scene sc = load_scene(std::string(GYROKIT_DATA_DIR) + "/three_disk_rotor.toml");
    const GyroscopicSystem& sys = sc.system;
    const Probe p = probe_at_node(sys, "NDE", 23, 45.0);
    CHECK(sys.dofs.names.at(p.dof_x) == "x23");
    CHECK(sys.dofs.names.at(p.dof_y) == "y23");
    CHECK(p.angle_degrees == 45.0);
    try {
        probe_at_node(sys, "far", 99, 0.0);
        FAIL("node 99 accepted");
    } catch (const InputError& e) {
        CHECK(std::string(e.what()).find("node 99 does not exist; allowed: 0 to 24") != std::string::npos);
    }
    // A pinned end holds x and y of node 0: no probe there.
    std::ifstream in(std::string(GYROKIT_DATA_DIR) + "/three_disk_rotor.toml");
    std::stringstream text;
    text << in.rdbuf();
    std::string t = text.str();
    t.insert(t.find("[speeds]"), "[[model.support]]\nz = 0.0\ntype = \"pinned\"\n\n");
    const Scene pinned = parse_scene(t, "pinned.toml", GYROKIT_DATA_DIR);
    try {
        probe_at_node(pinned.system, "held", 0, 0.0);
        FAIL("a held node accepted");
    } catch (const InputError& e) {
        CHECK(std::string(e.what()).find("node 0 has no free x and y") != std::string::npos);
    }
    CHECK_THROWS_AS(probe_at_node(jeffcott(5e3, 5e3, 4.0, 0.0).system, "none", 0, 0.0), InputError);
}

TEST_CASE("log decrement margin: Jeffcott rotor, delta = 2 pi zeta / sqrt(1 - zeta^2) at every speed",
          "[screening][stability]") {
    // k = 5e3, m = 2: zeta = c_e / (2 sqrt(k m)) = c_e / 200; delta = 0.0314, 0.0628, 0.126, 0.315.
    const double up_to = 100.0, limit = 0.1;
    const int count = 41;
    Sweep s = jeffcott_sweep("model.c_e", {1.0, 2.0, 4.0, 10.0});
    s.criteria.stability = StabilityCriterion{up_to, count, limit};
    finalize_sweep(s);
    const std::vector<std::string> q = quantity_columns(s);
    REQUIRE(q == std::vector<std::string>{"instability_onset_rad_s", "min_log_dec", "min_log_dec_speed_rad_s"});
    for (std::size_t i = 0; i < s.design_count(); ++i) {
        const DesignResult r = evaluate_design(s, i);   // the numbers unrounded (a row has 12 digits)
        const double ce = r.parameters[0], zeta = ce / 200.0;
        const double expected = 2.0 * M_PI * zeta / std::sqrt(1.0 - zeta * zeta);
        const double tol = largest_log_dec_bound(s.loader({{"model.c_e", ce}}), up_to, count);
        INFO("c_e = " << ce << ", delta = " << expected << " +- " << tol << ": " << r.reason);
        REQUIRE(r.quantities[1]);
        CHECK(std::abs(*r.quantities[1] - expected) <= tol);
        CHECK(*r.quantities[2] >= 0.0);
        CHECK(*r.quantities[2] <= up_to);
        CHECK_FALSE(r.quantities[0]);   // stable
        const bool fails = expected < limit;
        CHECK(r.verdict == (fails ? Verdict::Fail : Verdict::Pass));
        if (fails) {
            CHECK(r.failed == std::vector<std::string>{"stability"});
            CHECK(r.reason.find("stability: log decrement") != std::string::npos);
            CHECK(r.reason.find("required 0.1, short by") != std::string::npos);
        }
    }
    // The run writes them as columns after the onset.
    const RunResult run = run_screening(s, RunOptions{});
    CHECK(result_columns(s)[3] == "min_log_dec");
    for (const auto& row : run.rows) CHECK(std::abs(std::stod(row.cells[3]) - *evaluate_design(s, row.index).quantities[1]) <=
                                           1e-11 * std::stod(row.cells[3]));   // 12 digits
}

TEST_CASE("log decrement margin: internal damping, the forward mode is least damped at the top speed",
          "[screening][stability]") {
    // m r'' + (c_e + c_i) r' + (k - i c_i w) r = 0: the forward root loses damping with speed and
    // turns unstable at w_n (1 + c_e/c_i) = 250, 150, 75 rad/s for c_i = 1, 2, 8.
    const double k = 5e3, ce = 4.0, up_to = 100.0, limit = 0.1;
    const int count = 41;
    Sweep s = jeffcott_sweep("model.c_i", {1.0, 2.0, 8.0}, ce);
    s.criteria.stability = StabilityCriterion{up_to, count, limit};
    finalize_sweep(s);
    for (std::size_t i = 0; i < s.design_count(); ++i) {
        const DesignResult r = evaluate_design(s, i);
        const double ci = r.parameters[0];
        const auto least = [&](double w) {
            const auto l = roots(jm, ce + ci, cd(k, -ci * w));
            return std::min(log_dec(l[0]), log_dec(l[1]));
        };
        // The least decrement falls with speed: the minimum is the top speed's.
        for (int i = 1; i <= 1000; ++i) REQUIRE(least(up_to * i / 1000.0) < least(up_to * (i - 1) / 1000.0));
        const auto l = roots(jm, ce + ci, cd(k, -ci * up_to));
        const cd weakest = log_dec(l[0]) < log_dec(l[1]) ? l[0] : l[1];
        const double expected = log_dec(weakest);
        const double tol = largest_log_dec_bound(s.loader({{"model.c_i", ci}}), up_to, count);
        INFO("c_i = " << ci << ", delta = " << expected << " +- " << tol << ": " << r.reason);
        REQUIRE(r.quantities[1]);
        CHECK(std::abs(*r.quantities[1] - expected) <= tol);
        CHECK(*r.quantities[2] == up_to);
        const double threshold = std::sqrt(k / jm) * (1.0 + ce / ci);
        REQUIRE(std::abs(expected - limit) > tol);
        CHECK(r.verdict == (expected < limit || threshold < up_to ? Verdict::Fail : Verdict::Pass));
        CHECK(bool(r.quantities[0]) == (threshold < up_to));
        if (threshold < up_to) {   // unstable: the onset's reason, and the least decrement with it
            CHECK(expected < 0.0);
            CHECK(r.reason.find("is unstable from") != std::string::npos);
            CHECK(r.reason.find(", least log decrement -") != std::string::npos);
            CHECK(r.failed == std::vector<std::string>{"stability"});
        }
    }
}

TEST_CASE("response probes: the probe reading the largest amplitude, verdicts from the closed form",
          "[screening][response]") {
    // Supports kx = 5e3 (w_n,x = 50 rad/s) and ky varied: |Z_x| = m eps w^2 / |kx - m w^2 + i c w|,
    // |Z_y| the same with ky. Probe X at 0 degrees reads |Z_x|, probe Y at 90 degrees |Z_y|.
    const double kx = 5e3, c = 4.0, from = 30.0, to = 80.0, limit = 3e-3;
    Sweep s = jeffcott_sweep("model.ky", {2e3, 8e3, 2e4}, c);
    s.op_from = from;
    s.op_to = to;
    s.op_count = 26;
    s.criteria.response = ResponseCriterion{limit, {}, {{"X", "x", "y", -1, 0.0}, {"Y", "x", "y", -1, 90.0}}};
    finalize_sweep(s);
    const RunResult run = run_screening(s, RunOptions{});
    REQUIRE(run.rows.size() == 3);
    const std::size_t cv = column(s, "verdict"), ca = column(s, "max_amplitude"), cp = column(s, "max_amplitude_probe");
    CHECK(cp == ca + 2);   // after max_amplitude and its speed
    for (const auto& row : run.rows) {
        const DesignResult r = evaluate_design(s, row.index);   // the amplitude unrounded (a row has 12 digits)
        const double ky = r.parameters[0];
        // Largest |Z| over [from, to] of a support k: a range end, or the peak at
        // w_n / sqrt(1 - 2 zeta^2) inside. Brent stops within 4 sqrt(eps) w of the
        // peak, where the amplitude is short of it by (r/g)^2/2 (g = zeta w_n, the
        // half width); the LU solve of the dynamic stiffness adds about eps/zeta.
        const auto largest = [&](double k, double& tol) {
            const auto amp = [&](double w) { return jm * jeps * w * w / std::hypot(k - jm * w * w, c * w); };
            const double zeta = c / (2 * std::sqrt(k * jm)), wn = std::sqrt(k / jm), wp = wn / std::sqrt(1 - 2 * zeta * zeta);
            tol = 64.0 * eps / zeta;
            double a = std::max(amp(from), amp(to));
            if (wp > from && wp < to && amp(wp) > a) {
                a = amp(wp);
                tol += 2.0 * std::pow(4.0 * std::sqrt(eps) * wp / (zeta * wn), 2);
            }
            return a;
        };
        double tx = 0, ty = 0;
        const double ax = largest(kx, tx), ay = largest(ky, ty);
        const bool y_wins = ay > ax;
        const double expected = std::max(ax, ay), tol = y_wins ? ty : tx;
        INFO("ky = " << ky << ": X " << ax << ", Y " << ay << ", relative tolerance " << tol << ": " << row.cells.back());
        REQUIRE(std::abs(ax - ay) > 2 * tol * expected);
        CHECK(std::abs(*r.quantities[0] - expected) <= tol * expected);
        CHECK(r.labels == std::vector<std::string>{row.cells[cp]});
        CHECK(row.cells[cp] == (y_wins ? "Y" : "X"));
        REQUIRE(std::abs(expected - limit) > tol * expected);
        const bool fails = expected > limit;
        CHECK(row.cells[cv] == (fails ? "fail" : "pass"));
        if (fails) CHECK(row.cells.back().find("response: probe " + row.cells[cp] + " = ") != std::string::npos);
    }
    // ky = 8e3: Y resonates at 63 rad/s, above the limit; the others pass.
    CHECK(run.rows[1].cells[cv] == "fail");
    CHECK(run.rows[0].cells[cv] == "pass");
}

TEST_CASE("bad probes and log decrement limits: one-line errors naming key, value and what is allowed",
          "[screening][input]") {
    TempDir d;
    const std::string gyrostat = std::string(GYROKIT_DATA_DIR) + "/centrifuge.toml";
    const std::string fe = std::string(GYROKIT_DATA_DIR) + "/three_disk_rotor.toml";
    const auto sweep = [&](const std::string& scene, const std::string& criteria) {
        return "scene = \"" + scene + "\"\n[operating]\nfrom = 25.0\nto = 35.0\n" + criteria;
    };
    const auto probes = [&](const std::string& list, const std::string& scene = "") {
        return sweep(scene.empty() ? gyrostat : scene, "[criteria.response]\nmax_amplitude = 1e-3\nprobes = " + list + "\n");
    };
    const auto expect_error = [&](const std::string& text, const std::string& needle) {
        const std::string p = d.file("bad.toml", text);
        try {
            read_sweep(p);
            FAIL("no error for: " << needle);
        } catch (const InputError& e) {
            const std::string m = e.what();
            INFO(m);
            CHECK(m.find(needle) != std::string::npos);
            CHECK(m.find(p) == 0);   // the sweep file first
            CHECK(m.find('\n') == std::string::npos);
        }
    };
    const std::string xy = "dof_x = \"x\", dof_y = \"y\"";
    expect_error(probes("\"x\""), "[criteria.response] probes must be an array of tables such as");
    expect_error(probes("[]"), "probes is empty; allowed: one or more probes");
    expect_error(probes("[1]"), "probes[0] is not a table; allowed: { name = ");
    expect_error(probes("[{ name = \"A\", " + xy + ", angle = 0, phase = 1 }]"),
                 "[criteria.response.probes[0]] unknown key 'phase'; allowed: angle, dof_x, dof_y, name, node");
    expect_error(probes("[{ " + xy + ", angle = 0 }]"), "[criteria.response.probes[0]] name is missing");
    expect_error(probes("[{ name = \"A\", " + xy + ", angle = 0 }, { name = \"A\", " + xy + ", angle = 90 }]"),
                 "[criteria.response.probes[1]] name = 'A': probes[0] has that name already");
    expect_error(probes("[{ name = \"A\", dof_x = \"x\", angle = 0 }]"), "probes[0]] dof_y is missing; required:");
    expect_error(probes("[{ name = \"A\", dof_x = \"x\", dof_y = \"x\", angle = 0 }]"),
                 "dof_x = 'x' and dof_y = 'x': allowed: two different DOFs");
    expect_error(probes("[{ name = \"A\", " + xy + " }]"), "probes[0]] angle is missing; required:");
    expect_error(probes("[{ name = \"A\", " + xy + ", angle = 400.0 }]"),
                 "probes[0]] angle = 400: out of range; allowed: -360 to 360");
    expect_error(probes("[{ name = \"A\", " + xy + ", angle = \"up\" }]"), "probes[0]] angle must be a finite number");
    expect_error(probes("[{ name = \"A\", dof_x = \"x\", dof_y = \"q\", angle = 0 }]"),
                 "probes[0]] dof_y = 'q': not a DOF of the model; allowed: alpha, beta, x, y, psi, theta");
    expect_error(probes("[{ name = \"A\", dof_x = \"x\", dof_y = \"beta\", angle = 0 }]"),
                 "dof_x = 'x' (m) and dof_y = 'beta' (rad): allowed: two DOFs of one unit");
    expect_error(probes("[{ name = \"A\", node = 2, angle = 0 }]"),
                 "probes[0]] node = 2: the model has no nodes on an axis (only an fe_rotor scene has); allowed: dof_x");
    expect_error(probes("[{ name = \"A\", node = 2, dof_x = \"x2\", angle = 0 }]", fe),
                 "probes[0]] dof_x: given with node; allowed: either node or dof_x and dof_y");
    expect_error(probes("[{ name = \"A\", node = -1, angle = 0 }]", fe), "probes[0]] node = -1: out of range; allowed: [0,");
    expect_error(probes("[{ name = \"A\", node = 25, angle = 0 }]", fe),
                 "probes[0]] node = 25: node 25 does not exist; allowed: 0 to 24 (probe 'A', scene");
    expect_error(probes("[{ name = \"A\", dof_x = \"x3\", dof_y = \"ty3\", angle = 0 }]", fe),
                 "dof_x = 'x3' (m) and dof_y = 'ty3' (rad): allowed: two DOFs of one unit");
    expect_error(sweep(gyrostat, "[criteria.response]\nmax_amplitude = 1e-3\ndofs = [\"x\"]\nprobes = [{ name = \"A\", " +
                                     xy + ", angle = 0 }]\n"),
                 "[criteria.response] probes: given with dofs; allowed: either dofs or probes");
    expect_error(sweep(gyrostat, "[criteria.stability]\nmin_log_dec = 0.0\n"),
                 "[criteria.stability] min_log_dec = 0: out of range; allowed: > 0");
    expect_error(sweep(gyrostat, "[criteria.stability]\nmin_log_dec = \"0.1\"\n"),
                 "[criteria.stability] min_log_dec is not a number");
    // Good entries: by DOF names and by node.
    const Sweep ok = read_sweep(d.file("ok.toml", probes("[{ name = \"NDE\", node = 23, angle = 45.0 }, { name = \"DE\", "
                                                         "dof_x = \"x1\", dof_y = \"y1\", angle = -45.0 }]",
                                                         fe)));
    REQUIRE(ok.criteria.response->probes.size() == 2);
    CHECK(ok.criteria.response->probes[0].node == 23);
    CHECK(ok.criteria.response->probes[1].dof_y == "y1");
    CHECK(label_columns(ok) == std::vector<std::string>{"max_amplitude_probe"});
}

TEST_CASE("the study identity covers min_log_dec and the probes: a changed criterion is another study",
          "[screening][resume]") {
    TempDir d;
    const std::string scene = std::string(GYROKIT_DATA_DIR) + "/centrifuge.toml";
    const auto text = [&](double min_log_dec, double angle) {
        return "scene = \"" + scene + "\"\n[operating]\nfrom = 25.0\nto = 35.0\ncount = 3\n[criteria.stability]\n" +
               "up_to = 35.0\ncount = 11\nmin_log_dec = " + std::to_string(min_log_dec) +
               "\n[criteria.response]\nmax_amplitude = 1e-2\nprobes = [{ name = \"P\", dof_x = \"x\", dof_y = \"y\", " +
               "angle = " + std::to_string(angle) + " }]\n";
    };
    const std::string path = d.file("study.toml", text(0.1, 45.0));
    const Sweep s = read_sweep(path);
    RunOptions ro;
    ro.out = (d.path / "rows.csv").string();
    const RunResult first = run_screening(s, ro);
    REQUIRE(first.rows.size() == 1);
    ro.resume = true;
    CHECK(run_screening(s, ro).computed == 0);   // its own file: nothing left to do
    for (const auto& [limit, angle] : std::vector<std::pair<double, double>>{{0.2, 45.0}, {0.1, 30.0}}) {
        CAPTURE(limit, angle);
        d.file("study.toml", text(limit, angle));   // the same file, one criterion edited
        const Sweep changed = read_sweep(path);
        std::ifstream rows(ro.out);
        std::string written;
        std::getline(rows, written);   // the identity the first run wrote
        CHECK(study_identity_line(changed) != written);
        try {
            run_screening(changed, ro);
            FAIL("a result file of another study resumed");
        } catch (const InputError& e) {
            CHECK(std::string(e.what()).find("written by another study") != std::string::npos);
        }
    }
    // A file judged by an older revision of the rules says so.
    d.file("study.toml", text(0.1, 30.0));
    const Sweep same = read_sweep(path);
    const std::string identity = study_identity_line(same);
    const std::string old_rules = identity.substr(0, identity.rfind("rules ")) + "rules 1)";
    std::ifstream rows(ro.out);
    std::stringstream rest;
    std::string first_line;
    std::getline(rows, first_line);
    rest << rows.rdbuf();
    rows.close();
    std::ofstream(ro.out, std::ios::trunc) << old_rules << '\n' << rest.str();
    try {
        run_screening(same, ro);
        FAIL("a result file of older rules resumed");
    } catch (const InputError& e) {
        INFO(e.what());
        const std::string ours = identity.substr(identity.rfind("gyrokit "));   // "gyrokit V, rules N)"
        const std::string version = ours.substr(0, ours.find(','));
        CHECK(std::string(e.what()).find("were judged by " + version + ", rules 1 where this run judges by " + version +
                                         ", rules " + std::to_string(kScreeningRules) + ";") != std::string::npos);
    }
}

TEST_CASE("amplification factor limit: the largest AF of the scan, 1/(2 zeta) for a Jeffcott rotor, and its verdict",
          "[screening][separation]") {
    // k = 5e3, m = 2: the critical speed at w_n = 50 rad/s, zeta = c_e / 200 = 0.005 and 0.05:
    // AF = 100 and 10 to first order in zeta (half-power on the unbalance response, whose
    // w^2 forcing moves the half-power points by O(zeta) of their distance: within 10 %).
    Sweep s = jeffcott_sweep("model.c_e", {1.0, 10.0});
    s.op_from = 60.0;
    s.op_to = 80.0;
    SeparationCriterion c;
    c.margin_percent = 0.0;
    c.count = 61;
    c.max_amplification = 20.0;
    s.criteria.separation = c;
    finalize_sweep(s);
    REQUIRE(quantity_columns(s) == std::vector<std::string>{"critical_speed_rad_s", "separation_percent",
                                                            "max_amplification_factor",
                                                            "max_amplification_speed_rad_s"});
    for (std::size_t i = 0; i < 2; ++i) {
        const DesignResult r = evaluate_design(s, i);
        const double zeta = r.parameters[0] / 200.0;
        INFO("zeta = " << zeta << ": " << r.reason);
        REQUIRE(r.quantities[2]);
        CHECK(*r.quantities[2] == Approx(1.0 / (2.0 * zeta)).epsilon(0.1));
        // Im lambda = w_n sqrt(1 - zeta^2) at every speed (no gyroscopic term): the crossing, to
        // the root search's 1e-13 and the eigenvalue's bound (~1e-12 of it).
        CHECK(*r.quantities[3] == Approx(std::sqrt(5e3 / 2.0) * std::sqrt(1.0 - zeta * zeta)).epsilon(1e-9));
        // The value the critical speed study gives the design's scene.
        StudyOptions so = study_options(s.loader({{"model.c_e", r.parameters[0]}}));
        so.speeds = SpeedRange{0.0, s.op_to * 1.05, c.count}.points();
        const auto cs = critical_speed_study(s.loader({{"model.c_e", r.parameters[0]}}).system, so).critical;
        double top = 0.0;
        for (const auto& x : cs) top = std::max(top, x.amplification);
        CHECK(*r.quantities[2] == top);
        if (zeta < 0.01) {
            CHECK(r.verdict == Verdict::Fail);
            CHECK(r.failed == std::vector<std::string>{"amplification"});
            CHECK(r.reason.find("amplification: critical speed") != std::string::npos);
            CHECK(r.reason.find("allowed at most 20") != std::string::npos);
        } else {
            CHECK(r.verdict == Verdict::Pass);
        }
    }
    // Undamped: AF = inf, a failing design (not an error), inf in its column; the summary counts it.
    Sweep undamped = s;
    undamped.parameters[0].values = {0.0};
    finalize_sweep(undamped);
    const DesignResult u = evaluate_design(undamped, 0);
    INFO(u.reason);
    CHECK(u.verdict == Verdict::Fail);
    CHECK(u.failed == std::vector<std::string>{"amplification"});
    REQUIRE(u.quantities[2]);
    CHECK(std::isinf(*u.quantities[2]));
    const RunResult run = run_screening(undamped, RunOptions{});
    const Table t = summary_table(undamped, run.rows);
    bool counted = false;
    for (std::size_t i = 0; i < t.rows(); ++i)
        if (std::get<std::string>(t.row(i)[0]) == "failing amplification") counted = std::get<long long>(t.row(i)[1]) == 1;
    CHECK(counted);
}

TEST_CASE("max_amplification_factor in a sweep file: read, and refused below 1", "[screening][separation]") {
    TempDir d;
    const std::string head = "scene = \"" + (fs::path(GYROKIT_DATA_DIR) / "three_disk_rotor.toml").string() +
                             "\"\n[[parameter]]\nname = \"model.bearing[0].kxx\"\nvalues = [1e7]\n"
                             "[operating]\nfrom = 3000\nto = 5000\n[criteria.separation]\n";
    CHECK(read_sweep(d.file("ok.toml", head + "max_amplification_factor = 8\n")).criteria.separation->max_amplification ==
          8.0);
    CHECK_FALSE(read_sweep(d.file("none.toml", head)).criteria.separation->max_amplification);
    CHECK_THROWS_WITH(read_sweep(d.file("bad.toml", head + "max_amplification_factor = 0.5\n")),
                      Catch::Contains("max_amplification_factor") && Catch::Contains("> 1"));
}

TEST_CASE("a bearing stiffness sweep with heavily damped crossings: separation verdicts are what critical says",
          "[screening][separation]") {
    // data/three_disk_rotor.toml: damped bearings give modes 3 and 4 crossings with AF ~0.6 inside the operating
    // range, which `gyrokit critical` lists as heavily damped (not critical). A verdict that counted them
    // flipped pass/fail/pass along the stiffness; each design's verdict must be `critical`'s.
    TempDir d;
    const std::string scene = std::string(GYROKIT_DATA_DIR) + "/three_disk_rotor.toml";
    std::string values;
    for (const double k : {5e6, 1e7, 1.5e7, 2e7, 3e7, 5e7, 8e7, 1.2e8, 2e8}) values += (values.empty() ? "" : ", ") + fmt::format("{}", k);
    const auto sweep_text = [&](const std::string& extra) {
        return fmt::format("scene = \"{}\"\nunits = \"rpm\"\n[sampling]\nmethod = \"grid\"\n[[parameter]]\nname = "
                           "\"k\"\npaths = [\"model.bearing[*].kxx\", \"model.bearing[*].kyy\"]\nvalues = [{}]\n"
                           "[operating]\nfrom = 6000\nto = 12000\n[criteria.separation]\nmargin_percent = 15\n{}",
                           scene, values, extra);
    };
    const Sweep s = read_sweep(d.file("sweep.toml", sweep_text("")));
    const Sweep counting = read_sweep(d.file("counting.toml", sweep_text("heavily_damped = \"count\"\n")));
    const double from = s.op_from, to = s.op_to;   // rad/s
    const auto margin = [&](double wc) {   // API 684 style, as the criterion computes it
        return wc <= from ? 100.0 * (from - wc) / from
               : wc >= to ? 100.0 * (wc - to) / to
                          : -100.0 * std::min((wc - from) / from, (to - wc) / to);
    };
    int heavily_damped_inside = 0, differ = 0;
    for (std::size_t i = 0; i < s.design_count(); ++i) {
        const DesignResult r = evaluate_design(s, i);
        const DesignResult c = evaluate_design(counting, i);
        INFO("k = " << r.parameters[0] << ": " << r.reason << " | counting: " << c.reason);
        // The critical command's study on the design's scene over the criterion's scan.
        const Scene design = s.loader({{"model.bearing[*].kxx", r.parameters[0]}, {"model.bearing[*].kyy", r.parameters[0]}});
        StudyOptions so = study_options(design);
        so.speeds = SpeedRange{0.0, to * (1.0 + 15.0 / 100.0) * 1.05, 121}.points();
        bool critical_inside = false, damped_inside = false;
        for (const CriticalSpeed& x : critical_speed_study(design.system, so).critical)
            (x.api684_critical() ? critical_inside : damped_inside) |= margin(x.speed) < 15.0;
        heavily_damped_inside += damped_inside;
        CHECK((r.verdict == Verdict::Fail) == critical_inside);
        CHECK((c.verdict == Verdict::Fail) == (critical_inside || damped_inside));
        differ += r.verdict != c.verdict;
    }
    // The sweep holds designs where only a heavily damped crossing lies within the margin.
    CHECK(heavily_damped_inside >= 1);
    CHECK(differ >= 1);
    CHECK(study_identity_line(s).find("rules " + std::to_string(kScreeningRules)) != std::string::npos);
    CHECK(kScreeningRules >= 2);   // the revision that skips heavily damped crossings, or a later one
}
