// Shared fixtures of the tests: the centrifuge parameters, random gyrostats and
// the message a scene text is refused with.
#pragma once

#include <gyrokit/core/error.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/models/gyrostat.hpp>

#include <random>
#include <string>

namespace gyrokit::test {

// The parameter set of data/centrifuge.toml.
inline GyrostatParameters centrifuge() {
    GyrostatParameters p;
    p.A_G = p.B_G = 2.0;
    p.A_R = 0.09;
    p.C_R = 0.10;
    p.m = 8.0;
    p.s = 0.25;
    p.eps = 1e-3;
    p.c_G = 306.862;
    p.c_T = 2112.19;
    p.c_R = 74.1333;
    p.d_G = 4.0;
    p.d_T = 5.0;
    p.d_R = 0.02;
    return p;
}

inline double uniform(std::mt19937& g, double a, double b) { return std::uniform_real_distribution<double>(a, b)(g); }

// A random gyrostat over a wide, physically sensible range; symmetric cage if asked.
inline GyrostatParameters random_gyrostat(std::mt19937& g, bool symmetric_cage) {
    GyrostatParameters p;
    p.A_G = uniform(g, 0.2, 5.0);
    p.B_G = symmetric_cage ? p.A_G : p.A_G * uniform(g, 1.2, 2.0);
    p.A_R = uniform(g, 0.01, 0.3);
    p.C_R = uniform(g, 0.01, 0.4);
    p.m = uniform(g, 1.0, 30.0);
    p.s = uniform(g, 0.05, 0.6) * (uniform(g, 0, 1) < 0.5 ? -1.0 : 1.0);
    p.eps = 1e-3;
    p.c_G = uniform(g, 50.0, 5000.0);
    p.c_T = uniform(g, 500.0, 1e5);
    p.c_R = uniform(g, 5.0, 2000.0);
    p.d_G = uniform(g, 0.5, 5.0);
    p.d_T = uniform(g, 0.5, 20.0);
    p.d_R = uniform(g, 0.001, 0.1);
    return p;
}

// The InputError message parse_scene gives for `text` (origin "bad.toml"), or "no error".
inline std::string scene_error(const std::string& text) {
    try {
        parse_scene(text, "bad.toml");
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

}  // namespace gyrokit::test
