// The solvers on fuzzed small models: 1 to 6 DOFs, M, D, G, K and N with entries
// from 1e-30 to 1e30 and exact zeros (singular and structurally singular pencils,
// extreme scales, asymmetric M), at fuzzed speeds. Validation, the dense QZ and state matrix, the
// sparse shift-invert Arnoldi, a Campbell diagram with its critical speeds and
// the unbalance response may refuse with gyrokit's errors; they may not crash,
// hang, or report an eigenvalue or critical speed that is not finite, or an
// amplitude that is NaN.
#include "fuzz_common.hpp"

#include <gyrokit/analysis/campbell.hpp>
#include <gyrokit/analysis/critical_speeds.hpp>
#include <gyrokit/solve/spectrum_solver.hpp>
#include <gyrokit/analysis/unbalance_response.hpp>
#include <gyrokit/eig/sparse_eigensolver.hpp>

#include <cmath>
#include <cstdlib>

namespace {

struct Bytes {
    const uint8_t* p;
    size_t n, i = 0;
    uint8_t next() { return i < n ? p[i++] : 0; }
    // 0 (a quarter of the time), else +-m 10^e with m in [1, 8), e in [-30, 30].
    double value() {
        const uint8_t a = next(), b = next();
        if ((a & 3) == 0) return 0.0;
        const double m = 1.0 + (a >> 2) / 9.0;
        const int e = static_cast<int>(b % 61) - 30;
        return ((a & 4) ? -m : m) * std::pow(10.0, e);
    }
};

void require_finite(double x) {
    if (!std::isfinite(x)) std::abort();   // a silent NaN or infinity is a finding
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace gyrokit;
    Bytes in{data, size};
    const int n = 1 + in.next() % 6;
    const uint8_t shape = in.next();   // which matrices are present, symmetric, with whirl pairs
    Eigen::MatrixXd M(n, n), D(n, n), G(n, n), K(n, n), N(n, n);
    for (auto* A : {&M, &D, &G, &K, &N})
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) (*A)(i, j) = in.value();
    if (shape & 1) M = (0.5 * (M + M.transpose())).eval();
    if (shape & 2) K = (0.5 * (K + K.transpose())).eval();
    if (shape & 4) G = (0.5 * (G - G.transpose())).eval();
    GyroscopicSystem sys;
    sys.M = M;
    sys.K = K;
    if (shape & 8) sys.damping.push_back({"d", D});
    if (shape & 16) sys.G = G;
    if (shape & 32) sys.N = N;
    for (int i = 0; i < n; ++i) sys.dofs.names.push_back("q" + std::to_string(i));
    if ((shape & 64) && n >= 2) sys.whirl_pairs.push_back({0, 1});
    if (shape & 128) {
        sys.unbalance = Eigen::VectorXcd::Zero(n);
        sys.unbalance(0) = in.value();
    }
    const double w = std::fabs(in.value());

    fuzz::expect_gyrokit_errors_only([&] {
        const QuadraticSpectrum s = solve_at_speed(sys, w, {});
        for (const Mode& m : s.modes) {
            require_finite(m.lambda.real());
            require_finite(m.lambda.imag());
        }
    });
    // The state-matrix method: scaled state matrix, dgeev, refinement on the quadratic.
    fuzz::expect_gyrokit_errors_only([&] {
        const QuadraticSpectrum s = solve_at_speed(sys, w, {EigenMethod::StateMatrix, false});
        for (const Mode& m : s.modes) {
            require_finite(m.lambda.real());
            require_finite(m.lambda.imag());
        }
    });
    fuzz::expect_gyrokit_errors_only([&] {
        SparseEigenOptions o;
        o.modes = 1 + in.next() % 3;
        const SparseSpectrum s = solve_quadratic_sparse(sys.sparse_at_speed(w), o, sys.whirl_pairs);
        for (const Mode& m : s.modes) {
            require_finite(m.lambda.real());
            require_finite(m.lambda.imag());
        }
    });
    // The tracking and its root searches (a dozen solves) on a quarter of the inputs.
    if ((shape & 3) == 3) fuzz::expect_gyrokit_errors_only([&] {
        const std::vector<double> speeds{0.0, 0.5 * w, w + 1.0};
        CampbellOptions co;
        co.max_refine = 2;   // a random pencil's branches may stay ambiguous: 256 bisections per step otherwise
        const CampbellDiagram cd = campbell(sys, speeds, co);
        for (const CriticalSpeed& c : critical_speeds(sys, cd, {1})) require_finite(c.speed);
    });
    if (sys.unbalance.size() > 0)
        fuzz::expect_gyrokit_errors_only([&] {
            // Infinite only exactly on an undamped resonance; never NaN.
            const ResponseCurve r = unbalance_response(sys, {w, w + 1.0});
            for (Eigen::Index i = 0; i < r.Z.size(); ++i)
                if (std::isnan(r.Z(i).real()) || std::isnan(r.Z(i).imag())) std::abort();
        });
    return 0;
}
