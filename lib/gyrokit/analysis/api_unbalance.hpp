// The rules of API 617's unbalance response analysis (7th edition, 2.6.2; API RP 684,
// 2nd edition, 2.8): the unbalance magnitude, where it goes for a mode, the orbit a
// probe or a clearance sees, the allowable probe vibration and the scale factor, and
// the separation margin a critical speed has from the operating range
// (docs/api_unbalance.md). The study that runs them is study/api_unbalance_study.hpp.
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <string>
#include <vector>

namespace gyrokit {

// U = kApiUnbalanceMultiple * kApiUnbalanceConstant W / N (g mm; W kg, N rpm).
constexpr double kApiUnbalanceConstant = 6350.0;
constexpr double kApiUnbalanceMultiple = 2.0;
// Peak-to-peak orbits at close clearances are held below this fraction of the
// minimum diametral running clearance.
constexpr double kApiClearanceFraction = 0.75;
// The scale factor Scc = Avl / A1 is kept within these.
constexpr double kApiScaleMin = 0.5, kApiScaleMax = 6.0;
// Critical speeds are sought up to the higher of these multiples of the mcs and of the
// trip speed: a mode up to 26 % above the mcs can need a separation margin, and API 617
// asks for the modes up to 125 % of the trip speed.
constexpr double kApiMarginReach = 1.26;
constexpr double kApiTripReach = 1.25;
// A1, the probe's reading at the critical speed of concern: the largest refined peak of
// a probe within this fraction of that speed (else the reading at the speed itself).
constexpr double kApiPeakWindow = 0.1;
// The speeds of the grid from 0 to the highest speed sought unless asked otherwise.
constexpr int kApiResponseSpeeds = 201;

// The unbalance (kg m) of weight `weight` (kg) at the maximum continuous speed `mcs`
// (rad/s): 2 x 6350 W / N g mm.
double api_unbalance(double weight, double mcs);

// The allowable peak-to-peak probe vibration (m) at speed `speed` (rad/s): Avl =
// 25.4 sqrt(12000 / N) um, N in rpm, at most 25.4 um.
double api_allowable_vibration(double speed);

// The scale factor Scc = Avl / A1 of the amplitudes, within [0.5, 6]; 0.5 for an
// unbounded A1.
double api_scale_factor(double allowable, double amplitude);

// The peak-to-peak orbit of a point whose x and y move as Re(Zx e^{i w t}) and
// Re(Zy e^{i w t}): twice the major semi-axis of its ellipse, |Zx - i Zy| + |Zx + i Zy|
// (the sum of the forward and backward circles' diameters): the largest reading of a
// probe in any direction.
double orbit_peak_to_peak(std::complex<double> zx, std::complex<double> zy);

// Where a critical speed lies against the operating range [min_speed, mcs], and its
// margin in percent: below, (min_speed - Nc) / min_speed; above, (Nc - mcs) / mcs;
// inside, 0.
struct SeparationMargin {
    enum class Side { below, inside, above };
    Side side = Side::inside;
    double percent = 0.0;
};
const char* to_string(SeparationMargin::Side s);   // "below", "inside", "above"
SeparationMargin separation_margin(double critical, double min_speed, double mcs);

// How a mode is excited (API 617, Figure 2-2 as API RP 684 reads it): the first
// between-bearings mode at mid-span; a mode whose shape changes sign between the
// bearings at its largest deflections on either side, 180 degrees apart (the one nearer
// z = 0 at phase 0: which one leads is a turn of the whole loading); a mode whose
// largest deflection lies outboard of the bearings at that overhang.
enum class UnbalanceLayout { first_mode, second_mode, overhung };
const char* to_string(UnbalanceLayout l);   // "first mode (mid-span)", ...

struct UnbalancePoint {
    int index = 0;        // into the shape's nodes
    double phase = 0.0;   // rad, from +x
};
struct UnbalancePlacement {
    UnbalanceLayout layout = UnbalanceLayout::first_mode;
    std::vector<UnbalancePoint> points;   // one (first mode, overhung) or two (second mode)
};

// The placement for a mode shape given per node: axial positions z (m, ascending),
// the complex x and y deflections of each node, and the bearing span [z0, z1]; the
// nodes outboard of z0 (z1) count only where the rotor is overhung there
// (`overhung_below`, `overhung_above`: a disk, an impeller or a coupling outboard): a
// bare shaft end beyond its bearing is no overhang. The shape is read in the direction
// of its largest deflection, with that node's phase taken out; deflections below 5 %
// of the largest are no sign change. InputError for mismatched sizes, no node in the
// span, or a zero shape.
UnbalancePlacement api_unbalance_placement(const std::vector<double>& z, const Eigen::VectorXcd& zx,
                                           const Eigen::VectorXcd& zy, double z0, double z1,
                                           bool overhung_below = false, bool overhung_above = false);

}  // namespace gyrokit
