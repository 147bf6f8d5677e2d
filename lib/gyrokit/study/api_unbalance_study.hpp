// The API unbalance cases of a scene's FE rotor, as the CLI (gyrokit api-unbalance)
// and Python (gyrokit.api_unbalance) run them (API 617 7th ed. 2.6.2, API RP 684;
// docs/api_unbalance.md): the critical speeds from 0 to the higher of 1.25 x the trip
// speed and 1.26 mcs; for each, the API unbalance placed by its mode shape and sized by the
// journal (or overhang) weight; each case's steady response from 0 to the trip speed at
// the probes (the bearings) and the close clearances; each critical speed's
// amplification factor on that response, the margin it needs and the one it has; the
// scale factor Scc = Avl / A1; the clearance check; a verdict per case.
#pragma once

#include <gyrokit/analysis/api_unbalance.hpp>
#include <gyrokit/analysis/critical_speeds.hpp>
#include <gyrokit/core/diagnostics.hpp>
#include <gyrokit/core/length_unit.hpp>
#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/models/machine_stages.hpp>
#include <gyrokit/scene/scene.hpp>

#include <optional>
#include <string>
#include <vector>

namespace gyrokit {

struct ApiUnbalanceRequest {
    std::optional<std::string> unit;          // rad/s, Hz or rpm: of the speeds in and out
    std::optional<double> mcs;                // in unit
    std::optional<double> min_speed;          // in unit
    std::optional<double> trip_speed;         // in unit
    std::optional<int> speeds;                // grid speeds from 0 to the highest speed sought
};

// A probe (at a bearing: API places two there) or a close clearance.
struct ApiLocation {
    std::string name;
    bool probe = false;          // false: a close clearance
    int node = 0;
    double z = 0.0;              // m: the node's position
    double clearance = 0.0;      // m: minimum diametral running clearance (clearances only)
    bool relative = false;       // read against the bearing's pedestal (a probe or film on a pedestal)
};

// One unbalance of a case.
struct ApiUnbalanceLoad {
    int node = 0;
    double z = 0.0;              // m
    double weight = 0.0;         // kg: W of U's formula
    std::string weight_of;       // what W is ("the journals' static loads", "the bearing at z = ...", ...)
    double unbalance = 0.0;      // kg m
    double phase = 0.0;          // rad, from +x
};

// A critical speed of a case: its amplification factor on the case's response, the
// margin it needs and the one it has.
struct ApiCritical {
    CriticalSpeed critical;
    SeparationMargin margin;
    double required = 0.0;       // percent (0: none, AF < 2.5)
    bool met = true;
};

// A location's largest peak-to-peak orbit from 0 to the trip speed.
struct ApiAmplitude {
    double peak_to_peak = 0.0;   // m; +inf where unbounded (a resonance the response cannot resolve)
    double speed = 0.0;          // rad/s
    double scaled = 0.0;         // m: times Scc where the margins are not met (the clearance check)
    double limit = 0.0;          // m: 75 % of the clearance (clearances), Avl (probes)
    double ratio = 0.0;          // scaled / limit (clearances), peak_to_peak / limit (probes)
};

enum class ApiVerdict { pass, pass_scaled, fail, not_judged };
const char* to_string(ApiVerdict v);   // "pass", "pass (scaled clearances)", "fail", "not judged"

struct ApiUnbalanceCase {
    UnbalancePlacement placement;
    std::vector<ApiUnbalanceLoad> loads;
    std::vector<ApiCritical> criticals;     // the critical speeds this placement excites
    std::vector<ApiAmplitude> amplitudes;   // one per location
    Eigen::MatrixXd curves;                 // peak-to-peak (m): response speeds x locations
    double a1 = 0.0;                        // m: the probes' reading at `concern` (their largest refined
                                            //    peak within 10 % of it, else their reading at it)
    double concern = 0.0;                   // rad/s: the critical speed of concern (the first whose margin
                                            //    is not met, else the one of the largest AF)
    double avl = 0.0;                       // m: allowable at the operating speed nearest `concern`
    double scale = 1.0;                     // Scc
    bool margins_met = true;
    ApiVerdict verdict = ApiVerdict::not_judged;
    std::vector<std::string> reasons;
};

struct ApiUnbalanceStudy {
    SpeedUnit unit;
    LengthUnit length_unit;
    double mcs = 0.0, min_speed = 0.0, trip_speed = 0.0, search_to = 0.0;   // rad/s
    std::vector<ApiLocation> locations;
    std::vector<double> response_speeds;    // rad/s: 0 to the trip speed
    std::vector<ApiUnbalanceCase> cases;
    ApiVerdict verdict = ApiVerdict::not_judged;   // the worst case's; fail where a mode is unstable
    std::vector<std::string> reasons;       // why the whole study fails (unstable modes below the trip speed)
    long solves = 0;                        // response solves (the AF's half-power searches not counted)
    Diagnostics diagnostics;
};

// InputError for a scene without an FE rotor or without an mcs, naming the key, and for
// each value out of range.
ApiUnbalanceStudy api_unbalance_study(const Scene& scene, const ApiUnbalanceRequest& request = {});

}  // namespace gyrokit
