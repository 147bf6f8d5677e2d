#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/io/table.hpp>

using namespace gyrokit;

namespace {

const double kInf = std::numeric_limits<double>::infinity();
const double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string write(const Table& t, TableFormat f) {
    std::ostringstream os;
    write_table(os, t, f);
    return os.str();
}

std::vector<std::string> lines(const std::string& s) {
    std::vector<std::string> out;
    std::istringstream in(s);
    for (std::string l; std::getline(in, l);) out.push_back(l);
    return out;
}

std::string printf_g(double v, int digits) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    return buf;
}

// Values whose %.12g and full-precision forms differ, plus extremes.
const std::vector<double> values = {1.0 / 3.0, -M_PI * 1e5, 6.02214076e23, -1.5e-300, 0.1, 0.0, 123456789012345.0};

}  // namespace

TEST_CASE("parse_table_format accepts table, csv, json only") {
    CHECK(parse_table_format("table") == TableFormat::Text);
    CHECK(parse_table_format("csv") == TableFormat::Csv);
    CHECK(parse_table_format("json") == TableFormat::Json);
    try {
        parse_table_format("xml");
        FAIL("no exception");
    } catch (const InputError& e) {
        const std::string msg = e.what();
        CHECK(msg.find("'xml'") != std::string::npos);
        CHECK(msg.find("table, csv, json") != std::string::npos);
    }
}

TEST_CASE("a row of the wrong size and duplicate columns throw") {
    Table t({"a", "b"});
    CHECK_THROWS_AS(t.add_row({1.0}), Error);
    CHECK_THROWS_AS(t.add_row({1.0, 2LL, true}), Error);
    CHECK(t.rows() == 0);
    t.add_row({1.0, std::string("x")});
    CHECK(t.rows() == 1);
    CHECK(std::get<std::string>(t.row(0)[1]) == "x");
    CHECK_THROWS_AS(Table({"a", "a"}), Error);
}

TEST_CASE("CSV quotes only where RFC 4180 needs it") {
    Table t({"name", "n, count", "ok"});
    t.add_row({std::string("plain"), 42LL, true});
    t.add_row({std::string("a,b"), -7LL, false});
    t.add_row({std::string("say \"hi\""), 0LL, true});
    t.add_row({std::string("two\nlines"), 1LL, false});
    t.title = "ignored in CSV";
    CHECK(write(t, TableFormat::Csv) ==
          "name,\"n, count\",ok\n"
          "plain,42,true\n"
          "\"a,b\",-7,false\n"
          "\"say \"\"hi\"\"\",0,true\n"
          "\"two\nlines\",1,false\n");
}

TEST_CASE("CSV numbers have 12 significant digits and parse back exactly") {
    Table t({"v"});
    for (double v : values) t.add_row({v});
    const auto ls = lines(write(t, TableFormat::Csv));
    REQUIRE(ls.size() == values.size() + 1);
    for (std::size_t i = 0; i < values.size(); ++i) {
        CAPTURE(i);
        const std::string expected = printf_g(values[i], 12);
        CHECK(ls[i + 1] == expected);
        CHECK(std::strtod(ls[i + 1].c_str(), nullptr) == std::strtod(expected.c_str(), nullptr));
    }
}

TEST_CASE("JSON parses back to the same values, keys in column order") {
    Table t({"omega", "n", "name", "stable"});
    for (std::size_t i = 0; i < values.size(); ++i)
        t.add_row({values[i], static_cast<long long>(i) - 3, "mode \"" + std::to_string(i) + "\" ω", i % 2 == 0});
    t.add_row({kInf, 1LL << 53, std::string(), false});
    t.add_row({-kInf, std::numeric_limits<long long>::min(), std::string("x"), true});

    const auto j = nlohmann::ordered_json::parse(write(t, TableFormat::Json));
    REQUIRE(j.is_array());
    REQUIRE(j.size() == t.rows());
    for (std::size_t i = 0; i < values.size(); ++i) {
        CAPTURE(i);
        const auto& r = j[i];
        std::vector<std::string> keys;
        for (auto it = r.begin(); it != r.end(); ++it) keys.push_back(it.key());
        CHECK(keys == t.columns());
        CHECK(r["omega"].get<double>() == values[i]);   // full precision, exact
        CHECK(r["n"].is_number_integer());
        CHECK(r["n"].get<long long>() == static_cast<long long>(i) - 3);
        CHECK(r["name"].get<std::string>() == "mode \"" + std::to_string(i) + "\" ω");
        CHECK(r["stable"].get<bool>() == (i % 2 == 0));
    }
    CHECK(j[values.size()]["omega"] == "inf");
    CHECK(j[values.size()]["n"].get<long long>() == (1LL << 53));
    CHECK(j[values.size() + 1]["omega"] == "-inf");
    CHECK(j[values.size() + 1]["n"].get<long long>() == std::numeric_limits<long long>::min());

    CHECK(nlohmann::json::parse(write(Table({"a"}), TableFormat::Json)) == nlohmann::json::array());
}

TEST_CASE("Text is aligned: numbers right, strings left, 6 significant digits") {
    Table t({"mode", "f (Hz)", "whirl", "ω"});
    t.add_row({1LL, M_PI, std::string("forward"), true});
    t.add_row({12LL, -1234567.0, std::string("bw"), false});
    t.add_row({3LL, kInf, std::string("real"), true});
    t.add_row({4LL, -kInf, std::string("ω-wise"), true});
    t.title = "Modes";
    const auto ls = lines(write(t, TableFormat::Text));
    REQUIRE(ls.size() == 7);   // title, header, rule, 4 rows
    CHECK(ls[0] == "Modes");

    // Width in code points, since the table counts UTF-8 characters.
    auto width = [](const std::string& s) {
        std::size_t n = 0;
        for (unsigned char c : s) n += (c & 0xC0) != 0x80;
        return n;
    };
    for (std::size_t i = 2; i < ls.size(); ++i) {
        CAPTURE(i);
        CHECK(width(ls[i]) == width(ls[1]));
    }

    CHECK(ls[1] == "mode        f (Hz)  whirl    ω    ");
    CHECK(ls[2] == "----  ------------  -------  -----");
    CHECK(ls[3] == "   1       3.14159  forward  true ");
    CHECK(ls[4] == "  12  -1.23457e+06  bw       false");
    CHECK(ls[5] == "   3           inf  real     true ");
    CHECK(ls[6] == "   4          -inf  ω-wise   true ");

    // No title, no rows: just the header and the rule.
    CHECK(write(Table({"a", "bb"}), TableFormat::Text) == "a  bb\n-  --\n");
}

TEST_CASE("infinities print as inf and -inf in CSV") {
    Table t({"x"});
    t.add_row({kInf});
    t.add_row({-kInf});
    CHECK(write(t, TableFormat::Csv) == "x\ninf\n-inf\n");
}

TEST_CASE("a NaN cell throws naming the column and writes nothing") {
    Table t({"omega", "zeta"});
    t.title = "modes";
    t.add_row({1.0, 0.5});
    t.add_row({2.0, kNaN});
    for (auto f : {TableFormat::Text, TableFormat::Csv, TableFormat::Json}) {
        CAPTURE(f);
        std::ostringstream os;
        try {
            write_table(os, t, f);
            FAIL("no exception");
        } catch (const Error& e) {
            CHECK(std::string(e.what()).find("'zeta'") != std::string::npos);
        }
        CHECK(os.str().empty());
        std::ostringstream os2;
        CHECK_THROWS_AS(write_tables(os2, {Table({"a"}), t}, f), Error);
        CHECK(os2.str().empty());
    }
}

TEST_CASE("write_tables joins several tables, CSV holds one, write_result selects by key") {
    Table a({"x"}), b({"y"}), c({"z"});
    a.title = "first table";
    a.key = "first";
    a.add_row({1LL});
    b.add_row({2.5});
    c.title = "third (at w = 3.5)";
    c.key = "third";
    const std::vector<Table> ts{a, b, c};

    std::ostringstream text, csv, json;
    write_tables(text, ts, TableFormat::Text);
    CHECK_THROWS_AS(write_tables(csv, ts, TableFormat::Csv), Error);
    CHECK(csv.str().empty());
    write_tables(json, ts, TableFormat::Json);
    CHECK(text.str() == "first table\nx\n-\n1\n\n  y\n---\n2.5\n\nthird (at w = 3.5)\nz\n-\n");

    // JSON keys are the stable keys, never the human titles.
    const auto j = nlohmann::ordered_json::parse(json.str());
    REQUIRE(j.is_object());
    std::vector<std::string> keys;
    for (auto it = j.begin(); it != j.end(); ++it) keys.push_back(it.key());
    CHECK(keys == std::vector<std::string>{"first", "table2", "third"});
    CHECK(j["first"][0]["x"] == 1);
    CHECK(j["table2"][0]["y"].get<double>() == 2.5);
    CHECK((j["third"].is_array() && j["third"].empty()));

    std::ostringstream dup;
    CHECK_THROWS_AS(write_tables(dup, {a, a}, TableFormat::Json), Error);

    // write_result: CSV writes the first table and names the others; a key selects one.
    std::ostringstream one, chosen, bad;
    std::vector<std::string> left;
    write_result(one, ts, TableFormat::Csv, "", "--table", left);
    CHECK(one.str() == "x\n1\n");
    CHECK(left == std::vector<std::string>{"", "third"});
    left.clear();
    write_result(chosen, ts, TableFormat::Csv, "third", "--table", left);
    CHECK(chosen.str() == "z\n");
    CHECK(left.empty());
    try {
        write_result(bad, ts, TableFormat::Json, "fourth", "--table", left);
        FAIL("no exception");
    } catch (const InputError& e) {
        CHECK(std::string(e.what()) == "--table 'fourth': allowed: first, , third");
    }
}
