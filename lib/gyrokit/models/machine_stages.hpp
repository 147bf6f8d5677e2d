// The machine data of the API 617 / API 684 analyses ([api] of a scene): the speeds,
// the aerodynamic stages that make the anticipated cross-coupling QA of the Level I
// stability screen, and where the cross-coupling acts. Plain data in SI units; the
// screen itself is analysis/level1_stability.hpp and study/level1_study.hpp
// (docs/level1.md).
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace gyrokit {

// Centrifugal compressors (Wachel's form, with the density ratio and Bc = 3), or axial
// compressors and turbines (Alford's form, Bt = 1.5, no density ratio).
enum class MachineKind { centrifugal, axial };
const char* to_string(MachineKind k);   // "centrifugal" | "axial"

struct AeroStage {
    double z = 0.0;              // m: the stage's axial position (where its share of Q acts on an overhung rotor)
    double power = 0.0;          // W, > 0: rated power of the impeller or stage
    double diameter = 0.0;       // m, > 0: impeller diameter Dc, or blade pitch diameter Dp (axial)
    double width = 0.0;          // m, > 0: Hc, the smaller of diffuser and impeller discharge width,
                                 //          or the effective blade height He (axial)
    std::optional<double> density_ratio;   // rho_d / rho_s, > 0: discharge over suction density (required
                                           // for a centrifugal machine, unused by an axial one)
    std::string origin;          // names the stage in messages
};

// A close-clearance location of the API unbalance cases (a seal, a bearing, a
// balance piston): where the rotor's peak-to-peak orbit is held against 75 % of the
// minimum diametral running clearance.
struct CloseClearance {
    double z = 0.0;              // m: axial position (its nearest node is read)
    double clearance = 0.0;      // m, > 0: minimum diametral running clearance
    std::string name;            // as the report names it ("" : "clearance K")
    std::string origin;          // names the entry in messages
};

// The Q range of the curve unless asked otherwise: 0 to this many times QA.
constexpr double kLevel1QRatio = 10.0;

struct ApiMachine {
    MachineKind kind = MachineKind::centrifugal;
    std::optional<double> mcs;               // rad/s, > 0: maximum continuous speed (where the screen runs)
    std::optional<double> operating_speed;   // rad/s, > 0: normal operating speed N of QA's formula (default: mcs)
    std::vector<AeroStage> stages;
    std::optional<double> qa;                // N/m, > 0: the anticipated cross-coupling given directly (in place
                                             //    of the stages' sum; the stages still say where Q acts)
    std::optional<double> station;           // m: where Q acts (default: the middle of the bearing span of a
                                             //    between-bearings rotor, the stages of an overhung one)
    std::optional<double> gas_density;       // kg/m^3, > 0: average of suction and discharge (region A/B check)
    double q_ratio = kLevel1QRatio;          // the Q range: 0 to q_ratio QA, in [2, 1000]
    // The API unbalance cases (study/api_unbalance_study.hpp, docs/api_unbalance.md):
    std::optional<double> min_speed;         // rad/s, > 0: minimum operating speed (default: the mcs)
    std::optional<double> trip_speed;        // rad/s, >= mcs: the response's range 0 to trip speed
                                             //    (default: kApiTripRatio mcs)
    std::vector<CloseClearance> clearances;
    std::string origin;                      // names the table in messages
};

// API 617's constant C of QA's formula in SI units (W, m, rpm -> N/m): 60 / (2 pi)
// rounded as the standard writes it.
constexpr double kQaConstant = 9.55;
// B of QA's formula: Bc (centrifugal), Bt (axial and turbines).
constexpr double kQaCentrifugal = 3.0;
constexpr double kQaAxial = 1.5;

// One stage's anticipated cross-coupling (N/m) at the operating speed N (rad/s):
// B C P / (D H N_rpm), times rho_d / rho_s for a centrifugal stage.
double anticipated_cross_coupling(const AeroStage& stage, MachineKind kind, double operating_speed);

// The trip speed unless given: 105 % of the maximum continuous speed (API 617's
// trip speed of a variable-speed electric drive and of gas turbines).
constexpr double kApiTripRatio = 1.05;

// InputError naming the stage or key, the value and the allowed range, for each value
// given (what a Level I screen needs besides: level1_study; the order of min_speed, mcs
// and trip_speed, which only the unbalance cases read: the scene reader and
// api_unbalance_study, in the caller's unit).
void validate(const ApiMachine& machine);

}  // namespace gyrokit
