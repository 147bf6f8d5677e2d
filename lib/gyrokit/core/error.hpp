// Error types of gyrokit. Every library failure is an exception derived from
// gyrokit::Error, so applications catch one type at main and exit non-zero.
#pragma once

#include <stdexcept>
#include <string>

namespace gyrokit {

// Base of every error the library throws.
class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
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

}  // namespace gyrokit
