// Frequency response functions against closed forms and an independent modal
// superposition of the same model (the state matrix's eigenvectors).
#include <gyrokit/analysis/frequency_response.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/scene/scene.hpp>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <catch2/catch.hpp>
#include <cmath>

using namespace gyrokit;

TEST_CASE("frequency response: a damped Jeffcott rotor, H_xx = 1 / (k - m w^2 + i c w)") {
    const double m = 10.0, k = 1e6, c = 200.0;
    GyroscopicSystem s;
    s.dofs.names = {"x", "y"};
    s.M = SystemMatrix(Eigen::MatrixXd(Eigen::Matrix2d::Identity() * m).sparseView());
    s.K = SystemMatrix(Eigen::MatrixXd(Eigen::Matrix2d::Identity() * k).sparseView());
    s.damping.push_back({"d", SystemMatrix(Eigen::MatrixXd(Eigen::Matrix2d::Identity() * c).sparseView())});
    s.whirl_pairs = {{0, 1}};
    const std::vector<double> w = {0.0, 100.0, 316.2, std::sqrt(k / m), 1000.0};
    const FrequencyResponse r = frequency_response(s, 50.0, w, 0);
    for (std::size_t i = 0; i < w.size(); ++i) {
        const std::complex<double> exact = 1.0 / std::complex<double>(k - m * w[i] * w[i], c * w[i]);
        // One 2 x 2 LU: a few ulp of |H|.
        CHECK(std::abs(r.H(static_cast<Eigen::Index>(i), 0) - exact) <= 1e-14 * std::abs(exact));
        CHECK(std::abs(r.H(static_cast<Eigen::Index>(i), 1)) == 0.0);   // the planes do not couple
    }
    CHECK_THROWS_WITH(frequency_response(s, 50.0, w, 2), Catch::Contains("input DOF 2; allowed: 0 to 1"));
    CHECK_THROWS_WITH(frequency_response(s, 50.0, {-1.0}, 0), Catch::Contains("frequency -1"));
    CHECK_THROWS_WITH(frequency_response(s, 50.0, {}, 0), Catch::Contains("no frequencies; allowed: one or more"));
    CHECK_THROWS_AS(frequency_response(s, 50.0, {}, 0), InputError);
}

TEST_CASE("frequency response: an FE rotor's FRF equals the modal superposition of its state matrix") {
    const Scene sc = load_scene(std::string(GYROKIT_DATA_DIR) + "/three_disk_rotor.toml");
    const GyroscopicSystem& sys = sc.system;
    const double spin = 600.0;
    const int n = sys.size();
    const auto names = sys.dofs.names;
    const int input = static_cast<int>(std::find(names.begin(), names.end(), "y12") - names.begin());
    std::vector<double> w;
    for (int i = 0; i <= 40; ++i) w.push_back(75.0 * i);
    const FrequencyResponse r = frequency_response(sys, spin, w, input);

    // Independent: the state x = [s q; q'] with x' = A x + B f, A = [0 s I; -M^-1 K / s -M^-1 C]
    // at the spin, diagonalised: H(w) = [I / s 0] V diag(1 / (i w - lambda)) V^-1 B. The scale
    // s = sqrt(||M^-1 K||) keeps ||A|| near the largest |lambda| (unscaled, M^-1 K alone is its square).
    const QuadraticPencil p = sys.at_speed(spin);
    const Eigen::MatrixXd Minv = p.M.inverse();
    const double scale = std::sqrt((Minv * p.K).norm());
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
    A.topRightCorner(n, n) = scale * Eigen::MatrixXd::Identity(n, n);
    A.bottomLeftCorner(n, n) = -Minv * p.K / scale;
    A.bottomRightCorner(n, n) = -Minv * p.C;
    Eigen::VectorXcd B = Eigen::VectorXcd::Zero(2 * n);
    B.tail(n) = Minv.col(input).cast<std::complex<double>>();
    const Eigen::ComplexEigenSolver<Eigen::MatrixXcd> es(A.cast<std::complex<double>>());
    const Eigen::MatrixXcd& V = es.eigenvectors();
    const Eigen::VectorXcd b = V.partialPivLu().solve(B);
    const Eigen::JacobiSVD<Eigen::MatrixXcd> svd(V);
    const double cond = svd.singularValues()(0) / svd.singularValues()(2 * n - 1);
    for (std::size_t i = 0; i < w.size(); ++i) {
        const std::complex<double> iw(0.0, w[i]);
        Eigen::VectorXcd q(2 * n);
        for (int k = 0; k < 2 * n; ++k) q(k) = b(k) / (iw - es.eigenvalues()(k));
        const Eigen::VectorXcd modal = (V * q).head(n) / scale;
        // The modal sum carries the eigenvector basis's condition number times the
        // rounding of A (whose entries span K/M ~ 1e9 to 1): 1e3 cond eps relative.
        const double relative = (r.H.row(static_cast<Eigen::Index>(i)).transpose() - modal).norm() / modal.norm();
        // The modal sum's error: the eigenvectors' rounding (eps ||A|| over the distance to
        // the nearest eigenvalue, amplified by the basis's condition number) carried by each
        // term 1 / (i w - lambda_k): cond eps ||A|| / min_k |i w - lambda_k|.
        const double gap = (es.eigenvalues().array() - iw).abs().minCoeff();
        const double bound = cond * 2.2e-16 * A.norm() / gap;
        CAPTURE(w[i], cond, relative, bound);
        CHECK(relative <= bound);
    }
}
