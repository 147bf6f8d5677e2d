// A request meets a scene once, in the library (resolve_request): the call's
// values where given, else the scene's [speeds] and [analysis], else the table of
// defaults; the unit of speeds in and out is the scene's [speeds] units unless the
// call names one; every range check names the field through the library's API.
#include <gyrokit/gyrokit.hpp>

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <string>

using namespace gyrokit;

namespace {

// The centrifuge gyrostat with the given [speeds] and [analysis].
Scene scene_with(const std::string& settings) {
    return parse_scene(R"([model]
type = "gyrostat"
A_G = 2.0
B_G = 2.0
A_R = 0.09
C_R = 0.10
m = 8.0
s = 0.25
eps = 1.0e-3
c_G = 306.862
c_T = 2112.19
c_R = 74.1333
d_G = 4.0
d_T = 5.0
d_R = 0.02
)" + settings,
                       "request.toml");
}

std::string message_of(const Scene& sc, const RotorRequest& r, SpeedsNeeded need = SpeedsNeeded::Yes) {
    try {
        resolve_request(sc, r, need);
    } catch (const InputError& e) {
        return e.message({});
    }
    return "";
}

}  // namespace

TEST_CASE("request: the scene's [speeds] units are the unit of a study unless the call names one", "[request]") {
    const Scene rpm = scene_with("[speeds]\nfrom = 0\nto = 6000\ncount = 4\nunits = \"rpm\"\n");
    const double pi = std::acos(-1.0);
    const StudyOptions o = resolve_request(rpm, {});
    CHECK(o.unit.name == "rpm");
    REQUIRE(o.speeds.size() == 4);
    CHECK(o.speeds[1] == Approx(2000 * pi / 30).epsilon(1e-15));
    CHECK(o.speeds == rpm.speed_points());

    // Given speeds are in the request's unit: the scene's, or the one named.
    RotorRequest r;
    r.speeds = std::vector<double>{0, 600};
    CHECK(resolve_request(rpm, r).speeds.back() == Approx(20 * pi).epsilon(1e-15));
    r.unit = "hz";
    const StudyOptions hz = resolve_request(rpm, r);
    CHECK(hz.unit.name == "Hz");
    CHECK(hz.speeds.back() == Approx(1200 * pi).epsilon(1e-15));

    // A scene without [speeds] units (and a system alone) is in rad/s.
    const Scene plain = scene_with("[speeds]\nfrom = 0\nto = 10\ncount = 3\n");
    CHECK(resolve_request(plain, {}).unit.name == "rad/s");
    CHECK(resolve_request(scene_of(plain.system), {}, SpeedsNeeded::No).unit.name == "rad/s");
    CHECK(resolve_unit(rpm, std::nullopt).name == "rpm");
    CHECK(resolve_unit(rpm, std::string("RAD/S")).name == "rad/s");
}

TEST_CASE("request: a value given comes before the scene's, the scene's before the default", "[request]") {
    const Scene sc = scene_with("[speeds]\nfrom = 0\nto = 10\ncount = 3\n[analysis]\nmodes = 4\nharmonics = [1, 2]\n"
                                "f_cut = 50.0\n");
    const StudyOptions from_scene = resolve_request(sc, {});
    CHECK(from_scene.solver.modes == 4);
    CHECK(from_scene.harmonics == std::vector<int>{1, 2});
    CHECK(from_scene.f_cut == 50.0);
    CHECK(from_scene.solver.eig.method == parse_eigen_method(defaults::method));
    CHECK(from_scene.workers.count == worker_count(defaults::jobs));

    RotorRequest r;
    r.modes = 0;
    r.harmonics = std::vector<int>{3};
    r.f_cut = 20.0;
    r.method = "state";
    r.solver = "dense";
    r.target = 5.0;
    r.target_order = 1.0;
    r.lanczos = 40;
    r.jobs = 1;
    const StudyOptions given = resolve_request(sc, r);
    CHECK(given.solver.modes == 0);
    CHECK(given.harmonics == std::vector<int>{3});
    CHECK(given.f_cut == 20.0);
    CHECK(given.solver.eig.method == EigenMethod::StateMatrix);
    CHECK(given.solver.kind == SolverKind::Dense);
    CHECK(given.solver.target == 5.0);
    CHECK(given.solver.target_order == 1.0);
    CHECK(given.solver.lanczos_vectors == 40);
    CHECK(given.workers.count == 1);

    // Nothing in the scene: the table's defaults.
    const StudyOptions bare = resolve_request(scene_of(sc.system), {}, SpeedsNeeded::No);
    CHECK(bare.solver.modes == defaults::modes);
    CHECK(bare.harmonics == std::vector<int>{defaults::harmonic});
    CHECK_FALSE(bare.f_cut.has_value());
    CHECK(bare.speeds.empty());
}

TEST_CASE("request: each value out of range is refused naming its field", "[request][errors]") {
    const Scene sc = scene_with("[speeds]\nfrom = 0\nto = 10\ncount = 3\n");
    const auto refused = [&](RotorRequest r, const std::string& field) {
        const std::string m = message_of(sc, r);
        INFO(m);
        CHECK(m.rfind(field, 0) == 0);
        CHECK(m.find("allowed") != std::string::npos);
    };
    RotorRequest r;
    r.speeds = std::vector<double>{};
    refused(r, "speeds");
    r.speeds = std::vector<double>{0, -1};
    refused(r, "speeds =");
    r.speeds = std::vector<double>{0, std::nan("")};
    refused(r, "speeds =");
    r = {};
    r.modes = -2;
    refused(r, "modes =");
    r = {};
    r.harmonics = std::vector<int>{0};
    refused(r, "harmonics =");
    r.harmonics = std::vector<int>{};
    refused(r, "harmonics");
    r = {};
    r.f_cut = 0.0;
    refused(r, "f_cut =");
    r = {};
    r.target = -1.0;
    refused(r, "target =");
    r = {};
    r.target_order = std::nan("");
    refused(r, "target_order =");
    r = {};
    r.lanczos = -1;
    refused(r, "lanczos_vectors =");
    r = {};
    r.jobs = -1;
    refused(r, "jobs =");
    r = {};
    r.unit = "furlongs";
    refused(r, "units =");
    r = {};
    r.solver = "fast";
    refused(r, "solver =");
    r = {};
    r.method = "lu";
    refused(r, "method =");
    // A sweep needs speeds: none given and none in the scene.
    CHECK(message_of(scene_of(sc.system), {}).rfind("no speed range; give speeds", 0) == 0);
    CHECK(message_of(scene_of(sc.system), {}, SpeedsNeeded::No).empty());
}

TEST_CASE("request: the frequency response study takes its input, outputs and grid by name and unit", "[request][frf]") {
    const Scene rpm = load_scene(std::string(GYROKIT_DATA_DIR) + "/three_disk_rotor.toml");
    FrfRequest rq;
    rq.input = "y12";
    rq.speed = 6000.0;   // rpm: the scene's [speeds] units
    rq.frequencies = std::vector<double>{3000.0};
    const FrfStudy st = frf_study(rpm, {}, rq);
    CHECK(st.unit.name == "rpm");
    const double pi = std::acos(-1.0);
    CHECK(st.response.spin == Approx(200 * pi).epsilon(1e-15));
    CHECK(st.response.outputs == std::vector<int>{st.response.input});   // the driving point
    // The same response asked in rad/s: the same numbers, bit for bit where the speeds are.
    RotorRequest rad;
    rad.unit = "rad/s";
    FrfRequest same = rq;
    same.speed = st.response.spin;
    same.frequencies = std::vector<double>{st.response.frequencies[0]};
    CHECK(frf_study(rpm, rad, same).si == st.si);
    // Without frequencies: the scene's [speeds] grid.
    FrfRequest grid;
    grid.input = "y12";
    CHECK(frf_study(rpm, {}, grid).response.frequencies == rpm.speed_points());

    const auto refused = [&](FrfRequest r, const std::string& start) {
        try {
            frf_study(rpm, {}, r);
            FAIL("accepted");
        } catch (const InputError& e) {
            INFO(e.message({}));
            CHECK(e.message({}).rfind(start, 0) == 0);
        }
    };
    FrfRequest bad = rq;
    bad.input = "q9";
    refused(bad, "input = 'q9': not a DOF of the model");
    bad = rq;
    bad.dofs = {"y3", "y3"};
    refused(bad, "dofs = 'y3,y3': 'y3' is listed twice");
    bad = rq;
    bad.speed = -3.0;
    refused(bad, "speed = -3: allowed: a finite number >= 0 (rpm)");
    bad = rq;
    bad.frequencies = std::vector<double>{};
    refused(bad, "frequencies = (none)");
}

TEST_CASE("request: the fluid study checks its model and fill levels in the library", "[request][fluid]") {
    const Scene n2 = load_scene(std::string(GYROKIT_DATA_DIR) + "/fluid_N2.toml");
    const FluidStudy one = fluid_study(n2, {});
    REQUIRE(one.critical);
    CHECK_FALSE(one.sweep);
    CHECK(one.unit.name == "rad/s");
    CHECK(one.critical->moving_undamped == fluid_critical_speeds(build_fluid_rotor(*n2.fluid())).moving_undamped);
    FluidRequest rq;
    rq.unit = "rpm";
    rq.fill = std::vector<double>{0.1, 0.3};
    const FluidStudy sweep = fluid_study(n2, rq);
    REQUIRE(sweep.sweep);
    CHECK(sweep.unit.name == "rpm");
    CHECK(sweep.sweep->fills.size() + static_cast<std::size_t>(sweep.sweep->skipped) == 2);
    const auto message = [](const Scene& sc, const FluidRequest& r) {
        try {
            fluid_study(sc, r);
        } catch (const InputError& e) {
            return e.message({});
        }
        return std::string();
    };
    rq.fill = std::vector<double>{0.0};
    CHECK(message(n2, rq).rfind("fill = R0 = 0: allowed: 0 < R0 < R", 0) == 0);
    rq.fill = std::vector<double>{n2.fluid()->R};
    CHECK(message(n2, rq).find("allowed: 0 < R0 < R") != std::string::npos);
    const Scene centrifuge = load_scene(std::string(GYROKIT_DATA_DIR) + "/centrifuge.toml");
    CHECK(message(centrifuge, {}).find("needs type = \"fluid_rotor\"") != std::string::npos);
}

TEST_CASE("request: the transient study takes its speeds in the study's unit and checks its run", "[request][transient]") {
    const Scene rpm = load_scene(std::string(GYROKIT_DATA_DIR) + "/three_disk_rotor.toml");
    const double pi = std::acos(-1.0);
    TransientRequest rq;
    rq.run_up = std::array<double, 2>{0.0, 6000.0};   // rpm: the scene's [speeds] units
    rq.acceleration = 3000.0;                        // rpm/s
    const TransientOptions o = transient_options(rpm, {}, rq);
    CHECK(o.unit.name == "rpm");
    CHECK(o.profile.to == Approx(200 * pi).epsilon(1e-15));
    CHECK(o.profile.acceleration == Approx(100 * pi).epsilon(1e-15));
    CHECK(o.outputs == transient_outputs(rpm.system));   // the node of the largest unbalance
    CHECK_FALSE(o.start_steady);
    CHECK(o.max_steps == defaults::max_steps);
    // The same run asked in rad/s: the same options.
    RotorRequest rad;
    rad.unit = "rad/s";
    TransientRequest same = rq;
    same.run_up = std::array<double, 2>{0.0, o.profile.to};
    same.acceleration = o.profile.acceleration;
    const TransientOptions r = transient_options(rpm, rad, same);
    CHECK(r.profile.to == o.profile.to);
    CHECK(r.profile.acceleration == o.profile.acceleration);
    TransientRequest node = rq;
    node.node = 12;
    CHECK(transient_options(rpm, {}, node).outputs == rpm.system.node_translations(12));

    const auto refused = [&](TransientRequest t, const std::string& start) {
        try {
            transient_options(rpm, {}, t);
            FAIL("accepted");
        } catch (const InputError& e) {
            INFO(e.message({}));
            CHECK(e.message({}).rfind(start, 0) == 0);
        }
    };
    refused({}, "no speed: allowed: speed (a constant speed), or run_up (from, to) with acceleration");
    TransientRequest bad = rq;
    bad.speed = 600.0;
    refused(bad, "speed and run_up: allowed: one of them");
    bad = rq;
    bad.acceleration.reset();
    refused(bad, "run_up needs acceleration (rpm/s; > 0 for a run-up");
    bad = rq;
    bad.acceleration = -5.0;
    refused(bad, "acceleration = -5 rpm/s with a run-up from 0 to 6000 rpm: allowed: a finite number > 0");
    bad = rq;
    bad.run_up = std::array<double, 2>{100.0, 100.0};
    refused(bad, "run_up = 100:100 rpm: allowed: two different finite speeds >= 0");
    bad = rq;
    bad.dt = 0.0;
    refused(bad, "dt = 0 s: allowed: a finite time step > 0 (s)");
    bad = rq;
    bad.start = "hot";
    refused(bad, "start = 'hot': allowed: rest, steady");
    bad = rq;
    bad.node = 99;
    refused(bad, "node = 99: node 99 does not exist");
    bad = rq;
    bad.node = 12;
    bad.dofs = {"x12"};
    refused(bad, "dofs and node: allowed: one of them");
    bad = rq;
    bad.max_steps = 0;
    refused(bad, "max_steps = 0: allowed: 1 to");
    TransientRequest constant;
    constant.speed = 0.0;   // exerts no force
    refused(constant, "speed = 0 rpm: allowed: a finite speed > 0 (rpm)");
}

TEST_CASE("request: the balancer and Sommerfeld studies check their runs in the library", "[request][balancer]") {
    const BalancerScene table1 = load_balancer_scene(std::string(GYROKIT_DATA_DIR) + "/balancer_table1.toml");
    const BalancerStudy states = balancer_study(table1, {});
    CHECK(states.tables.size() == 2);
    CHECK(states.verdicts.size() == range_verdicts(state_stability_ranges(table1.params)).size());
    const auto refused = [](auto study, const std::string& start) {
        try {
            study();
            FAIL("accepted");
        } catch (const InputError& e) {
            INFO(e.message({}));
            CHECK(e.message({}).rfind(start, 0) == 0);
        }
    };
    BalancerRequest b;
    b.speed = 40.0;
    refused([&] { balancer_plan(table1, b); }, "averaged, speed, duration, integrator, abs_tol and rel_tol need simulate");
    b.simulate = true;
    b.speed = -1.0;
    refused([&] { balancer_plan(table1, b); }, "speed = -1: allowed: a finite number > 0 (rad/s)");
    const BalancerScene bild7 = load_balancer_scene(std::string(GYROKIT_DATA_DIR) + "/balancer_bild7.toml");
    b.speed.reset();
    b.integrator = "euler";
    refused([&] { balancer_plan(bild7, b); }, "integrator = 'euler': allowed: rk2, rk4");
    b.integrator.reset();
    b.abs_tol = 2.0;
    refused([&] { balancer_plan(bild7, b); }, "abs_tol = 2 / rel_tol = ");
    b.abs_tol.reset();
    b.duration = 0.0;
    refused([&] { balancer_plan(bild7, b); }, "duration = 0: allowed: a finite number > 0 (s)");

    const BalancerScene rotor = load_balancer_scene(std::string(GYROKIT_DATA_DIR) + "/sommerfeld_rotor.toml");
    SommerfeldRequest s;
    s.speeds = SpeedRange{0.0, 400.0, 5};
    const SommerfeldStudy curves = sommerfeld_study(rotor, s);
    CHECK(curves.tables.size() == 3);
    CHECK(curves.speeds.count == 5);
    s.max_speed = 100.0;
    refused([&] { sommerfeld_plan(rotor, s); }, "integrator, abs_tol, rel_tol and max_speed need runup");
    s.runup = true;
    refused([&] { sommerfeld_plan(rotor, s); }, "speeds sets the stationary curves; not with runup");
    s.speeds.reset();
    s.max_speed = -3.0;
    if (rotor.has_runup) refused([&] { sommerfeld_plan(rotor, s); }, "max_speed = -3: allowed: a finite number > 0");
    SommerfeldRequest bad;
    bad.speeds = SpeedRange{10.0, 5.0, 3};
    refused([&] { sommerfeld_plan(rotor, bad); }, "speeds: FROM = 10 is greater than TO = 5");
}

TEST_CASE("request: DOFs given one by one are checked one by one", "[request][errors]") {
    const std::vector<std::string> names = {"x0", "y0", "x1"};
    CHECK(dofs_by_name(std::vector<std::string>{"y0", "x1"}, names, "dofs") == std::vector<int>{1, 2});
    CHECK(dofs_by_name(std::vector<std::string>{}, names, "dofs").empty());
    for (const auto& bad : {std::vector<std::string>{""}, std::vector<std::string>{"x0,y0"},
                            std::vector<std::string>{"x0", ""}, std::vector<std::string>{"x0", "x0"}}) {
        CAPTURE(bad);
        CHECK_THROWS_AS(dofs_by_name(bad, names, "dofs"), InputError);
    }
}
