// The table of defaults (study/defaults.hpp) is what the library's own options
// use when a caller leaves a field unset, and the range checks live in the
// library (not only in the front ends). tests/defaults_check.py checks the CLI's
// help, the Python signatures and docs/defaults.md against the same table.
#include <gyrokit/gyrokit.hpp>

#include <catch2/catch.hpp>

#include <set>
#include <string>

using namespace gyrokit;

TEST_CASE("the options' unset fields are the table's defaults", "[defaults]") {
    const StudyOptions so;
    CHECK(so.solver.modes == defaults::modes);
    CHECK(so.solver.kind == parse_solver_kind(defaults::solver));
    CHECK(so.solver.eig.method == parse_eigen_method(defaults::method));
    CHECK(so.solver.lanczos_vectors == defaults::lanczos);
    CHECK(so.harmonics == std::vector<int>{defaults::harmonic});
    CHECK(so.workers.count == worker_count(defaults::jobs));
    CHECK(so.unit.name == defaults::unit);
    CHECK_FALSE(so.f_cut.has_value());   // the rule: f_cut_margin times the highest excitation
    CHECK(PervasiveOptions{}.tolerance == defaults::pervasive_tolerance);
    CHECK(CriticalSpeedMapOptions{}.modes == defaults::critical_map_modes);
    CHECK(StaticOptions{}.gravity == defaults::gravity);
    CHECK(TransientOptions{}.max_steps == defaults::max_steps);
    const Scene unset;
    CHECK(unset.solver.modes == defaults::modes);
    CHECK(unset.analysis.harmonics == std::vector<int>{defaults::harmonic});
}

TEST_CASE("the table of defaults names each default once", "[defaults]") {
    std::set<std::string> names;
    for (const defaults::Entry& e : defaults::table()) {
        INFO(e.name);
        CHECK(names.insert(e.name).second);
        CHECK_FALSE(e.meaning.empty());
        // A value is written as a front end reads it back.
        if (e.name == "units") CHECK(e.value.empty());   // a rule: the scene's [speeds] units
        if (e.name == "units") CHECK(SpeedUnit{}.name == defaults::unit);
        if (e.name == "method") CHECK(to_string(parse_eigen_method(e.value)) == e.value);
        if (e.name == "tolerance") CHECK(std::stod(e.value) == defaults::pervasive_tolerance);
        if (e.name == "gravity") CHECK(std::stod(e.value) == defaults::gravity);
    }
    CHECK(names.count("jobs") == 1);
    CHECK(names.count("threads") == 0);
    CHECK(names.count("workers") == 0);
}

TEST_CASE("the pervasive tolerance is checked by the library, naming its field", "[defaults][errors]") {
    const Scene sc = load_scene(std::string(GYROKIT_DATA_DIR) + "/three_disk_rotor.toml");
    for (const double t : {0.0, -1e-8, 1.0, 2.0}) {
        PervasiveOptions po;
        po.tolerance = t;
        INFO(t);
        try {
            (void)pervasive_damping(sc.system, {0.0, 100.0}, po);
            FAIL("no error");
        } catch (const InputError& e) {
            const std::string m = e.what();
            CHECK(m.find("tolerance") != std::string::npos);
            CHECK(m.find("allowed: 0 < tolerance < 1") != std::string::npos);
        }
    }
}
