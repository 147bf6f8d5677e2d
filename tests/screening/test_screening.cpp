// Design screening: verdicts against closed forms (gyrostat (29), rigid rotor
// critical speeds, Jeffcott response and stability threshold), Latin
// hypercube reproducibility, shards that merge to the unsharded table, and
// resume after an interrupted run.
#include <gyrokit/core/error.hpp>
#include <gyrokit/screening/screening.hpp>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

using namespace gyrokit;
namespace fs = std::filesystem;

namespace {

const Eigen::Matrix2d J = (Eigen::Matrix2d() << 0, 1, -1, 0).finished();

struct TempDir {
    fs::path path;
    TempDir() {
        path = fs::temp_directory_path() /
               ("gyrokit_screen_" + std::to_string(reinterpret_cast<std::uintptr_t>(this)) + "_" +
                std::to_string(std::rand()));
        fs::create_directories(path);
    }
    ~TempDir() { fs::remove_all(path); }
    std::string file(const std::string& name, const std::string& text) const {
        const fs::path p = path / name;
        std::ofstream(p) << text;
        return p.string();
    }
};

std::string slurp(const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

std::size_t column(const Sweep& s, const std::string& name) {
    const auto c = result_columns(s);
    return static_cast<std::size_t>(std::find(c.begin(), c.end(), name) - c.begin());
}

// Gyrostat (29), corrected: w1 = (A_R/C_R) |w_R^2 - w_T^2| / w_T.
double omega1(double A_R, double C_R, double m, double c_T, double c_R) {
    const double wT2 = c_T / m, wR2 = c_R / A_R;
    return (A_R / C_R) * std::abs(wR2 - wT2) / std::sqrt(wT2);
}

// The centrifuge with only cage damping, c_R varied so that w1 moves through
// the operating range 25-35 rad/s.
std::string pervasive_sweep(const TempDir& d, const std::string& extra = "") {
    return d.file("perv.toml", std::string(R"(title = "cage damping vs w1"
scene = ")") + GYROKIT_DATA_DIR + R"(/centrifuge.toml"
[[parameter]]
name = "model.c_R"
values = [50.0, 60.0, 74.1333, 90.0, 100.0]
[[parameter]]
name = "model.d_T"
values = [0.0]
[[parameter]]
name = "model.d_R"
values = [0.0]
[[parameter]]
name = "model.d_G"
values = [2.0, 4.0]
[operating]
from = 25.0
to = 35.0
count = 21
[criteria.pervasive]
damping = ["total"]
)" + extra);
}

// Rigid rotor on isotropic tilt springs: forward critical sqrt(kt/(It-Ip)),
// backward sqrt(kt/(It+Ip)).
Sweep rigid_rotor_sweep(double margin, bool forward_only) {
    const double It = 0.5, Ip = 0.2;
    Sweep s;
    s.path = "rigid-rotor sweep";
    s.loader = [=](const std::map<std::string, double>& o) {
        const auto it = o.find("model.kt");
        const double kt = it == o.end() ? 800.0 : it->second;
        if (!(kt > 0)) throw InputError("model.kt must be > 0");
        Scene sc;
        sc.system.M = It * Eigen::Matrix2d::Identity();
        sc.system.K = kt * Eigen::Matrix2d::Identity();
        sc.system.G = Ip * J;
        sc.system.dofs.names = {"tilt_x", "tilt_y"};
        sc.system.whirl_pairs = {{0, 1}};
        return sc;
    };
    SweepParameter p;
    p.name = "model.kt";
    p.from = 100.0;
    p.to = 3000.0;
    p.count = 30;
    p.log_scale = true;
    s.parameters = {p};
    s.op_from = 40.0;
    s.op_to = 60.0;
    SeparationCriterion c;
    c.margin_percent = margin;
    c.forward_only = forward_only;
    c.count = 61;
    s.criteria.separation = c;
    finalize_sweep(s);
    return s;
}

// Jeffcott rotor: m z'' + (c_e + c_i) z' + k z - i c_i w z = m eps w^2 e^{iwt}.
Sweep jeffcott_sweep(const std::string& varied, double from, double to, int count) {
    const double m = 2.0, eps = 1e-4;
    Sweep s;
    s.path = "jeffcott sweep";
    s.loader = [=](const std::map<std::string, double>& o) {
        const auto get = [&](const std::string& k, double d) {
            const auto it = o.find(k);
            return it == o.end() ? d : it->second;
        };
        const double k = get("model.k", 5e3), ce = get("model.c_e", 4.0), ci = get("model.c_i", 0.0);
        Scene sc;
        GyroscopicSystem& g = sc.system;
        g.M = m * Eigen::Matrix2d::Identity();
        g.K = k * Eigen::Matrix2d::Identity();
        g.damping.push_back({"c_e", ce * Eigen::Matrix2d::Identity()});
        if (ci > 0) {
            g.damping.push_back({"c_i", ci * Eigen::Matrix2d::Identity()});
            g.N = ci * J;
        }
        g.unbalance = Eigen::Vector2cd(m * eps, std::complex<double>(0, -m * eps));
        g.dofs.names = {"x", "y"};
        g.whirl_pairs = {{0, 1}};
        return sc;
    };
    SweepParameter p;
    p.name = varied;
    p.from = from;
    p.to = to;
    p.count = count;
    s.parameters = {p};
    return s;
}

}  // namespace

TEST_CASE("Latin hypercube: one point per stratum, same points for the same seed", "[screening]") {
    const std::size_t n = 50, d = 3;
    const auto a = latin_hypercube(n, d, 42), b = latin_hypercube(n, d, 42), c = latin_hypercube(n, d, 43);
    CHECK(a == b);
    CHECK(a != c);
    for (std::size_t j = 0; j < d; ++j) {
        CAPTURE(j);
        std::set<int> strata;
        for (std::size_t i = 0; i < n; ++i) {
            CAPTURE(i);
            const double x = a[i * d + j];
            REQUIRE(x >= 0.0);
            REQUIRE(x < 1.0);
            strata.insert(static_cast<int>(x * n));
        }
        CHECK(strata.size() == n);
    }
}

TEST_CASE("grid designs: last parameter fastest, ends exact, log spacing", "[screening]") {
    const Sweep s = rigid_rotor_sweep(15.0, false);
    REQUIRE(s.design_count() == 30);
    CHECK(s.design(0)[0] == 100.0);
    CHECK(s.design(29)[0] == 3000.0);
    CHECK(s.design(1)[0] / s.design(0)[0] == Approx(std::pow(30.0, 1.0 / 29)).epsilon(1e-12));
    CHECK(Shard::parse("2/5").owns(7));
    CHECK_FALSE(Shard::parse("2/5").owns(8));
    CHECK_THROWS_AS(Shard::parse("5/5"), InputError);
    CHECK_THROWS_AS(Shard::parse("x"), InputError);
}

TEST_CASE("gyrostat: cage damping verdict from the closed form (29)", "[screening][pervasive]") {
    TempDir d;
    const Sweep s = read_sweep(pervasive_sweep(d));
    REQUIRE(s.design_count() == 10);
    RunOptions ro;
    ro.jobs = 2;
    const RunResult r = run_screening(s, ro);
    REQUIRE(r.rows.size() == 10);
    const std::size_t cv = column(s, "verdict"), cl = column(s, "pervasive_loss_rad_s");
    int failing = 0;
    for (const auto& row : r.rows) {
        const double c_R = std::stod(row.cells[1]);
        const double w1 = omega1(0.09, 0.10, 8.0, 2112.19, c_R);
        REQUIRE(std::abs(w1 - 25.0) > 1.0);   // no design on the edge of the range
        REQUIRE(std::abs(w1 - 35.0) > 1.0);
        const bool inside = w1 > 25.0 && w1 < 35.0;
        INFO("c_R = " << c_R << ", w1 = " << w1 << ", reason: " << row.cells.back());
        CHECK(row.cells[cv] == (inside ? "fail" : "pass"));
        if (inside) {
            ++failing;
            CHECK(std::stod(row.cells[cl]) == Approx(w1).epsilon(1e-6));
        } else {
            CHECK(row.cells[cl].empty());
        }
    }
    CHECK(failing == 2);   // c_R = 74.1333 with both d_G
}

TEST_CASE("rigid rotor: separation margin verdicts from the closed-form critical speeds", "[screening][separation]") {
    const double It = 0.5, Ip = 0.2, from = 40.0, to = 60.0;
    for (const bool fwd : {false, true}) {
        const double margin = 15.0;
        const Sweep s = rigid_rotor_sweep(margin, fwd);
        RunOptions ro;
        ro.jobs = 2;
        const RunResult r = run_screening(s, ro);
        REQUIRE(r.rows.size() == 30);
        const std::size_t cv = column(s, "verdict"), cc = column(s, "critical_speed_rad_s"),
                          cm = column(s, "separation_percent");
        const double w_scan = to * (1 + margin / 100) * 1.05;
        for (const auto& row : r.rows) {
            const double kt = std::stod(row.cells[1]);
            std::vector<double> crit{std::sqrt(kt / (It - Ip))};
            if (!fwd) crit.push_back(std::sqrt(kt / (It + Ip)));
            double worst = 1e300, worst_w = 0;
            for (double w : crit) {
                if (w > w_scan) continue;
                const double sm = w <= from ? 100 * (from - w) / from
                                  : w >= to ? 100 * (w - to) / to
                                            : -100 * std::min((w - from) / from, (to - w) / to);
                if (sm < worst) worst = sm, worst_w = w;
            }
            INFO("kt = " << kt << ", forward only " << fwd << ": " << row.cells.back());
            if (worst_w == 0) {
                CHECK(row.cells[cc].empty());
                CHECK(row.cells[cv] == "pass");
                continue;
            }
            REQUIRE(!row.cells[cc].empty());
            CHECK(std::stod(row.cells[cc]) == Approx(worst_w).epsilon(1e-8));
            CHECK(std::stod(row.cells[cm]) == Approx(worst).epsilon(1e-6).margin(1e-6));
            if (std::abs(worst - margin) > 1e-3) CHECK(row.cells[cv] == (worst < margin ? "fail" : "pass"));
        }
    }
}

TEST_CASE("Jeffcott rotor: stability verdict at w_n (1 + c_e/c_i)", "[screening][stability]") {
    const double m = 2.0, k = 5e3, ce = 4.0, up_to = 100.0;
    Sweep s = jeffcott_sweep("model.c_i", 2.0, 40.0, 9);
    s.criteria.stability = StabilityCriterion{up_to, 41};
    finalize_sweep(s);
    const RunResult r = run_screening(s, RunOptions{});
    const std::size_t cv = column(s, "verdict"), co = column(s, "instability_onset_rad_s");
    for (const auto& row : r.rows) {
        const double ci = std::stod(row.cells[1]);
        const double threshold = std::sqrt(k / m) * (1 + ce / ci);
        INFO("c_i = " << ci << ", threshold " << threshold << ": " << row.cells.back());
        CHECK(row.cells[cv] == (threshold < up_to ? "fail" : "pass"));
        if (threshold < up_to) CHECK(std::stod(row.cells[co]) == Approx(threshold).epsilon(1e-8));
    }
}

TEST_CASE("Jeffcott rotor: maximum unbalance response against the closed form", "[screening][response]") {
    const double m = 2.0, eps = 1e-4, c = 4.0, from = 30.0, to = 80.0, limit = 1.5e-3;
    Sweep s = jeffcott_sweep("model.k", 1e3, 2e4, 12);
    s.op_from = from;
    s.op_to = to;
    s.op_count = 26;
    s.criteria.response = ResponseCriterion{limit, {"x"}};
    finalize_sweep(s);
    const RunResult r = run_screening(s, RunOptions{});
    const std::size_t cv = column(s, "verdict"), ca = column(s, "max_amplitude");
    for (const auto& row : r.rows) {
        const double k = std::stod(row.cells[1]);
        const auto amp = [&](double w) { return m * eps * w * w / std::hypot(k - m * w * w, c * w); };
        const double zeta = c / (2 * std::sqrt(k * m)), wp = std::sqrt(k / m) / std::sqrt(1 - 2 * zeta * zeta);
        double expected = std::max(amp(from), amp(to));
        if (wp > from && wp < to) expected = std::max(expected, amp(wp));
        INFO("k = " << k << ": " << row.cells.back());
        CHECK(std::stod(row.cells[ca]) == Approx(expected).epsilon(1e-7));
        if (std::abs(expected - limit) > 1e-3 * limit) CHECK(row.cells[cv] == (expected > limit ? "fail" : "pass"));
    }
}

TEST_CASE("Jeffcott rotor without damping: the response criterion fails as unbounded", "[screening][response]") {
    // c_e = 0: every design whose w_n = sqrt(k/m) lies in 30..80 rad/s (k = 1800..12800) passes an
    // undamped resonance; outside that range the response is finite.
    Sweep s = jeffcott_sweep("model.k", 1e3, 2e4, 12);
    s.op_from = 30.0;
    s.op_to = 80.0;
    s.op_count = 26;
    s.criteria.response = ResponseCriterion{1.0, {"x"}};
    const auto loader = s.loader;
    s.loader = [loader](std::map<std::string, double> o) {
        o["model.c_e"] = 0.0;
        return loader(o);
    };
    finalize_sweep(s);
    const RunResult r = run_screening(s, RunOptions{});
    const std::size_t cv = column(s, "verdict"), ca = column(s, "max_amplitude");
    int unbounded = 0;
    for (const auto& row : r.rows) {
        const double k = std::stod(row.cells[1]), wn = std::sqrt(k / 2.0);
        INFO("k = " << k << ": " << row.cells.back());
        const bool resonant = wn > 30.0 && wn < 80.0;
        CHECK(std::isinf(std::stod(row.cells[ca])) == resonant);
        CHECK(row.cells[cv] == (resonant ? "fail" : "pass"));
        if (resonant) CHECK(row.cells.back().find("unbounded") != std::string::npos);
        unbounded += resonant;
    }
    CHECK(unbounded >= 4);
}

TEST_CASE("invalid designs are reported with the reason and the sweep goes on", "[screening]") {
    TempDir d;
    std::string text = slurp(pervasive_sweep(d));
    text.replace(text.find("values = [50.0"), 14, "values = [-5.0");   // c_R < 0 is not a valid scene
    const Sweep s = read_sweep(d.file("bad_value.toml", text));
    const RunResult r = run_screening(s, RunOptions{});
    REQUIRE(r.rows.size() == 10);
    const std::size_t cv = column(s, "verdict");
    CHECK(r.rows[0].cells[cv] == "error");
    CHECK(r.rows[0].cells.back().find("invalid parameters") != std::string::npos);
    CHECK(r.rows[0].cells.back().find("c_R") != std::string::npos);
    CHECK(r.rows[2].cells[cv] == "pass");
    // The safe-region picture: one series per verdict present, every design drawn.
    const Figure f = safe_region_figure(s, r.rows, "model.c_R", "model.d_G");
    REQUIRE(f.panels.size() == 1);
    std::size_t points = 0;
    for (const auto& se : f.panels[0].series) points += se.x.size();
    CHECK(f.panels[0].series.size() == 3);   // pass, fail (w1 inside), error (c_R < 0)
    CHECK(points == 10);
}

TEST_CASE("Latin hypercube sweep file: samples within the ranges, one per stratum", "[screening]") {
    TempDir d;
    const std::string p = d.file("lhs.toml", std::string("scene = \"") + GYROKIT_DATA_DIR + R"(/centrifuge.toml"
[sampling]
method = "lhs"
samples = 8
seed = 3
[[parameter]]
name = "model.c_R"
from = 50.0
to = 100.0
[[parameter]]
name = "model.d_G"
from = 0.1
to = 10.0
scale = "log"
[operating]
from = 25.0
to = 35.0
[criteria.pervasive]
)");
    const Sweep s = read_sweep(p);
    REQUIRE(s.design_count() == 8);
    std::set<int> strata;
    for (std::size_t i = 0; i < 8; ++i) {
        CAPTURE(i);
        const auto x = s.design(i);
        CHECK(x[0] >= 50.0);
        CHECK(x[0] < 100.0);
        CHECK(x[1] >= 0.1);
        CHECK(x[1] < 10.0);
        strata.insert(static_cast<int>((x[0] - 50.0) / 50.0 * 8));
    }
    CHECK(strata.size() == 8);
    CHECK(read_sweep(p).design(5) == s.design(5));
}

TEST_CASE("shards merge to the unsharded table, jobs do not change the rows", "[screening][shard]") {
    TempDir d;
    const Sweep s = read_sweep(pervasive_sweep(d));
    RunOptions one;
    one.jobs = 1;
    one.out = (d.path / "all.csv").string();
    run_screening(s, one);
    const std::string all = slurp(one.out);

    RunOptions two = one;
    two.jobs = 2;
    two.out = (d.path / "all2.csv").string();
    run_screening(s, two);
    CHECK(slurp(two.out) == all);

    std::vector<std::string> files;
    for (int k = 0; k < 3; ++k) {
        CAPTURE(k);
        RunOptions ro;
        ro.jobs = 2;
        ro.shard = Shard{k, 3};
        ro.out = (d.path / ("shard" + std::to_string(k) + ".csv")).string();
        const RunResult r = run_screening(s, ro);
        for (const auto& row : r.rows) {
            CAPTURE(row);
            CHECK(static_cast<int>(row.index % 3) == k);
        }
        files.push_back(ro.out);
    }
    const auto merged = merge_results(s, files, true);
    std::ostringstream os;
    write_results(os, s, merged, TableFormat::Csv);
    // The file holds the study's identity line first, then the table.
    CHECK(study_identity_line(s) + "\n" + os.str() == all);
    // A missing shard is detected.
    CHECK_THROWS_AS(merge_results(s, {files[0], files[1]}, true), InputError);
    CHECK_THROWS_AS(merge_results(s, {files[0], files[0]}, false), InputError);
}

TEST_CASE("a result file whose trailer names no changed file is refused, not a crash", "[screening][merge]") {
    TempDir d;
    const Sweep s = read_sweep(pervasive_sweep(d));
    for (const std::string tail : {"", " ", " a.toml"}) {
        CAPTURE(tail);
        const std::string path = (d.path / "trailer.csv").string();
        {
            std::ofstream f(path);
            f << study_identity_line(s) << "\n" << kInputsChangedTrailer << tail << "\n";
        }
        CHECK_THROWS_AS(merge_results(s, {path}, false), InputError);
    }
}

TEST_CASE("an interrupted run resumes without duplicates or gaps", "[screening][resume]") {
    TempDir d;
    const Sweep s = read_sweep(pervasive_sweep(d));
    RunOptions full;
    full.out = (d.path / "full.csv").string();
    run_screening(s, full);
    const std::string expected = slurp(full.out);

    RunOptions part;
    part.jobs = 2;
    part.out = (d.path / "part.csv").string();
    part.limit = 4;
    const RunResult first = run_screening(s, part);
    CHECK(first.computed == 4);
    // A write cut short: half of the next row, no newline.
    {
        std::ofstream f(part.out, std::ios::app | std::ios::binary);
        f << "4,74.1333,0,0,2,30.99";
    }
    part.resume = true;
    part.limit = 0;
    const RunResult second = run_screening(s, part);
    CHECK(second.resumed == 4);
    CHECK(second.computed == 6);
    CHECK(second.rows.size() == 10);
    CHECK(slurp(part.out) == expected);

    // Resuming a finished file computes nothing and leaves it as it is.
    const RunResult third = run_screening(s, part);
    CHECK(third.computed == 0);
    CHECK(slurp(part.out) == expected);

    // A file of another sweep or another shard is refused.
    RunOptions other = part;
    other.shard = Shard{1, 2};
    CHECK_THROWS_AS(run_screening(s, other), InputError);
    const Sweep s2 = read_sweep(pervasive_sweep(d, "[criteria.stability]\nup_to = 50.0\n"));
    CHECK_THROWS_AS(run_screening(s2, part), InputError);
}

TEST_CASE("bad sweep files: one-line InputError", "[screening][input]") {
    TempDir d;
    const std::string base = slurp(pervasive_sweep(d));
    const std::string values = "values = [50.0, 60.0, 74.1333, 90.0, 100.0]";
    const auto expect_error = [&](const std::string& text, const std::string& needle) {
        const std::string p = d.file("bad.toml", text);
        try {
            read_sweep(p);
            FAIL("no error for: " << needle);
        } catch (const InputError& e) {
            const std::string m = e.what();
            INFO(m);
            CHECK(m.find(needle) != std::string::npos);
            CHECK(m.find('\n') == std::string::npos);
        }
    };
    std::string t = base;
    t.replace(t.find("model.c_R"), 9, "model.c_X");
    expect_error(t, "unknown key 'c_X'");
    t = base;
    t.replace(t.find(values), values.size(), "from = 5.0\nto = 5.0\ncount = 3");
    expect_error(t, "empty range");
    t = base;
    t.replace(t.find(values), values.size(), "values = []");
    expect_error(t, "is empty");
    expect_error(base + "[criteria.balancer]\nlimit_speed_ratio = 1.2\n", "no balancer model in scene");
    expect_error(base + "[criteria.response]\nmax_amplitude = 1e-3\ndofs = [\"q\"]\n", "'q' is not a DOF");
    expect_error(base + "[criteria.oops]\n", "unknown key 'oops'");
    t = base;
    t.replace(t.find("[criteria.pervasive]"), 20, "[unused]");
    expect_error(t, "unknown key 'unused'");
}
