// A uniform grid of spin speeds (rad/s) and output unit conversion.
#pragma once

#include <string>
#include <vector>

namespace gyrokit {

struct SpeedRange {
    double from = 0.0, to = 0.0;
    int count = 0;
    // Parses "FROM:TO:N" as written (the caller's unit; resolve_request converts), e.g.
    // "0:60:601". Throws InputError quoting the text.
    static SpeedRange parse(const std::string& text, const std::string& option);
    // Throws InputError naming `origin` unless 0 <= from <= to, count >= 2 (or
    // count == 1 with from == to), all finite.
    void validate(const std::string& origin) const;
    std::vector<double> points() const;
};

// Output units of speeds and frequencies: rad/s, Hz or rpm. `factor` converts
// from rad/s: value_in_unit = factor * value_in_rad_per_s.
struct SpeedUnit {
    std::string name = "rad/s";
    double factor = 1.0;
    static SpeedUnit parse(const std::string& name);   // throws InputError
    // A column name that records the unit: "speed" -> speed_rad_s, speed_hz, speed_rpm.
    std::string column(const std::string& base) const;
    // The unit of an angular acceleration in it: rad/s^2, Hz/s, rpm/s.
    std::string per_second() const;
};

}  // namespace gyrokit
