// Build a model from its parameters and print its Campbell diagram:
// the gyrostat with elastic shaft (docs/gyrostat.md), 0 to 60 rad/s.
#include <gyrokit/gyrokit.hpp>

#include <cstdio>

int main() {
    gyrokit::GyrostatParameters p;
    p.A_G = 1.2; p.B_G = 1.2;       // cage inertia, kg m^2
    p.A_R = 0.05; p.C_R = 0.08;     // rotor inertia, kg m^2
    p.m = 10.0; p.s = 0.3;          // rotor mass (kg), distance to the suspension point (m)
    p.c_G = 5e4; p.c_T = 2e5; p.c_R = 1e4;
    p.d_G = 20.0;                   // cage damping only
    const gyrokit::GyroscopicSystem sys = gyrokit::make_system(p);

    const auto speeds = gyrokit::SpeedRange{0.0, 60.0, 7}.points();
    const gyrokit::CampbellDiagram cd = gyrokit::campbell(sys, speeds);
    std::printf("%d branches, max backward error %.1e\n", static_cast<int>(cd.branches.size()), cd.max_backward_error);
    for (const auto& b : cd.branches) {
        std::printf("branch %d:", b.id);
        for (const auto& pt : b.points)
            if (pt.speed == speeds.front() || pt.speed == speeds.back())
                std::printf("  w = %4.0f rad/s: %9.4f rad/s (%s)", pt.speed, pt.mode.frequency(),
                            gyrokit::to_string(pt.mode.whirl).c_str());
        std::printf("\n");
    }
    return cd.branches.empty() ? 1 : 0;
}
