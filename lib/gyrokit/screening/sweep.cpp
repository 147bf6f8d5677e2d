#include <gyrokit/screening/sweep.hpp>
#include <gyrokit/screening/screening.hpp>

#include <gyrokit/screening/detail/probes.hpp>

#include <gyrokit/core/error.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <random>
#include <set>

namespace gyrokit {

namespace {

constexpr std::size_t max_designs = 100000000;

// Uniform integer in [0, n) by rejection, so it depends only on the engine's
// (standardized) output sequence.
std::uint64_t uniform_index(std::mt19937_64& g, std::uint64_t n) {
    const std::uint64_t limit = std::numeric_limits<std::uint64_t>::max() - std::numeric_limits<std::uint64_t>::max() % n;
    std::uint64_t x;
    do x = g();
    while (x >= limit);
    return x % n;
}

// Uniform real in [0, 1) from the top 53 bits.
double uniform_unit(std::mt19937_64& g) { return static_cast<double>(g() >> 11) * 0x1.0p-53; }

double map_unit(const SweepParameter& p, double u) {
    if (p.log_scale) return std::exp(std::log(p.from) + u * (std::log(p.to) - std::log(p.from)));
    return p.from + u * (p.to - p.from);
}

// Every parameter must name a key the scene accepts: the scene is loaded with
// the parameter at each candidate value, and the sweep is rejected only if no
// candidate is accepted (single bad values are reported per design).
// Whether two models are the same at the speeds of the study: matrices, bearing
// tables, damping and unbalance (what every analysis reads).
bool same_model(const GyroscopicSystem& a, const GyroscopicSystem& b, const std::vector<double>& speeds) {
    const auto same = [](const SparseMatrix& x, const SparseMatrix& y) {
        return x.rows() == y.rows() && x.cols() == y.cols() && SparseMatrix(x - y).norm() == 0.0;
    };
    if (a.size() != b.size()) return false;
    for (double w : speeds) {
        const SparsePencil pa = a.sparse_at_speed(w), pb = b.sparse_at_speed(w);
        if (!same(pa.M, pb.M) || !same(pa.C, pb.C) || !same(pa.K, pb.K)) return false;
        if (!(a.unbalance_force(w) - b.unbalance_force(w)).isZero(0.0)) return false;
    }
    return a.damping_names() == b.damping_names();
}

void check_parameter(const Sweep& s, const SweepParameter& p) {
    std::vector<double> candidates = p.values;
    if (candidates.empty()) candidates = {p.from, p.to, map_unit(p, 0.5)};
    std::string first_error;
    std::vector<std::pair<double, Scene>> models;
    for (double v : candidates) {
        std::map<std::string, double> overrides;
        for (const std::string& path : p.paths.empty() ? std::vector<std::string>{p.name} : p.paths)
            overrides[path] = v;
        try {
            models.emplace_back(v, s.loader(overrides));
        } catch (const InputError& e) {
            if (first_error.empty()) first_error = e.what();
        }
    }
    if (models.empty())
        throw InputError(fmt::format("{}: parameter '{}' is not accepted by the scene: {}", s.path, p.name, first_error));
    // A key the model reads but does not use (c_T of a rigid shaft): every design would be the same.
    // Compared at every operating speed and up to the stability criterion's reach, with the
    // scene's settings. (A fluid rotor's fill enters its own analysis, not the matrices: not judged here.)
    if (models.size() >= 2 && !models.front().second.fluid()) {
        std::vector<double> speeds = s.operating_speeds();
        if (s.criteria.stability) speeds.push_back(s.criteria.stability->up_to);
        const Scene& a = models.front().second;
        for (std::size_t i = 1; i < models.size(); ++i) {
            const Scene& b = models[i].second;
            if (a.speeds.has_value() != b.speeds.has_value() ||
                (a.speeds && b.speeds && a.speed_points() != b.speed_points()) || a.solver.modes != b.solver.modes ||
                a.analysis.harmonics != b.analysis.harmonics || a.solver.target != b.solver.target ||
                a.solver.target_order != b.solver.target_order)
                return;   // it changes the analysis settings
        }
        for (std::size_t i = 1; i < models.size(); ++i)
            if (models[i].first != models.front().first &&
                !same_model(models.front().second.system, models[i].second.system, speeds))
                return;
        if (std::any_of(models.begin(), models.end(), [&](const auto& m) { return m.first != models.front().first; }))
            throw InputError(fmt::format("{}: parameter '{}' does not change the model of scene {} (the values {} and "
                                         "{} give the same matrices, damping and unbalance): every design would be "
                                         "the same; allowed: a key the model uses",
                                         s.path, p.name, s.scene, models.front().first, models.back().first));
    }
}

// A name as it can stand in one line of a message: control characters as '?'.
std::string printable(std::string text) {
    for (char& c : text)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    return text;
}

}  // namespace

std::vector<double> latin_hypercube(std::size_t n, std::size_t d, std::uint64_t seed) {
    std::mt19937_64 g(seed);
    std::vector<double> x(n * d);
    std::vector<std::size_t> perm(n);
    for (std::size_t j = 0; j < d; ++j) {
        for (std::size_t i = 0; i < n; ++i) perm[i] = i;
        for (std::size_t i = n; i > 1; --i) std::swap(perm[i - 1], perm[uniform_index(g, i)]);   // Fisher-Yates
        for (std::size_t i = 0; i < n; ++i) x[i * d + j] = (static_cast<double>(perm[i]) + uniform_unit(g)) / n;
    }
    return x;
}

std::size_t Sweep::design_count() const {
    if (sampling == Sampling::LatinHypercube) return static_cast<std::size_t>(samples);
    if (sampling == Sampling::List) return designs.size();
    std::size_t n = 1;
    for (const auto& p : parameters) n *= p.values.empty() ? static_cast<std::size_t>(p.count) : p.values.size();
    return n;
}

std::vector<double> Sweep::design(std::size_t i) const {
    const std::size_t d = parameters.size();
    if (sampling == Sampling::List) return designs.at(i);
    std::vector<double> x(d);
    if (sampling == Sampling::LatinHypercube) {
        for (std::size_t j = 0; j < d; ++j) x[j] = map_unit(parameters[j], lhs.at(i * d + j));
        return x;
    }
    // Grid: the last parameter varies fastest.
    for (std::size_t j = d; j-- > 0;) {
        const SweepParameter& p = parameters[j];
        const std::size_t n = p.values.empty() ? static_cast<std::size_t>(p.count) : p.values.size();
        const std::size_t k = i % n;
        i /= n;
        if (!p.values.empty()) x[j] = p.values[k];
        else x[j] = k == 0 ? p.from : (k + 1 == n ? p.to : map_unit(p, static_cast<double>(k) / (n - 1)));
    }
    return x;
}

std::vector<double> Sweep::operating_speeds() const {
    return SpeedRange{op_from, op_to, op_from == op_to ? 1 : op_count}.points();
}

Shard Shard::parse(const std::string& text) {
    Shard s;
    const size_t slash = text.find('/');
    try {
        if (slash == std::string::npos) throw std::invalid_argument(text);
        size_t p1 = 0, p2 = 0;
        const std::string a = text.substr(0, slash), b = text.substr(slash + 1);
        const long k = std::stol(a, &p1), n = std::stol(b, &p2);
        if (p1 != a.size() || p2 != b.size() || n < 1 || n > 1000000 || k < 0 || k >= n)
            throw std::out_of_range(text);
        s.index = static_cast<int>(k);
        s.count = static_cast<int>(n);
    } catch (const std::exception&) {
        throw InputError(fmt::format("--shard '{}': allowed: K/N with whole numbers 0 <= K < N <= 1000000 (e.g. 0/4)",
                                     text));
    }
    return s;
}

namespace {

// Whether two parameter paths can name one value: equal step by step, where an
// index [*] meets any index and [1] meets [01].
bool overlap(const std::string& a, const std::string& b) {
    const auto steps = [](const std::string& p) {
        std::vector<std::pair<std::string, std::string>> out;   // key, index ("" none, "*" every)
        std::size_t at = 0;
        while (at <= p.size()) {
            const std::size_t dot = std::min(p.find('.', at), p.size());
            const std::string part = p.substr(at, dot - at);
            const std::size_t open = part.find('[');
            std::string index = open == std::string::npos ? "" : part.substr(open + 1, part.size() - open - 2);
            if (!index.empty() && index != "*") index.erase(0, std::min(index.find_first_not_of('0'), index.size() - 1));
            out.emplace_back(part.substr(0, open), index);
            at = dot + 1;
        }
        return out;
    };
    const auto x = steps(a), y = steps(b);
    if (x.size() != y.size()) return false;
    for (std::size_t i = 0; i < x.size(); ++i)
        if (x[i].first != y[i].first ||
            (x[i].second != y[i].second && x[i].second != "*" && y[i].second != "*"))
            return false;
    return true;
}

}  // namespace

std::map<std::string, double> design_overrides(const Sweep& s, const std::vector<double>& values) {
    std::map<std::string, double> o;
    for (std::size_t j = 0; j < s.parameters.size() && j < values.size(); ++j) {
        const SweepParameter& p = s.parameters[j];
        for (const std::string& path : p.paths.empty() ? std::vector<std::string>{p.name} : p.paths) {
            for (const auto& [other, v] : o)
                if (overlap(path, other))
                    throw InputError(fmt::format("{}: paths '{}' and '{}' can name the same value; allowed: each "
                                                 "value set by one path",
                                                 s.path, other, path));
            o[path] = values[j];
        }
    }
    return o;
}

namespace {

// The parameters' names: each once, a CSV column name, a tie's name one of its paths.
std::set<std::string> check_parameter_names(const Sweep& s) {
    std::set<std::string> names;
    for (const auto& p : s.parameters) {
        if (!names.insert(p.name).second)
            throw InputError(fmt::format("{}: parameter '{}' appears twice", s.path, p.name));
        // A column name of the result file: one CSV cell on one line that --resume reads back.
        for (const char c : p.name)
            if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f || c == ',' || c == '"')
                throw InputError(fmt::format("{}: parameter name '{}' holds a line break, control character, comma or "
                                             "quote; allowed: printable text without commas or quotes (a CSV column "
                                             "name)",
                                             s.path, printable(p.name.substr(0, 60))));
        // A tie's name that reads as a scene path must be one of its paths, or the column names the wrong key.
        if (!p.paths.empty() && p.name.rfind("model.", 0) == 0 &&
            std::find(p.paths.begin(), p.paths.end(), p.name) == p.paths.end())
            throw InputError(fmt::format("{}: parameter name '{}' reads as a scene path but the parameter sets {}; "
                                         "allowed: one of its paths, or a label that is no path (e.g. 'kxx')",
                                         s.path, p.name, fmt::join(p.paths, ", ")));
    }
    return names;
}

// The designs the sampling makes: no path set twice, the list's rows whole and finite,
// a grid within max_designs; the operating range.
void check_designs(Sweep& s) {
    design_overrides(s, std::vector<double>(s.parameters.size(), 0.0));   // no path set twice
    if (s.sampling == Sampling::LatinHypercube && s.parameters.empty())
        throw InputError(s.path + ": Latin hypercube sampling needs at least one [[parameter]]");
    if (s.sampling == Sampling::List) {
        if (s.designs.size() > max_designs)
            throw InputError(fmt::format("{}: {} designs; allowed: at most {}", s.path, s.designs.size(), max_designs));
        for (std::size_t i = 0; i < s.designs.size(); ++i) {
            if (s.designs[i].size() != s.parameters.size())
                throw InputError(fmt::format("{}: design {} has {} values for {} parameters", s.path, i,
                                             s.designs[i].size(), s.parameters.size()));
            for (double v : s.designs[i])
                if (!std::isfinite(v))
                    throw InputError(fmt::format("{}: design {} has a value that is not a finite number", s.path, i));
        }
    }
    // Guard the grid size before it overflows.
    long double n = 1;
    for (const auto& p : s.parameters) n *= p.values.empty() ? p.count : static_cast<long double>(p.values.size());
    if (s.sampling == Sampling::Grid && n > max_designs)
        throw InputError(fmt::format("{}: the grid has {:.0f} designs; allowed: at most {}", s.path,
                                     static_cast<double>(n), max_designs));
    if (!(s.op_from >= 0 && s.op_to >= s.op_from && std::isfinite(s.op_to)))
        throw InputError(fmt::format("{}: [operating] from = {}, to = {}; allowed: 0 <= from <= to", s.path,
                                     s.op_from * s.unit.factor, s.op_to * s.unit.factor));
}

// The criteria alone: at least one, each within its range.
void check_criteria(const Sweep& s) {
    const Criteria& c = s.criteria;
    if (!c.separation && !c.stability && !c.pervasive && !c.response)
        throw InputError(s.path + ": no criteria; required: at least one of [criteria.separation], "
                                  "[criteria.stability], [criteria.pervasive], [criteria.response]");
    const std::optional<double> min_log_dec = c.stability ? c.stability->min_log_dec : std::nullopt;
    if (min_log_dec && !(*min_log_dec > 0 && std::isfinite(*min_log_dec)))   // a sweep assembled in code
        throw InputError(fmt::format("{}: [criteria.stability] min_log_dec = {}: out of range; allowed: > 0", s.path,
                                     *min_log_dec));
    if (c.separation && !(s.op_from > 0))
        throw InputError(s.path + ": [criteria.separation] needs [operating] from > 0 (the margin is relative to it)");

}

// The criteria against the base scene: its DOFs, unbalance, damping components and harmonics.
void check_against_base(Sweep& s) {
    const Criteria& c = s.criteria;
    const Scene base = s.loader({});
    s.dofs.names = base.system.dofs.names;
    if (c.separation && c.separation->harmonics.empty()) s.criteria.separation->harmonics = base.analysis.harmonics;
    if (c.response) {
        if (base.system.unbalance.size() == 0 || base.system.unbalance.norm() == 0.0)
            throw InputError(fmt::format("{}: [criteria.response] needs an unbalance, but scene {} has none", s.path,
                                         s.scene));
        for (const auto& d : c.response->dofs)
            if (s.dofs.find(d) < 0)
                throw InputError(fmt::format("{}: [criteria.response] dofs: '{}' is not a DOF of scene {}", s.path, d,
                                             s.scene));
        if (!c.response->dofs.empty() && !c.response->probes.empty())
            throw InputError(s.path + ": [criteria.response] probes: given with dofs; allowed: either dofs or probes");
        check_probes(s.path, s.scene, c.response->probes, base.system);
    }
    if (c.pervasive) {
        if (base.system.damping_names().empty() && s.parameters.empty())
            throw InputError(fmt::format("{}: [criteria.pervasive] needs damping, but scene {} has none", s.path,
                                         s.scene));
        for (const auto& d : c.pervasive->damping) {
            if (d == "total") continue;
            // A component may be zero in the base scene but switched on by a parameter.
            const std::vector<std::string> names = base.system.damping_names();
            const bool known = std::find(names.begin(), names.end(), d) != names.end() ||
                               std::any_of(s.parameters.begin(), s.parameters.end(),
                                           [&](const SweepParameter& p) { return p.name == "model." + d; });
            if (!known)
                throw InputError(fmt::format("{}: [criteria.pervasive] damping: '{}' is not a damping component of "
                                             "scene {}; allowed: total or a component name",
                                             s.path, d, s.scene));
        }
    }
}

}  // namespace

void finalize_sweep(Sweep& s, bool check_parameters) {
    if (!s.loader) {
        const std::string scene = s.scene;
        s.loader = [scene](const std::map<std::string, double>& o) { return load_scene(scene, o); };
    }
    const std::set<std::string> names = check_parameter_names(s);
    check_designs(s);
    check_criteria(s);
    check_against_base(s);
    // A parameter named as another column of the result (verdict, a quantity) would give two columns of one name.
    const std::vector<std::string> columns = result_columns(s);
    for (const auto& p : s.parameters)
        if (std::count(columns.begin(), columns.end(), p.name) > 1)
            throw InputError(fmt::format("{}: parameter name '{}' is also the name of a result column; allowed: a "
                                         "name that is not one of: design, verdict, failed, reason or a criterion's "
                                         "quantity",
                                         s.path, p.name));
    if (check_parameters)
        for (const auto& p : s.parameters) check_parameter(s, p);
    if (!s.plot_axes.empty()) {
        if (s.plot_axes.size() != 2)
            throw InputError(s.path + ": [plot] axes must name exactly two parameters");
        for (const auto& a : s.plot_axes)
            if (!names.count(a))
                throw InputError(fmt::format("{}: [plot] axes: '{}' is not a parameter of the sweep", s.path, a));
    }
    if (s.sampling == Sampling::LatinHypercube)
        s.lhs = latin_hypercube(static_cast<std::size_t>(s.samples), s.parameters.size(), s.seed);
}

}  // namespace gyrokit
