#include <gyrokit/models/machine_stages.hpp>

#include <gyrokit/core/constants.hpp>
#include <gyrokit/core/error.hpp>

#include <cmath>
#include <fmt/format.h>

namespace gyrokit {

const char* to_string(MachineKind k) { return k == MachineKind::centrifugal ? "centrifugal" : "axial"; }

double anticipated_cross_coupling(const AeroStage& s, MachineKind kind, double operating_speed) {
    const double rpm = operating_speed * 60.0 / (2.0 * kPi);
    const double b = kind == MachineKind::centrifugal ? kQaCentrifugal : kQaAxial;
    const double q = b * kQaConstant * s.power / (s.diameter * s.width * rpm);
    return kind == MachineKind::centrifugal ? q * s.density_ratio.value_or(1.0) : q;
}

namespace {

bool positive(std::optional<double> v) { return !v || (std::isfinite(*v) && *v > 0.0); }

}  // namespace

void validate(const ApiMachine& m) {
    const std::string& o = m.origin.empty() ? std::string("api") : m.origin;
    if (m.mcs) check_parameter(positive(m.mcs), o, "mcs", *m.mcs, "a finite speed > 0");
    if (m.operating_speed)
        check_parameter(positive(m.operating_speed), o, "operating_speed", *m.operating_speed, "a finite speed > 0");
    if (m.qa) check_parameter(positive(m.qa), o, "qa", *m.qa, "a finite stiffness > 0 (N/m)");
    if (m.gas_density)
        check_parameter(positive(m.gas_density), o, "gas_density", *m.gas_density, "a finite density > 0 (kg/m^3)");
    if (m.station) check_parameter(std::isfinite(*m.station), o, "station", *m.station, "a position on the shaft");
    check_parameter(std::isfinite(m.q_ratio) && m.q_ratio >= 2.0 && m.q_ratio <= 1000.0, o, "q_ratio", m.q_ratio,
                    "[2, 1000] (the Q range in multiples of QA)");
    for (std::size_t i = 0; i < m.stages.size(); ++i) {
        const AeroStage& s = m.stages[i];
        const std::string so = s.origin.empty() ? fmt::format("{}: stage {}", o, i) : s.origin;
        check_parameter(std::isfinite(s.z), so, "z", s.z, "a position on the shaft");
        check_parameter(std::isfinite(s.power) && s.power > 0, so, "power", s.power, "a finite power > 0 (W)");
        check_parameter(std::isfinite(s.diameter) && s.diameter > 0, so, "diameter", s.diameter,
                        "a finite diameter > 0 (m)");
        check_parameter(std::isfinite(s.width) && s.width > 0, so, "width", s.width, "a finite width > 0 (m)");
        if (m.kind == MachineKind::centrifugal && !s.density_ratio)
            throw InputError(so + ": density_ratio is missing; required for a centrifugal machine: the discharge over "
                                  "suction density, > 0");
        check_parameter(s.width < s.diameter, so, "width", s.width,
                        fmt::format("below the diameter {} (m)", s.diameter).c_str());
        if (s.density_ratio)
            check_parameter(std::isfinite(*s.density_ratio) && *s.density_ratio >= 1, so, "density_ratio",
                            *s.density_ratio, "a finite ratio >= 1 (a compressor's discharge is at least as dense "
                                              "as its suction)");
    }
    if (m.min_speed) check_parameter(positive(m.min_speed), o, "min_speed", *m.min_speed, "a finite speed > 0");
    if (m.trip_speed) check_parameter(positive(m.trip_speed), o, "trip_speed", *m.trip_speed, "a finite speed > 0");
    for (std::size_t i = 0; i < m.clearances.size(); ++i) {
        const CloseClearance& c = m.clearances[i];
        const std::string co = c.origin.empty() ? fmt::format("{}: clearance {}", o, i) : c.origin;
        check_parameter(std::isfinite(c.z), co, "z", c.z, "a position on the shaft");
        check_parameter(std::isfinite(c.clearance) && c.clearance > 0, co, "clearance", c.clearance,
                        "a finite diametral clearance > 0 (m)");
    }
}

}  // namespace gyrokit
