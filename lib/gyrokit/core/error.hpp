// Error types of gyrokit. Every library failure is an exception derived from
// gyrokit::Error, so applications catch one type at main and exit non-zero.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace gyrokit {

// An option field named inside an error message: option_field("modes") in the
// text reads "modes =" in what(), and each front end writes it in its own
// words through Error::message (the CLI "--modes", Python "modes ="), from one
// table of its own; no front end rewrites the library's prose.
std::string option_field(const std::string& name);
// The same field named as a noun ("run_up needs acceleration"): Python writes it
// without " =", the CLI as its flag.
std::string option_noun(const std::string& name);

// How a front end writes an option field (name -> words); empty words keep the
// library's "name =".
using FieldSpelling = std::function<std::string(const std::string& name)>;
// A text with option_field marks (an error's, a note's) in a front end's words.
std::string spell_fields(const std::string& marked, const FieldSpelling& spell);

// Base of every error the library throws.
class Error : public std::runtime_error {
public:
    explicit Error(const std::string& text);
    explicit Error(const char* text) : Error(std::string(text)) {}
    // The message with each option field in the front end's words.
    std::string message(const FieldSpelling& spell) const;
    // The option fields the message names, in order.
    std::vector<std::string> fields() const;
    // The text with its field marks, to carry the error whole (e.g. out of a
    // worker process) and rebuild it with the same type.
    const std::string& marked_text() const { return text_; }

private:
    std::string text_;
};

// Bad input: a scene key, a matrix file, a command-line value. The message names
// the file or option, the key, the offending value and the allowed range.
class InputError : public Error {
public:
    using Error::Error;
};

// A numerical method failed (singular matrix, no convergence). The message says
// what to change.
class SolverError : public Error {
public:
    using Error::Error;
};

// A model parameter built in code, checked as a scene key is: InputError
// "ORIGIN: KEY = V: out of range; allowed: ALLOWED" where !ok, and for a subnormal
// value (0 < |v| < 2.2e-308: it has lost precision, and a written scene would not
// read back).
void check_parameter(bool ok, const std::string& origin, const char* key, double v, const char* allowed);

}  // namespace gyrokit
