#include <gyrokit/analysis/transient_signals.hpp>

#include <gyrokit/analysis/campbell.hpp>
#include <gyrokit/analysis/unbalance_response.hpp>
#include <gyrokit/core/constants.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/core/interrupt.hpp>

#include <cmath>
#include <complex>
#include <fmt/format.h>
#include <limits>

namespace gyrokit {

TransientEnvelope transient_envelope(const TransientResult& r, int max_windows) {
    if (max_windows < 1)
        throw InputError(fmt::format("transient envelope: {} windows; allowed: at least 1", max_windows));
    TransientEnvelope e;
    e.dofs = r.dofs;
    const std::size_t samples = r.t.size();
    if (samples == 0) return e;
    // The revolution each sample lies in; the last one, unfinished, is left out.
    std::vector<long long> rev(samples);
    for (std::size_t n = 0; n < samples; ++n)
        rev[n] = static_cast<long long>(std::floor(r.profile.angle(r.t[n]) / (2.0 * kPi)));
    const long long whole = rev.back();
    const double span = r.t.back() / max_windows;
    const auto cols = static_cast<Eigen::Index>(r.dofs.size());
    long long key = -1;   // the time slot of the window being filled
    for (std::size_t n = 0; n < samples && (whole == 0 || rev[n] < whole);) {
        // One revolution (a run shorter than one: every sample), ending at the next one's first sample.
        std::size_t end = n;
        while (end < samples && (whole == 0 || rev[end] == rev[n])) ++end;
        const double t_end = r.t[std::min(end, samples - 1)];
        const long long slot = std::min<long long>(max_windows - 1, static_cast<long long>(t_end / span));
        if (slot != key) {
            key = slot;
            e.end.push_back(t_end);
            const auto rows = static_cast<Eigen::Index>(e.end.size());
            for (Eigen::MatrixXd* m : {&e.peak, &e.t, &e.speed}) {
                m->conservativeResize(rows, cols);
                m->row(rows - 1).setConstant(-1.0);
            }
            e.revolution.conservativeResize(rows, cols);
        }
        const Eigen::Index w = e.peak.rows() - 1;
        e.end.back() = t_end;
        for (; n < end; ++n)
            for (Eigen::Index k = 0; k < cols; ++k) {
                const double a = std::abs(r.z(static_cast<Eigen::Index>(n), k));
                if (a <= e.peak(w, k)) continue;
                e.peak(w, k) = a;
                e.t(w, k) = r.t[n];
                e.speed(w, k) = r.speed[n];
                e.revolution(w, k) = rev[n] + 1;
            }
    }
    return e;
}

Eigen::MatrixXd envelope_steady(const GyroscopicSystem& sys, const TransientEnvelope& e, SolverKind kind) {
    Eigen::MatrixXd a(e.peak.rows(), e.peak.cols());
    for (Eigen::Index k = 0; k < a.cols(); ++k) {
        const Eigen::VectorXd w = e.speed.col(k);
        a.col(k) = steady_amplitudes(sys, std::vector<double>(w.data(), w.data() + w.size()),
                                     {e.dofs[static_cast<std::size_t>(k)]}, kind);
    }
    return a;
}

Eigen::MatrixXd steady_amplitudes(const GyroscopicSystem& sys, const std::vector<double>& speeds,
                                  const std::vector<int>& dofs, SolverKind kind) {
    Eigen::MatrixXd a(static_cast<Eigen::Index>(speeds.size()), static_cast<Eigen::Index>(dofs.size()));
    for (std::size_t i = 0; i < speeds.size(); ++i) {
        throw_if_interrupted();
        const auto row = static_cast<Eigen::Index>(i);
        try {
            const Eigen::VectorXcd Z = unbalance_response(sys, speeds[i], kind);
            for (std::size_t k = 0; k < dofs.size(); ++k) a(row, static_cast<Eigen::Index>(k)) = std::abs(Z(dofs[k]));
        } catch (const SolverError&) {   // exactly on an undamped resonance: unbounded
            a.row(row).setConstant(std::numeric_limits<double>::infinity());
        }
    }
    return a;
}

namespace {

// Amplitudes of the Hann-weighted samples x[i0..i1] at the frequencies: a sine of
// amplitude A reads A (2 |sum h x e^{-i w t}| / sum h; at w = 0 without the 2).
Eigen::VectorXd window_spectrum(const TransientResult& r, int column, std::size_t i0, std::size_t i1,
                                const std::vector<double>& frequencies) {
    const double span = static_cast<double>(i1 - i0);
    std::vector<double> hx;   // the weighted samples
    double weights = 0.0;
    for (std::size_t n = i0; n <= i1; ++n) {
        const double h = std::pow(std::sin(kPi * static_cast<double>(n - i0) / span), 2);
        weights += h;
        hx.push_back(h * r.z(static_cast<Eigen::Index>(n), column));
    }
    Eigen::VectorXd out(static_cast<Eigen::Index>(frequencies.size()));
    for (std::size_t j = 0; j < frequencies.size(); ++j) {
        const double w = frequencies[j];
        // e^{-i w t_n} by rotation from t_i0 (the steps are uniform).
        std::complex<double> sum = 0.0, turn = std::polar(1.0, -w * r.t[i0]);
        const std::complex<double> rot = std::polar(1.0, -w * r.dt);
        for (const double v : hx) {
            sum += v * turn;
            turn *= rot;
        }
        out(static_cast<Eigen::Index>(j)) = (w == 0.0 ? 1.0 : 2.0) * std::abs(sum) / weights;
    }
    return out;
}

}  // namespace

Waterfall transient_waterfall(const TransientResult& r, int column, int windows, int frequencies) {
    if (column < 0 || column >= static_cast<int>(r.dofs.size()))
        throw InputError(fmt::format("waterfall: column {}; allowed: 0 to {}", column,
                                     static_cast<int>(r.dofs.size()) - 1));
    if (windows < 2 || windows > 10000 || frequencies < 2 || frequencies > 10000)
        throw InputError(fmt::format("waterfall: {} windows, {} frequencies; allowed: 2 to 10000 each", windows,
                                     frequencies));
    Waterfall wf;
    wf.dof = r.dofs[static_cast<std::size_t>(column)];
    const std::size_t samples = r.t.size();
    if (samples < 4) throw InputError("waterfall: the run has fewer than 4 samples; allowed: a longer run");
    const double band = kBandMargin * r.profile.top();
    for (int j = 0; j < frequencies; ++j) wf.frequencies.push_back(band * j / (frequencies - 1));
    // Windows of 2 T / windows, at least kWaterfallPeriods periods of the top speed (the
    // resolution), at most the run; centres evenly spaced from the first to the last half window.
    const std::size_t last = samples - 1;
    const double periods = kWaterfallPeriods * 2.0 * kPi / r.profile.top();
    const auto shortest = static_cast<std::size_t>(std::ceil(periods / r.dt));
    const std::size_t length =
        std::min(last, std::max<std::size_t>({3, shortest, 2 * last / static_cast<std::size_t>(windows)}));
    if (length == last) windows = 1;
    wf.window = r.t[length] - r.t[0];
    wf.amplitude.resize(windows, frequencies);
    for (int i = 0; i < windows; ++i) {
        throw_if_interrupted();
        const auto i0 = windows == 1 ? std::size_t(0)
                                     : static_cast<std::size_t>(std::llround(static_cast<double>(last - length) * i /
                                                                             (windows - 1)));
        const std::size_t mid = i0 + length / 2;
        wf.t.push_back(r.t[mid]);
        wf.speed.push_back(r.speed[mid]);
        wf.amplitude.row(i) = window_spectrum(r, column, i0, i0 + length, wf.frequencies).transpose();
    }
    return wf;
}

}  // namespace gyrokit
