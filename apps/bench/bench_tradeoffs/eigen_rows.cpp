// gyrokit-bench-tradeoffs: the rows of the eigensolvers. Dense and sparse
// solvers on the same pencil against long-double references (area "eig"), the
// FE mesh density against a closed form (area "mesh"), and the time per speed
// point against model size with its growth exponents (tables size, growth).
#include "models.hpp"
#include "reference.hpp"
#include "tradeoffs.hpp"

#include <gyrokit/solve/spectrum_solver.hpp>
#include <gyrokit/core/constants.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/scene/scene.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <fmt/format.h>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

using namespace gyrokit;
using namespace gyrokit::bench;

namespace tradeoffs {

namespace {

struct EigCase {
    std::string name;
    GyroscopicSystem sys;
    std::function<SparsePencil(double)> pencil;   // the sparse form the sparse path would use
    double speed;
    std::vector<std::pair<int, int>> sparse_settings;   // (modes k, Lanczos vectors; 0 = default)
};

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

}  // namespace

// ---------------------------------------------------------------------------
// 1. Eigensolvers on the same pencil

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
        const QuadraticSpectrum qz = solve_at_speed(c.sys, c.speed, {EigenMethod::ScaledQZ, false});
        const Reference ref = refine_long_double(c.pencil(c.speed), qz);
        std::string reference = fmt::format("QZ + long-double Newton (bwd {})", sci(ref.max_backward_error));
        if (!ref.distinct) reference += ", two pairs met";
        if (ref.max_move > 1e-8) reference += fmt::format(", moved up to {}", sci(ref.max_move));
        const auto dense_row = [&](EigenMethod m) {
            EigenOptions opt;
            opt.method = m;
            Trade r{"eig", c.name, "dense method", to_string(m) + (m == EigenMethod::Auto ? " (default)" : ""),
                    std::string("-"), std::string("-"), "rel. eigenvalue, all modes", reference, ""};
            try {
                QuadraticSpectrum sp;
                r.seconds = s.time([&] { sp = solve_at_speed(c.sys, c.speed, opt); }, 1.0);
                r.error = max_rel_diff(sp, ref.spectrum);
                r.note = fmt::format("{}{} modes, max bwd {}; 6 nearest 0: {}",
                                     m == EigenMethod::Auto ? "by " + sp.method + ", " : "", sp.modes.size(),
                                     sci(sp.max_backward_error()),
                                     sci(max_rel_diff(window(sp, 6, 0.0), window(ref.spectrum, 6, 0.0))));
            } catch (const Error& e) {
                r.note = failure(e);
            }
            add(t, r);
        };
        dense_row(EigenMethod::Auto);
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
// Time per speed point against model size

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

}  // namespace tradeoffs
