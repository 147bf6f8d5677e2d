// Plain cylindrical fluid-film journal bearing in the short-bearing (Ocvirk)
// approximation with Gümbel (half-Sommerfeld) cavitation: the static
// eccentricity under a steady load and the 8 speed-dependent stiffness and
// damping coefficients of the oil film (docs/fe_rotor.md gives the equations).
// A finite-difference solution of the finite-length Reynolds equation is the
// option `solution` (reynolds_bearing.hpp).
#pragma once

#include <gyrokit/core/bearing_table.hpp>

#include <Eigen/Dense>
#include <optional>
#include <string>

namespace gyrokit {

// How the film is solved: the short-bearing closed form (L/D -> 0) or the
// finite-difference solution of the Reynolds equation of finite length.
enum class FilmSolution { short_bearing, finite_difference };

struct JournalBearing {
    double diameter = 0.0;    // D, m
    double length = 0.0;      // L, m
    double clearance = 0.0;   // radial clearance c, m (c < D / 2)
    double viscosity = 0.0;   // dynamic viscosity eta, Pa s
    double load = 0.0;        // static load W carried by this bearing, N
    // Direction of the load on the journal, rad from +x towards +y: -pi/2 is
    // gravity along -y. The spin turns from +x towards +y.
    double load_angle = -1.5707963267948966;
    // Beyond this eccentricity ratio (at low speed) the coefficients of the speed
    // where it is reached are held: the film is then thinner than the short-bearing
    // solution's use, and at standstill the film carries no load at all.
    double max_eccentricity = 0.95;
    FilmSolution solution = FilmSolution::short_bearing;
    // Finite-difference grid (used by FilmSolution::finite_difference): intervals
    // around the circumference (even, 16 to 2880) and over the length (a multiple
    // of 4, 4 to 256). The defaults keep the eccentricity, attitude angle and
    // coefficients at a given load and speed within 1e-3 of the converged
    // solution for e <= 0.9 and 0.25 <= L/D <= 2 (docs/fe_rotor.md).
    int grid_circumferential = 240;
    int grid_axial = 32;
    // The tolerance band of the running clearance and of the oil's viscosity (its supply
    // temperature's range), given in pairs: clearance_min <= clearance <= clearance_max,
    // viscosity_min <= viscosity <= viscosity_max. Unset: the nominal values only. API 617
    // screens Level I at both ends (film_extreme).
    std::optional<double> clearance_min, clearance_max;   // m
    std::optional<double> viscosity_min, viscosity_max;   // Pa s

    // Throws InputError naming `origin`, the key, the value and the allowed range.
    // Lengths in messages are divided by `metres_per_unit` and named `unit` (a scene in mm).
    void validate(const std::string& origin, double metres_per_unit = 1.0, const char* unit = "m") const;
};

// The two ends of a film's tolerance band. Both raise or both lower the Sommerfeld number
// S = eta w R L^3 / (4 W c^2), the conventional pairing of API RP 684: the smallest
// clearance with the coldest oil (the largest viscosity) is the stiffest and most damped
// film, the largest clearance with the hottest oil (the smallest viscosity) the softest.
enum class FilmExtreme { minimum_clearance, maximum_clearance };

const char* to_string(FilmExtreme e);   // "minimum clearance", "maximum clearance"

// True where the bearing gives a clearance or a viscosity band.
bool has_extremes(const JournalBearing& b);

// The bearing at one end of its band: clearance and viscosity from the band where it is
// given, else the nominal ones; the band itself is cleared.
JournalBearing film_extreme(const JournalBearing& b, FilmExtreme e);

// Modified Sommerfeld number of the short bearing at eccentricity ratio e:
// S_s = eta Omega R L^3 / (4 W c^2) = (1 - e^2)^2 / (e sqrt(16 e^2 + pi^2 (1 - e^2))).
double short_bearing_sommerfeld(double eccentricity);

struct JournalBearingState {
    double sommerfeld = 0.0;        // S_s at this speed
    double eccentricity = 0.0;      // e = journal offset / c, in (0, 1)
    double attitude_angle = 0.0;    // rad, from the load line to the line of centres, with the spin
    // Dimensionless coefficients in axes (u, v) where the load acts along -v and
    // the spin turns u into v (a load along -y: u = x, v = y):
    // K = (W / c) a, C = (W / (c Omega)) b.
    Eigen::Matrix2d a = Eigen::Matrix2d::Zero(), b = Eigen::Matrix2d::Zero();
    BearingCoefficients coefficients;   // N/m and N s/m in (x, y)
};

// Dimensionless coefficients a, b in the load axes (u, v) turned into N/m and N s/m in
// (x, y) at spin speed w: K = T^T (W/c) a T, C = T^T (W/(c w)) b T, (u, v) = T (x, y).
BearingCoefficients journal_bearing_coefficients(const JournalBearing& bearing, double w, const Eigen::Matrix2d& a,
                                                 const Eigen::Matrix2d& b);

// The bearing at spin speed w > 0 (rad/s): eccentricity from S_s(e) = S_s(w)
// by root finding, coefficients in closed form, turned into (x, y).
JournalBearingState short_bearing(const JournalBearing& b, double w);

// The speed (rad/s) at which the eccentricity ratio falls to e (S_s(e) = S_s(w)).
double journal_bearing_speed_at(const JournalBearing& b, double eccentricity);

// The bearing as a speed-dependent bearing between the DOF pair (dof_x, dof_y)
// and the ground, by b.solution; below the speed of max_eccentricity its
// coefficients there hold.
BearingTable journal_bearing_table(const JournalBearing& b, const std::string& name, int dof_x, int dof_y);

}  // namespace gyrokit
