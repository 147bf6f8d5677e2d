#include "gyrokit/eig/lapack.hpp"

#include <gyrokit/core/error.hpp>

#include <algorithm>
#include <complex>
#include <vector>
#define lapack_complex_float std::complex<float>
#define lapack_complex_double std::complex<double>
#include <lapacke.h>

#include <fmt/format.h>

namespace gyrokit {

// dggev3 through its _work form with zero-filled buffers: LAPACK 3.11's multishift
// QZ (dlaqz0, dlaqz4) reads entries of its workspace and of alphar/alphai/beta before
// writing them (valgrind: "depends on uninitialised value"), which made the result
// differ in its last digits with whatever the memory held: from call to call in one
// process and from worker to worker. Zeroed, the same pencil gives the same bits.
lapack_int dggev3_zeroed(char jobvl, char jobvr, lapack_int n, Eigen::MatrixXd& A, Eigen::MatrixXd& B,
                         Eigen::VectorXd& ar, Eigen::VectorXd& ai, Eigen::VectorXd& be, Eigen::MatrixXd& vl,
                         lapack_int ldvl, Eigen::MatrixXd& vr, lapack_int ldvr) {
    double query = 0.0;
    lapack_int info = LAPACKE_dggev3_work(LAPACK_COL_MAJOR, jobvl, jobvr, n, A.data(), n, B.data(), n, ar.data(),
                                          ai.data(), be.data(), vl.data(), ldvl, vr.data(), ldvr, &query, -1);
    if (info != 0) return info;
    std::vector<double> work(static_cast<std::size_t>(std::max(1.0, query)), 0.0);
    return LAPACKE_dggev3_work(LAPACK_COL_MAJOR, jobvl, jobvr, n, A.data(), n, B.data(), n, ar.data(), ai.data(),
                               be.data(), vl.data(), ldvl, vr.data(), ldvr, work.data(),
                               static_cast<lapack_int>(work.size()));
}

namespace {

void check_finite(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
    // The _work form skips LAPACKE's NaN check, and the QZ routines index out of
    // bounds on NaN input (memory corruption, not an error code): check here.
    if (!A.allFinite() || !B.allFinite())
        throw SolverError("the pencil for LAPACK's QZ holds NaN or infinite entries: the model's matrices "
                          "are zero where they may not be (a zero mass matrix) or too badly scaled");
}

void check_info(lapack_int info, bool classic) {
    if (info != 0)
        throw SolverError(fmt::format("LAPACK {} (QZ) failed with info = {}; the pencil may contain "
                                      "NaN or be too badly scaled",
                                      classic ? "dggev" : "dggev3", info));
}

}  // namespace

GeneralizedEigen lapack_dggev_values(Eigen::MatrixXd A, Eigen::MatrixXd B, bool classic) {
    const lapack_int n = static_cast<lapack_int>(A.rows());
    check_finite(A, B);
    Eigen::VectorXd ar = Eigen::VectorXd::Zero(n), ai = Eigen::VectorXd::Zero(n), be = Eigen::VectorXd::Zero(n);
    Eigen::MatrixXd none = Eigen::MatrixXd::Zero(1, 1);
    const lapack_int info =
        classic ? LAPACKE_dggev(LAPACK_COL_MAJOR, 'N', 'N', n, A.data(), n, B.data(), n, ar.data(), ai.data(),
                                be.data(), none.data(), 1, none.data(), 1)
                : dggev3_zeroed('N', 'N', n, A, B, ar, ai, be, none, 1, none, 1);
    check_info(info, classic);
    GeneralizedEigen g;
    g.alpha.resize(n);
    for (lapack_int j = 0; j < n; ++j) g.alpha(j) = {ar(j), ai(j)};
    g.beta = be;
    return g;
}

GeneralizedEigen lapack_dggev(Eigen::MatrixXd A, Eigen::MatrixXd B, bool want_left, bool classic) {
    const lapack_int n = static_cast<lapack_int>(A.rows());
    check_finite(A, B);
    Eigen::VectorXd ar = Eigen::VectorXd::Zero(n), ai = Eigen::VectorXd::Zero(n), be = Eigen::VectorXd::Zero(n);
    Eigen::MatrixXd vl = Eigen::MatrixXd::Zero(want_left ? n : 1, want_left ? n : 1);
    Eigen::MatrixXd vr = Eigen::MatrixXd::Zero(n, n);
    const char jobvl = want_left ? 'V' : 'N';
    const lapack_int ldvl = want_left ? n : 1;
    const lapack_int info =
        classic ? LAPACKE_dggev(LAPACK_COL_MAJOR, jobvl, 'V', n, A.data(), n, B.data(), n, ar.data(), ai.data(),
                                be.data(), vl.data(), ldvl, vr.data(), n)
                : dggev3_zeroed(jobvl, 'V', n, A, B, ar, ai, be, vl, ldvl, vr, n);
    check_info(info, classic);
    GeneralizedEigen g;
    g.alpha.resize(n);
    g.beta = be;
    g.right.resize(n, n);
    if (want_left) g.left.resize(n, n);
    // Complex pairs are stored as (real part, imaginary part) in consecutive columns.
    for (lapack_int j = 0; j < n; ++j) {
        g.alpha(j) = {ar(j), ai(j)};
        if (ai(j) == 0.0) {
            g.right.col(j) = vr.col(j).cast<std::complex<double>>();
            if (want_left) g.left.col(j) = vl.col(j).cast<std::complex<double>>();
        } else if (ai(j) > 0.0 && j + 1 < n) {
            const std::complex<double> I(0.0, 1.0);
            g.right.col(j) = vr.col(j).cast<std::complex<double>>() + I * vr.col(j + 1);
            g.right.col(j + 1) = g.right.col(j).conjugate();
            if (want_left) {
                g.left.col(j) = vl.col(j).cast<std::complex<double>>() + I * vl.col(j + 1);
                g.left.col(j + 1) = g.left.col(j).conjugate();
            }
            g.alpha(j + 1) = {ar(j + 1), ai(j + 1)};
            ++j;
        }
    }
    return g;
}

Eigen::VectorXcd lapack_dgeev_values(Eigen::MatrixXd A) {
    const lapack_int n = static_cast<lapack_int>(A.rows());
    if (!A.allFinite())
        throw SolverError("the state matrix holds NaN or infinite entries: the model is too badly scaled");
    Eigen::VectorXd wr(n), wi(n);
    double none = 0.0;
    const lapack_int info = LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', n, A.data(), n, wr.data(), wi.data(), &none, 1,
                                          &none, 1);
    if (info != 0)
        throw SolverError(fmt::format("LAPACK dgeev (the state matrix's QR) failed with info = {}", info));
    Eigen::VectorXcd l(n);
    for (lapack_int j = 0; j < n; ++j) l(j) = {wr(j), wi(j)};
    return l;
}

GeneralizedEigen lapack_dgeev(Eigen::MatrixXd A, bool want_left) {
    const lapack_int n = static_cast<lapack_int>(A.rows());
    Eigen::VectorXd wr(n), wi(n);
    Eigen::MatrixXd vl(want_left ? n : 1, want_left ? n : 1), vr(n, n);
    const lapack_int info = LAPACKE_dgeev(LAPACK_COL_MAJOR, want_left ? 'V' : 'N', 'V', n, A.data(), n, wr.data(),
                                          wi.data(), vl.data(), want_left ? n : 1, vr.data(), n);
    if (info != 0)
        throw SolverError(fmt::format("LAPACK dgeev (the state matrix's QR) failed with info = {}; the matrix may "
                                      "contain NaN or be too badly scaled",
                                      info));
    GeneralizedEigen g;
    g.alpha.resize(n);
    g.right.resize(n, n);
    if (want_left) g.left.resize(n, n);
    // Complex pairs are stored as (real part, imaginary part) in consecutive columns.
    const auto unpack = [&](const Eigen::MatrixXd& v, Eigen::MatrixXcd& out, lapack_int j) {
        if (wi(j) == 0.0) {
            out.col(j) = v.col(j).cast<std::complex<double>>();
        } else if (wi(j) > 0.0 && j + 1 < n) {
            out.col(j).real() = v.col(j);
            out.col(j).imag() = v.col(j + 1);
            out.col(j + 1) = out.col(j).conjugate();
        }
    };
    for (lapack_int j = 0; j < n; ++j) {
        g.alpha(j) = {wr(j), wi(j)};
        unpack(vr, g.right, j);
        if (want_left) unpack(vl, g.left, j);
    }
    return g;
}

GeneralizedEigen lapack_zggev(Eigen::MatrixXcd A, Eigen::MatrixXcd B) {
    const lapack_int n = static_cast<lapack_int>(A.rows());
    Eigen::VectorXcd al(n), be(n);
    Eigen::MatrixXcd vl(1, 1), vr(n, n);
    const lapack_int info = LAPACKE_zggev(LAPACK_COL_MAJOR, 'N', 'V', n, A.data(), n, B.data(), n, al.data(),
                                          be.data(), vl.data(), 1, vr.data(), n);
    if (info != 0)
        throw SolverError(fmt::format("LAPACK zggev (QZ) failed with info = {}", info));
    GeneralizedEigen g;
    g.alpha = al;
    g.beta_c = be;
    g.right = vr;
    return g;
}

}  // namespace gyrokit
