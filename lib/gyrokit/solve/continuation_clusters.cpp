// The clusters of a failed continuation step: which modes move as a group, and the
// Ritz pairs of their span that seed them (continuation_steps.cpp's step_seeds).
// docs/numerics.md ("Continuation").
#include <gyrokit/solve/detail/continuation_parts.hpp>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace gyrokit {
namespace continuation_detail {

namespace {

constexpr Eigen::Index kMaxClusterSize = 8;   // a cluster's eigenvalues (conjugates counted), at most

}  // namespace

double pair_distance(cd a, cd b) { return std::min(std::abs(a - b), std::abs(a - std::conj(b))); }

// The modes of a failed step that move as a group: each mode that failed with its
// nearest neighbour (the distance between eigenvalues, a conjugate's included), or
// alone where its own conjugate is nearer (a complex pair about to meet on the real
// axis). A near-double pair splits along a hyperbola whose slope at the start is no
// guide, and two real eigenvalues that meet become a complex pair (and back) where
// the slopes are infinite: the Ritz pairs of the group's span follow both.
std::vector<std::vector<size_t>> clusters_of(const std::vector<Mode>& track, const std::vector<size_t>& failed,
                                             double real_tol) {
    std::vector<size_t> root(track.size());
    for (size_t i = 0; i < root.size(); ++i) root[i] = i;
    const auto find = [&](size_t i) {
        while (root[i] != i) i = root[i] = root[root[i]];
        return i;
    };
    std::vector<char> member(track.size(), 0);
    for (const size_t i : failed) {
        member[i] = 1;
        const cd a = track[i].lambda;
        double own = std::abs(a.imag()) > real_tol ? 2.0 * std::abs(a.imag()) : std::numeric_limits<double>::infinity();
        size_t best = track.size();
        double dist = std::numeric_limits<double>::infinity();
        for (size_t j = 0; j < track.size(); ++j)
            if (j != i && pair_distance(a, track[j].lambda) < dist) dist = pair_distance(a, track[j].lambda), best = j;
        if (best < track.size() && dist < own) member[best] = 1, root[find(i)] = find(best);
    }
    std::map<size_t, std::vector<size_t>> groups;
    for (size_t i = 0; i < track.size(); ++i)
        if (member[i]) groups[find(i)].push_back(i);
    std::vector<std::vector<size_t>> out;
    for (auto& [r, g] : groups) out.push_back(std::move(g));
    return out;
}

// The Ritz pairs of a cluster at w: the pencil projected on the real span of its
// modes' right vectors (Galerkin: M stays definite), the eigenvalues nearest the
// cluster's own (as many as it has, conjugates counted, closed under conjugation),
// each with its Ritz vector; none where the span or the choice fails.
std::optional<std::vector<Seed>> cluster_seeds(const SparsePencil& p, const std::vector<Mode>& track,
                                               const std::vector<size_t>& members, double real_tol) {
    std::vector<Eigen::VectorXd> columns;
    std::vector<cd> own;   // the cluster's eigenvalues, conjugates included
    for (size_t i : members) {
        const Mode& m = track[i];
        const Eigen::VectorXcd x = unit_vector(m.right);
        for (const Eigen::VectorXd& c : {Eigen::VectorXd(x.real()), Eigen::VectorXd(x.imag())})
            if (c.norm() > 1e-8) columns.push_back(c);
        own.push_back(m.lambda);
        if (std::abs(m.lambda.imag()) > real_tol) own.push_back(std::conj(m.lambda));
    }
    const Eigen::Index d = static_cast<Eigen::Index>(own.size());
    if (d > kMaxClusterSize) return std::nullopt;
    Eigen::MatrixXd A(p.M.rows(), static_cast<Eigen::Index>(columns.size()));
    for (size_t j = 0; j < columns.size(); ++j) A.col(static_cast<Eigen::Index>(j)) = columns[j];
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeThinU);
    Eigen::Index r = 0;
    while (r < svd.singularValues().size() && svd.singularValues()(r) > 1e-8 * svd.singularValues()(0)) ++r;
    // A projected pencil of r directions has 2 r eigenvalues: enough where 2 r >= d (two
    // real eigenvalues of one direction, as next to an exceptional point, share a vector).
    if (r == 0 || 2 * r < d) return std::nullopt;
    const Eigen::MatrixXd V = svd.matrixU().leftCols(r);
    const Eigen::MatrixXd Mr = V.transpose() * (p.M * V), Cr = V.transpose() * (p.C * V),
                          Kr = V.transpose() * (p.K * V);
    const Eigen::LDLT<Eigen::MatrixXd> mass(Mr);
    if (mass.info() != Eigen::Success || !(mass.rcond() > 1e-12)) return std::nullopt;
    Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(2 * r, 2 * r);
    companion.topRightCorner(r, r).setIdentity();
    companion.bottomLeftCorner(r, r) = -mass.solve(Kr);
    companion.bottomRightCorner(r, r) = -mass.solve(Cr);
    const Eigen::EigenSolver<Eigen::MatrixXd> es(companion, false);
    if (es.info() != Eigen::Success) return std::nullopt;
    const Eigen::VectorXcd mu = es.eigenvalues();
    std::vector<char> taken(static_cast<size_t>(2 * r), 0);
    std::vector<cd> chosen;
    for (const cd l : own) {
        Eigen::Index best = -1;
        double dist = std::numeric_limits<double>::infinity();
        for (Eigen::Index k = 0; k < 2 * r; ++k)
            if (!taken[static_cast<size_t>(k)] && std::abs(mu(k) - l) < dist) dist = std::abs(mu(k) - l), best = k;
        if (best < 0) return std::nullopt;
        taken[static_cast<size_t>(best)] = 1;
        chosen.push_back(mu(best));
    }
    // Closed under conjugation: a real pencil's eigenvalues near the real axis come
    // in conjugate pairs or are real.
    // Each value above the axis takes a distinct partner below it.
    std::vector<char> partnered(chosen.size(), 0);
    for (size_t a = 0; a < chosen.size(); ++a) {
        if (!(chosen[a].imag() > real_tol)) continue;
        size_t b = chosen.size();
        for (size_t o = 0; o < chosen.size() && b == chosen.size(); ++o)
            if (!partnered[o] && chosen[o].imag() < -real_tol &&
                std::abs(chosen[o] - std::conj(chosen[a])) <= 1e-6 * std::abs(chosen[a]))
                b = o;
        if (b == chosen.size()) return std::nullopt;
        partnered[a] = partnered[b] = 1;
    }
    for (size_t a = 0; a < chosen.size(); ++a)
        if (std::abs(chosen[a].imag()) > real_tol && !partnered[a]) return std::nullopt;
    std::vector<Seed> out;
    for (const cd c : chosen) {
        if (c.imag() < -real_tol) continue;   // its conjugate stands for it
        const cd l = std::abs(c.imag()) <= real_tol ? cd(c.real(), 0.0) : c;
        const Eigen::MatrixXcd P = (l * l) * Mr.cast<cd>() + l * Cr.cast<cd>() + Kr.cast<cd>();
        const Eigen::JacobiSVD<Eigen::MatrixXcd> null(P, Eigen::ComputeFullV);
        Seed sd;
        sd.predicted = l;
        sd.start.right = V.cast<cd>() * null.matrixV().col(r - 1);
        sd.start.lambda = l;
        out.push_back(std::move(sd));
    }
    return out;
}

}  // namespace continuation_detail
}  // namespace gyrokit
