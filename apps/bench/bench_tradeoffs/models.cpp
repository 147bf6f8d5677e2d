// gyrokit-bench-tradeoffs: the FE rotor models (models.hpp).
#include "models.hpp"

#include <algorithm>
#include <cmath>

using namespace gyrokit;

namespace tradeoffs {

FeRotor fe_machine(int elements, bool damped) {
    FeRotor r = fe_uniform_shaft(1.5, elements, 0.06, 0.0, kE, kNu, kRho);
    for (int e = 0; e < elements; ++e)
        r.elements[static_cast<size_t>(e)].outer_diameter += 0.02 * std::sin(3.0 * e / elements);
    const double c = damped ? 1.0 : 0.0;
    r.disks.push_back({elements / 3, 12.0, 0.09, 0.16, 1e-4, 0.0});
    r.disks.push_back({(2 * elements) / 3, 8.0, 0.05, 0.09, 0.0, 0.0});
    r.bearings.push_back({elements / 10, 2e7, 0.0, 0.0, 3e7, 400.0 * c, 0.0, 0.0, 600.0 * c});
    r.bearings.push_back({elements - elements / 10, 3e7, 0.0, 0.0, 2.5e7, 500.0 * c, 0.0, 0.0, 500.0 * c});
    return r;
}

FeRotor fe_train(int dofs) {
    const int elements = dofs / 4 - 1;
    FeRotor r;
    for (int e = 0; e < elements; ++e) {
        FeShaftElement s;
        const int span = e / 50;
        s.length = span == 1 ? 0.03 : span == 3 ? 0.026 : 0.02;
        s.outer_diameter = 0.08;
        s.inner_diameter = 0.03;
        s.youngs_modulus = 211e9;
        s.poisson_ratio = 0.3;
        s.density = 7810;
        r.elements.push_back(s);
    }
    for (int node = 0; node <= elements; node += 50) {
        r.bearings.push_back({node, 5e8, 0.0, 0.0, 5e8, 2e3, 0.0, 0.0, 2e3});
        const int end = std::min(node + 50, elements);
        if (end > node + 1) r.disks.push_back({(node + end) / 2, 15.0, 0.1, 0.18, 0.0, 0.0});
    }
    if (elements % 50 != 0) r.bearings.push_back({elements, 5e8, 0.0, 0.0, 5e8, 2e3, 0.0, 0.0, 2e3});
    return r;
}

}  // namespace tradeoffs
