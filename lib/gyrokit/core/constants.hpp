#pragma once
// Mathematical constants, defined once (C++17 has no std::numbers; M_PI is POSIX, not C++).

namespace gyrokit {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kDegreesPerRadian = 180.0 / kPi;

}  // namespace gyrokit
