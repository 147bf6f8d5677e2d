// The three-disk rotor of data/three_disk_rotor.toml built in code: five steel
// sections, three disks from their geometry, two anisotropic damped bearings. Its
// matrices equal those of the scene file (given as the argument) entry for entry;
// it prints its critical speeds and writes its own scene to stdout with --write.
// Usage: rotor_in_code SCENE.toml [--write]
#include <gyrokit/gyrokit.hpp>

#include <cstdio>
#include <cstring>
#include <exception>

namespace {

gyrokit::RotorModel three_disk_rotor() {
    const double E = 211e9, nu = 211e9 / (2 * 81.2e9) - 1, rho = 7810;   // steel (Friswell et al.)
    gyrokit::RotorModel r;
    const struct { double length; int elements; double diameter; } sections[] = {
        {0.1, 2, 0.06}, {0.25, 5, 0.09}, {0.5, 10, 0.10}, {0.25, 5, 0.09}, {0.1, 2, 0.06}};
    for (const auto& s : sections) {
        gyrokit::RotorSection sec;
        sec.shape.length = s.length;
        sec.shape.outer_diameter = s.diameter;
        sec.shape.youngs_modulus = E;
        sec.shape.poisson_ratio = nu;
        sec.shape.density = rho;
        sec.elements = s.elements;
        r.sections.push_back(sec);
    }
    const struct { double z, outer, width, unbalance; } disks[] = {
        {0.35, 0.32, 0.05, 0.0}, {0.6, 0.40, 0.07, 2e-4}, {0.85, 0.32, 0.05, 0.0}};
    for (const auto& d : disks) {
        gyrokit::RotorDisk disk;
        disk.z = d.z;
        disk.geometry = gyrokit::DiskGeometry{d.outer, 0.10, d.width, rho};
        disk.disk.unbalance = d.unbalance;   // kg m
        r.disks.push_back(disk);
    }
    for (double z : {0.05, 1.15}) {
        gyrokit::RotorBearing b;
        b.z = z;
        b.constant.kxx = 2e7;
        b.constant.kyy = 1.5e7;
        b.constant.cxx = b.constant.cyy = 3e4;
        r.bearings.push_back(b);
    }
    return r;
}

bool same(const gyrokit::SparseMatrix& a, const gyrokit::SparseMatrix& b) {
    return a.rows() == b.rows() && a.cols() == b.cols() && Eigen::MatrixXd(a) == Eigen::MatrixXd(b);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s SCENE.toml [--write]\n", argv[0]);
        return 2;
    }
    try {
        gyrokit::Scene built = gyrokit::rotor_scene(three_disk_rotor(), "three-disk rotor, built in code");
        const gyrokit::Scene file = gyrokit::load_scene(argv[1]);
        built.speeds = file.speeds;
        built.speed_unit = file.speed_unit;   // [speeds] as written, in their units
        if (argc > 2 && std::strcmp(argv[2], "--write") == 0) {
            std::fputs(gyrokit::scene_text(built).c_str(), stdout);
            return 0;
        }
        const gyrokit::GyroscopicSystem &a = built.system, &b = file.system;
        if (!same(a.M, b.M) || !same(a.K, b.K) || !same(a.G, b.G) || !same(a.damping_matrix(), b.damping_matrix()) ||
            a.unbalance != b.unbalance) {
            std::fprintf(stderr, "the rotor built in code differs from %s\n", argv[1]);
            return 1;
        }
        std::printf("M, K, G, D and the unbalance equal those of %s (%d DOFs)\n", argv[1], a.size());
        gyrokit::StudyOptions study = gyrokit::study_options(built);
        for (const gyrokit::CriticalSpeed& c : gyrokit::critical_speed_study(built.system, study).critical)
            std::printf("critical speed %8.2f rad/s  %s\n", c.speed, gyrokit::to_string(c.mode.whirl).c_str());
    } catch (const std::exception& e) {   // gyrokit::InputError: one line naming the item and value
        std::fprintf(stderr, "%s\n", e.what());
        return 2;
    }
    return 0;
}
