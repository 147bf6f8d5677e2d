#include <gyrokit/io/matrix_market.hpp>

#include <gyrokit/core/input_file.hpp>
#include <gyrokit/core/run_files.hpp>
#include <gyrokit/io/output_file.hpp>

#include <gyrokit/core/error.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <complex>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string_view>
#include <type_traits>
#include <unordered_map>
#include <vector>

namespace gyrokit {
namespace {

constexpr std::string_view kBanner = "%%MatrixMarket matrix <format> <field> <symmetry>";
// The size line alone decides allocations: the sparse result's index arrays
// grow with rows + columns, a dense result with rows * columns, however few
// entries follow. Bounds far beyond any model the solvers can take (the largest
// tested has 10^5 DOFs; the dense solver stops at 3,000), so a hostile header
// costs at most a few hundred megabytes before it is refused.
constexpr long long kMaxSide = 20'000'000;
constexpr long long kMaxCells = 25'000'000;

enum class Symmetry { general, symmetric, skew };

struct Header {
    bool coordinate = true;
    bool integer = false;  // field "integer": values must be whole numbers
    bool complex = false;  // field "complex": two numbers per entry
    Symmetry symmetry = Symmetry::general;
};

const char* name(Symmetry s) {
    return s == Symmetry::general ? "general" : s == Symmetry::symmetric ? "symmetric" : "skew-symmetric";
}

// Quotes text for a message, cut short and with control characters replaced,
// so that a binary or very long line still gives a short one-line message.
std::string quote(std::string_view s) {
    std::string out = "'";
    for (char c : s.substr(0, 40)) out += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
    return out + (s.size() > 40 ? "...'" : "'");
}

std::string lower(std::string_view s) {
    std::string out(s);
    for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

// Parses the whole token; "12abc" fails. from_chars rejects a leading '+', which
// Matrix Market writers may emit, so one is skipped.
template <typename T>
std::errc parse(std::string_view s, T& out) {
    if (s.size() > 1 && s[0] == '+' && s[1] != '+' && s[1] != '-') s.remove_prefix(1);
    auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    if (ec == std::errc() && end != s.data() + s.size()) return std::errc::invalid_argument;
    return ec;
}

// Reads a file line by line, keeps the line number and formats errors with it.
class LineReader {
public:
    // Read once per run (read_input checks it is a regular file of bounded size: an
    // ifstream "opens" a directory and reads nothing, /dev/zero never ends).
    explicit LineReader(const std::string& path)
        : path_(path), bytes_(read_input(path, "Matrix Market file", kMaxDataInputBytes)) {}

    // Advances to the next line and splits it at whitespace; false at end of file.
    bool next() {
        const std::string& all = *bytes_;
        if (pos_ >= all.size()) return false;
        const std::size_t end = std::min(all.find('\n', pos_), all.size());
        text_.assign(all, pos_, end - pos_);
        pos_ = end + 1;
        ++number_;
        if (!text_.empty() && text_.back() == '\r') text_.pop_back();  // CRLF files
        tokens_.clear();
        std::string_view rest = text_;
        while (true) {
            const auto begin = rest.find_first_not_of(" \t\r\f\v");
            if (begin == std::string_view::npos) break;
            rest.remove_prefix(begin);
            const auto end = std::min(rest.find_first_of(" \t\r\f\v"), rest.size());
            tokens_.push_back(rest.substr(0, end));
            rest.remove_prefix(end);
        }
        return true;
    }

    // Advances past blank lines and % comments.
    bool next_data() {
        while (next())
            if (!tokens_.empty() && tokens_[0].front() != '%') return true;
        return false;
    }

    const std::vector<std::string_view>& tokens() const { return tokens_; }
    const std::string& text() const { return text_; }
    std::size_t number() const { return number_; }

    template <typename... Args>
    [[noreturn]] void fail(fmt::format_string<Args...> format, Args&&... args) const {
        throw InputError(
            fmt::format("{}: line {}: {}", path_, number_, fmt::format(format, std::forward<Args>(args)...)));
    }

    // Requires exactly n tokens on the line; `form` names them for the message.
    void expect_tokens(std::size_t n, std::string_view what, std::string_view form) const {
        if (tokens_.size() < n) fail("{} {} is incomplete; expected '{}'", what, quote(text_), form);
        if (tokens_.size() > n) fail("unexpected text {} after the {}; expected '{}'", quote(tokens_[n]), what, form);
    }

    long long integer(std::string_view token, std::string_view what) const {
        long long v = 0;
        if (parse(token, v) != std::errc()) fail("{} {} is not an integer", what, quote(token));
        return v;
    }

    double value(std::string_view token, bool integer_field) const {
        if (integer_field) {
            long long v = 0;
            if (parse(token, v) != std::errc())
                fail("value {} is not an integer; field 'integer' allows whole numbers only", quote(token));
            return static_cast<double>(v);
        }
        double v = 0;
        const std::errc ec = parse(token, v);
        if (ec == std::errc::result_out_of_range)
            fail("value {} is outside the range of a double; allowed magnitudes 0 and 4.9e-324..1.8e308",
                 quote(token));
        if (ec != std::errc()) fail("value {} is not a number", quote(token));
        if (!std::isfinite(v)) fail("value {} is not a finite number", quote(token));
        return v;
    }

private:
    std::string path_;
    std::shared_ptr<const std::string> bytes_;
    std::size_t pos_ = 0;
    std::string text_;
    std::vector<std::string_view> tokens_;
    std::size_t number_ = 0;
};

Header read_banner(LineReader& r, const std::string& path, bool complex_allowed) {
    if (!r.next()) throw InputError(fmt::format("{}: file is empty; expected the banner '{}'", path, kBanner));
    const auto& t = r.tokens();
    if (t.empty() || t[0] != "%%MatrixMarket")
        // Not quoted: a file that is not what it should be (a wrong path: /etc/shadow) is named, never echoed.
        r.fail("missing banner; expected '{}' as the first line; this file does not start with it (not a Matrix "
               "Market file?)",
               kBanner);
    r.expect_tokens(5, "banner", kBanner);

    // The qualifiers are case-insensitive in the Matrix Market specification.
    Header h;
    if (lower(t[1]) != "matrix") r.fail("object {} is not supported; allowed matrix", quote(t[1]));

    const std::string format = lower(t[2]);
    if (format == "array") h.coordinate = false;
    else if (format != "coordinate") r.fail("format {} is not supported; allowed coordinate, array", quote(t[2]));

    const std::string field = lower(t[3]);
    if (field == "integer") h.integer = true;
    else if (field == "complex" && complex_allowed) h.complex = true;
    else if (field != "real")
        r.fail("field {} is not supported{}; allowed {}", quote(t[3]), complex_allowed ? "" : " for a real matrix",
               complex_allowed ? "real, integer, complex" : "real, integer");

    const std::string symmetry = lower(t[4]);
    if (symmetry == "symmetric") h.symmetry = Symmetry::symmetric;
    else if (symmetry == "skew-symmetric") h.symmetry = Symmetry::skew;
    else if (symmetry != "general")
        r.fail("symmetry {} is not supported; allowed general, symmetric, skew-symmetric", quote(t[4]));
    return h;
}

// Reads any supported file into a dense Matrix (MatrixXd or MatrixXcd).
// The entries of a file, symmetric and skew halves mirrored.
template <class Scalar>
struct Entries {
    long long rows = 0, cols = 0;
    std::vector<Eigen::Triplet<Scalar, long long>> values;
};

template <class Scalar>
Entries<Scalar> read(const std::string& path, bool vector, bool dense) {
    constexpr bool kComplex = !std::is_same_v<Scalar, double>;

    LineReader r(path);
    const Header h = read_banner(r, path, kComplex);
    const auto& t = r.tokens();

    // Size line.
    const std::string_view form = h.coordinate ? "rows columns entries" : "rows columns";
    if (!r.next_data()) r.fail("file ends here; expected the size line '{}'", form);
    r.expect_tokens(h.coordinate ? 3 : 2, "size line", form);
    const long long rows = r.integer(t[0], "rows"), cols = r.integer(t[1], "columns");
    if (rows < 1) r.fail("rows {} is not positive; allowed 1 or more", rows);
    if (cols < 1) r.fail("columns {} is not positive; allowed 1 or more", cols);
    // Before any arithmetic on the sizes: with both at most kMaxSide (below INT_MAX,
    // Eigen's index), rows * cols and the cell keys j * rows + i stay below 2^49.
    if (rows > kMaxSide || cols > kMaxSide)
        r.fail("size {}x{} is too large; allowed at most {} rows and columns", rows, cols, kMaxSide);
    if ((dense || !h.coordinate) && rows > kMaxCells / cols)
        r.fail("size {}x{} is too large for a dense matrix; allowed at most {} entries (coordinate files are "
               "read sparse at any size up to {} rows)", rows, cols, kMaxCells, kMaxSide);
    if (h.symmetry != Symmetry::general && rows != cols)
        r.fail("a {} matrix must be square, got {}x{}; allowed rows equal to columns", name(h.symmetry), rows, cols);
    if (vector && rows != 1 && cols != 1) r.fail("size {}x{} is not a vector; allowed n x 1 or 1 x n", rows, cols);

    // How many entries the storage scheme holds: symmetric keeps the lower triangle,
    // skew-symmetric the strictly lower one (its diagonal is zero).
    const long long capacity = h.symmetry == Symmetry::general     ? rows * cols
                               : h.symmetry == Symmetry::symmetric ? rows * (rows + 1) / 2
                                                                   : rows * (rows - 1) / 2;
    long long expected = capacity;
    std::string source;  // where `expected` comes from, for count errors
    if (h.coordinate) {
        expected = r.integer(t[2], "entry count");
        if (expected < 0 || expected > capacity)
            r.fail("entry count {} does not fit a {}x{} {} matrix; allowed 0..{}", expected, rows, cols,
                   name(h.symmetry), capacity);
        source = fmt::format("entries declared on line {}", r.number());
    } else {
        source = fmt::format("entries a {}x{} {} array holds{}", rows, cols, name(h.symmetry),
                             h.symmetry == Symmetry::general ? "" : " (lower triangle, column by column)");
    }

    Entries<Scalar> A;
    A.rows = rows;
    A.cols = cols;
    // A small head start only: the entry count is the file's claim, not yet its content.
    A.values.reserve(static_cast<std::size_t>(std::min(expected, 1LL << 16)) * (h.symmetry == Symmetry::general ? 1 : 2));
    // Coordinate files: the line that set each cell, to report duplicates with both lines.
    std::unordered_map<long long, std::size_t> set_on_line;
    // Array files: the next (0-based) position, column-major; skew starts below the diagonal.
    long long i = h.symmetry == Symmetry::skew ? 1 : 0, j = 0;

    const std::size_t numbers = h.complex ? 2 : 1;
    const std::string value_form = h.complex ? "real imaginary" : "value";
    for (long long k = 0; k < expected; ++k) {
        if (!r.next_data()) r.fail("file ends after {} of the {} {}", k, expected, source);
        if (h.coordinate) {
            r.expect_tokens(2 + numbers, "entry", "row column " + value_form);
            const long long row = r.integer(t[0], "row index"), col = r.integer(t[1], "column index");
            if (row < 1 || row > rows || col < 1 || col > cols)
                r.fail("entry ({}, {}) is outside the {}x{} matrix; allowed rows 1..{}, columns 1..{}", row, col,
                       rows, cols, rows, cols);
            if (h.symmetry == Symmetry::skew && row == col)
                r.fail("entry ({}, {}) is on the diagonal, which is zero in a skew-symmetric matrix; "
                       "allowed only row != column",
                       row, col);
            i = row - 1;
            j = col - 1;
            // (i, j) and (j, i) are one stored entry unless the matrix is general.
            const bool mirror = h.symmetry != Symmetry::general && i < j;
            std::size_t& seen = set_on_line[(mirror ? i : j) * rows + (mirror ? j : i)];
            if (seen != 0)
                r.fail("entry ({}, {}) repeats the entry on line {}; each entry may appear once{}", row, col, seen,
                       h.symmetry == Symmetry::general ? "" : " ((i, j) and (j, i) count as the same entry)");
            seen = r.number();
        } else {
            r.expect_tokens(numbers, "entry", value_form);
        }

        const std::size_t first = h.coordinate ? 2 : 0;
        Scalar v = r.value(t[first], h.integer);
        if constexpr (kComplex) {
            if (h.complex) v.imag(r.value(t[first + 1], false));
        }
        A.values.emplace_back(i, j, v);
        if (h.symmetry == Symmetry::symmetric && i != j) A.values.emplace_back(j, i, v);
        if (h.symmetry == Symmetry::skew) A.values.emplace_back(j, i, -v);

        if (!h.coordinate && ++i == rows) {  // next array position
            ++j;
            i = h.symmetry == Symmetry::general ? 0 : h.symmetry == Symmetry::symmetric ? j : j + 1;
        }
    }
    if (r.next_data()) r.fail("extra entry {} beyond the {} {}", quote(r.text()), expected, source);
    return A;
}

template <class Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> to_dense(const Entries<Scalar>& e) {
    Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> A =
        Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>::Zero(e.rows, e.cols);
    for (const auto& t : e.values) A(t.row(), t.col()) = t.value();
    return A;
}

}  // namespace

Eigen::MatrixXd read_matrix_market(const std::string& path) { return to_dense(read<double>(path, false, true)); }

Eigen::SparseMatrix<double> read_matrix_market_sparse(const std::string& path) {
    const Entries<double> e = read<double>(path, false, false);
    if (e.rows > std::numeric_limits<int>::max() || e.cols > std::numeric_limits<int>::max())
        throw InputError(fmt::format("{}: size {}x{} is too large; allowed at most {} rows and columns", path, e.rows,
                                     e.cols, std::numeric_limits<int>::max()));
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(e.values.size());
    for (const auto& v : e.values)
        if (v.value() != 0.0) t.emplace_back(static_cast<int>(v.row()), static_cast<int>(v.col()), v.value());
    Eigen::SparseMatrix<double> A(static_cast<int>(e.rows), static_cast<int>(e.cols));
    A.setFromTriplets(t.begin(), t.end());
    A.makeCompressed();
    return A;
}

Eigen::VectorXcd read_matrix_market_vector(const std::string& path) {
    const Eigen::MatrixXcd A = to_dense(read<std::complex<double>>(path, true, true));
    return Eigen::Map<const Eigen::VectorXcd>(A.data(), A.size());  // n x 1 and 1 x n alike
}


namespace {

// Writes the entries (1-based row, column, value), given in column order, in
// "coordinate real general" form.
struct Entry {
    Eigen::Index row, col;
    double value;
};
void write_entries(const std::string& path, Eigen::Index rows, Eigen::Index cols, const std::vector<Entry>& entries,
                   const std::string& comment, const std::string& option) {
    // Refuse what read_matrix_market would reject, so every written file reads back.
    if (rows == 0 || cols == 0)
        throw InputError(fmt::format("{}: cannot write a {}x{} matrix; allowed at least 1 row and 1 column", path,
                                     rows, cols));
    for (const Entry& e : entries)
        if (!std::isfinite(e.value))
            throw InputError(fmt::format("{}: entry ({}, {}) is {}, not a finite number; allowed finite values",
                                         path, e.row, e.col, e.value));
    fmt::memory_buffer out;
    auto put = std::back_inserter(out);
    fmt::format_to(put, "%%MatrixMarket matrix coordinate real general\n");
    // Each comment line gets its own '%' so a multi-line comment cannot break the header.
    for (std::string_view rest = comment; !rest.empty();) {
        const auto end = std::min(rest.find('\n'), rest.size());
        fmt::format_to(put, "% {}\n", rest.substr(0, end));
        rest.remove_prefix(std::min(end + 1, rest.size()));
    }
    fmt::format_to(put, "{} {} {}\n", rows, cols, entries.size());
    for (const Entry& e : entries) fmt::format_to(put, "{} {} {:.17g}\n", e.row, e.col, e.value);

    OutputFile file(path, option, "Matrix Market file");
    file.write(std::string_view(out.data(), out.size()));
    file.commit();
}

// -0.0 is kept so the round trip is bitwise exact.
bool stored(double v) { return v != 0.0 || std::signbit(v); }

}  // namespace

void write_matrix_market(const std::string& path, const Eigen::MatrixXd& A, const std::string& comment,
                         const std::string& option) {
    std::vector<Entry> entries;
    for (Eigen::Index j = 0; j < A.cols(); ++j)
        for (Eigen::Index i = 0; i < A.rows(); ++i)
            if (stored(A(i, j)) || !std::isfinite(A(i, j))) entries.push_back({i + 1, j + 1, A(i, j)});
    write_entries(path, A.rows(), A.cols(), entries, comment, option);
}

void write_matrix_market(const std::string& path, const Eigen::SparseMatrix<double>& A, const std::string& comment,
                         const std::string& option) {
    Eigen::SparseMatrix<double> S = A;   // column order with sorted rows
    S.makeCompressed();
    std::vector<Entry> entries;
    entries.reserve(static_cast<size_t>(S.nonZeros()));
    for (Eigen::Index j = 0; j < S.outerSize(); ++j)
        for (Eigen::SparseMatrix<double>::InnerIterator it(S, j); it; ++it)
            if (stored(it.value()) || !std::isfinite(it.value())) entries.push_back({it.row() + 1, j + 1, it.value()});
    write_entries(path, S.rows(), S.cols(), entries, comment, option);
}

}  // namespace gyrokit
