// A model from your own Eigen matrices: a Jeffcott rotor (mass m on a shaft of
// stiffness k) with a disk of polar inertia Ip and diametral inertia Id at the
// shaft end, as M, G, K in the coordinates [x, y, theta_x, theta_y]. Prints the
// eigenvalues at 100 rad/s with their backward errors and whirl direction, and
// checks them against the closed form: sqrt(k/m) for translation, and for tilt
// the roots of Id f^2 -+ Ip w f - kt = 0 (forward and backward whirl).
#include <gyrokit/gyrokit.hpp>

#include <cmath>
#include <cstdio>

int main() {
    const double m = 5.0, Id = 0.02, Ip = 0.04, k = 2e5, kt = 4e3;
    gyrokit::GyroscopicSystem sys;
    sys.dofs.names = {"x", "y", "theta_x", "theta_y"};
    sys.M = Eigen::Vector4d(m, m, Id, Id).asDiagonal();
    sys.K = Eigen::Vector4d(k, k, kt, kt).asDiagonal();
    Eigen::Matrix4d G = Eigen::Matrix4d::Zero();
    G(2, 3) = Ip;   // gyroscopic moments per unit speed: Ip w theta_y' and -Ip w theta_x'
    G(3, 2) = -Ip;
    sys.G = G;      // stored sparse; a large model assigns an Eigen::SparseMatrix<double> instead
    sys.whirl_pairs = {{0, 1}, {2, 3}};
    sys.validate("own_matrices");

    const double w = 100.0;
    const gyrokit::QuadraticSpectrum s = gyrokit::solve_at_speed(sys, w);
    const double root = std::sqrt(Ip * Ip * w * w + 4 * Id * kt);
    const double expected[] = {std::sqrt(k / m), std::sqrt(k / m), (root - Ip * w) / (2 * Id), (root + Ip * w) / (2 * Id)};
    if (s.modes.size() != 4) return 1;
    int wrong = 0;
    for (size_t i = 0; i < 4; ++i) {
        const auto& mode = s.modes[i];
        std::printf("lambda = %+.3e %+.10fi  closed form %.10f  backward error %.1e  %s\n", mode.lambda.real(),
                    mode.lambda.imag(), expected[i], mode.backward_error, gyrokit::to_string(mode.whirl).c_str());
        if (std::abs(mode.lambda - std::complex<double>(0.0, expected[i])) > 1e-12 * expected[i]) ++wrong;
    }
    return wrong == 0 ? 0 : 1;
}
