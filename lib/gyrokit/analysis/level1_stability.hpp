// The Level I stability screen of API 617 (8th edition, 2014, lateral analysis; the
// same screen as API 684, 2nd edition, 2005, explains it): a destabilising cross-coupled stiffness Q
// (kxy = +Q, kyx = -Q, shared among its stations) is added to the rotor on its
// bearings, and the first forward mode at Q = 0 is followed at the maximum continuous
// speed as Q grows; its logarithmic decrement against Q, and Q0 where it reaches zero.
// docs/level1.md states the equations as implemented.
#pragma once

#include <gyrokit/core/diagnostics.hpp>
#include <gyrokit/core/gyroscopic_system.hpp>
#include <gyrokit/core/length_unit.hpp>
#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/core/solver_kind.hpp>
#include <gyrokit/eig/mode.hpp>
#include <gyrokit/models/machine_stages.hpp>

#include <complex>
#include <optional>
#include <string>
#include <vector>

namespace gyrokit {

// Where Q acts: a node's (x, y) pair and its share of Q (the shares sum to 1).
struct CrossCouplingStation {
    int node = 0;
    double share = 1.0;
};

struct Level1Options {
    std::vector<CrossCouplingStation> stations;
    double speed = 0.0;                 // rad/s, > 0: the maximum continuous speed
    double q_max = 0.0;                 // N/m, > 0: the curve runs from 0 to q_max
    int intervals = 20;                 // equal steps of the curve, in [2, 10000]
    std::vector<double> marks;          // N/m: values in (0, q_max] the curve also holds (QA)
    SolverOptions solver;               // the dense method; above kAutoSparseDofs a window of modes
};

struct Level1Point {
    double q = 0.0;                     // N/m
    std::complex<double> lambda;        // the followed eigenvalue, 1/s
    double error_bound = 0.0;           // on |lambda - exact|, 1/s
    double log_decrement = 0.0;         // -2 pi Re(lambda) / Im(lambda) (Mode::log_decrement: 0 where neutral)
    Whirl whirl = Whirl::Undefined;
};

// A forward mode below the followed one that Q does not load (kLevel1MinStationOrbit),
// at Q = 0: to first order Q moves its eigenvalue by the square of its orbit ratio.
struct PassedMode {
    std::complex<double> lambda;        // 1/s
    double error_bound = 0.0;           // on |lambda - exact|, 1/s
    double log_decrement = 0.0;
    double orbit_ratio = 0.0;           // its orbit where Q acts over its largest orbit
};

struct Level1Curve {
    std::vector<Level1Point> points;    // by q, from 0
    // Q0: the first Q where the log decrement reaches zero; unset where it stays
    // positive up to q_max, and 0 where the mode is unstable at Q = 0 or neutral there
    // (no damping: any Q > 0 destabilises it).
    std::optional<double> q0;
    double q0_bound = 0.0;              // N/m: |Q0 - exact| at most this (the bracket and the eigenvalue's bound)
    int solves = 0;                     // eigenvalue solves made (curve, halved steps and Q0's bracket)
    std::vector<std::string> notes;     // steps that could not be told apart, solver notes
    std::vector<PassedMode> passed;     // lower forward modes Q does not load (kLevel1MinStationOrbit)
};

// Adds Q times the stations' skew coupling to sys.K: K(x, y) += share Q, K(y, x) -= share Q.
GyroscopicSystem with_cross_coupling(const GyroscopicSystem& sys, const std::vector<CrossCouplingStation>& stations,
                                     double q);

// The curve and Q0. InputError for options out of range (naming the field), for a
// station that is no node with a whirl pair, and where the rotor has no forward mode
// at Q = 0 that Q loads. The mode is followed by its eigenvector (the candidate of
// largest |x_prev^H x|, which must also be, to 1e-6, the nearest eigenvalue; where two
// candidates' vectors are that close, the eigenvalue decides: less than half the way to
// the next nearest, and nearest to the linear predictor from the last two points); a
// step where that fails is halved, at most 10 times between two points of the curve, and
// a step taken undecided is noted. Q0's bracket on the followed mode is narrowed (regula
// falsi, Illinois) until it is below 1e-10 Q or Re(lambda) lies within its error bound. Dense up to kAutoSparseDofs DOFs (solver auto),
// else a sparse window of 12 modes centred on the followed one.
Level1Curve level1_curve(const GyroscopicSystem& sys, const Level1Options& options);

// "the forward mode at 3123.65 rpm (log decrement 2.4) barely moves where Q acts ...".
std::string passed_text(const PassedMode& m, const SpeedUnit& unit);

// API 617's chart of the critical speed ratio against average gas density: the ratio
// above which a centrifugal compressor lies in region B (docs/level1.md): 2.5 up to
// 16.53 kg/m^3, then falling linearly (2.69 - 0.0115 rho) to 2.0 at 60 kg/m^3; beyond
// the chart's last density every ratio counts as region B (0).
double region_b_boundary(double gas_density);

// The log decrement at QA below which Level II is required.
constexpr double kLevel1MinLogDecrement = 0.1;
// Q0 / QA below which Level II is required; and up to which (centrifugal compressors)
// the critical speed ratio's region decides.
constexpr double kLevel1MinRatio = 2.0;
constexpr double kLevel1RegionRatio = 10.0;
// The followed mode is the lowest forward mode whose orbit where Q acts is at least this
// fraction of its largest orbit: a mode with a node there (the conical rigid-body mode of a
// symmetric rotor at mid-span) is not loaded by Q (to first order the change of its
// eigenvalue scales with the square of that ratio, here 0.25 % of a mode loaded at its
// largest orbit), and screening it would pass any QA.
constexpr double kLevel1MinStationOrbit = 0.05;
// Equal steps of the curve from Q = 0 to q_ratio QA.
constexpr int kLevel1Intervals = 20;

// The screen's result: what level1_study ran and decided.
struct Level1Screen {
    std::string bearing_set;            // "": the bearings as given; else the end of their bands (BearingSet)
    ApiMachine machine;                 // as run (speeds rad/s, lengths m)
    SpeedUnit unit;                        // of the speeds the tables print
    LengthUnit length_unit;                // of the positions they print
    double qa = 0.0;                       // N/m
    std::vector<double> stage_qa;          // N/m, each stage's share of QA (empty: qa given)
    std::string layout;                    // "between bearings" | "overhung" | "station given"
    std::vector<CrossCouplingStation> stations;
    std::vector<double> station_z;         // m, each station's node position
    Level1Curve curve;
    Level1Point at_zero, at_qa;            // the curve at Q = 0 and at QA
    std::optional<double> rigid_critical;  // rad/s: the first forward critical speed on rigid supports
    std::optional<double> csr;             // mcs / rigid_critical
    std::optional<double> region_boundary; // the chart's ratio at the gas density (centrifugal)
    bool level2_required = false;
    std::vector<std::string> reasons;      // each criterion that requires Level II, or why it passes
    Diagnostics diagnostics;
};

// One screen per bearing set: the bearings as given, or (where a fluid film gives a
// clearance or viscosity band) both ends of the bands. The verdict is the worse screen's.
struct Level1Study {
    std::vector<Level1Screen> screens;
    std::size_t governing = 0;          // the worse screen (governing_screen)
    Diagnostics diagnostics;            // the placement's notes and each screen's, named by its set
    const Level1Screen& verdict() const { return screens.at(governing); }
    bool level2_required() const { return verdict().level2_required; }
};

// The worse of the screens: the first requiring Level II before any that passes; among
// equals the smaller Q0/QA (none in the range counts as above it), then the smaller log
// decrement at QA.
std::size_t governing_screen(const std::vector<Level1Screen>& screens);

}  // namespace gyrokit
