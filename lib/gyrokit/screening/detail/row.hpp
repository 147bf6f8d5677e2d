// One design's row as the screening's criteria fill it, and the checks that fill it
// (one source file per criterion: criteria_separation.cpp, criteria_stability.cpp,
// criteria_response.cpp). Not installed.
#pragma once

#include <gyrokit/scene/scene.hpp>
#include <gyrokit/screening/screening.hpp>

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace gyrokit::screening_detail {

inline constexpr double inf = std::numeric_limits<double>::infinity();

// A criterion filling a column it did not declare: the code's error, never a design's.
struct UndeclaredColumn : std::logic_error {
    using std::logic_error::logic_error;
};

// One design's row as its criteria fill it: each value by the name of a column the
// criterion declared (a name it did not declare is a bug, not a design's failure).
class Row {
public:
    Row(DesignResult& r, const std::vector<std::string>& quantities, const std::vector<std::string>& labels)
        : result(r), quantities_(quantities), labels_(labels) {}
    void set(const std::string& column, double value) { result.quantities.at(index(quantities_, column)) = value; }
    void label(const std::string& column, std::string text) { result.labels.at(index(labels_, column)) = std::move(text); }
    // A criterion not met: its name in `failed`, "name: text" in the reason.
    void fail(const std::string& criterion, const std::string& text) {
        result.failed.push_back(criterion);
        result.reason += (result.reason.empty() ? "" : "; ") + criterion + ": " + text;
    }
    DesignResult& result;

private:
    static std::size_t index(const std::vector<std::string>& columns, const std::string& name) {
        const auto it = std::find(columns.begin(), columns.end(), name);
        if (it == columns.end()) throw UndeclaredColumn("screening: column " + name + " is not declared");
        return static_cast<std::size_t>(it - columns.begin());
    }
    const std::vector<std::string>& quantities_;
    const std::vector<std::string>& labels_;
};

// Each criterion's check of one design: fills the columns it declared, and fails the
// row with its reason where the design does not meet it.
void check_separation(const Sweep& s, const Scene& sc, const SeparationCriterion& c, Row& row);
void check_stability(const Sweep& s, const Scene& sc, const StabilityCriterion& c, Row& row);
void check_pervasive(const Sweep& s, const Scene& sc, const PervasiveCriterion& c, Row& row);
void check_response(const Sweep& s, const Scene& sc, const ResponseCriterion& c, Row& row);

}  // namespace gyrokit::screening_detail
