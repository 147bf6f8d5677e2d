#include <gyrokit/io/table.hpp>

#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/io/csv.hpp>

namespace gyrokit {

namespace {

using Json = nlohmann::ordered_json;   // ordered: keys stay in column order

FieldSpelling& field_spelling() {
    static FieldSpelling spell;
    return spell;
}

// A title or text cell with its option fields in the front end's words.
std::string spelled(const std::string& s) { return spell_fields(s, field_spelling()); }

bool is_number(const Cell& c) {
    return std::holds_alternative<double>(c) || std::holds_alternative<long long>(c);
}

// Checked before anything is formatted, so a bad table writes no partial output.
void check_no_nan(const Table& t) {
    for (std::size_t i = 0; i < t.rows(); ++i)
        for (std::size_t j = 0; j < t.columns().size(); ++j)
            if (auto d = std::get_if<double>(&t.row(i)[j]); d && std::isnan(*d))
                throw Error(fmt::format("NaN in column '{}' (row {}){} of an output table; "
                                        "a NaN result is a bug upstream",
                                        t.columns()[j], i + 1,
                                        t.title.empty() ? "" : " of table '" + t.title + "'"));
}

// Cell text for Text and CSV; doubles with `digits` significant digits (%.<digits>g).
std::string format_cell(const Cell& c, int digits) {
    if (auto d = std::get_if<double>(&c)) {
        if (std::isinf(*d)) return *d > 0 ? "inf" : "-inf";
        return fmt::format("{:.{}g}", *d + 0.0, digits);   // + 0.0: a negative zero prints as 0
    }
    if (auto i = std::get_if<long long>(&c)) return std::to_string(*i);
    if (auto b = std::get_if<bool>(&c)) return *b ? "true" : "false";
    return spelled(std::get<std::string>(c));
}

// Width in UTF-8 code points, so labels such as "ω (rad/s)" line up.
std::size_t display_width(const std::string& s) {
    return std::count_if(s.begin(), s.end(),
                         [](char ch) { return (static_cast<unsigned char>(ch) & 0xC0) != 0x80; });
}

std::string pad(const std::string& s, std::size_t width, bool right) {
    const std::string fill(width - display_width(s), ' ');
    return right ? fill + s : s + fill;
}

std::string render_text(const Table& t) {
    const auto& cols = t.columns();
    const std::size_t n = cols.size();
    std::vector<std::vector<std::string>> cells(t.rows());
    std::vector<std::size_t> width(n);
    std::vector<bool> numeric(n, t.rows() > 0);   // a numeric column gets a right-aligned header
    for (std::size_t j = 0; j < n; ++j) width[j] = display_width(cols[j]);
    for (std::size_t i = 0; i < t.rows(); ++i)
        for (std::size_t j = 0; j < n; ++j) {
            cells[i].push_back(format_cell(t.row(i)[j], 6));
            width[j] = std::max(width[j], display_width(cells[i][j]));
            numeric[j] = numeric[j] && is_number(t.row(i)[j]);
        }

    // Every line is padded to the full width, so the columns line up.
    auto line = [&](auto&& field) {
        std::string s;
        for (std::size_t j = 0; j < n; ++j) s += (j ? "  " : "") + field(j);
        return s + '\n';
    };
    std::string out = t.title.empty() ? "" : spelled(t.title) + '\n';
    out += line([&](std::size_t j) { return pad(cols[j], width[j], numeric[j]); });
    out += line([&](std::size_t j) { return std::string(width[j], '-'); });
    for (std::size_t i = 0; i < t.rows(); ++i)
        out += line([&](std::size_t j) { return pad(cells[i][j], width[j], is_number(t.row(i)[j])); });
    return out;
}

std::string render_csv(const Table& t) {
    auto line = [&](auto&& field) {
        std::string s;
        for (std::size_t j = 0; j < t.columns().size(); ++j) s += (j ? "," : "") + csv_field(field(j));
        return s + '\n';
    };
    std::string out = line([&](std::size_t j) { return t.columns()[j]; });
    for (std::size_t i = 0; i < t.rows(); ++i)
        out += line([&](std::size_t j) { return format_cell(t.row(i)[j], 12); });
    return out;
}

Json cell_json(const Cell& c) {
    if (auto d = std::get_if<double>(&c)) {
        if (std::isinf(*d)) return *d > 0 ? "inf" : "-inf";   // JSON has no infinity literal
        return *d + 0.0;
    }
    if (auto i = std::get_if<long long>(&c)) return *i;
    if (auto b = std::get_if<bool>(&c)) return *b;
    return spelled(std::get<std::string>(c));
}

Json table_json(const Table& t) {
    Json rows = Json::array();
    for (std::size_t i = 0; i < t.rows(); ++i) {
        Json obj = Json::object();
        for (std::size_t j = 0; j < t.columns().size(); ++j) obj[t.columns()[j]] = cell_json(t.row(i)[j]);
        rows.push_back(std::move(obj));
    }
    return rows;
}

// Invalid UTF-8 in a string cell is replaced rather than failing the whole output.
std::string dump(const Json& j) {
    return j.dump(2, ' ', false, Json::error_handler_t::replace) + '\n';
}

std::string render(const Table& t, TableFormat f) {
    check_no_nan(t);
    switch (f) {
    case TableFormat::Text: return render_text(t);
    case TableFormat::Csv: return render_csv(t);
    case TableFormat::Json: return dump(table_json(t));
    }
    throw Error("unknown TableFormat value");
}

// Output is built in full first: an error leaves the stream untouched.
void put(std::ostream& os, const std::string& s) {
    if (!(os << s)) throw Error("writing the table failed: its stream refused the bytes (a full disk, or a closed reader)");
}

}  // namespace

TableFormat parse_table_format(const std::string& s) {
    if (s == "table") return TableFormat::Text;
    if (s == "csv") return TableFormat::Csv;
    if (s == "json") return TableFormat::Json;
    throw InputError(fmt::format("unknown table format '{}'; allowed values: table, csv, json", s));
}

Table::Table(std::vector<std::string> columns) : columns_(std::move(columns)) {
    std::set<std::string> seen;
    for (const auto& c : columns_)
        if (!seen.insert(c).second) throw Error(fmt::format("duplicate table column '{}'", c));
}

void Table::add_row(std::vector<Cell> row) {
    if (row.size() != columns_.size())
        throw Error(fmt::format("table row has {} cells but the table has {} columns{}", row.size(),
                                columns_.size(), title.empty() ? "" : " (table '" + title + "')"));
    rows_.push_back(std::move(row));
}

void set_field_spelling(FieldSpelling spell) { field_spelling() = std::move(spell); }

std::string spelled_text(const std::string& marked) { return spelled(marked); }

void write_table(std::ostream& os, const Table& t, TableFormat f) { put(os, render(t, f)); }

void write_tables(std::ostream& os, const std::vector<Table>& ts, TableFormat f) {
    if (f == TableFormat::Json) {
        Json all = Json::object();
        for (std::size_t i = 0; i < ts.size(); ++i) {
            check_no_nan(ts[i]);
            const std::string key = ts[i].key.empty() ? fmt::format("table{}", i + 1) : ts[i].key;
            if (all.contains(key)) throw Error(fmt::format("two output tables share the key '{}'", key));
            all[key] = table_json(ts[i]);
        }
        return put(os, dump(all));
    }
    // A CSV reader sees one header and rows of one shape: several tables would be one broken table.
    if (f == TableFormat::Csv && ts.size() > 1)
        throw Error(fmt::format("CSV holds one table; {} given (select one)", ts.size()));
    std::string out;
    for (std::size_t i = 0; i < ts.size(); ++i) out += (i ? "\n" : "") + render(ts[i], f);
    put(os, out);
}

void write_result(std::ostream& os, const std::vector<Table>& ts, TableFormat f, const std::string& key,
                  const std::string& option, std::vector<std::string>& left_out) {
    if (!key.empty()) return write_table(os, select_table(ts, key, option), f);
    if (f != TableFormat::Csv || ts.size() <= 1) return write_tables(os, ts, f);
    for (std::size_t i = 1; i < ts.size(); ++i) left_out.push_back(ts[i].key);
    write_table(os, ts.front(), f);
}

const Table& select_table(const std::vector<Table>& ts, const std::string& key, const std::string& option) {
    std::string keys;
    for (const Table& t : ts) {
        if (t.key == key) return t;
        keys += (keys.empty() ? "" : ", ") + t.key;
    }
    throw InputError(fmt::format("{} '{}': allowed: {}", option, key, keys));
}

}  // namespace gyrokit
