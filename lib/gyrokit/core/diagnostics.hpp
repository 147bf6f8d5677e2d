// What an analysis says besides its result: notes and warnings, typed, returned
// with the result so that every front end shows the same ones (the CLI on
// stderr, Python as the result's notes and warnings). Texts may name option
// fields (option_field), which each front end writes in its own words.
#pragma once

#include <string>
#include <vector>

namespace gyrokit {

struct Diagnostic {
    enum class Level { Note, Warning };
    // What it is about, so that a front end can leave out what its output already shows.
    enum class Topic {
        Solver,          // the solver choice and its steps (fallbacks, windows)
        Extrapolation,   // bearing tables used beyond their speeds
        RigidBody,       // rigid-body eigenvalues left out of the tracking
        Ambiguity,       // speed steps the tracking could not decide
        Instability,     // unstable ranges (warnings)
        OutOfRange,      // modes beyond the excitation band, not judged
        Verdict          // what the result means where its table is empty
    };
    Level level = Level::Note;
    Topic topic = Topic::Solver;
    std::string text;
};

using Diagnostics = std::vector<Diagnostic>;

inline void add_notes(Diagnostics& d, Diagnostic::Topic topic, const std::vector<std::string>& texts) {
    for (const auto& t : texts) d.push_back({Diagnostic::Level::Note, topic, t});
}

}  // namespace gyrokit
