// The pervasive-damping check on the undamped system's continued modes against the
// definition solved in full: at every grid speed, every damping set's own system
// (that set alone) by dense QZ with left vectors, each mode up to f_cut tested on
// [P_D(lambda)^T; D] over its left plane. Every clear loss of the reference is
// found, and every loss found is one (at a grid speed: the reference's residual
// below the tolerance; between grid speeds: an eigenvalue of the set's system there
// with a residual at the loss level), on every data/ scene with damping.
#include <gyrokit/analysis/pervasive_damping.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>
#include <gyrokit/scene/scene.hpp>

#include <Eigen/QR>
#include <Eigen/SVD>
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <utility>
#include <limits>
#include <string>
#include <vector>

using namespace gyrokit;

namespace {

// The reference residual of every mode of the set's own system at w up to `band`
// (rad/s): the smallest over its left plane (modes within 1e-6: a double eigenvalue).
struct Reference {
    std::complex<double> lambda;
    double residual;
};
std::vector<Reference> reference_at(const GyroscopicSystem& set, double w, double band) {
    const QuadraticSpectrum s = solve_at_speed(set, w, {EigenMethod::ScaledQZ, true});
    const QuadraticPencil p = set.at_speed(w);
    const Eigen::MatrixXd D = set.damping_matrix(w);
    std::vector<Reference> out;
    for (const Mode& m : s.modes) {
        if (!(std::abs(m.lambda.imag()) <= band)) continue;
        std::vector<const Mode*> near;
        for (const Mode& o : s.modes)
            if (std::abs(o.lambda - m.lambda) <= 1e-6 * std::abs(m.lambda)) near.push_back(&o);
        Eigen::MatrixXcd Y(m.left.size(), static_cast<Eigen::Index>(near.size()));
        for (size_t c = 0; c < near.size(); ++c) Y.col(static_cast<Eigen::Index>(c)) = near[c]->left;
        // sigma_min over z = conj(Y) c, |c| = 1, of [P(lambda)^T z / |P|; D^T z / |D|]
        // (z^T P = 0 and z^T D = 0), written out here apart from the library's.
        const Eigen::MatrixXcd Z = Eigen::HouseholderQR<Eigen::MatrixXcd>(Y.conjugate()).householderQ() *
                                   Eigen::MatrixXcd::Identity(Y.rows(), Y.cols());
        const double np = std::norm(m.lambda) * p.M.norm() + std::abs(m.lambda) * p.C.norm() + p.K.norm();
        Eigen::MatrixXcd S(2 * Y.rows(), Y.cols());
        S.topRows(Y.rows()) = p.evaluate(m.lambda).transpose() * Z / np;
        S.bottomRows(Y.rows()) = D.transpose().cast<std::complex<double>>() * Z / D.norm();
        out.push_back({m.lambda, Eigen::JacobiSVD<Eigen::MatrixXcd>(S).singularValues()(Y.cols() - 1)});
    }
    return out;
}

// Returns how many losses were compared: clear ones of the reference at grid speeds,
// and refined ones between them.
std::pair<int, int> check_scene(const std::string& name) {
    INFO(name);
    const Scene sc = load_scene(std::string(GYROKIT_DATA_DIR) + "/" + name);
    const GyroscopicSystem& sys = sc.system;
    REQUIRE(sc.speeds);
    std::vector<double> all = sc.speeds->points();
    for (double& w : all) w /= sc.speed_unit.factor;   // rad/s
    std::vector<double> speeds;   // 11 of the scene's speeds: the reference solves each in full
    for (int k = 0; k <= 10; ++k) speeds.push_back(all[static_cast<size_t>(k * (all.size() - 1) / 10)]);
    PervasiveOptions po;
    po.modes = kModesInRange;
    const PervasiveReport rep = pervasive_damping(sys, speeds, po);
    REQUIRE(std::isfinite(rep.band));
    const double eps = std::numeric_limits<double>::epsilon();
    const double floor = 1e3 * std::sqrt(static_cast<double>(sys.size())) * eps;
    int clear = 0, refined = 0;
    for (const std::string& set_name : rep.checked) {
        CAPTURE(set_name);
        const GyroscopicSystem set = set_name == "total" ? sys : sys.with_damping_only({set_name});
        const auto found = [&](double w, std::complex<double> l) {
            return std::any_of(rep.losses.begin(), rep.losses.end(), [&](const DampingLoss& x) {
                return x.damping == set_name && x.speed == w && std::abs(x.lost.lambda - l) <= 1e-6 * std::abs(l);
            });
        };
        for (const double w : speeds) {
            CAPTURE(w);
            const std::vector<Reference> ref = reference_at(set, w, rep.band);
            // Where the set's damping vanishes (a fluid's at standstill) the residual is 0 by
            // convention and no refined loss is sought there: not compared.
            if (set.damping_matrix(w).norm() == 0.0) continue;
            // A clear loss (a hundredth of the loss level) is found.
            for (const Reference& r : ref) {
                CAPTURE(r.lambda, r.residual);
                if (r.residual <= 0.01 * floor) {
                    ++clear;
                    CHECK(found(w, r.lambda));
                }
            }
            // A loss found at a grid speed is no mode the set clearly reaches.
            for (const DampingLoss& x : rep.losses) {
                if (x.damping != set_name || x.speed != w) continue;
                CAPTURE(x.lost.lambda);
                CHECK(std::any_of(ref.begin(), ref.end(), [&](const Reference& r) {
                    return std::abs(r.lambda - x.lost.lambda) <= 1e-6 * std::abs(r.lambda) && r.residual <= po.tolerance;
                }));
            }
        }
        // A loss between grid speeds (a refined V): the set's own system has that
        // eigenvalue there, unreached to the loss level.
        for (const DampingLoss& x : rep.losses) {
            if (x.damping != set_name || std::find(speeds.begin(), speeds.end(), x.speed) != speeds.end()) continue;
            CAPTURE(x.speed, x.lost.lambda);
            ++refined;
            const std::vector<Reference> ref = reference_at(set, x.speed, rep.band);
            CHECK(std::any_of(ref.begin(), ref.end(), [&](const Reference& r) {
                return std::abs(r.lambda - x.lost.lambda) <= 1e-6 * std::abs(r.lambda) && r.residual <= floor;
            }));
        }
    }
    return {clear, refined};
}

}  // namespace

TEST_CASE("pervasive damping on the continued undamped modes finds the losses of the full-solve definition",
          "[pervasive][scenes]") {
    int clear = 0, refined = 0;
    for (const std::string name : {"centrifuge.toml", "three_disk_rotor.toml", "three_disk_rotor_journal.toml",
                                   "compressor.toml", "fe_rotor.toml", "drive_train.toml", "fluid_N2.toml"}) {
        const auto [c, r] = check_scene(name);
        clear += c, refined += r;
    }
    // The comparisons ran: the drive train's coupling leaves modes unreached at every
    // speed (grid losses), the centrifuge's cage and rotation dampers lose modes between
    // grid speeds (refined).
    CHECK(clear >= 11);
    CHECK(refined >= 3);
}
