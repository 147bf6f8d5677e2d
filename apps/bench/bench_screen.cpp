// gyrokit-bench-screen: designs per second of a design study for the
// centrifuge gyrostat (6 DOFs) and a generated multi-disk rotor (4 DOFs per
// disk), with 1..J worker threads. Prints a table.
// Exit status: 0 success, 2 bad input, 1 anything else.
#include "bench_common.hpp"
#include <gyrokit/core/error.hpp>
#include <gyrokit/io/table.hpp>
#include <gyrokit/screening/screening.hpp>
#include <gyrokit/core/constants.hpp>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <iostream>
#include <thread>

#ifndef GYROKIT_DATA_DIR
#define GYROKIT_DATA_DIR "data"
#endif

using namespace gyrokit;

namespace {

// Disks on an elastic shaft (Euler-Bernoulli elements), DOFs (x, y, tilt_x,
// tilt_y) per disk, bearings at the two end disks with stiffness k and damping c.
Scene multi_disk_rotor(int disks, double k_bearing, double c_bearing) {
    const double L = 1.2, d = 0.05, E = 2.1e11, m = 40.0 / disks, Id = 0.4 / disks, Ip = 0.6 / disks;
    const double l = L / (disks - 1), EI = E * kPi * std::pow(d, 4) / 64.0;
    const int n = 4 * disks;
    Scene sc;
    GyroscopicSystem& s = sc.system;
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n), K = M, G = M;
    Eigen::MatrixXd D = Eigen::MatrixXd::Zero(n, n);
    Eigen::Matrix4d ke;
    ke << 12, 6 * l, -12, 6 * l, 6 * l, 4 * l * l, -6 * l, 2 * l * l, -12, -6 * l, 12, -6 * l, 6 * l, 2 * l * l,
        -6 * l, 4 * l * l;
    ke *= EI / (l * l * l);
    for (int i = 0; i < disks; ++i) {
        const int b = 4 * i;
        M(b, b) = M(b + 1, b + 1) = m;
        M(b + 2, b + 2) = M(b + 3, b + 3) = Id;
        G(b + 2, b + 3) = Ip;
        G(b + 3, b + 2) = -Ip;
        for (const char* nm : {"x", "y", "tilt_x", "tilt_y"}) s.dofs.names.push_back(fmt::format("{}{}", nm, i + 1));
        s.whirl_pairs.emplace_back(b, b + 1);
        s.whirl_pairs.emplace_back(b + 2, b + 3);
    }
    for (int e = 0; e + 1 < disks; ++e) {
        // Bending in x-z uses (x, tilt_y), in y-z (y, tilt_x).
        for (const auto& [w, t] : {std::pair<int, int>{0, 3}, std::pair<int, int>{1, 2}}) {
            const int idx[4] = {4 * e + w, 4 * e + t, 4 * (e + 1) + w, 4 * (e + 1) + t};
            for (int a = 0; a < 4; ++a)
                for (int c = 0; c < 4; ++c) K(idx[a], idx[c]) += ke(a, c);
        }
    }
    for (int end : {0, disks - 1})
        for (int q : {4 * end, 4 * end + 1}) {
            K(q, q) += k_bearing;
            D(q, q) += c_bearing;
        }
    DampingComponent bearings;
    bearings.name = "bearings";
    bearings.D = to_sparse(D);
    s.M = to_sparse(M);
    s.K = to_sparse(K);
    s.G = to_sparse(G);
    s.damping.push_back(bearings);
    s.unbalance = Eigen::VectorXcd::Zero(n);
    const int mid = 4 * (disks / 2);
    s.unbalance(mid) = m * 1e-4;
    s.unbalance(mid + 1) = std::complex<double>(0, -m * 1e-4);
    sc.solver.modes = 8;
    return sc;
}

double get(const std::map<std::string, double>& o, const std::string& k, double fallback) {
    const auto it = o.find(k);
    return it == o.end() ? fallback : it->second;
}

struct Study {
    std::string name;
    Sweep sweep;
};

Sweep centrifuge_study(long long samples) {
    Sweep s;
    s.path = "bench: centrifuge";
    s.scene = std::string(GYROKIT_DATA_DIR) + "/centrifuge.toml";
    s.sampling = Sampling::LatinHypercube;
    s.samples = samples;
    s.seed = 7;
    SweepParameter cG{"model.c_G", 150.0, 600.0, 0, {}, false, {}}, dG{"model.d_G", 0.5, 10.0, 0, {}, false, {}};
    s.parameters = {cG, dG};
    s.op_from = 24.0;
    s.op_to = 50.0;
    s.op_count = 27;
    s.criteria.separation = SeparationCriterion{15.0, true, {}, 121, false, std::nullopt};
    s.criteria.stability = StabilityCriterion{80.0, 121, std::nullopt};
    s.criteria.pervasive = PervasiveCriterion{};
    s.criteria.response = ResponseCriterion{2.6e-3, {"x", "y"}, {}};
    finalize_sweep(s);
    return s;
}

Sweep rotor_study(int disks, long long samples) {
    Sweep s;
    s.path = fmt::format("bench: {}-disk rotor", disks);
    s.loader = [disks](const std::map<std::string, double>& o) {
        return multi_disk_rotor(disks, get(o, "model.k_bearing", 5e7), get(o, "model.c_bearing", 2e3));
    };
    s.sampling = Sampling::LatinHypercube;
    s.samples = samples;
    s.seed = 7;
    SweepParameter kb{"model.k_bearing", 1e7, 1e9, 0, {}, true, {}}, cb{"model.c_bearing", 5e2, 5e3, 0, {}, true, {}};
    s.parameters = {kb, cb};
    s.op_from = 150.0;
    s.op_to = 300.0;
    s.op_count = 31;
    s.criteria.separation = SeparationCriterion{15.0, true, {1}, 61, false, std::nullopt};
    s.criteria.stability = StabilityCriterion{400.0, 61, std::nullopt};
    s.criteria.pervasive = PervasiveCriterion{};
    // Translation of the middle disk, where the unbalance sits.
    s.criteria.response =
        ResponseCriterion{1e-4, {fmt::format("x{}", disks / 2 + 1), fmt::format("y{}", disks / 2 + 1)}, {}};
    finalize_sweep(s);
    return s;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"gyrokit-bench-screen: designs per second of a design study vs worker threads"};
    long long designs = 48, rotor_designs = 4;
    int disks = 6, max_jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    app.add_option("--designs", designs, "centrifuge designs (Latin hypercube)")->capture_default_str();
    app.add_option("--rotor-designs", rotor_designs, "multi-disk rotor designs")->capture_default_str();
    app.add_option("--disks", disks, "disks of the generated rotor (4 DOFs each)")->capture_default_str();
    app.add_option("--max-jobs", max_jobs, "largest number of worker threads")->capture_default_str();
    CLI11_PARSE(app, argc, argv);
    return bench::guarded_main([&] {
        if (designs < 1 || rotor_designs < 1 || disks < 3 || max_jobs < 1)
            throw InputError("--designs, --rotor-designs >= 1, --disks >= 3, --max-jobs >= 1");
        std::vector<Study> studies{{"centrifuge gyrostat", centrifuge_study(designs)},
                                   {fmt::format("{}-disk rotor", disks), rotor_study(disks, rotor_designs)}};
        // The pervasive-damping check refines every residual minimum of every
        // branch; this row shows what the other three criteria cost alone.
        Study light{fmt::format("{}-disk rotor, no pervasive", disks), rotor_study(disks, 4 * rotor_designs)};
        light.sweep.criteria.pervasive.reset();
        studies.push_back(std::move(light));
        Table t({"model", "DOFs", "designs", "jobs", "time_s", "designs_per_s", "speedup", "pass", "fail", "error"});
        t.title = "design screening throughput";
        std::vector<std::string> notes;
        for (const auto& st : studies) {
            const int dofs = st.sweep.loader({}).system.size();
            double t1 = 0;
            for (int jobs = 1; jobs <= max_jobs; ++jobs) {
                RunOptions ro;
                ro.jobs = jobs;
                const auto start = std::chrono::steady_clock::now();
                const RunResult r = run_screening(st.sweep, ro);
                const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
                if (jobs == 1) {
                    t1 = sec;
                    notes.push_back(fmt::format("{}, design 0: {}", st.name, r.rows.front().cells.back()));
                }
                long long pass = 0, fail = 0, error = 0;
                const std::size_t cv = r.columns.size() - 3;
                for (const auto& row : r.rows)
                    (row.cells[cv] == "pass" ? pass : row.cells[cv] == "fail" ? fail : error)++;
                t.add_row({st.name, static_cast<long long>(dofs), static_cast<long long>(r.rows.size()),
                           static_cast<long long>(jobs), sec, r.rows.size() / sec, t1 / sec, pass, fail, error});
            }
        }
        write_table(std::cout, t, TableFormat::Text);
        for (const auto& n : notes) std::cout << n << "\n";
    });
}
