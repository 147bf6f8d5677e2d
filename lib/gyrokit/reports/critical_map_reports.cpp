#include <gyrokit/reports/critical_map_reports.hpp>

#include <gyrokit/reports/detail/cells.hpp>

#include <fmt/format.h>
#include <cmath>
#include <limits>
#include <map>

namespace gyrokit {

using detail::ll;

Table critical_map_table(const CriticalSpeedMap& map, const SpeedUnit& u) {
    Table t({"stiffness_n_m", "whirl", "critical", u.column("speed"), "backward_error"});
    t.key = "critical_map";
    t.title = "undamped critical speeds against bearing stiffness (inf: rigid supports)";
    for (const auto* list : {&map.points, &map.rigid})
        for (const MapPoint& p : *list)
            t.add_row({p.stiffness, p.whirl, ll(p.number), u.factor * p.speed, p.backward_error});
    return t;
}

Table bearing_curve_table(const CriticalSpeedMap& map, const SpeedUnit& u) {
    Table t({"curve", u.column("speed"), "stiffness_n_m"});
    t.key = "bearing_curves";
    t.title = "the bearings' own stiffness over speed";
    for (const BearingCurve& c : map.bearings)
        for (std::size_t i = 0; i < c.speed.size(); ++i) t.add_row({c.name, u.factor * c.speed[i], c.stiffness[i]});
    return t;
}

Figure critical_map_figure(const CriticalSpeedMap& map, const SpeedUnit& u, const std::string& title) {
    Figure f;
    f.title = title.empty() ? "critical speed map" : title;
    f.height_per_panel = 560;
    Panel p;
    p.xlabel = "bearing stiffness [N/m]";
    p.ylabel = "critical speed [" + u.name + "]";
    p.title = "undamped critical speed map (forward solid, backward dashed, rigid supports dotted)";
    p.logx = p.logy = true;
    const char* colors[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};
    std::map<std::pair<std::string, int>, Series> lines;
    for (const MapPoint& q : map.points) {
        Series& s = lines[{q.whirl, q.number}];
        if (s.x.empty()) {
            s.label = fmt::format("{} {}", q.whirl, q.number);
            s.style = q.whirl == "forward" ? "lines" : "dashed";
            s.color = colors[(q.number - 1) % 6];
        }
        s.x.push_back(q.stiffness);
        s.y.push_back(u.factor * q.speed);
    }
    for (auto& [key, s] : lines) p.series.push_back(std::move(s));
    const double k0 = map.stiffness.front(), k1 = map.stiffness.back();
    for (const MapPoint& q : map.rigid)
        if (q.whirl == "forward")
            p.series.push_back({{k0, k1}, {u.factor * q.speed, u.factor * q.speed},
                                q.number == 1 ? "rigid supports (forward)" : "", "dotted", "#7f7f7f"});
    // The log speed axis has no 0: a constant bearing's line (from speed 0) starts a
    // decade below the lowest critical speed of the map.
    double low = std::numeric_limits<double>::infinity();
    for (const MapPoint& q : map.points)
        if (q.speed > 0) low = std::min(low, u.factor * q.speed);
    const double floor = std::isfinite(low) ? low / 10 : 1.0;
    for (const BearingCurve& c : map.bearings) {
        // kxx solid, kyy dashed: the two directions of one bearing apart.
        Series s{c.stiffness, {}, c.name, c.name.rfind("kyy", 0) == 0 ? "dashed" : "lines", "#000000"};
        for (const double w : c.speed) s.y.push_back(w > 0 ? u.factor * w : floor);
        p.series.push_back(std::move(s));
    }
    p.xmin = k0;
    p.xmax = k1;
    f.panels = {p};
    return f;
}

}  // namespace gyrokit
