// Tests of the Matrix Market reader/writer: round trips, symmetry expansion,
// array and complex input, and one strict one-line error per kind of bad file.
#include <gyrokit/io/matrix_market.hpp>

#include <gyrokit/core/error.hpp>

#include <catch2/catch.hpp>

#include <cfloat>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using gyrokit::read_matrix_market;
using gyrokit::read_matrix_market_vector;
using gyrokit::write_matrix_market;

namespace {

// A fresh directory under the system temp dir, removed when the tests end.
const fs::path& scratch_dir() {
    struct Dir {
        fs::path path;
        Dir() {
            path = fs::temp_directory_path() / ("gyrokit_mm_" + std::to_string(std::random_device{}()));
            fs::create_directories(path);
        }
        ~Dir() {
            std::error_code ec;
            fs::remove_all(path, ec);
        }
    };
    static const Dir dir;
    return dir.path;
}

std::string write_file(const std::string& name, const std::string& text) {
    const std::string path = (scratch_dir() / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

// Message of the InputError thrown by f; fails the test if none is thrown.
std::string input_error(const std::function<void()>& f) {
    try {
        f();
    } catch (const gyrokit::InputError& e) {
        return e.what();
    }
    FAIL("no gyrokit::InputError thrown");
    return "";
}

bool bitwise_equal(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
    return a.rows() == b.rows() && a.cols() == b.cols() &&
           std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

}  // namespace

TEST_CASE("write/read round trip is bitwise exact", "[io][matrix_market]") {
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
    std::uniform_int_distribution<int> exponent(-300, 300);
    Eigen::MatrixXd A(7, 5);
    for (Eigen::Index k = 0; k < A.size(); ++k) A.data()[k] = mantissa(rng) * std::pow(10.0, exponent(rng));
    A(0, 0) = 1e-300;
    A(1, 0) = 1e300;
    A(2, 0) = -1e300;
    A(3, 0) = 0.1;
    A(4, 0) = DBL_MAX;
    A(5, 0) = 4.9406564584124654e-324;  // smallest subnormal
    A(6, 0) = -0.0;                     // kept by the writer so signs survive
    A(0, 1) = 0.0;                      // zeros are not written and read back as zero
    A.col(2).setZero();

    const std::string path = (scratch_dir() / "round_trip.mtx").string();
    write_matrix_market(path, A, "round trip\nsecond comment line");
    CHECK(bitwise_equal(read_matrix_market(path), A));

    std::ifstream in(path);
    std::string banner, comment1, comment2;
    std::getline(in, banner);
    std::getline(in, comment1);
    std::getline(in, comment2);
    CHECK(banner == "%%MatrixMarket matrix coordinate real general");
    CHECK(comment1 == "% round trip");
    CHECK(comment2 == "% second comment line");
}

TEST_CASE("writer errors", "[io][matrix_market]") {
    const Eigen::MatrixXd A = Eigen::MatrixXd::Identity(2, 2);
    CHECK_THROWS_AS(write_matrix_market((scratch_dir() / "no_such_dir" / "A.mtx").string(), A), gyrokit::Error);
    Eigen::MatrixXd B = A;
    B(1, 0) = std::nan("");
    CHECK_THROWS_AS(write_matrix_market((scratch_dir() / "nan.mtx").string(), B), gyrokit::InputError);
    CHECK_THROWS_AS(write_matrix_market((scratch_dir() / "empty.mtx").string(), Eigen::MatrixXd(0, 3)),
                    gyrokit::InputError);
}

TEST_CASE("coordinate symmetric and skew-symmetric expansion", "[io][matrix_market]") {
    const auto S = read_matrix_market(write_file("sym.mtx",
                                                 "%%MatrixMarket matrix coordinate real symmetric\n"
                                                 "% lower triangle\n"
                                                 "\n"
                                                 "3 3 4\n"
                                                 "1 1 2.0\n"
                                                 "2 1 -1.0\n"
                                                 "3 2 -1.5\n"
                                                 "1 3 0.5\n"));  // upper-triangle entries are mirrored too
    Eigen::Matrix3d S_expected;
    S_expected << 2.0, -1.0, 0.5, -1.0, 0.0, -1.5, 0.5, -1.5, 0.0;
    CHECK(S == S_expected);

    const auto K = read_matrix_market(write_file("skew.mtx",
                                                 "%%MatrixMarket matrix coordinate integer skew-symmetric\n"
                                                 "3 3 2\n"
                                                 "2 1 4\n"
                                                 "1 3 -7\n"));
    Eigen::Matrix3d K_expected;
    K_expected << 0, -4, -7, 4, 0, 0, 7, 0, 0;
    CHECK(K == K_expected);
}

TEST_CASE("array format, case-insensitive banner and CRLF lines", "[io][matrix_market]") {
    const auto G = read_matrix_market(write_file("general_array.mtx",
                                                 "%%MatrixMarket Matrix ARRAY Real General\r\n"
                                                 "2 3\r\n1\r\n2\r\n3\r\n4\r\n5\r\n+6e0\r\n"));
    Eigen::MatrixXd G_expected(2, 3);
    G_expected << 1, 3, 5, 2, 4, 6;  // column-major
    CHECK(G == G_expected);

    const auto S = read_matrix_market(write_file("sym_array.mtx",
                                                 "%%MatrixMarket matrix array real symmetric\n"
                                                 "3 3\n1\n2\n3\n4\n5\n6\n"));  // lower triangle by columns
    Eigen::Matrix3d S_expected;
    S_expected << 1, 2, 3, 2, 4, 5, 3, 5, 6;
    CHECK(S == S_expected);

    const auto K = read_matrix_market(write_file("skew_array.mtx",
                                                 "%%MatrixMarket matrix array real skew-symmetric\n"
                                                 "3 3\n1\n2\n3\n"));  // strictly lower triangle
    Eigen::Matrix3d K_expected;
    K_expected << 0, -1, -2, 1, 0, -3, 2, 3, 0;
    CHECK(K == K_expected);
}

TEST_CASE("vector reading: complex, real, row and column", "[io][matrix_market]") {
    using C = std::complex<double>;
    const auto a = read_matrix_market_vector(write_file("cvec_array.mtx",
                                                        "%%MatrixMarket matrix array complex general\n"
                                                        "3 1\n1.5 -2\n0 0\n-3e-5 4.25\n"));
    CHECK(a == Eigen::Vector3cd(C(1.5, -2), C(0, 0), C(-3e-5, 4.25)));

    const auto c = read_matrix_market_vector(write_file("cvec_coord.mtx",
                                                        "%%MatrixMarket matrix coordinate complex general\n"
                                                        "1 4 2\n1 2 1 1\n1 4 0 -1\n"));
    CHECK(c == Eigen::Vector4cd(C(0, 0), C(1, 1), C(0, 0), C(0, -1)));

    const auto r = read_matrix_market_vector(write_file("rvec.mtx",
                                                        "%%MatrixMarket matrix array real general\n"
                                                        "2 1\n7\n-8\n"));
    CHECK(r == Eigen::Vector2cd(C(7, 0), C(-8, 0)));
}

TEST_CASE("bad files throw one-line InputErrors naming file, line and value", "[io][matrix_market]") {
    struct Case {
        const char* name;     // file name, expected in the message
        std::string text;     // file content
        int line;             // expected "line N:" (0: none)
        const char* fragment; // expected part of the message
        bool vector = false;  // read with read_matrix_market_vector
    };
    const std::string B = "%%MatrixMarket matrix coordinate real general\n";
    const std::vector<Case> cases = {
        {"empty.mtx", "", 0, "file is empty"},
        {"no_banner.mtx", "3 3 1\n1 1 1\n", 1, "missing banner"},
        {"short_banner.mtx", "%%MatrixMarket matrix coordinate real\n1 1 0\n", 1, "banner"},
        {"long_banner.mtx", "%%MatrixMarket matrix coordinate real general x\n1 1 0\n", 1, "unexpected text 'x'"},
        {"object.mtx", "%%MatrixMarket vector coordinate real general\n1 1 0\n", 1, "object 'vector'"},
        {"format.mtx", "%%MatrixMarket matrix sparse real general\n1 1 0\n", 1, "format 'sparse'"},
        {"pattern.mtx", "%%MatrixMarket matrix coordinate pattern general\n1 1 0\n", 1, "field 'pattern'"},
        {"complex.mtx", "%%MatrixMarket matrix coordinate complex general\n1 1 0\n", 1, "field 'complex'"},
        {"hermitian.mtx", "%%MatrixMarket matrix coordinate real hermitian\n1 1 0\n", 1, "symmetry 'hermitian'"},
        {"no_size.mtx", (B + "% only a comment\n\n"), 3, "size line"},
        {"size_word.mtx", (B + "3 x 1\n"), 2, "columns 'x' is not an integer"},
        {"size_short.mtx", (B + "3 3\n"), 2, "size line '3 3' is incomplete"},
        {"size_long.mtx", (B + "3 3 0 9\n"), 2, "unexpected text '9'"},
        {"size_zero.mtx", (B + "0 3 0\n"), 2, "rows 0 is not positive"},
        {"size_negative.mtx", (B + "3 -2 0\n"), 2, "columns -2 is not positive"},
        {"nnz_negative.mtx", (B + "2 2 -1\n"), 2, "entry count -1"},
        {"nnz_large.mtx", (B + "2 2 5\n"), 2, "entry count 5"},
        {"too_few.mtx", (B + "3 3 3\n1 1 1\n2 2 1\n"), 4, "file ends after 2 of the 3 entries"},
        {"too_many.mtx", (B + "3 3 1\n1 1 1\n2 2 1\n"), 4, "extra entry '2 2 1'"},
        {"array_few.mtx", "%%MatrixMarket matrix array real general\n2 2\n1\n2\n3\n", 5, "3 of the 4 entries"},
        {"sym_array_many.mtx", "%%MatrixMarket matrix array real symmetric\n2 2\n1\n2\n3\n4\n", 6,
         "beyond the 3 entries"},
        {"skew_array_many.mtx", "%%MatrixMarket matrix array real skew-symmetric\n3 3\n1\n2\n3\n4\n", 6,
         "beyond the 3 entries"},
        {"out_of_range.mtx", (B + "6 6 1\n3 9 1.0\n"), 3,
         "entry (3, 9) is outside the 6x6 matrix; allowed rows 1..6, columns 1..6"},
        {"zero_index.mtx", (B + "2 2 1\n0 1 1.0\n"), 3, "entry (0, 1) is outside"},
        {"bad_index.mtx", (B + "2 2 1\n1.0 1 1.0\n"), 3, "row index '1.0' is not an integer"},
        {"bad_value.mtx", (B + "2 2 1\n1 1 abc\n"), 3, "value 'abc' is not a number"},
        {"half_value.mtx", (B + "2 2 1\n1 1 1.5x\n"), 3, "value '1.5x' is not a number"},
        {"nan.mtx", (B + "2 2 1\n1 1 nan\n"), 3, "value 'nan' is not a finite number"},
        {"inf.mtx", (B + "2 2 1\n1 1 -inf\n"), 3, "value '-inf' is not a finite number"},
        {"overflow.mtx", (B + "2 2 1\n1 1 1e400\n"), 3, "value '1e400' is outside the range"},
        {"integer_field.mtx", "%%MatrixMarket matrix coordinate integer general\n2 2 1\n1 1 1.5\n", 3,
         "value '1.5' is not an integer"},
        {"not_square.mtx", "%%MatrixMarket matrix coordinate real symmetric\n3 4 0\n", 2, "must be square, got 3x4"},
        {"skew_diag.mtx", "%%MatrixMarket matrix coordinate real skew-symmetric\n3 3 1\n2 2 1\n", 3,
         "entry (2, 2) is on the diagonal"},
        {"duplicate.mtx", (B + "3 3 3\n1 2 1\n% comment\n2 2 1\n1 2 5\n"), 6,
         "entry (1, 2) repeats the entry on line 3"},
        {"sym_duplicate.mtx", "%%MatrixMarket matrix coordinate real symmetric\n3 3 2\n2 1 1\n1 2 1\n", 4,
         "entry (1, 2) repeats the entry on line 3"},
        {"trailing.mtx", (B + "2 2 1\n1 1 1.0 x\n"), 3, "unexpected text 'x'"},
        {"array_trailing.mtx", "%%MatrixMarket matrix array real general\n2 1\n1.0 2.0\n2.0\n", 3,
         "unexpected text '2.0'"},
        {"short_entry.mtx", (B + "2 2 1\n1 1\n"), 3, "entry '1 1' is incomplete"},
        {"not_vector.mtx", "%%MatrixMarket matrix array real general\n2 2\n1\n2\n3\n4\n", 2,
         "size 2x2 is not a vector", true},
        {"complex_short.mtx", "%%MatrixMarket matrix array complex general\n2 1\n1 2\n3\n", 4,
         "entry '3' is incomplete", true},
        {"vector_hermitian.mtx", "%%MatrixMarket matrix array complex hermitian\n1 1\n1 0\n", 1,
         "symmetry 'hermitian'", true},
    };
    for (const Case& c : cases) {
        INFO(c.name);
        const std::string path = write_file(c.name, c.text);
        const std::string msg = input_error([&] {
            if (c.vector) read_matrix_market_vector(path);
            else read_matrix_market(path);
        });
        INFO(msg);
        CHECK(msg.find(path) == 0);
        if (c.line > 0) CHECK(msg.find(": line " + std::to_string(c.line) + ": ") != std::string::npos);
        CHECK(msg.find(c.fragment) != std::string::npos);
        CHECK(msg.find('\n') == std::string::npos);
    }
}

TEST_CASE("missing and unreadable files throw InputError naming the path", "[io][matrix_market]") {
    const std::string missing = (scratch_dir() / "missing.mtx").string();
    std::string msg = input_error([&] { read_matrix_market(missing); });
    CHECK(msg.find(missing) != std::string::npos);
    CHECK(msg.find("not found") != std::string::npos);

    const std::string dir = scratch_dir().string();
    msg = input_error([&] { read_matrix_market_vector(dir); });
    CHECK(msg.find(dir) != std::string::npos);
    CHECK(msg.find("is a directory") != std::string::npos);
}

TEST_CASE("hostile size lines are refused before any arithmetic on the sizes", "[io][matrix_market][reliability]") {
    // rows * rows, rows * (rows + 1) / 2 and the cell key j * rows + i would overflow
    // a 64-bit integer for sizes near 3e9 and above: refused on the size line.
    for (const char* sym : {"general", "symmetric", "skew-symmetric"}) {
        const std::string path = write_file(std::string("huge_") + sym + ".mtx",
                                            std::string("%%MatrixMarket matrix coordinate real ") + sym +
                                                "\n4000000000 4000000000 1\n2 1 1.0\n");
        CHECK(input_error([&] { gyrokit::read_matrix_market_sparse(path); }).find("line 2: size 4000000000x4000000000 is too "
                                                                         "large; allowed at most 20000000") !=
              std::string::npos);
    }
    const std::string path = write_file("huge_cols.mtx", "%%MatrixMarket matrix coordinate real general\n"
                                                         "1 9223372036854775807 1\n1 1 1.0\n");
    CHECK(input_error([&] { gyrokit::read_matrix_market_sparse(path); }).find("is too large") != std::string::npos);
    // Found by fuzz_matrix_market: a size line with no entries made the sparse result
    // allocate index arrays for 506 million rows (2 GB) before anything else.
    const std::string empty = write_file("tall_empty.mtx", "%%MatrixMarket matrix coordinate real general\n"
                                                           "0000000000000000506234049 42 0\n");
    CHECK(input_error([&] { gyrokit::read_matrix_market_sparse(empty); }).find("size 506234049x42 is too large") !=
          std::string::npos);
    CHECK(input_error([&] { gyrokit::read_matrix_market_vector(empty); }).find("is too large") != std::string::npos);
    // The dense result: at most 25 million cells, whatever the entry count says.
    const std::string wide = write_file("dense_wide.mtx", "%%MatrixMarket matrix coordinate real general\n"
                                                          "6000 6000 1\n1 1 1.0\n");
    CHECK(input_error([&] { gyrokit::read_matrix_market(wide); }).find("too large for a dense matrix") !=
          std::string::npos);
    CHECK(gyrokit::read_matrix_market_sparse(wide).nonZeros() == 1);
}
