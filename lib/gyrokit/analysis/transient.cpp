#include <gyrokit/analysis/transient.hpp>

#include <gyrokit/analysis/campbell.hpp>
#include <gyrokit/analysis/unbalance_response.hpp>
#include <gyrokit/core/constants.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/core/interrupt.hpp>

#include <Eigen/SparseLU>
#include <cmath>
#include <optional>
#include <fmt/format.h>

namespace gyrokit {

double SpeedProfile::ramp_end() const { return acceleration == 0.0 ? 0.0 : (to - from) / acceleration; }

double SpeedProfile::speed(double t) const { return t < ramp_end() ? from + acceleration * t : to; }

double SpeedProfile::angle(double t) const {
    const double te = ramp_end();
    if (t <= te) return from * t + 0.5 * acceleration * t * t;
    return from * te + 0.5 * acceleration * te * te + to * (t - te);
}

double SpeedProfile::angular_acceleration(double t) const { return t < ramp_end() ? acceleration : 0.0; }

void SpeedProfile::validate(const SpeedUnit& u) const {
    const double f = u.factor;   // speeds named to 12 digits: as given, not the last bit of a conversion
    const std::string& n = u.name;
    if (acceleration == 0.0) {
        if (!(std::isfinite(from) && from > 0.0 && to == from))
            throw InputError(fmt::format("{} {:.12g} {}: allowed: a finite speed > 0 ({}); at 0 the unbalance "
                                         "exerts no force",
                                         option_field("speed"), from * f, n, n));
        return;
    }
    if (!(std::isfinite(from) && std::isfinite(to) && from >= 0.0 && to >= 0.0 && from != to))
        throw InputError(fmt::format("{} {:.12g}:{:.12g} {}: allowed: two different finite speeds >= 0 (from:to)",
                                     option_field("run_up"), from * f, to * f, n));
    if (!std::isfinite(acceleration) || (to - from) * acceleration < 0.0)
        throw InputError(fmt::format("{} {:.12g} {} with a {} from {:.12g} to {:.12g} {}: allowed: a finite number {} 0",
                                     option_field("acceleration"), acceleration * f, u.per_second(),
                                     to > from ? "run-up" : "run-down", from * f, to * f, n, to > from ? ">" : "<"));
}

Eigen::VectorXd unbalance_force_at(const Eigen::VectorXcd& u, const SpeedProfile& p, double t) {
    const double phi = p.angle(t), w = p.speed(t), acc = p.angular_acceleration(t);
    const double c = std::cos(phi), s = std::sin(phi);
    // Re(u (w^2 - i acc) (c + i s)) = Re(u) (w^2 c + acc s) - Im(u) (w^2 s - acc c).
    return u.real() * (w * w * c + acc * s) - u.imag() * (w * w * s - acc * c);
}

double transient_time_step(const SpeedProfile& p) {
    p.validate();
    return 2.0 * kPi / (kStepsPerPeriod * kBandMargin * p.top());
}

double steady_deviation(const GyroscopicSystem& sys, double w, double dt, const std::vector<int>& outputs,
                        SolverKind kind) {
    const Eigen::VectorXcd f = w * w * sys.unbalance;
    const Eigen::VectorXcd exact = dynamic_response(sys, w, w, f, kind);
    const Eigen::VectorXcd settled = dynamic_response(sys, w, 2.0 / dt * std::tan(0.5 * w * dt), f, kind);
    double largest = 0.0, deviation = 0.0;
    for (const int k : outputs) largest = std::max(largest, std::abs(exact(k)));
    for (const int k : outputs)
        if (std::abs(exact(k)) >= 1e-3 * largest && largest > 0.0)
            deviation = std::max(deviation, std::abs(std::abs(settled(k)) / std::abs(exact(k)) - 1.0));
    return deviation;
}

SteadyStep steady_time_step(const GyroscopicSystem& sys, const SpeedProfile& p, const std::vector<int>& outputs,
                            double duration, long long max_steps, SolverKind kind) {
    SteadyStep s;
    s.dt = transient_time_step(p);
    if (p.acceleration != 0.0) return s;   // a run-up settles on nothing
    const double w = p.from, target = 0.5 * kSteadyDeviation;
    // Never below 1/16 of the band's step, nor so short that the run would exceed max_steps.
    const double floor = std::min(s.dt, std::max(kSteadyStepFloor * s.dt, duration / static_cast<double>(max_steps)));
    s.deviation = steady_deviation(sys, w, s.dt, outputs, kind);
    // The deviation goes as dt^2 (as dt^4 at a resonance's peak, where |Z| is flat): the step
    // scaled for dt^2, at most 8 tries, each checked by its own solve.
    for (int k = 0; k < 8 && s.deviation > target && s.dt > floor; ++k) {
        s.dt = std::max(floor, s.dt * std::min(0.7, std::sqrt(target / s.deviation) * 0.95));
        s.deviation = steady_deviation(sys, w, s.dt, outputs, kind);
    }
    return s;
}

// ---------------------------------------------------------------------------
// The integrator.

namespace {

bool present(const SparseMatrix& A) { return A.rows() > 0 && A.nonZeros() > 0; }

// Residual corrections with a factorization of S at another speed before S is refactored.
constexpr int kMaxCorrections = 2;
// A solve is accepted when ||S z - r|| <= kSolveTolerance (||S|| ||z|| + ||r||) ...
constexpr double kSolveTolerance = 1e-14;
// ... or, with S factored at this very speed, up to kSingularTolerance (beyond: singular).
constexpr double kSingularTolerance = 1e-8;

}  // namespace

struct NewmarkIntegrator::Impl {
    GyroscopicSystem sys;   // a copy: a temporary model is safe
    double dt, scale;
    bool dense, speed_dependent = false;
    double c0, c1, c2;   // 4/dt^2, 2/dt, 4/dt
    SparseMatrix M, G, N, K2;
    // The pencil at w_ref: the speed-dependent coefficients held from there.
    double w_ref = -1.0;
    SparseMatrix C_ref, K_ref;
    // S factored at w_fac.
    double w_fac = -1.0, norm_S = 0.0;
    Eigen::PartialPivLU<Eigen::MatrixXd> dlu;
    Eigen::SparseLU<SparseMatrix, Eigen::COLAMDOrdering<int>> slu;
    double t = 0.0;
    Eigen::VectorXd z, v, a;
    Stats stats;

    Impl(const GyroscopicSystem& s, double step, double speed_scale, SolverKind kind)
        : sys(s), dt(step), scale(speed_scale), dense(resolve_solver_kind(s.size(), kind) == SolverKind::Dense) {
        c0 = 4.0 / (dt * dt);
        c1 = 2.0 / dt;
        c2 = 4.0 / dt;
        M = s.M;
        if (present(s.G)) G = s.G;
        if (present(s.N)) N = s.N;
        if (present(s.K2)) K2 = s.K2;
        speed_dependent = !s.bearings.empty();
        for (const auto& d : s.damping) speed_dependent = speed_dependent || static_cast<bool>(d.of_speed);
    }

    void hold(double w) {
        const SparsePencil p = sys.sparse_at_speed(w);
        C_ref = p.C;
        K_ref = p.K;
        w_ref = w;
        ++stats.coefficient_updates;
    }
    Eigen::VectorXd C_times(double w, const Eigen::VectorXd& x) const {
        Eigen::VectorXd y = C_ref * x;
        if (G.rows()) y += (w - w_ref) * (G * x);
        return y;
    }
    Eigen::VectorXd K_times(double w, const Eigen::VectorXd& x) const {
        Eigen::VectorXd y = K_ref * x;
        if (N.rows()) y += (w - w_ref) * (N * x);
        if (K2.rows()) y += (w * w - w_ref * w_ref) * (K2 * x);
        return y;
    }
    Eigen::VectorXd S_times(double w, const Eigen::VectorXd& x) const {
        return c0 * (M * x) + c1 * C_times(w, x) + K_times(w, x);
    }
    void factor(double w);
    Eigen::VectorXd lu_solve(const Eigen::VectorXd& r) const {
        if (dense) return dlu.solve(r);
        return slu.solve(r);
    }
    Eigen::VectorXd solve(double w, const Eigen::VectorXd& r);
    double ratio(double w, const Eigen::VectorXd& x, const Eigen::VectorXd& r, Eigen::VectorXd& res) const {
        res = r - S_times(w, x);
        return res.norm() / (norm_S * x.norm() + r.norm());
    }
};

void NewmarkIntegrator::Impl::factor(double w) {
    SparseMatrix S = c0 * M + c1 * C_ref + K_ref;
    if (G.rows()) S += (c1 * (w - w_ref)) * G;
    if (N.rows()) S += (w - w_ref) * N;
    if (K2.rows()) S += (w * w - w_ref * w_ref) * K2;
    norm_S = S.norm();
    if (dense) {
        dlu.compute(Eigen::MatrixXd(S));
    } else {
        S.makeCompressed();
        slu.compute(S);
        if (slu.info() != Eigen::Success)
            throw SolverError(fmt::format("the Newmark effective matrix 4/dt^2 M + 2/dt C + K is singular at {} "
                                          "rad/s (dt {} s): a DOF without mass, damping and stiffness",
                                          w, dt));
    }
    w_fac = w;
    ++stats.factorizations;
}

Eigen::VectorXd NewmarkIntegrator::Impl::solve(double w, const Eigen::VectorXd& r) {
    if (w_fac < 0.0) factor(w);
    for (;;) {
        const bool exact = w == w_fac;   // S(w) itself is factored
        Eigen::VectorXd x = lu_solve(r), res;
        double q = ratio(w, x, r, res);
        int corrections = 0;
        while (!(q <= kSolveTolerance) && corrections < kMaxCorrections && std::isfinite(q)) {
            x += lu_solve(res);
            ++corrections;
            q = ratio(w, x, r, res);
        }
        if (q <= kSolveTolerance || (exact && q <= kSingularTolerance)) {
            stats.max_corrections = std::max(stats.max_corrections, corrections);
            stats.max_residual = std::max(stats.max_residual, q);
            return x;
        }
        if (exact)
            throw SolverError(fmt::format("the Newmark effective matrix 4/dt^2 M + 2/dt C + K is singular at {} "
                                          "rad/s (dt {} s; residual {:.3g} of its norm)",
                                          w, dt, q));
        factor(w);   // the factorization is too far from S(w): refactor here
    }
}

NewmarkIntegrator::NewmarkIntegrator(const GyroscopicSystem& sys, double dt, double speed_scale, SolverKind kind)
    : impl_(std::make_unique<Impl>(sys, dt, speed_scale, kind)) {
    if (!(std::isfinite(dt) && dt > 0.0))
        throw InputError(fmt::format("{} {} s: allowed: a finite time step > 0", option_field("dt"), dt));
}

NewmarkIntegrator::~NewmarkIntegrator() = default;

void NewmarkIntegrator::start(double t, double w, const Eigen::VectorXd& z, const Eigen::VectorXd& v,
                              const Eigen::VectorXd& f) {
    Impl& m = *impl_;
    const auto n = static_cast<Eigen::Index>(m.sys.size());
    if (z.size() != n || v.size() != n || f.size() != n)
        throw InputError(fmt::format("Newmark start: z, z' and f of sizes {}, {}, {}; allowed: {} (the model's DOFs)",
                                     z.size(), v.size(), f.size(), n));
    m.hold(w);
    m.factor(w);
    m.t = t;
    m.z = z;
    m.v = v;
    const Eigen::VectorXd rhs = f - m.C_times(w, v) - m.K_times(w, z);
    Eigen::VectorXd a;
    if (m.dense) {
        a = Eigen::MatrixXd(m.M).partialPivLu().solve(rhs);
    } else {
        Eigen::SparseLU<SparseMatrix, Eigen::COLAMDOrdering<int>> lu;
        lu.compute(m.M);
        if (lu.info() == Eigen::Success) a = lu.solve(rhs);
    }
    const double q = a.size() ? (m.M * a - rhs).norm() / (m.M.norm() * a.norm() + rhs.norm()) : INFINITY;
    if (!(q <= kSingularTolerance))
        throw SolverError("the mass matrix is singular: the initial acceleration M^-1 (f - C z' - K z) does not "
                          "exist; the Newmark method needs mass or inertia on every DOF");
    m.a = a;
}

void NewmarkIntegrator::step(double w, const Eigen::VectorXd& f) {
    Impl& m = *impl_;
    if (m.w_ref < 0.0) throw Error("NewmarkIntegrator::step before start");
    if (f.size() != m.z.size())
        throw InputError(fmt::format("Newmark step: a force of size {}; allowed: {} (the model's DOFs)", f.size(),
                                     m.z.size()));
    // Speed-dependent coefficients held within kCoefficientSpeedStep of the speed.
    if (m.speed_dependent &&
        std::abs(w - m.w_ref) > kCoefficientSpeedStep * std::max(std::abs(m.w_ref), 0.01 * m.scale)) {
        m.hold(w);
        m.factor(w);
    }
    // S z1 = f + M (c0 z + c2 v + a) + C(w) (c1 z + v); then a1 and v1 from the Newmark relations.
    const Eigen::VectorXd r = f + m.M * (m.c0 * m.z + m.c2 * m.v + m.a) + m.C_times(w, m.c1 * m.z + m.v);
    Eigen::VectorXd z1;
    if (r.allFinite()) z1 = m.solve(w, r);
    if (!z1.size() || !z1.allFinite())
        throw SolverError(fmt::format("the motion grew without bound at t = {:.6g} s, {:.6g} rad/s: the rotor is "
                                      "unstable there (gyrokit stability finds where)",
                                      m.t + m.dt, w));
    const Eigen::VectorXd a1 = m.c0 * (z1 - m.z) - m.c2 * m.v - m.a;
    m.v = m.c1 * (z1 - m.z) - m.v;
    m.z = z1;
    m.a = a1;
    m.t += m.dt;
    ++m.stats.steps;
}

double NewmarkIntegrator::time() const { return impl_->t; }
const Eigen::VectorXd& NewmarkIntegrator::z() const { return impl_->z; }
const Eigen::VectorXd& NewmarkIntegrator::v() const { return impl_->v; }
const Eigen::VectorXd& NewmarkIntegrator::a() const { return impl_->a; }
const NewmarkIntegrator::Stats& NewmarkIntegrator::stats() const { return impl_->stats; }

// ---------------------------------------------------------------------------
// A run under the unbalance.

std::vector<int> transient_outputs(const GyroscopicSystem& sys) {
    if (sys.unbalance.size() == 0) throw InputError("the model defines no unbalance load; the response is zero");
    Eigen::Index k = 0;
    sys.unbalance.cwiseAbs().maxCoeff(&k);
    const int dof = static_cast<int>(k);
    if (!sys.dofs.nodes.empty() && sys.dofs.nodes[static_cast<std::size_t>(dof)] >= 0) {
        const std::vector<int> d = sys.node_translations(sys.dofs.nodes[static_cast<std::size_t>(dof)]);
        if (!d.empty()) return d;
    }
    for (const auto& [x, y] : sys.whirl_pairs)
        if (x == dof || y == dof) return {x, y};
    return {dof};
}

namespace {

struct Plan {
    double duration = 0.0, dt = 0.0;
    long long steps = 0;
    std::optional<SteadyStep> steady;   // a constant-speed run's default step
    bool singular = false;              // no steady response at that speed (an undamped resonance)
};

// The duration, the time step and the step count, each checked against its range.
Plan plan_run(const GyroscopicSystem& sys, const TransientOptions& o, bool steady) {
    const SpeedProfile& p = o.profile;
    p.validate(o.unit);
    if (!(o.max_steps >= 1 && o.max_steps <= kTransientStepLimit))
        throw InputError(fmt::format("{} {}: allowed: 1 to {}", option_field("max_steps"), o.max_steps,
                                     kTransientStepLimit));
    Plan plan;
    const double top = p.top(), policy = transient_time_step(p), coarsest = 2.0 * kPi / (8.0 * top);
    plan.duration = o.duration != 0.0 ? o.duration : p.acceleration != 0.0 ? p.ramp_end() : 200.0 * kPi / p.from;
    if (!(std::isfinite(o.duration) && o.duration >= 0.0))
        throw InputError(fmt::format("{} {} s: allowed: a finite time > 0 (s); none: the ramp (a run-up) or 100 "
                                     "revolutions (constant speed)",
                                     option_field("duration"), o.duration));
    double dt = o.dt != 0.0 ? o.dt : policy;
    // The steady solves of a constant-speed run's default step: only for the run itself (the
    // checks before it need none: that step never exceeds max_steps).
    if (steady && o.dt == 0.0 && p.acceleration == 0.0 && std::isfinite(plan.duration) && plan.duration > 0.0) {
        try {
            plan.steady = steady_time_step(sys, p, o.outputs.empty() ? transient_outputs(sys) : o.outputs,
                                           plan.duration, o.max_steps, o.kind);
            dt = plan.steady->dt;
        } catch (const SolverError&) {
            plan.singular = true;   // the run goes on at the band's step; the note says why
        }
    }
    if (!(std::isfinite(o.dt) && o.dt >= 0.0 && dt <= coarsest))
        throw InputError(fmt::format("{} {} s: allowed: (0, {:.6g}] s, at least 8 steps per revolution at the top "
                                     "speed {:.6g} {}; none: {:.6g} s, {} steps per period of the excitation band{}",
                                     option_field("dt"), o.dt, coarsest, top * o.unit.factor, o.unit.name, policy,
                                     kStepsPerPeriod,
                                     p.acceleration == 0.0 ? ", shorter where the steady response needs it" : ""));
    if (dt > plan.duration)
        throw InputError(fmt::format("{} {} s is longer than the run ({} {} s); allowed: (0, {:.6g}] s",
                                     option_field("dt"), dt, option_field("duration"), plan.duration, plan.duration));
    const double steps = std::ceil(plan.duration / dt * (1.0 - 1e-12));
    if (steps > static_cast<double>(o.max_steps))
        throw InputError(fmt::format("{} {:.6g} s at {} {:.6g} s takes {} steps; allowed: at most {} {} (up to "
                                     "{}): shorten the run, lengthen the step or raise the limit",
                                     option_field("duration"), plan.duration, option_field("dt"), dt,
                                     // a count beyond 1e15 in its leading digits, not 300 of them
                                     steps < 1e15 ? fmt::format("{:.0f}", steps) : fmt::format("{:.3g}", steps),
                                     option_field("max_steps"), o.max_steps, kTransientStepLimit));
    plan.steps = static_cast<long long>(steps);
    plan.dt = plan.duration / steps;   // lands on the end of the run; never above the step asked for
    return plan;
}

// What a constant-speed run at the default step settles on, against the steady response.
std::string steady_note(const Plan& plan) {
    if (plan.singular)
        return "; no steady response at this speed (the dynamic stiffness is singular): the band's step";
    if (!plan.steady) return "";
    std::string note = fmt::format("; the amplitude it settles on (the response at (2/dt) tan(w dt/2)) within "
                                   "{:.2g} % of the steady response",
                                   100.0 * plan.steady->deviation);
    if (plan.steady->deviation > kSteadyDeviation)
        note += fmt::format(", above {:.2g} % at the shortest default step (1/{:.0f} of the band's, or {} over the "
                            "run): the response is that sensitive here; {} sets a shorter one",
                            100.0 * kSteadyDeviation, 1.0 / kSteadyStepFloor, option_field("max_steps"),
                            option_field("dt"));
    return note;
}

std::string step_note(const SpeedProfile& p, const Plan& plan, const SpeedUnit& u) {
    const double band = kBandMargin * p.top(), wdt = band * plan.dt;
    return fmt::format("Newmark average acceleration, {} steps of {:.4g} s over {:.6g} s: {:.1f} steps per period at "
                       "the band edge {:.6g} {} ({} x the top speed), {:.1f} per revolution at the top speed; "
                       "period error (w dt)^2/12 there {:.2g} %",
                       plan.steps, plan.dt, plan.duration, 2.0 * kPi / wdt, band * u.factor, u.name, kBandMargin,
                       2.0 * kPi / (p.top() * plan.dt), 100.0 * wdt * wdt / 12.0) +
           steady_note(plan);
}

// The initial state: at rest, or the steady response to the force at t = 0 held harmonic.
void initial_state(const GyroscopicSystem& sys, const TransientOptions& o, Eigen::VectorXd& z, Eigen::VectorXd& v) {
    z = v = Eigen::VectorXd::Zero(sys.size());
    const SpeedProfile& p = o.profile;
    if (!o.start_steady || p.from == 0.0) return;
    const std::complex<double> f(p.from * p.from, -p.angular_acceleration(0.0));
    const Eigen::VectorXcd Z = dynamic_response(sys, p.from, p.from, f * sys.unbalance, o.kind);
    z = Z.real();
    v = -p.from * Z.imag();
}

}  // namespace

void check_transient_options(const GyroscopicSystem& sys, const TransientOptions& o) {
    if (sys.unbalance.size() == 0) throw InputError("the model defines no unbalance load; the response is zero");
    check_dof_list(sys, o.outputs.empty() ? transient_outputs(sys) : o.outputs, "transient");
    plan_run(sys, o, false);
}

TransientResult transient_response(const GyroscopicSystem& sys, const TransientOptions& o) {
    TransientResult r;
    r.dofs = o.outputs.empty() ? transient_outputs(sys) : o.outputs;
    check_transient_options(sys, o);
    Plan plan = plan_run(sys, o, true);
    // The deviation at the step the run takes (landed on its end: a little shorter).
    if (plan.steady) {
        try {
            plan.steady->deviation =
                steady_deviation(sys, o.profile.from, plan.dt, r.dofs, o.kind);
        } catch (const SolverError&) {
            plan.singular = true;
        }
    }
    const SpeedProfile& p = o.profile;
    r.profile = p;
    r.dt = plan.dt;
    r.notes.push_back(step_note(p, plan, o.unit));
    for (const auto& n : extrapolation_notes(sys.bearings, std::min(p.from, p.to), p.top())) r.notes.push_back(n);

    Eigen::VectorXd z0, v0;
    initial_state(sys, o, z0, v0);
    NewmarkIntegrator integ(sys, plan.dt, p.top(), o.kind);
    integ.start(0.0, p.from, z0, v0, unbalance_force_at(sys.unbalance, p, 0.0));
    const auto rows = static_cast<Eigen::Index>(plan.steps + 1);
    r.t.resize(static_cast<std::size_t>(rows));
    r.speed.resize(static_cast<std::size_t>(rows));
    r.z.resize(rows, static_cast<Eigen::Index>(r.dofs.size()));
    const auto record = [&](long long n, double t) {
        r.t[static_cast<std::size_t>(n)] = t;
        r.speed[static_cast<std::size_t>(n)] = p.speed(t);
        for (std::size_t k = 0; k < r.dofs.size(); ++k)
            r.z(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(k)) = integ.z()(r.dofs[k]);
    };
    record(0, 0.0);
    for (long long n = 1; n <= plan.steps; ++n) {
        if ((n & 255) == 0) throw_if_interrupted();
        const double t = n == plan.steps ? plan.duration : static_cast<double>(n) * plan.dt;
        integ.step(p.speed(t), unbalance_force_at(sys.unbalance, p, t));
        record(n, t);
    }
    r.stats = integ.stats();
    if (r.stats.coefficient_updates > 1)
        r.notes.push_back(fmt::format("speed-dependent coefficients (bearing tables, fluid films, damping) evaluated "
                                      "{} times, each held over {:.2g} % of the speed",
                                      r.stats.coefficient_updates, 100.0 * kCoefficientSpeedStep));
    return r;
}

}  // namespace gyrokit
