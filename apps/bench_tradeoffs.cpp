// gyrokit-bench-tradeoffs: the speed-accuracy trade across the toolkit in one
// run. Every row is one setting of one knob (eigensolver, speed grid, Campbell
// step, mesh, truncation, ODE tolerance, averaged equations) with its time per
// call and its largest error against a high-accuracy reference; a second table
// gives the time per speed point of the dense and the sparse eigensolver
// against model size, with the fitted growth exponents (docs/benchmarks.md).
// Exit status: 0 success, 2 bad input, 1 anything else.
#include <gyrokit/analysis/campbell.hpp>
#include <gyrokit/analysis/critical_speeds.hpp>
#include <gyrokit/analysis/spectrum_solver.hpp>
#include <gyrokit/balancing/sommerfeld.hpp>
#include "bench_common.hpp"
#include <gyrokit/core/error.hpp>
#include <gyrokit/io/scene.hpp>
#include <gyrokit/io/table.hpp>
#include <gyrokit/models/fe_rotor.hpp>

#include <CLI/CLI.hpp>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <functional>
#include <iostream>
#include <limits>
#include <set>
#include <sstream>
#include <utility>

using namespace gyrokit;
using namespace gyrokit::bench;

namespace {

constexpr double kPi = 3.14159265358979323846;
const std::vector<std::string> kAreas{"eig", "critical", "campbell", "mesh", "fluid", "balancer", "averaged", "size"};

struct Settings {
    bool quick = false;
    double min_time = 0.2;   // s of repeated calls per row (median of the calls)
    int min_repeats = 3;     // calls per row at least

    // Seconds per call of f (bench_common.hpp); a call longer than `single` s is not repeated.
    template <class F>
    double time(F&& f, double single = 5.0) const {
        return median_seconds(std::forward<F>(f), min_time, min_repeats, single);
    }
};

// The columns of the trade-off table; `seconds` and `error` are "-" when the setting failed.
struct Trade {
    std::string area, model, knob, setting;
    Cell seconds, error;
    std::string error_of, reference, note;
};

void add(Table& t, const Trade& r) {
    t.add_row({r.area, r.model, r.knob, r.setting, r.seconds, r.error, r.error_of, r.reference, r.note});
}

std::string sci(double v) { return fmt::format("{:.1e}", v); }

// The first clause of an error message (the advice after "; " names CLI options).
std::string failure(const std::exception& e) {
    const std::string what = e.what();
    return "failed: " + what.substr(0, what.find("; "));
}

// ---------------------------------------------------------------------------
// Models

constexpr double kE = 2.1e11, kNu = 0.3, kRho = 7850.0;

// Stepped steel shaft of 1.5 m (diameter 60..80 mm) in `elements` equal
// elements, two disks, two anisotropic bearings inboard of the ends
// (overhangs), with or without bearing damping.
FeRotor fe_machine(int elements, bool damped) {
    FeRotor r = fe_uniform_shaft(1.5, elements, 0.06, 0.0, kE, kNu, kRho);
    for (int e = 0; e < elements; ++e)
        r.elements[static_cast<size_t>(e)].outer_diameter += 0.02 * std::sin(3.0 * e / elements);
    const double c = damped ? 1.0 : 0.0;
    r.disks.push_back({elements / 3, 12.0, 0.09, 0.16, 1e-4, 0.0});
    r.disks.push_back({(2 * elements) / 3, 8.0, 0.05, 0.09, 0.0, 0.0});
    r.bearings.push_back({elements / 10, 2e7, 0.0, 0.0, 3e7, 400.0 * c, 0.0, 0.0, 600.0 * c});
    r.bearings.push_back({elements - elements / 10, 3e7, 0.0, 0.0, 2.5e7, 500.0 * c, 0.0, 0.0, 500.0 * c});
    return r;
}

// The family of data/fe_rotor_100k.toml at any size: a hollow shaft (80/30 mm)
// of dofs/4 nodes in 20 mm elements, a bearing (5e8 N/m, 2e3 N s/m) every 50
// elements and at both ends, a disk in the middle of each span; the second and
// fourth spans have longer elements (1.5 m and 1.3 m spans), so that their
// modes are the lowest, apart from the cluster of the equal 1 m spans.
FeRotor fe_train(int dofs) {
    const int elements = dofs / 4 - 1;
    FeRotor r;
    for (int e = 0; e < elements; ++e) {
        FeShaftElement s;
        const int span = e / 50;
        s.length = span == 1 ? 0.03 : span == 3 ? 0.026 : 0.02;
        s.outer_diameter = 0.08;
        s.inner_diameter = 0.03;
        s.youngs_modulus = 211e9;
        s.poisson_ratio = 0.3;
        s.density = 7810;
        r.elements.push_back(s);
    }
    for (int node = 0; node <= elements; node += 50) {
        r.bearings.push_back({node, 5e8, 0.0, 0.0, 5e8, 2e3, 0.0, 0.0, 2e3});
        const int end = std::min(node + 50, elements);
        if (end > node + 1) r.disks.push_back({(node + end) / 2, 15.0, 0.1, 0.18, 0.0, 0.0});
    }
    if (elements % 50 != 0) r.bearings.push_back({elements, 5e8, 0.0, 0.0, 5e8, 2e3, 0.0, 0.0, 2e3});
    return r;
}

// ---------------------------------------------------------------------------
// Reference eigenvalues: every eigenpair of a dense solver refined by Newton's
// method in long double on the bordered system [P(l) x; v^H x - 1] (v the
// start vector): solve P(l) u = P'(l) x, l <- l - 1 / (v^H u), x <- u / (v^H u).
// The pencil's double entries are exact in long double, so the refined pairs
// are eigenpairs of the given pencil with backward errors near long-double
// rounding (1e-19 and below), three orders below what double precision allows.

using cld = std::complex<long double>;
using SpLd = Eigen::SparseMatrix<cld>;
using VecLd = Eigen::Matrix<cld, Eigen::Dynamic, 1>;

struct Reference {
    QuadraticSpectrum spectrum;       // the refined eigenvalues (rounded to double)
    double max_backward_error = 0;    // of the refined pairs, evaluated in long double
    double max_move = 0;              // largest |l_refined - l_start| / |l_start|
    bool distinct = true;             // no two pairs converged to the same eigenvalue
};

Reference refine_long_double(const SparsePencil& p, const QuadraticSpectrum& start) {
    const SpLd M = p.M.cast<cld>(), C = p.C.cast<cld>(), K = p.K.cast<cld>();
    const long double nM = M.norm(), nC = C.norm(), nK = K.norm();
    const SpLd pattern = M + C + K;
    Eigen::SparseLU<SpLd, Eigen::COLAMDOrdering<int>> lu;
    lu.analyzePattern(pattern);
    Reference ref;
    ref.spectrum = start;
    const auto bwd = [&](cld l, const VecLd& x) {
        const VecLd r = (l * l) * (M * x) + l * (C * x) + K * x;
        return r.norm() / ((std::norm(l) * nM + std::abs(l) * nC + nK) * x.norm());
    };
    for (Mode& m : ref.spectrum.modes) {
        cld l(m.lambda.real(), m.lambda.imag());
        VecLd x = m.right.cast<cld>();
        const VecLd v = x / x.squaredNorm();   // v^H x = 1
        long double e = bwd(l, x);
        for (int it = 0; it < 10 && e > 1e-18L; ++it) {
            SpLd P = (l * l) * M + l * C + K;
            lu.factorize(P);
            if (lu.info() != Eigen::Success) break;   // P(l) singular: l is exact
            const VecLd u = lu.solve((cld(2) * l) * (M * x) + C * x);
            const cld vu = v.dot(u);
            const cld l_next = l - cld(1) / vu;
            const VecLd x_next = u / vu;
            if (!std::isfinite(std::abs(l_next)) || !x_next.allFinite()) break;   // keep the last finite pair
            l = l_next;
            x = x_next;
            e = bwd(l, x);
        }
        const std::complex<double> refined(static_cast<double>(l.real()), static_cast<double>(l.imag()));
        ref.max_move = std::max(ref.max_move, std::abs(refined - m.lambda) / std::abs(m.lambda));
        ref.max_backward_error = std::max(ref.max_backward_error, static_cast<double>(e));
        m.lambda = refined;
    }
    for (size_t i = 0; i < ref.spectrum.modes.size(); ++i)
        for (size_t j = i + 1; j < ref.spectrum.modes.size(); ++j)
            if (std::abs(ref.spectrum.modes[i].lambda - ref.spectrum.modes[j].lambda) <=
                1e-12 * std::abs(ref.spectrum.modes[i].lambda))
                ref.distinct = false;
    return ref;
}

// The `k` modes of `s` nearest the shift: the window a sparse solve should return.
QuadraticSpectrum window(const QuadraticSpectrum& s, int k, std::complex<double> shift) {
    QuadraticSpectrum w = s;
    std::sort(w.modes.begin(), w.modes.end(), [&](const Mode& a, const Mode& b) {
        return std::abs(a.lambda - shift) < std::abs(b.lambda - shift);
    });
    if (static_cast<int>(w.modes.size()) > k) w.modes.resize(static_cast<size_t>(k));
    return w;
}

// ---------------------------------------------------------------------------
// 1. Eigensolvers on the same pencil

struct EigCase {
    std::string name;
    GyroscopicSystem sys;
    std::function<SparsePencil(double)> pencil;   // the sparse form the sparse path would use
    double speed;
    std::vector<std::pair<int, int>> sparse_settings;   // (modes k, Lanczos vectors; 0 = default)
};

void eig_rows(Table& t, const Settings& s) {
    const Scene centrifuge = load_scene(std::string(GYROKIT_DATA_DIR) + "/centrifuge.toml");
    const int elements = s.quick ? 24 : 75;
    const FeRotorMatrices fe = fe_machine(elements, true).assemble();
    const auto fe_sys = std::make_shared<GyroscopicSystem>(fe.to_system());
    const GyroscopicSystem& csys = centrifuge.system;
    std::vector<EigCase> cases;
    cases.push_back({"centrifuge (6 DOFs, 30 rad/s)", csys,
                     [&csys](double w) { return csys.sparse_at_speed(w); }, 30.0, {{2, 0}, {4, 0}}});
    cases.push_back({fmt::format("FE rotor ({} DOFs, 1000 rad/s)", fe.size()), fe.to_system(),
                     [fe_sys](double w) { return fe_sys->sparse_at_speed(w); }, 1000.0,
                     {{2, 0}, {6, 16}, {6, 0}, {6, 60}, {12, 28}, {12, 0}}});
    for (const EigCase& c : cases) {
        const QuadraticSpectrum qz = solve_at_speed(c.sys, c.speed);
        const Reference ref = refine_long_double(c.pencil(c.speed), qz);
        std::string reference = fmt::format("QZ + long-double Newton (bwd {})", sci(ref.max_backward_error));
        if (!ref.distinct) reference += ", two pairs met";
        if (ref.max_move > 1e-8) reference += fmt::format(", moved up to {}", sci(ref.max_move));
        const auto dense_row = [&](EigenMethod m) {
            EigenOptions opt;
            opt.method = m;
            Trade r{"eig", c.name, "dense method", to_string(m) + (m == EigenMethod::ScaledQZ ? " (default)" : ""),
                    std::string("-"), std::string("-"), "rel. eigenvalue, all modes", reference, ""};
            try {
                QuadraticSpectrum sp;
                r.seconds = s.time([&] { sp = solve_at_speed(c.sys, c.speed, opt); }, 1.0);
                r.error = max_rel_diff(sp, ref.spectrum);
                r.note = fmt::format("{} modes, max bwd {}; 6 nearest 0: {}", sp.modes.size(),
                                     sci(sp.max_backward_error()),
                                     sci(max_rel_diff(window(sp, 6, 0.0), window(ref.spectrum, 6, 0.0))));
            } catch (const Error& e) {
                r.note = failure(e);
            }
            add(t, r);
        };
        dense_row(EigenMethod::ScaledQZ);
        dense_row(EigenMethod::StateMatrix);
        for (const auto& [k, ncv] : c.sparse_settings) {
            SparseEigenOptions so;
            so.modes = k;
            so.lanczos_vectors = ncv;
            const int nev = std::min(2 * k + 2, 2 * c.sys.size() - 2);
            const int used = ncv > 0 ? ncv : std::min(std::max(2 * nev + 1, 30), 2 * c.sys.size());
            Trade r{"eig", c.name, "sparse shift-invert (sigma = 0)",
                    fmt::format("k = {}, ncv = {}{}", k, used, ncv > 0 ? "" : " (default)"), std::string("-"),
                    std::string("-"), fmt::format("rel. eigenvalue, {} nearest 0", k), reference, ""};
            try {
                SparseSpectrum sp;
                r.seconds = s.time([&] { sp = solve_quadratic_sparse(c.pencil(c.speed), so, c.sys.whirl_pairs); });
                const QuadraticSpectrum q = to_spectrum(sp, c.pencil(c.speed));
                r.error = max_rel_diff(q, window(ref.spectrum, k, 0.0));
                r.note = fmt::format("max bwd {}, {} restarts", sci(q.max_backward_error()), sp.iterations);
            } catch (const Error& e) {
                r.note = failure(e);
            }
            add(t, r);
        }
    }
}

// ---------------------------------------------------------------------------
// 2. Critical speeds: grid crossings vs refined roots

// Crossings of Im lambda = k w read off the branch points by linear interpolation.
std::vector<double> grid_crossings(const CampbellDiagram& cd, int k) {
    std::vector<double> out;
    for (const Branch& b : cd.branches)
        for (size_t i = 0; i + 1 < b.points.size(); ++i) {
            const BranchPoint &p0 = b.points[i], &p1 = b.points[i + 1];
            if (p0.mode.whirl == Whirl::Real || p1.mode.whirl == Whirl::Real) continue;
            const double g0 = p0.mode.lambda.imag() - k * p0.speed, g1 = p1.mode.lambda.imag() - k * p1.speed;
            if (g0 == 0.0 && i > 0) continue;
            if ((g0 > 0) == (g1 > 0) && g0 != 0.0 && g1 != 0.0) continue;
            out.push_back(p0.speed + (p1.speed - p0.speed) * g0 / (g0 - g1));
        }
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<double> speeds_of(const std::vector<CriticalSpeed>& cs) {
    std::vector<double> w;
    for (const auto& c : cs) w.push_back(c.speed);
    return w;
}

// Largest relative distance of each speed to the nearest one of the other list, both ways.
double speed_list_error(const std::vector<double>& w, const std::vector<double>& ref) {
    if (w.empty() || ref.empty()) return w.size() == ref.size() ? 0.0 : std::numeric_limits<double>::infinity();
    const auto one_way = [](const std::vector<double>& a, const std::vector<double>& b, bool a_is_ref) {
        double worst = 0.0;
        for (double x : a) {
            double nearest = b.front();
            for (double y : b)
                if (std::fabs(y - x) < std::fabs(nearest - x)) nearest = y;
            worst = std::max(worst, std::fabs(x - nearest) / std::fabs(a_is_ref ? x : nearest));
        }
        return worst;
    };
    return std::max(one_way(w, ref, false), one_way(ref, w, true));
}

struct SpeedCase {
    std::string name;
    GyroscopicSystem sys;
    double from, to;
    int modes;   // branches kept (CampbellOptions::modes)
};

void critical_rows(Table& t, const Settings& s) {
    std::vector<SpeedCase> cases;
    cases.push_back({"centrifuge (6 DOFs)", load_scene(std::string(GYROKIT_DATA_DIR) + "/centrifuge.toml").system,
                     0.0, 60.0, 6});
    cases.push_back({"FE rotor, undamped (52 DOFs)", fe_machine(12, false).assemble().to_system(), 0.0, 3000.0, 8});
    const std::vector<int> counts = s.quick ? std::vector<int>{4, 13, 61} : std::vector<int>{4, 7, 13, 25, 61, 241};
    for (const SpeedCase& c : cases) {
        CampbellOptions opt;
        opt.modes = c.modes;
        std::vector<double> ref;
        std::string reference;
        if (c.sys.has_damping()) {
            const int fine = s.quick ? 241 : 961;
            ref = speeds_of(critical_speeds(c.sys, campbell(c.sys, linspace(c.from, c.to, fine), opt), {1}));
            reference = fmt::format("Brent (1e-13) on {} speeds", fine);
        } else {
            ref = speeds_of(critical_speeds_direct(c.sys, 1, c.from, c.to));
            // Independent of tracking and root finding: the eigenvalues w^2 of a Hermitian pencil (the
            // range holds only crossings of the tracked branches). The library's refined result on a
            // fine grid is shown beside it.
            const int check = s.quick ? 61 : 241;
            const std::vector<double> tracked =
                speeds_of(critical_speeds(c.sys, campbell(c.sys, linspace(c.from, c.to, check), opt), {1}));
            reference = fmt::format("direct Hermitian pencil in w^2 (Brent on {} speeds: {})", check,
                                    sci(speed_list_error(tracked, ref)));
        }
        const std::string model = fmt::format("{}, {}..{} rad/s, {} crit.", c.name, c.from, c.to, ref.size());
        for (int n : counts) {
            const std::vector<double> grid = linspace(c.from, c.to, n);
            CampbellDiagram cd;
            const double t_cd = s.time([&] { cd = campbell(c.sys, grid, opt); });
            std::vector<CriticalSpeed> refined;
            const double t_ref = s.time([&] { refined = critical_speeds(c.sys, cd, {1}); });
            const std::vector<double> lin = grid_crossings(cd, 1);
            const std::string note = fmt::format("{} inserted speeds", cd.inserted_speeds);
            add(t, {"critical", model, "speed grid", fmt::format("{} speeds, linear interpolation", n), t_cd,
                    speed_list_error(lin, ref), "rel. critical speed", reference,
                    fmt::format("{} found; {}", lin.size(), note)});
            add(t, {"critical", model, "speed grid", fmt::format("{} speeds + Brent refinement", n), t_cd + t_ref,
                    speed_list_error(speeds_of(refined), ref), "rel. critical speed", reference,
                    fmt::format("{} found; {}", refined.size(), note)});
        }
    }
}

// ---------------------------------------------------------------------------
// 3. Campbell tracking step

// The point of a branch at speed w (nullptr if the branch has none there).
const BranchPoint* point_at(const Branch& b, double w) {
    for (const BranchPoint& p : b.points)
        if (std::fabs(p.speed - w) <= 1e-9 * std::max(1.0, std::fabs(w))) return &p;
    return nullptr;
}

// lambda of a branch at w by linear interpolation between its points.
std::complex<double> interpolate(const Branch& b, double w) {
    const auto& p = b.points;
    if (w <= p.front().speed) return p.front().mode.lambda;
    for (size_t i = 0; i + 1 < p.size(); ++i)
        if (w <= p[i + 1].speed) {
            const double u = (w - p[i].speed) / (p[i + 1].speed - p[i].speed);
            return (1.0 - u) * p[i].mode.lambda + u * p[i + 1].mode.lambda;
        }
    return p.back().mode.lambda;
}

void campbell_rows(Table& t, const Settings& s) {
    std::vector<SpeedCase> cases;
    // The centrifuge beyond its scene's range (0..60 rad/s), where coarse steps skip over crossings.
    cases.push_back({"centrifuge (6 DOFs)", load_scene(std::string(GYROKIT_DATA_DIR) + "/centrifuge.toml").system,
                     0.0, 300.0, 6});
    cases.push_back({"FE rotor, damped (52 DOFs)", fe_machine(12, true).assemble().to_system(), 0.0, 4000.0, 8});
    // Every coarse grid speed is a fine one: 480 = 3 * 160 = 10 * 48 = 40 * 12 = 160 * 3, 120 = 3 * 40 = 10 * 12.
    const int fine = s.quick ? 121 : 481;
    const std::vector<int> counts = s.quick ? std::vector<int>{4, 11, 41} : std::vector<int>{4, 11, 41, 161};
    for (const SpeedCase& c : cases) {
        CampbellOptions opt;
        opt.modes = c.modes;
        const std::vector<double> fine_grid = linspace(c.from, c.to, fine);
        const CampbellDiagram ref = campbell(c.sys, fine_grid, opt);
        const std::string reference =
            fmt::format("tracking on {} speeds ({} inserted, {} ambiguous)", fine, ref.inserted_speeds,
                        ref.ambiguous_steps);
        const std::string model = fmt::format("{}, {}..{} rad/s, {} branches", c.name, c.from, c.to, c.modes);
        for (int n : counts)
            for (int max_refine : {8, 0}) {
                if (max_refine == 0 && (n == 4 || n == 161)) continue;
                CampbellOptions o = opt;
                o.max_refine = max_refine;
                const std::vector<double> grid = linspace(c.from, c.to, n);
                CampbellDiagram cd;
                const double sec = s.time([&] { cd = campbell(c.sys, grid, o); });
                // Mis-connection: a grid point of coarse branch b that is not the reference's branch b there.
                int wrong = 0, points = 0;
                double err = 0.0;
                for (size_t b = 0; b < cd.branches.size() && b < ref.branches.size(); ++b) {
                    for (double w : grid) {
                        const BranchPoint* p = point_at(cd.branches[b], w);
                        const BranchPoint* q = point_at(ref.branches[b], w);
                        if (!p && !q) continue;
                        ++points;
                        if (!p || !q || std::abs(p->mode.lambda - q->mode.lambda) > 1e-8 * std::abs(q->mode.lambda))
                            ++wrong;
                    }
                    // The coarse branch drawn as a polyline, read at the fine speeds.
                    for (const BranchPoint& q : ref.branches[b].points) {
                        const double f = interpolate(cd.branches[b], q.speed).imag(), f_ref = q.mode.lambda.imag();
                        err = std::max(err, std::fabs(f - f_ref) / std::abs(q.mode.lambda));
                    }
                }
                std::string note = fmt::format("mis-connected {}/{} grid points; {} inserted, {} ambiguous", wrong,
                                               points, cd.inserted_speeds, cd.ambiguous_steps);
                if (wrong > 0 && cd.ambiguous_steps == 0) note += "; not flagged";
                add(t, {"campbell", model, "tracking step",
                        fmt::format("{} speeds, max_refine {}{}", n, max_refine, max_refine == 8 ? " (default)" : ""),
                        sec, err, fmt::format("rel. branch frequency ({} speeds)", fine), reference, note});
            }
    }
}

// ---------------------------------------------------------------------------
// 4. FE mesh density against the closed-form pinned-pinned beam

void mesh_rows(Table& t, const Settings& s) {
    const double L = 1.0, d = 0.02;   // L/d = 50, Euler-Bernoulli (shear and rotary inertia off)
    FeShaftElement probe;
    probe.outer_diameter = d;
    const FeSection sec = fe_section(probe);
    const double c = std::sqrt(kE * sec.second_moment / (kRho * sec.area));
    const std::vector<int> counts =
        s.quick ? std::vector<int>{4, 16, 64} : std::vector<int>{4, 8, 16, 32, 64, 128, 256, 512, 1024};
    const std::string reference = "(k pi / L)^2 sqrt(EI / rho A), k = 1..3";
    for (int count : counts) {
        FeRotor r = fe_uniform_shaft(L, count, d, 0.0, kE, kNu, kRho);
        r.supports.push_back({0, true, true, false, false});
        r.supports.push_back({count, true, true, false, false});
        r.shear_deformation = false;
        r.rotary_inertia = false;
        const auto error = [&](const QuadraticSpectrum& sp) {
            double e = 0.0;   // modes 1..6: x and y planes of k = 1, 2, 3
            for (int i = 0; i < 6; ++i) {
                const int k = i / 2 + 1;
                const double exact = std::pow(k * kPi / L, 2) * c;
                e = std::max(e, std::fabs(sp.modes[static_cast<size_t>(i)].frequency() - exact) / exact);
            }
            return e;
        };
        SparseEigenOptions so;
        so.modes = 6;
        QuadraticSpectrum sp;
        const double t_sparse = s.time(
            [&] {
                const FeRotorMatrices m = r.assemble();
                sp = to_spectrum(solve_quadratic_sparse(m.at_speed(0.0), so, m.whirl_pairs), m.at_speed(0.0));
            });
        const int n = r.assemble().size();
        const std::string model = "pinned-pinned Euler-Bernoulli beam, L/d = 50";
        add(t, {"mesh", model, "elements", fmt::format("{} ({} DOFs), sparse k = 6", count, n), t_sparse, error(sp),
                "rel. frequency, 3 lowest (x, y)", reference, fmt::format("max bwd {}", sci(sp.max_backward_error()))});
        if (count <= (s.quick ? 16 : 64)) {
            const double t_dense = s.time([&] { sp = solve_at_speed(r.assemble().to_system(), 0.0); }, 1.0);
            add(t, {"mesh", model, "elements", fmt::format("{} ({} DOFs), dense QZ", count, n), t_dense, error(sp),
                    "rel. frequency, 3 lowest (x, y)", reference,
                    fmt::format("max bwd {}", sci(sp.max_backward_error()))});
        }
    }
}

// ---------------------------------------------------------------------------
// 5. Liquid-filled rotor truncation, auto-balancer ODE, averaged equations

void fluid_rows(Table& t, const Settings& s) {
    // (sloshing modes, J* terms); 0, 0 is the default: modes until the tolerance 1e-10, 100 J* terms plus the tail.
    const std::vector<std::pair<int, int>> settings =
        s.quick ? std::vector<std::pair<int, int>>{{5, 10}, {0, 0}}
                : std::vector<std::pair<int, int>>{{1, 10}, {5, 10},   {10, 10},  {30, 10}, {100, 3},
                                                   {100, 10}, {100, 100}, {100, 1000}, {0, 0}};
    for (int N : {2, 4}) {
        const std::vector<double> w_ref = fluid_undamped_speeds(fluid_reference_case(N));
        for (const auto& [modes, nj] : settings) {
            FluidRotorParameters p = fluid_table_case(N);
            p.modes = modes;
            p.jstar_terms = nj;
            std::vector<double> w;
            const double sec = s.time([&] { w = fluid_undamped_speeds(p); });
            const FluidRotor f = build_fluid_rotor(p);
            const std::string setting =
                modes == 0 ? "to tol 1e-10 / auto (default)" : fmt::format("{} / {}", modes, nj);
            add(t, {"fluid", fmt::format("Tabelle 2 case N{}", N), "sloshing modes / J* terms", setting, sec,
                    max_rel_deviation(w, w_ref), "rel. critical speed", "400 modes, 20000 J* terms",
                    fmt::format("{} modes, {} J* terms used", f.liquid.modes.size(), f.liquid.jstar_terms)});
        }
    }
}

void balancer_rows(Table& t, const Settings& s) {
    struct Setting {
        OdeMethod method;
        double tol;
    };
    const std::vector<Setting> settings =
        s.quick ? std::vector<Setting>{{OdeMethod::Rk8pd, 1e-6}, {OdeMethod::Rk8pd, 1e-10}}
                : std::vector<Setting>{{OdeMethod::Rk8pd, 1e-6},  {OdeMethod::Rk8pd, 1e-8},  {OdeMethod::Rk8pd, 1e-10},
                                       {OdeMethod::Rk8pd, 1e-12}, {OdeMethod::Rkf45, 1e-6},  {OdeMethod::Rkf45, 1e-10},
                                       {OdeMethod::Msbdf, 1e-8}};
    for (const std::string name : {"bild9", "bild10"}) {
        const BalancerScene sc = load_data_balancer_scene("balancer_" + name + ".toml");
        const SimulationResult r0 = balancer_reference(sc);
        for (const Setting& st : settings) {
            const bool def = st.method == OdeMethod::Rk8pd && st.tol == 1e-10;
            Trade r{"balancer", "auto-balancer " + name + ", full equations (18)", "ODE method / tolerance",
                    fmt::format("{} {:g}{}", ode_method_name(st.method), st.tol, def ? " (default)" : ""),
                    std::string("-"), std::string("-"), "final phases, deg", "rk8pd, tol 1e-13", ""};
            try {
                SimulationResult res;
                r.seconds = s.time([&] { res = run_balancer(sc, false, st.method, st.tol); });
                r.error = final_phase_error(res, r0) * 180 / kPi;
                r.note = fmt::format("{} steps", res.stats.steps);
            } catch (const Error& e) {
                r.note = failure(e);
            }
            add(t, r);
        }
    }
}

void averaged_rows(Table& t, const Settings& s) {
    // Auto-balancer: averaged slow-phase equations and their stationary state vs the full equations.
    for (const std::string name : {"bild9", "bild10"}) {
        const BalancerScene sc = load_data_balancer_scene("balancer_" + name + ".toml");
        const SimulationResult r0 = balancer_reference(sc);
        const std::string model = "auto-balancer " + name, reference = "full (18), rk8pd, tol 1e-13";
        SimulationResult full, avg;
        const double t_full = s.time([&] { full = run_balancer(sc, false, OdeMethod::Rk8pd, 1e-10); });
        const double t_avg = s.time([&] { avg = run_balancer(sc, true, OdeMethod::Rk8pd, 1e-10); });
        add(t, {"averaged", model, "equations", "full (18), rk8pd 1e-10", t_full,
                final_phase_error(full, r0) * 180 / kPi, "final phases, deg", reference,
                fmt::format("{} steps", full.stats.steps)});
        add(t, {"averaged", model, "equations", "averaged slow-phase, rk8pd 1e-10", t_avg,
                final_phase_error(avg, r0) * 180 / kPi, "final phases, deg", reference,
                fmt::format("{} steps", avg.stats.steps)});
        // The stationary state of the damped slow equations, started from the
        // synchronous state nearest to where the full run ends.
        const double speed = sc.params.reference_speed();
        SynchronousState near;
        double best = std::numeric_limits<double>::infinity();
        for (const SynchronousState& st : synchronous_states(sc.params)) {
            double dist = 0.0;
            for (size_t i = 0; i < st.alpha.size(); ++i)
                dist = std::max(dist, phase_distance(st.alpha[i], r0.final_alpha[i]));
            if (dist < best) best = dist, near = st;
        }
        SimulationResult eq;
        const double t_eq = s.time([&] { eq.final_alpha = damped_equilibrium(sc.params, speed, near.alpha); });
        add(t, {"averaged", model, "equations", fmt::format("stationary slow-phase state ({})", near.label), t_eq,
                final_phase_error(eq, r0) * 180 / kPi, "final phases, deg", reference, "Newton on V_i = 0"});
    }
    // Sommerfeld run-ups: the speeds held after the run-up vs the stationary curves.
    for (const std::string name : {"rotor", "two_rollers_unbalance"}) {
        const BalancerScene sc = load_data_balancer_scene("sommerfeld_" + name + ".toml");
        const RunupSettings ref = sommerfeld_reference_settings(sc);
        const RunupResult r0 = simulate_runup(sc.params, ref);
        const bool rollers = !sc.params.rollers.empty();
        const auto held_error = [&](double rotor, double roller) {
            double e = std::fabs(rotor / r0.held_rotor_speed - 1.0);
            if (rollers) e = std::max(e, std::fabs(roller / r0.held_roller_speed - 1.0));
            return e;
        };
        const std::string model = "Sommerfeld run-up " + name, reference = "full (7), rk8pd, tol 1e-12";
        const std::string error_of = rollers ? "rel. held rotor and roller speed" : "rel. held rotor speed";
        RunupSettings def = ref;
        def.ode = sc.runup.ode;
        RunupResult r;
        const double t_full = s.time([&] { r = simulate_runup(sc.params, def); }, 1.0);
        add(t, {"averaged", model, "equations",
                fmt::format("full (7), {} {:g}", ode_method_name(def.ode.method), def.ode.rel_tol), t_full,
                held_error(r.held_rotor_speed, r.held_roller_speed), error_of, reference,
                fmt::format("{} steps, {}", r.stats.steps, summarize_runup(sc.params, r).outcome)});
        RunupSummary sum;
        const double t_st = s.time([&] { sum = summarize_runup(sc.params, r0); });
        add(t, {"averaged", model, "equations", "stationary curve at the held nominal speed", t_st,
                held_error(sum.stationary_rotor_speed, sum.stationary_roller_speed), error_of, reference,
                fmt::format("branch {}, {}", sum.branch, sum.outcome)});
    }
}

// ---------------------------------------------------------------------------
// Time per speed point against model size

struct SizePoint {
    std::string path;
    int n;
    double seconds;
};

// Least-squares slope of log(seconds) against log(n).
double growth_exponent(const std::vector<SizePoint>& pts) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    const double m = static_cast<double>(pts.size());
    for (const SizePoint& p : pts) {
        const double x = std::log(p.n), y = std::log(p.seconds);
        sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
    return (m * sxy - sx * sy) / (m * sxx - sx * sx);
}

void size_rows(Table& t, Table& fit, const Settings& s) {
    const double w = 300.0;
    const std::vector<int> dense_sizes = s.quick ? std::vector<int>{100, 200} : std::vector<int>{100, 200, 400, 1000};
    const std::vector<int> sparse_sizes =
        s.quick ? std::vector<int>{100, 1000, 10000} : std::vector<int>{100, 300, 1000, 3000, 10000, 30000, 100000};
    const std::vector<int> train_sizes = s.quick ? std::vector<int>{1000} : std::vector<int>{1000, 3000, 10000};
    const std::string dense = "dense QZ, all modes", sparse = "sparse k = 6", train = "sparse k = 6, train of spans";
    std::vector<SizePoint> pts;
    const auto row = [&](const std::string& path, int n, const FeRotor& r, double sec, const QuadraticSpectrum& sp,
                         const std::string& note) {
        pts.push_back({path, n, sec});
        t.add_row({path, static_cast<long long>(n), static_cast<long long>(r.elements.size()), sec,
                   static_cast<long long>(sp.modes.size()), sp.max_backward_error(), note});
    };
    for (int n : dense_sizes) {
        const FeRotor r = fe_machine(n / 4 - 1, true);
        const GyroscopicSystem sys = r.assemble().to_system();
        QuadraticSpectrum sp;
        const double sec = s.time([&] { sp = solve_at_speed(sys, w); }, 2.0);
        row(dense, sys.size(), r, sec, sp, "");
    }
    SparseEigenOptions so;
    so.modes = 6;
    const auto sparse_run = [&](const std::string& path, const FeRotor& r) {
        const GyroscopicSystem sys = r.assemble().to_system();
        QuadraticSpectrum sp;
        int restarts = 0;
        const double sec = s.time(
            [&] {
                const SparsePencil p = sys.sparse_at_speed(w);
                SparseSpectrum ss = solve_quadratic_sparse(p, so, sys.whirl_pairs);
                restarts = ss.iterations;
                sp = to_spectrum(std::move(ss), p);
            },
            2.0);
        const double lowest = sp.modes.empty() ? 0.0 : sp.modes.front().frequency();
        row(path, sys.size(), r, sec, sp, fmt::format("{} restarts; lowest {:.6g} rad/s", restarts, lowest));
    };
    for (int n : sparse_sizes) sparse_run(sparse, fe_machine(n / 4 - 1, true));
    for (int n : train_sizes) sparse_run(train, fe_train(n));
    for (const std::string& path : {dense, sparse, train}) {
        std::vector<SizePoint> p;
        for (const SizePoint& q : pts)
            if (q.path == path) p.push_back(q);
        for (size_t from : {size_t(0), p.size() >= 4 ? p.size() - 3 : p.size()}) {
            if (p.size() - from < 2) continue;
            const std::vector<SizePoint> sub(p.begin() + static_cast<std::ptrdiff_t>(from), p.end());
            fit.add_row({path, fmt::format("{}..{} ({} sizes)", sub.front().n, sub.back().n, sub.size()),
                         growth_exponent(sub)});
        }
    }
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Speed-accuracy trade across gyrokit: time per call and error against a reference for every "
                 "knob, and time per speed point against model size"};
    Settings s;
    std::string format = "table", only, table;
    app.add_flag("--quick", s.quick, "small sizes and few settings (a smoke run)");
    app.add_option("--only", only, "run only these areas (comma-separated): eig, critical, campbell, mesh, fluid, "
                                   "balancer, averaged, size");
    app.add_option("--min-time", s.min_time, "minimum measuring time per row, s (median of the calls)")
        ->check(CLI::Range(0.0, 3600.0));
    app.add_option("--format", format, "output format: table, csv or json")->capture_default_str();
    app.add_option("--table", table, "only this table: tradeoffs, size, growth (CSV holds the first unless one is "
                                     "named)");
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << "error: " << e.what() << " (see --help)\n";
        return 2;
    }
    if (s.quick) {
        s.min_repeats = 1;
        if (app.count("--min-time") == 0) s.min_time = 0.02;
    }

    return bench::guarded_main([&] {
        const TableFormat fmt_out = parse_table_format(format);
        std::set<std::string> areas(kAreas.begin(), kAreas.end());
        if (!only.empty()) {
            areas.clear();
            std::stringstream ss(only);
            for (std::string a; std::getline(ss, a, ',');) {
                if (std::find(kAreas.begin(), kAreas.end(), a) == kAreas.end())
                    throw InputError(fmt::format("--only {}: unknown area '{}'; allowed: eig, critical, campbell, "
                                                 "mesh, fluid, balancer, averaged, size",
                                                 only, a));
                areas.insert(a);
            }
        }
        Table trade({"area", "model", "knob", "setting", "seconds", "error", "error_of", "reference", "note"});
        trade.key = "tradeoffs";
        trade.title = "Speed-accuracy trade: seconds per call (median), largest error against the reference";
        if (areas.count("eig")) eig_rows(trade, s);
        if (areas.count("critical")) critical_rows(trade, s);
        if (areas.count("campbell")) campbell_rows(trade, s);
        if (areas.count("mesh")) mesh_rows(trade, s);
        if (areas.count("fluid")) fluid_rows(trade, s);
        if (areas.count("balancer")) balancer_rows(trade, s);
        if (areas.count("averaged")) averaged_rows(trade, s);
        std::vector<Table> out;
        if (trade.rows() > 0) out.push_back(trade);
        if (areas.count("size")) {
            Table size({"path", "n", "elements", "seconds_per_point", "modes", "max_backward_error", "note"});
            size.key = "size";
            size.title = "Time per speed point against model size (FE rotor, 300 rad/s)";
            Table fit({"path", "sizes", "growth_exponent"});
            fit.key = "growth";
            fit.title = "Growth exponent: slope of log(seconds) against log(n)";
            size_rows(size, fit, s);
            out.push_back(size);
            out.push_back(fit);
        }
        std::vector<std::string> left_out;
        write_result(std::cout, out, fmt_out, table, "--table", left_out);
        for (const auto& k : left_out) std::cerr << "note: CSV holds one table; --table " << k << " gives another\n";
    });
}
