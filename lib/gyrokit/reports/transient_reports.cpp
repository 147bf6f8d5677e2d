#include <gyrokit/reports/transient_reports.hpp>

#include <gyrokit/core/constants.hpp>
#include <gyrokit/reports/detail/cells.hpp>

#include <gyrokit/analysis/unbalance_response.hpp>
#include <gyrokit/core/error.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace gyrokit {

namespace {

const char* const kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};

std::string colour(std::size_t k) { return kColours[k % (sizeof(kColours) / sizeof(kColours[0]))]; }

std::string with_unit(const std::string& what, const std::string& unit) {
    return unit.empty() ? what : what + " [" + unit + "]";
}

}  // namespace

Table transient_table(const std::vector<std::string>& names, const std::vector<std::string>& units,
                      const TransientEnvelope& e, const Eigen::MatrixXd& steady, const SpeedUnit& u) {
    Table t({"time_s", u.column("speed"), "revolution", "dof", "unit", "peak", "steady"});
    t.key = "transient";
    for (Eigen::Index i = 0; i < e.peak.rows(); ++i)
        for (std::size_t k = 0; k < e.dofs.size(); ++k) {
            const auto col = static_cast<Eigen::Index>(k);
            t.add_row({e.t(i, col), u.factor * e.speed(i, col), e.revolution(i, col),
                       names[static_cast<std::size_t>(e.dofs[k])], detail::unit_of(units, e.dofs[k]), e.peak(i, col),
                       steady(i, col)});
        }
    return t;
}

Table transient_history_table(const std::vector<std::string>& names, const TransientResult& r, const SpeedUnit& u) {
    std::vector<std::string> columns = {"time_s", u.column("speed")};
    for (const int k : r.dofs) columns.push_back(names[static_cast<std::size_t>(k)]);
    Table t(columns);
    t.key = "history";
    for (std::size_t n = 0; n < r.t.size(); ++n) {
        std::vector<Cell> row = {r.t[n], u.factor * r.speed[n]};
        for (Eigen::Index k = 0; k < r.z.cols(); ++k) row.emplace_back(r.z(static_cast<Eigen::Index>(n), k));
        t.add_row(std::move(row));
    }
    return t;
}

Figure transient_orbit_figure(const std::vector<std::string>& names, const std::vector<std::string>& units,
                              const TransientResult& r, int cx, int cy, std::complex<double> Zx,
                              std::complex<double> Zy, const std::string& title) {
    const int dx = r.dofs[static_cast<std::size_t>(cx)], dy = r.dofs[static_cast<std::size_t>(cy)];
    Panel p{with_unit(names[static_cast<std::size_t>(dx)], detail::unit_of(units, dx)),
            with_unit(names[static_cast<std::size_t>(dy)], detail::unit_of(units, dy)), "", false, {}, {}, {}, {}, {}};
    p.equal_axes = true;
    Series run;
    run.label = fmt::format("transient, {:.4g} s", r.t.empty() ? 0.0 : r.t.back());
    run.color = colour(0);
    const std::size_t stride = std::max<std::size_t>(1, r.t.size() / 20000);
    for (std::size_t n = 0; n < r.t.size(); n += stride) {
        run.x.push_back(r.z(static_cast<Eigen::Index>(n), cx));
        run.y.push_back(r.z(static_cast<Eigen::Index>(n), cy));
    }
    Series steady;
    steady.label = "steady unbalance response";
    steady.style = "dashed";
    steady.color = "#000000";
    for (int i = 0; i <= 180; ++i) {
        const std::complex<double> turn = std::polar(1.0, 2.0 * kPi * i / 180.0);
        steady.x.push_back((Zx * turn).real());
        steady.y.push_back((Zy * turn).real());
    }
    p.series = {std::move(run), std::move(steady)};
    Figure f;
    f.title = title;
    f.height_per_panel = 760;
    f.panels.push_back(std::move(p));
    return f;
}

Figure transient_runup_figure(const std::vector<std::string>& names, const std::vector<std::string>& units,
                              const TransientEnvelope& e, const std::vector<double>& speeds,
                              const Eigen::MatrixXd& steady, const SpeedUnit& u, const std::string& title) {
    Figure f;
    f.title = title;
    for (const std::string& unit : detail::units_in(units, e.dofs)) {
        Panel p{detail::speed_label(u), with_unit("amplitude", unit), "", false, {}, 0.0, {}, {}, {}};
        for (std::size_t k = 0; k < e.dofs.size(); ++k) {
            if (detail::unit_of(units, e.dofs[k]) != unit) continue;
            const std::string name = names[static_cast<std::size_t>(e.dofs[k])];
            Series run, ss;
            run.label = name + " run (peak per window)";
            ss.label = name + " steady response";
            run.color = ss.color = colour(k);
            ss.style = "thin";
            for (Eigen::Index i = 0; i < e.peak.rows(); ++i) {
                run.x.push_back(u.factor * e.speed(i, static_cast<Eigen::Index>(k)));
                run.y.push_back(e.peak(i, static_cast<Eigen::Index>(k)));
            }
            for (std::size_t i = 0; i < speeds.size(); ++i) {
                ss.x.push_back(u.factor * speeds[i]);
                ss.y.push_back(steady(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)));
            }
            p.series.push_back(std::move(run));
            p.series.push_back(std::move(ss));
        }
        f.panels.push_back(std::move(p));
    }
    return f;
}

Figure waterfall_figure(const std::vector<std::string>& names, const std::vector<std::string>& units,
                        const std::vector<Waterfall>& ws, const SpeedUnit& u, bool by_speed,
                        const std::string& title) {
    Figure f;
    f.title = title;
    f.height_per_panel = 560;
    for (const Waterfall& w : ws) {
        const std::size_t n = w.t.size();
        std::vector<double> base(n);
        for (std::size_t i = 0; i < n; ++i) base[i] = by_speed ? u.factor * w.speed[i] : w.t[i];
        const double spacing = n > 1 ? std::abs(base.back() - base.front()) / static_cast<double>(n - 1) : 1.0;
        const double top = w.amplitude.size() ? w.amplitude.maxCoeff() : 0.0;
        const double scale = top > 0.0 ? 3.0 * spacing / top : 0.0;
        const std::string unit = detail::unit_of(units, w.dof);
        Panel p{"frequency [" + u.name + "]", by_speed ? detail::speed_label(u) : "time [s]",
                fmt::format("{}: spectra of {} windows of {:.3g} s; a spacing = {:.3g}{}", names[static_cast<std::size_t>(w.dof)],
                            n, w.window, spacing / (scale > 0.0 ? scale : 1.0), unit.empty() ? "" : " " + unit),
                false, {}, {}, {}, {}, {}};
        for (std::size_t i = n; i-- > 0;) {   // the latest window first, drawn below the earlier ones
            Series s;
            s.color = "#1f3a93";
            for (std::size_t j = 0; j < w.frequencies.size(); ++j) {
                s.x.push_back(u.factor * w.frequencies[j]);
                s.y.push_back(base[i] + scale * w.amplitude(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)));
            }
            p.series.push_back(std::move(s));
        }
        Series once;
        once.label = "1x";
        once.style = "dashed";
        once.color = "#d62728";
        for (std::size_t i = 0; i < n; ++i) {
            once.x.push_back(u.factor * w.speed[i]);
            once.y.push_back(base[i]);
        }
        p.series.push_back(std::move(once));
        f.panels.push_back(std::move(p));
    }
    return f;
}


std::string transient_description(const SpeedProfile& p, const SpeedUnit& u, bool steady_start) {
    const std::string from = steady_start ? "from its steady state" : "from rest";
    if (p.acceleration == 0.0) return fmt::format("at {:.6g} {} {}", u.factor * p.from, u.name, from);
    return fmt::format("{} {:.6g} to {:.6g} {} at {:.6g} {} {}", p.to > p.from ? "run-up" : "run-down",
                       u.factor * p.from, u.factor * p.to, u.name, u.factor * p.acceleration, u.per_second(), from);
}

namespace {

// The run as the scene states lengths: the recorded columns in m scaled to `length`
// (`factor` per column), the DOF units renamed.
struct ShownRun {
    TransientResult run;
    std::vector<std::string> units;
    Eigen::VectorXd factor;
};

ShownRun shown(const GyroscopicSystem& sys, const TransientResult& r, const LengthUnit& length) {
    ShownRun out{r, length.display_units(sys.dofs.units), Eigen::VectorXd::Ones(static_cast<Eigen::Index>(r.dofs.size()))};
    if (sys.dofs.units.empty()) return out;
    for (std::size_t k = 0; k < r.dofs.size(); ++k) {
        const double f = length.display_factor(sys.dofs.units.at(static_cast<std::size_t>(r.dofs[k])));
        out.factor(static_cast<Eigen::Index>(k)) = f;
        if (f != 1.0) out.run.z.col(static_cast<Eigen::Index>(k)) *= f;
    }
    return out;
}

}  // namespace

Table transient_run_table(const GyroscopicSystem& sys, const TransientResult& r, const SpeedUnit& u, bool steady_start,
                          SolverKind kind, const LengthUnit& length) {
    const ShownRun s = shown(sys, r, length);
    const TransientEnvelope e = transient_envelope(s.run, kTransientTableWindows);
    const Eigen::MatrixXd steady = envelope_steady(sys, e, kind) * s.factor.asDiagonal();
    Table t = transient_table(sys.dofs.names, s.units, e, steady, u);
    t.title = fmt::format("transient unbalance response {}: peak |z| over the whole revolutions of each 1/{} of the "
                          "run, where it occurred; steady: the steady response at that speed",
                          transient_description(r.profile, u, steady_start), kTransientTableWindows);
    return t;
}

Figure transient_figure(const GyroscopicSystem& sys, const TransientResult& run, const SpeedUnit& u,
                        bool steady_start, SolverKind kind, const LengthUnit& length) {
    const ShownRun s = shown(sys, run, length);
    const TransientResult& r = s.run;
    const std::string what = transient_description(r.profile, u, steady_start);
    if (r.profile.acceleration == 0.0) {
        if (r.dofs.size() < 2)
            throw InputError(fmt::format("the orbit of a run at a constant speed needs two recorded DOFs, {} given; "
                                         "allowed: a node, or two DOFs",
                                         r.dofs.size()));
        const Eigen::VectorXcd Z = unbalance_response(sys, r.profile.from, kind);
        return transient_orbit_figure(sys.dofs.names, s.units, r, 0, 1, s.factor(0) * Z(r.dofs[0]),
                                      s.factor(1) * Z(r.dofs[1]), "Orbit " + what);
    }
    std::vector<double> speeds;
    const double lo = std::min(r.profile.from, r.profile.to), hi = r.profile.top();
    for (int i = 0; i <= 1000; ++i) speeds.push_back(lo + (hi - lo) * i / 1000.0);
    const TransientEnvelope fine = transient_envelope(r, 400);
    const Eigen::MatrixXd steady = steady_amplitudes(sys, speeds, r.dofs, kind) * s.factor.asDiagonal();
    return transient_runup_figure(sys.dofs.names, s.units, fine, speeds, steady, u, "Unbalance response, " + what);
}

Figure transient_waterfall_figure(const GyroscopicSystem& sys, const TransientResult& run, const SpeedUnit& u,
                                  bool steady_start, const LengthUnit& length) {
    const ShownRun s = shown(sys, run, length);
    const TransientResult& r = s.run;
    std::vector<Waterfall> ws;
    for (int k = 0; k < std::min<int>(2, static_cast<int>(r.dofs.size())); ++k) ws.push_back(transient_waterfall(r, k));
    return waterfall_figure(sys.dofs.names, s.units, ws, u, r.profile.acceleration != 0.0,
                            "Waterfall, " + transient_description(r.profile, u, steady_start));
}

}  // namespace gyrokit
