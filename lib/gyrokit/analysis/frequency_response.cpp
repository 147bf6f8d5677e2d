#include <gyrokit/analysis/frequency_response.hpp>

#include <gyrokit/analysis/unbalance_response.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/core/interrupt.hpp>

#include <cmath>
#include <fmt/format.h>
#include <numeric>

namespace gyrokit {

FrequencyResponse frequency_response(const GyroscopicSystem& sys, double spin, const std::vector<double>& frequencies,
                                     int input, const std::vector<int>& outputs, SolverKind kind) {
    const int n = sys.size();
    if (input < 0 || input >= n)
        throw InputError(fmt::format("frequency response: input DOF {}; allowed: 0 to {}", input, n - 1));
    if (!(std::isfinite(spin) && spin >= 0))
        throw InputError(fmt::format("frequency response: spin speed {}; allowed: a finite number >= 0 (rad/s)", spin));
    if (frequencies.empty())
        throw InputError("frequency response: no frequencies; allowed: one or more finite frequencies >= 0 (rad/s)");
    for (const double w : frequencies)
        if (!(std::isfinite(w) && w >= 0))
            throw InputError(fmt::format("frequency response: frequency {}; allowed: finite numbers >= 0 (rad/s)", w));
    FrequencyResponse r;
    r.spin = spin;
    r.frequencies = frequencies;
    r.input = input;
    r.outputs = outputs;
    if (r.outputs.empty()) {
        r.outputs.resize(static_cast<std::size_t>(n));
        std::iota(r.outputs.begin(), r.outputs.end(), 0);
    }
    check_dof_list(sys, r.outputs, "frequency response");
    const Eigen::VectorXcd f = Eigen::VectorXcd::Unit(n, input);
    r.H.resize(static_cast<Eigen::Index>(frequencies.size()), static_cast<Eigen::Index>(r.outputs.size()));
    for (std::size_t i = 0; i < frequencies.size(); ++i) {
        throw_if_interrupted();
        const Eigen::VectorXcd h = dynamic_response(sys, spin, frequencies[i], f, kind);
        for (std::size_t k = 0; k < r.outputs.size(); ++k)
            r.H(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)) = h(r.outputs[k]);
    }
    return r;
}

}  // namespace gyrokit
