// The tracker of a Campbell diagram from complete spectra: matches the modes of
// one speed to the next (an optimal assignment on trapezoid residuals and mode
// shapes), bisects a step while a match is ambiguous, and grows the branches.
// Internal to analysis/ (campbell.cpp).
#pragma once
#include <gyrokit/analysis/campbell.hpp>
#include <gyrokit/solve/spectrum_solver.hpp>

#include <complex>
#include <vector>

namespace gyrokit::tracking {

using cd = std::complex<double>;

struct Tracker {
    SpectrumSolver& solve;
    const CampbellOptions& opt;
    CampbellDiagram& out;
    std::vector<int> active;   // branch index per mode of the last spectrum
    bool window = false;       // spectra hold a window of modes, not all
    // Branches whose matches decide ambiguity. A dense spectrum holds every mode,
    // but only the K lowest branches at the first speed are reported: a veering
    // among the high modes must not cost bisections (on a model of a thousand
    // DOFs it would cost hundreds of full solves).
    std::vector<char> watched;
    char watch_new = 1;        // whether branches that start later are watched

    // Modes beyond twice the band at both ends are matched by frequency order only:
    // they are not reported, and an optimal assignment over hundreds of them would
    // cost more than the solve.
    bool far(const Mode& m) const { return std::isfinite(opt.band) && std::abs(m.frequency()) > 2.0 * opt.band; }

    // Assignment of the modes of `prev` (speed w0) to those of `next` (w0 + h).
    // A watched match is clear when every rival's trapezoid residual is at least
    // four times larger (or beyond the error bounds' noise), and in a window also
    // when the eigenvalue continues the branch's slope (residual within a tenth of
    // the step's change); without
    // slopes, when the mode shapes correlate (MAC >= mac_min) and no rival's cost
    // is within 0.05. Else the step is ambiguous.
    std::vector<int> match(const std::vector<Mode>& prev, const std::vector<cd>& predicted,
                           const std::vector<Mode>& next, double h, bool& ambiguous) const;

    // Whether mode i shares its eigenvalue with another (either match is then right).
    static bool degenerate(const std::vector<Mode>& modes, size_t i);

    // Each branch's eigenvalue at w, extrapolated linearly from its last two points.
    std::vector<cd> predictions(const std::vector<Mode>& modes, double w) const;

    // The spectrum at w appended: matched modes continue their branches, the others start new ones.
    void append(double w, QuadraticSpectrum&& s, const std::vector<int>& assign);

    // The last mode of each active branch, in `buf`.
    const std::vector<Mode>& last_modes(std::vector<Mode>& buf) const;

    // Moves from the last appended speed to w1 (whose spectrum is s1), bisecting while ambiguous.
    void step(double w1, QuadraticSpectrum s1, int depth);
};

}  // namespace gyrokit::tracking
