#include <gyrokit/reports/frf_reports.hpp>

#include <gyrokit/reports/detail/cells.hpp>
#include <gyrokit/reports/response_reports.hpp>

#include <cmath>
#include <fmt/format.h>

namespace gyrokit {

std::vector<std::string> frf_units(const std::vector<std::string>& dof_units, int input) {
    if (dof_units.empty()) return {};
    const std::string& in = dof_units[static_cast<std::size_t>(input)];
    // A force drives a translation (in m, or mm as printed), a moment a rotation.
    const std::string per = in == "m" || in == "mm" ? "N" : in == "rad" ? "(N m)" : "(unit force)";
    std::vector<std::string> out;
    for (const std::string& u : dof_units) out.push_back(u + "/" + per);
    return out;
}

ResponseCurve frf_curve(const FrequencyResponse& r) { return {r.frequencies, r.outputs, r.H}; }

Table frf_table(const std::vector<std::string>& names, const std::vector<std::string>& units,
                const FrequencyResponse& r, const SpeedUnit& u) {
    const std::vector<std::string> per = frf_units(units, r.input);
    Table t({u.column("frequency"), "dof", "unit", "re", "im", "amplitude", "phase_deg"});
    t.key = "frf";
    t.title = fmt::format("frequency response to a unit harmonic force at {} (spin {:.6g} {})",
                          names[static_cast<std::size_t>(r.input)], u.factor * r.spin, u.name);
    for (std::size_t i = 0; i < r.frequencies.size(); ++i)
        for (std::size_t k = 0; k < r.outputs.size(); ++k) {
            const std::complex<double> h = r.H(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k));
            const int dof = r.outputs[k];
            t.add_row({u.factor * r.frequencies[i], names[static_cast<std::size_t>(dof)],
                       per.empty() ? std::string() : per[static_cast<std::size_t>(dof)], h.real(), h.imag(),
                       std::abs(h), std::abs(h) == 0.0 ? 0.0 : detail::degrees(std::arg(h))});
        }
    return t;
}

Figure frf_figure(const std::vector<std::string>& names, const std::vector<std::string>& units,
                  const FrequencyResponse& r, const SpeedUnit& u, bool polar, bool log_amplitude) {
    const std::vector<std::string> per = frf_units(units, r.input);
    const std::string title = fmt::format("FRF, force at {}, spin {:.6g} {}", names.at(static_cast<std::size_t>(r.input)),
                                          u.factor * r.spin, u.name);
    return polar ? response_polar_figure(names, per, frf_curve(r), u, title, {}, "frequency")
                 : response_figure(names, per, frf_curve(r), u, title, {}, "frequency", log_amplitude);
}

}  // namespace gyrokit
