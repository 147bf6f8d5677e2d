// Tabular results (mode lists, Campbell data, sweeps) written as aligned text
// for people, CSV for spreadsheets, or JSON for scripts, from one Table.
#pragma once

#include <gyrokit/core/error.hpp>

#include <cstddef>
#include <ostream>
#include <string>
#include <variant>
#include <vector>

namespace gyrokit {

enum class TableFormat { Text, Csv, Json };

// "table" | "csv" | "json"; anything else is an InputError naming the value
// and the allowed values.
TableFormat parse_table_format(const std::string& s);

// A cell: a number (double), an integer, a string or a bool.
using Cell = std::variant<double, long long, std::string, bool>;

class Table {
public:
    // Throws gyrokit::Error on duplicate column names (they would collide as JSON keys).
    explicit Table(std::vector<std::string> columns);

    // Throws gyrokit::Error if the row's size differs from the column count.
    void add_row(std::vector<Cell> row);

    const std::vector<std::string>& columns() const { return columns_; }
    std::size_t rows() const { return rows_.size(); }
    const std::vector<Cell>& row(std::size_t i) const { return rows_.at(i); }

    std::string title;   // optional; printed as a heading line in Text format only
    std::string key;     // stable snake_case identifier: the JSON key among several tables, --table NAME

private:
    std::vector<std::string> columns_;
    std::vector<std::vector<Cell>> rows_;
};

// The front end's words for the option fields that titles and text cells name
// (option_field marks, e.g. "modes" -> "--modes" in the CLI, "modes =" in Python):
// set once at startup, before any table is written. Unset: "modes =".
void set_field_spelling(FieldSpelling spell);
// A text with option_field marks (a title, a cell, a note, an error) in that spelling:
// what write_table does to its strings, for writers of other formats (the HTML report).
std::string spelled_text(const std::string& marked);

// Writes the table.
//  Text: optional title line, header, rule, aligned rows (all padded to one
//        width); numbers %.6g and right-aligned, strings and bools left-aligned.
//  Csv:  header then rows; numbers %.12g; RFC 4180 quoting only where needed;
//        bools true/false.
//  Json: an array of objects (keys = column names, in column order); doubles
//        at full round-trip precision.
// +-inf prints as inf/-inf (JSON: the strings "inf"/"-inf"). A NaN cell is a bug
// upstream: it throws gyrokit::Error naming the column, and nothing is written.
void write_table(std::ostream& os, const Table& t, TableFormat f);

// Several tables in one output. Text: each with its title, a blank line between.
// Json: one object mapping each table's key (or "table<i>", i counted from 1, for
// a table without one) to its array; two tables with the same key throw
// gyrokit::Error. Csv holds one table: more than one throws gyrokit::Error
// (select one with select_table).
void write_tables(std::ostream& os, const std::vector<Table>& ts, TableFormat f);

// What a command writes: with `key`, the table of that key alone (`option` names
// it in the error); otherwise every table (Text, Json) or the first (Csv holds one
// table), the keys of the tables left out in `left_out`.
void write_result(std::ostream& os, const std::vector<Table>& ts, TableFormat f, const std::string& key,
                  const std::string& option, std::vector<std::string>& left_out);

// The table whose key is `key`; an InputError naming `option`, the value and the
// keys there are otherwise.
const Table& select_table(const std::vector<Table>& ts, const std::string& key, const std::string& option);

}  // namespace gyrokit
