// gyrokit-bench-tradeoffs: the rows of speeds. Critical speeds from grid
// crossings and refined roots (area "critical"), the Campbell tracking step
// (area "campbell"), and the truncation of the liquid-filled rotor's series
// (area "fluid").
#include "models.hpp"
#include "tradeoffs.hpp"

#include <gyrokit/analysis/campbell.hpp>
#include <gyrokit/analysis/critical_speeds.hpp>
#include <gyrokit/scene/scene.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <fmt/format.h>
#include <limits>
#include <string>
#include <utility>
#include <vector>

using namespace gyrokit;
using namespace gyrokit::bench;

namespace tradeoffs {

namespace {

// Crossings of Im lambda = k w read off the branch points by linear interpolation.
std::vector<double> grid_crossings(const CampbellDiagram& cd, int k) {
    std::vector<double> out;
    for (const Branch& b : cd.branches)
        for (size_t i = 0; i + 1 < b.points.size(); ++i) {
            const BranchPoint &p0 = b.points[i], &p1 = b.points[i + 1];
            if (p0.mode.whirl == Whirl::Real || p1.mode.whirl == Whirl::Real) continue;
            const double g0 = p0.mode.lambda.imag() - k * p0.speed, g1 = p1.mode.lambda.imag() - k * p1.speed;
            if (g0 == 0.0 && i > 0) continue;
            if ((g0 > 0) == (g1 > 0) && g0 != 0.0 && g1 != 0.0) continue;
            out.push_back(p0.speed + (p1.speed - p0.speed) * g0 / (g0 - g1));
        }
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<double> speeds_of(const std::vector<CriticalSpeed>& cs) {
    std::vector<double> w;
    for (const auto& c : cs) w.push_back(c.speed);
    return w;
}

// Largest relative distance of each speed to the nearest one of the other list, both ways.
double speed_list_error(const std::vector<double>& w, const std::vector<double>& ref) {
    if (w.empty() || ref.empty()) return w.size() == ref.size() ? 0.0 : std::numeric_limits<double>::infinity();
    const auto one_way = [](const std::vector<double>& a, const std::vector<double>& b, bool a_is_ref) {
        double worst = 0.0;
        for (double x : a) {
            double nearest = b.front();
            for (double y : b)
                if (std::fabs(y - x) < std::fabs(nearest - x)) nearest = y;
            worst = std::max(worst, std::fabs(x - nearest) / std::fabs(a_is_ref ? x : nearest));
        }
        return worst;
    };
    return std::max(one_way(w, ref, false), one_way(ref, w, true));
}

struct SpeedCase {
    std::string name;
    GyroscopicSystem sys;
    double from, to;
    int modes;   // branches kept (CampbellOptions::modes)
};

// The point of a branch at speed w (nullptr if the branch has none there).
const BranchPoint* point_at(const Branch& b, double w) {
    for (const BranchPoint& p : b.points)
        if (std::fabs(p.speed - w) <= 1e-9 * std::max(1.0, std::fabs(w))) return &p;
    return nullptr;
}

// lambda of a branch at w by linear interpolation between its points.
std::complex<double> interpolate(const Branch& b, double w) {
    const auto& p = b.points;
    if (w <= p.front().speed) return p.front().mode.lambda;
    for (size_t i = 0; i + 1 < p.size(); ++i)
        if (w <= p[i + 1].speed) {
            const double u = (w - p[i].speed) / (p[i + 1].speed - p[i].speed);
            return (1.0 - u) * p[i].mode.lambda + u * p[i + 1].mode.lambda;
        }
    return p.back().mode.lambda;
}

}  // namespace

// ---------------------------------------------------------------------------
// 2. Critical speeds: grid crossings vs refined roots

void critical_rows(Table& t, const Settings& s) {
    std::vector<SpeedCase> cases;
    cases.push_back({"centrifuge (6 DOFs)", load_scene(std::string(GYROKIT_DATA_DIR) + "/centrifuge.toml").system,
                     0.0, 60.0, 6});
    cases.push_back({"FE rotor, undamped (52 DOFs)", fe_machine(12, false).assemble().to_system(), 0.0, 3000.0, 8});
    const std::vector<int> counts = s.quick ? std::vector<int>{4, 13, 61} : std::vector<int>{4, 7, 13, 25, 61, 241};
    for (const SpeedCase& c : cases) {
        CampbellOptions opt;
        opt.modes = c.modes;
        std::vector<double> ref;
        std::string reference;
        if (c.sys.has_damping()) {
            const int fine = s.quick ? 241 : 961;
            ref = speeds_of(critical_speeds(c.sys, campbell(c.sys, linspace(c.from, c.to, fine), opt), {1}));
            reference = fmt::format("Brent (1e-13) on {} speeds", fine);
        } else {
            ref = speeds_of(critical_speeds_direct(c.sys, 1, c.from, c.to));
            // Independent of tracking and root finding: the eigenvalues w^2 of a Hermitian pencil (the
            // range holds only crossings of the tracked branches). The library's refined result on a
            // fine grid is shown beside it.
            const int check = s.quick ? 61 : 241;
            const std::vector<double> tracked =
                speeds_of(critical_speeds(c.sys, campbell(c.sys, linspace(c.from, c.to, check), opt), {1}));
            reference = fmt::format("direct Hermitian pencil in w^2 (Brent on {} speeds: {})", check,
                                    sci(speed_list_error(tracked, ref)));
        }
        const std::string model = fmt::format("{}, {}..{} rad/s, {} crit.", c.name, c.from, c.to, ref.size());
        for (int n : counts) {
            const std::vector<double> grid = linspace(c.from, c.to, n);
            CampbellDiagram cd;
            const double t_cd = s.time([&] { cd = campbell(c.sys, grid, opt); });
            std::vector<CriticalSpeed> refined;
            const double t_ref = s.time([&] { refined = critical_speeds(c.sys, cd, {1}); });
            const std::vector<double> lin = grid_crossings(cd, 1);
            const std::string note = fmt::format("{} inserted speeds", cd.inserted_speeds);
            add(t, {"critical", model, "speed grid", fmt::format("{} speeds, linear interpolation", n), t_cd,
                    speed_list_error(lin, ref), "rel. critical speed", reference,
                    fmt::format("{} found; {}", lin.size(), note)});
            add(t, {"critical", model, "speed grid", fmt::format("{} speeds + Brent refinement", n), t_cd + t_ref,
                    speed_list_error(speeds_of(refined), ref), "rel. critical speed", reference,
                    fmt::format("{} found; {}", refined.size(), note)});
        }
    }
}

// ---------------------------------------------------------------------------
// 3. Campbell tracking step

void campbell_rows(Table& t, const Settings& s) {
    std::vector<SpeedCase> cases;
    // The centrifuge beyond its scene's range (0..60 rad/s), where coarse steps skip over crossings.
    cases.push_back({"centrifuge (6 DOFs)", load_scene(std::string(GYROKIT_DATA_DIR) + "/centrifuge.toml").system,
                     0.0, 300.0, 6});
    cases.push_back({"FE rotor, damped (52 DOFs)", fe_machine(12, true).assemble().to_system(), 0.0, 4000.0, 8});
    // Every coarse grid speed is a fine one: 480 = 3 * 160 = 10 * 48 = 40 * 12 = 160 * 3, 120 = 3 * 40 = 10 * 12.
    const int fine = s.quick ? 121 : 481;
    const std::vector<int> counts = s.quick ? std::vector<int>{4, 11, 41} : std::vector<int>{4, 11, 41, 161};
    for (const SpeedCase& c : cases) {
        CampbellOptions opt;
        opt.modes = c.modes;
        const std::vector<double> fine_grid = linspace(c.from, c.to, fine);
        const CampbellDiagram ref = campbell(c.sys, fine_grid, opt);
        const std::string reference =
            fmt::format("tracking on {} speeds ({} inserted, {} ambiguous)", fine, ref.inserted_speeds,
                        ref.ambiguous_steps);
        const std::string model = fmt::format("{}, {}..{} rad/s, {} branches", c.name, c.from, c.to, c.modes);
        for (int n : counts)
            for (int max_refine : {8, 0}) {
                if (max_refine == 0 && (n == 4 || n == 161)) continue;
                CampbellOptions o = opt;
                o.max_refine = max_refine;
                const std::vector<double> grid = linspace(c.from, c.to, n);
                CampbellDiagram cd;
                const double sec = s.time([&] { cd = campbell(c.sys, grid, o); });
                // Mis-connection: a grid point of coarse branch b that is not the reference's branch b there.
                int wrong = 0, points = 0;
                double err = 0.0;
                for (size_t b = 0; b < cd.branches.size() && b < ref.branches.size(); ++b) {
                    for (double w : grid) {
                        const BranchPoint* p = point_at(cd.branches[b], w);
                        const BranchPoint* q = point_at(ref.branches[b], w);
                        if (!p && !q) continue;
                        ++points;
                        if (!p || !q || std::abs(p->mode.lambda - q->mode.lambda) > 1e-8 * std::abs(q->mode.lambda))
                            ++wrong;
                    }
                    // The coarse branch drawn as a polyline, read at the fine speeds.
                    for (const BranchPoint& q : ref.branches[b].points) {
                        const double f = interpolate(cd.branches[b], q.speed).imag(), f_ref = q.mode.lambda.imag();
                        err = std::max(err, std::fabs(f - f_ref) / std::abs(q.mode.lambda));
                    }
                }
                std::string note = fmt::format("mis-connected {}/{} grid points; {} inserted, {} ambiguous", wrong,
                                               points, cd.inserted_speeds, cd.ambiguous_steps);
                if (wrong > 0 && cd.ambiguous_steps == 0) note += "; not flagged";
                add(t, {"campbell", model, "tracking step",
                        fmt::format("{} speeds, max_refine {}{}", n, max_refine, max_refine == 8 ? " (default)" : ""),
                        sec, err, fmt::format("rel. branch frequency ({} speeds)", fine), reference, note});
            }
    }
}

// ---------------------------------------------------------------------------
// 5. Liquid-filled rotor truncation

void fluid_rows(Table& t, const Settings& s) {
    // (sloshing modes, J* terms); 0, 0 is the default: modes until the tolerance 1e-10, 100 J* terms plus the tail.
    const std::vector<std::pair<int, int>> settings =
        s.quick ? std::vector<std::pair<int, int>>{{5, 10}, {0, 0}}
                : std::vector<std::pair<int, int>>{{1, 10}, {5, 10},   {10, 10},  {30, 10}, {100, 3},
                                                   {100, 10}, {100, 100}, {100, 1000}, {0, 0}};
    for (int N : {2, 4}) {
        const std::vector<double> w_ref = fluid_undamped_speeds(fluid_reference_case(N));
        for (const auto& [modes, nj] : settings) {
            FluidRotorParameters p = fluid_table_case(N);
            p.modes = modes;
            p.jstar_terms = nj;
            std::vector<double> w;
            const double sec = s.time([&] { w = fluid_undamped_speeds(p); });
            const FluidRotor f = build_fluid_rotor(p);
            const std::string setting =
                modes == 0 ? "to tol 1e-10 / auto (default)" : fmt::format("{} / {}", modes, nj);
            add(t, {"fluid", fmt::format("Tabelle 2 case N{}", N), "sloshing modes / J* terms", setting, sec,
                    max_rel_deviation(w, w_ref), "rel. critical speed", "400 modes, 20000 J* terms",
                    fmt::format("{} modes, {} J* terms used", f.liquid.modes.size(), f.liquid.jstar_terms)});
        }
    }
}

}  // namespace tradeoffs
