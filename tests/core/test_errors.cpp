// Errors name option fields structurally: the library writes "modes =", each
// front end its own words, and nothing depends on the wording of the prose.
#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/solve/workers.hpp>
#include <gyrokit/core/error.hpp>

#include <catch2/catch.hpp>

#include <thread>

using namespace gyrokit;

namespace {
std::string flags(const std::string& field) { return field == "lanczos_vectors" ? "--lanczos" : "--" + field; }
}  // namespace

TEST_CASE("an option field in an error is written by each front end in its own words") {
    const InputError e(option_field("lanczos_vectors") + " -1: allowed: 0 (automatic) or more; see " +
                       option_field("modes") + " 3");
    CHECK(std::string(e.what()) == "lanczos_vectors = -1: allowed: 0 (automatic) or more; see modes = 3");
    CHECK(e.message(flags) == "--lanczos -1: allowed: 0 (automatic) or more; see --modes 3");
    CHECK(e.message({}) == e.what());
    CHECK(e.fields() == std::vector<std::string>{"lanczos_vectors", "modes"});
    // A stray mark byte in quoted input stays text; only a closed snake_case name is a field.
    const Error stray(std::string("file 'a\x1e" "b.toml': not found; \x1f") + option_field("jobs") + " 3");
    CHECK(stray.message(flags) == std::string("file 'a\x1e" "b.toml': not found; \x1f") + "--jobs 3");
    CHECK(stray.fields() == std::vector<std::string>{"jobs"});
    // A field named as a noun: no " =" in the library's and Python's words, the flag in the CLI's.
    const InputError noun(option_noun("run_up") + " needs " + option_noun("acceleration") + "; " +
                          option_field("dt") + " 0");
    CHECK(std::string(noun.what()) == "run_up needs acceleration; dt = 0");
    CHECK(noun.message(flags) == "--run_up needs --acceleration; --dt 0");
    CHECK(noun.message([](const std::string& f) { return f == "dt" ? "dt =" : ""; }) ==
          "run_up needs acceleration; dt = 0");
    CHECK(noun.fields() == std::vector<std::string>{"run_up", "acceleration", "dt"});
}

TEST_CASE("the solver choice names its fields structurally, whatever the prose") {
    GyroscopicSystem sys;
    sys.M = Eigen::MatrixXd::Identity(2, 2);
    sys.K = Eigen::MatrixXd::Identity(2, 2);
    SolverOptions o;
    o.modes = -3;
    try {
        choose_solver(sys, o);
        FAIL("modes = -3 accepted");
    } catch (const InputError& e) {
        CHECK(e.fields() == std::vector<std::string>{"modes"});
        CHECK(e.message(flags).rfind("--modes -3: allowed", 0) == 0);
    }
    o.modes = 0;
    o.lanczos_vectors = -1;
    try {
        choose_solver(sys, o);
        FAIL("lanczos_vectors = -1 accepted");
    } catch (const InputError& e) {
        CHECK(e.fields() == std::vector<std::string>{"lanczos_vectors"});
    }
    try {
        parse_solver_kind("fast");
        FAIL("solver 'fast' accepted");
    } catch (const InputError& e) {
        CHECK(e.message(flags) == "--solver 'fast': allowed: auto, dense, sparse");
    }
}

TEST_CASE("one parallelism rule: 0 is every core, more than the cores is capped with a note, negative refused") {
    const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    std::vector<std::string> notes;
    CHECK(worker_count(0, &notes) == cores);
    CHECK(worker_count(1, &notes) == 1);
    CHECK(notes.empty());
    CHECK(worker_count(cores + 5, &notes) == cores);
    REQUIRE(notes.size() == 1);
    CHECK(spell_fields(notes[0], flags).rfind("--jobs " + std::to_string(cores + 5) + " capped to the", 0) == 0);
    CHECK_THROWS_AS(worker_count(-1), InputError);
}
