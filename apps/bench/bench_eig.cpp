// gyrokit-bench-eig: times the dense quadratic eigensolvers, scaled QZ (LAPACK
// dggev3, multishift), the same with the classic QZ (dggev) and the M^-1 state
// matrix, on the same pencils and prints their accuracy beside the time, so that
// the price of the default (QZ) can be read off directly.
// Exit status: 0 success, 2 bad input, 1 anything else.
#include "bench_common.hpp"
#include <gyrokit/core/error.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/io/table.hpp>
#include <gyrokit/models/gyrostat.hpp>
#include <gyrokit/core/constants.hpp>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <iostream>
#include <limits>
#include <toml++/toml.h>

using namespace gyrokit;
using gyrokit::bench::linspace;

namespace {

struct Case {
    std::string name;
    GyroscopicSystem sys;
    std::vector<double> speeds;
};

std::string describe(const std::vector<double>& w) {
    if (w.size() == 1) return fmt::format("{:g}", w.front());
    return fmt::format("{:g}..{:g} ({})", w.front(), w.back(), w.size());
}

// Lumped rotor: `disks` equal disks evenly spaced on a massless steel shaft of
// fixed length, DOFs (x, y, tilt_x, tilt_y) per disk. Total mass and inertia
// are fixed, so larger n is a finer model of the same rotor: the low spectrum
// stays put while the high end (and with it the spread of scales) grows, as in
// a refined finite-element model.
GyroscopicSystem make_multi_disk_rotor(int disks) {
    const double L = 1.2, d = 0.06, E = 2.1e11;                 // shaft: m, m, Pa
    const double mass = 40.0, I_d = 0.4, I_p = 0.6;              // totals: kg, kg m^2, kg m^2
    const double k_bearing = 1e8;                                // N/m, both ends, x and y
    const double alpha = 0.5, beta = 1e-8;                       // proportional damping D = alpha M + beta K
    const int n = 4 * disks;
    const double l = L / (disks - 1), EI = E * kPi * std::pow(d, 4) / 64.0;

    GyroscopicSystem sys;
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n), G = M, K = M;
    for (int i = 0; i < disks; ++i) {
        const int b = 4 * i;
        M.diagonal().segment(b, 4) << mass / disks, mass / disks, I_d / disks, I_d / disks;
        G(b + 2, b + 3) = I_p / disks;
        G(b + 3, b + 2) = -I_p / disks;
        for (const char* dof : {"x", "y", "tilt_x", "tilt_y"}) sys.dofs.names.push_back(fmt::format("{}{}", dof, i + 1));
        sys.whirl_pairs.emplace_back(b, b + 1);
        sys.whirl_pairs.emplace_back(b + 2, b + 3);
    }
    // Euler-Bernoulli element (w1, slope1, w2, slope2) between neighbouring disks.
    Eigen::Matrix4d ke;
    ke << 12, 6 * l, -12, 6 * l,
          6 * l, 4 * l * l, -6 * l, 2 * l * l,
          -12, -6 * l, 12, -6 * l,
          6 * l, 2 * l * l, -6 * l, 4 * l * l;
    ke *= EI / (l * l * l);
    for (int i = 0; i + 1 < disks; ++i) {
        const int b = 4 * i, c = 4 * (i + 1);
        // x-z plane: slope dx/dz = tilt_y; y-z plane: slope dy/dz = -tilt_x.
        const int xz[4] = {b + 0, b + 3, c + 0, c + 3}, yz[4] = {b + 1, b + 2, c + 1, c + 2};
        const double sign_yz[4] = {1, -1, 1, -1};
        for (int r = 0; r < 4; ++r)
            for (int s = 0; s < 4; ++s) {
                K(xz[r], xz[s]) += ke(r, s);
                K(yz[r], yz[s]) += sign_yz[r] * sign_yz[s] * ke(r, s);
            }
    }
    for (int dof : {0, 1, n - 4, n - 3}) K(dof, dof) += k_bearing;
    sys.M = to_sparse(M);
    sys.G = to_sparse(G);
    sys.K = to_sparse(K);
    sys.damping.push_back({"proportional", to_sparse(alpha * M + beta * K)});
    sys.validate(fmt::format("rotor with {} disks", disks));
    return sys;
}

// The gyrostat parameters of a scene's [model] (already checked by load_scene),
// so that the extreme variants start from the same centrifuge.
GyrostatParameters gyrostat_parameters(const Scene& scene) {
    if (scene.model_type() != "gyrostat" || scene.system.size() != 6)
        throw InputError(scene.path + ": the extreme cases need a gyrostat with elastic shaft and housing");
    const toml::table doc = toml::parse_file(scene.path);
    const auto num = [&](const char* key, double fallback) {
        return doc["model"][key].value<double>().value_or(fallback);
    };
    GyrostatParameters p;
    p.A_G = num("A_G", 0); p.B_G = num("B_G", 0); p.A_R = num("A_R", 0); p.C_R = num("C_R", 0);
    p.m = num("m", 0); p.s = num("s", 0); p.eps = num("eps", 0);
    p.c_G = num("c_G", 0); p.c_T = num("c_T", 0); p.c_R = num("c_R", 0);
    p.d_G = num("d_G", 0); p.d_T = num("d_T", 0); p.d_R = num("d_R", 0);
    return p;
}

struct Run {
    double seconds_per_speed = 0.0;
    std::vector<QuadraticSpectrum> spectra;   // one per speed, from the first sweep
};

// Repeats the whole sweep until at least `min_time` has passed; the first sweep
// counts too, as the large cases take longer than `min_time` for one sweep.
Run run(const Case& c, EigenMethod method, double min_time) {
    using clock = std::chrono::steady_clock;
    EigenOptions opt;
    opt.method = method;
    Run r;
    long sweeps = 0;
    const auto start = clock::now();
    double elapsed = 0.0;
    do {
        for (double w : c.speeds) {
            QuadraticSpectrum s = solve_at_speed(c.sys, w, opt);
            if (sweeps == 0) r.spectra.push_back(std::move(s));
        }
        ++sweeps;
        elapsed = std::chrono::duration<double>(clock::now() - start).count();
    } while (elapsed < min_time);
    r.seconds_per_speed = elapsed / (static_cast<double>(sweeps) * c.speeds.size());
    return r;
}

double max_backward_error(const Run& r) {
    double e = 0.0;
    for (const auto& s : r.spectra) e = std::max(e, s.max_backward_error());
    return e;
}

// Largest relative eigenvalue difference over all speeds (bench_common.hpp).
double max_rel_diff(const std::vector<QuadraticSpectrum>& a, const std::vector<QuadraticSpectrum>& ref) {
    double worst = 0.0;
    for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, bench::max_rel_diff(a[i], ref[i]));
    return worst;
}

// A differing number of finite modes (e.g. infinite eigenvalues taken as huge
// finite ones) is worth a note beside the numbers.
std::string count_note(const Run& r, const Run& ref, const std::vector<double>& speeds) {
    for (size_t i = 0; i < r.spectra.size(); ++i)
        if (r.spectra[i].modes.size() != ref.spectra[i].modes.size())
            return fmt::format("{} modes vs {} (qz) at w = {:g}", r.spectra[i].modes.size(),
                               ref.spectra[i].modes.size(), speeds[i]);
    return "";
}

void add_case(Table& t, const Case& c, double min_time) {
    const Run qz = run(c, EigenMethod::ScaledQZ, min_time);
    t.add_row({c.name, static_cast<long long>(c.sys.size()), describe(c.speeds), std::string("qz"),
               qz.seconds_per_speed, 1.0, max_backward_error(qz), 0.0, std::string("reference")});
    // The classic single-shift QZ (LAPACK dggev) on the same scaled companion pencil.
    const Run classic = run(c, EigenMethod::ClassicQZ, min_time);
    t.add_row({c.name, static_cast<long long>(c.sys.size()), describe(c.speeds), std::string("qz-classic"),
               classic.seconds_per_speed, classic.seconds_per_speed / qz.seconds_per_speed,
               max_backward_error(classic), max_rel_diff(classic.spectra, qz.spectra), count_note(classic, qz, c.speeds)});
    try {
        const Run st = run(c, EigenMethod::StateMatrix, min_time);
        std::string note = count_note(st, qz, c.speeds);
        t.add_row({c.name, static_cast<long long>(c.sys.size()), describe(c.speeds), std::string("state"),
                   st.seconds_per_speed, st.seconds_per_speed / qz.seconds_per_speed, max_backward_error(st),
                   max_rel_diff(st.spectra, qz.spectra), note});
    } catch (const Error& e) {
        // A failing path is a result of the benchmark, not a reason to stop it.
        // The advice after "; " names a CLI option, which means nothing here.
        const std::string na = "-", what = e.what();
        t.add_row({c.name, static_cast<long long>(c.sys.size()), describe(c.speeds), std::string("state"), na, na,
                   na, na, "failed: " + what.substr(0, what.find("; "))});
    }
    // The default: the state matrix where it is verified (from kAutoStateDofs DOFs), else QZ.
    const Run au = run(c, EigenMethod::Auto, min_time);
    const auto by_state = std::count_if(au.spectra.begin(), au.spectra.end(),
                                        [](const QuadraticSpectrum& s) { return s.method == "state matrix"; });
    std::string note = count_note(au, qz, c.speeds);
    note += fmt::format("{}default: state matrix at {} of {} speeds", note.empty() ? "" : "; ", by_state,
                        au.spectra.size());
    t.add_row({c.name, static_cast<long long>(c.sys.size()), describe(c.speeds), std::string("auto"),
               au.seconds_per_speed, au.seconds_per_speed / qz.seconds_per_speed, max_backward_error(au),
               max_rel_diff(au.spectra, qz.spectra), note});
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Times the dense quadratic eigensolvers: scaled QZ (qz: dggev3), classic QZ (qz-classic: dggev), "
                 "M^-1 state matrix (state) and the default (auto: the state matrix where verified, else qz)"};
    std::string scene_path = std::string(GYROKIT_DATA_DIR) + "/centrifuge.toml", format = "table";
    std::vector<int> sizes{24, 96, 240, 480};
    int rotor_speeds = 3;
    double min_time = 0.2;
    app.add_option("--scene", scene_path, "centrifuge scene (gyrostat with elastic shaft and housing)")
        ->capture_default_str();
    app.add_option("--sizes", sizes, "DOF counts of the multi-disk rotor (multiples of 4, >= 8)")
        ->delimiter(',')
        ->capture_default_str();
    app.add_option("--rotor-speeds", rotor_speeds, "number of speeds 0..1000 rad/s for the rotor")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    app.add_option("--min-time", min_time, "minimum measuring time per case and method, s")
        ->check(CLI::Range(0.0, 3600.0))
        ->capture_default_str();
    app.add_option("--format", format, "output format: table, csv or json")->capture_default_str();
    CLI11_PARSE(app, argc, argv);

    return bench::guarded_main([&] {
        const TableFormat fmt_out = parse_table_format(format);
        for (int n : sizes)
            if (n < 8 || n % 4 != 0)
                throw InputError(fmt::format("--sizes {}: allowed: multiples of 4, at least 8", n));

        const Scene scene = load_scene(scene_path);
        const std::vector<double> scene_speeds = scene.speeds ? scene.speed_points() : linspace(0.0, 60.0, 241);
        std::vector<Case> cases{{"centrifuge", scene.system, scene_speeds}};
        for (int n : sizes)
            cases.push_back({fmt::format("rotor {} disks", n / 4), make_multi_disk_rotor(n / 4),
                             linspace(0.0, 1000.0, rotor_speeds)});

        const GyrostatParameters base = gyrostat_parameters(scene);
        GyrostatParameters stiff = base, tiny = base, all = base, singular = base;
        stiff.c_T = stiff.c_R = 1e12;
        tiny.A_R = 1e-9;
        tiny.C_R = 1.1e-9;
        all.c_T = all.c_R = 1e12;
        all.A_R = 1e-9;
        all.C_R = 1.1e-9;
        singular.A_R = singular.C_R = 0.0;   // massless rotor tilt: M singular
        const std::vector<double> fast{1e5};
        cases.push_back({"centrifuge c_T=c_R=1e12", make_system(stiff), scene_speeds});
        cases.push_back({"centrifuge w=1e5", scene.system, fast});
        cases.push_back({"centrifuge A_R=1e-9", make_system(tiny), scene_speeds});
        cases.push_back({"centrifuge combined", make_system(all), fast});
        cases.push_back({"centrifuge A_R=C_R=0", make_system(singular), scene_speeds});

        Table t({"case", "n", "speeds_rad_s", "method", "seconds_per_speed", "time_vs_qz", "max_backward_error",
                 "max_rel_diff_to_qz", "note"});
        t.title = "Dense eigensolvers: scaled QZ (dggev3) vs classic QZ (dggev) vs M^-1 state matrix";
        for (const auto& c : cases) add_case(t, c, min_time);
        write_table(std::cout, t, fmt_out);
    });
}
