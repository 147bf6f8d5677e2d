// gyrokit: command-line front end. Parses options, calls the library, prints.
// Exit status: 0 success, 2 bad input, 3 solver failure, 1 anything else.
#include "cli/common.hpp"
#include <gyrokit/core/error.hpp>
#include <gyrokit/core/run_files.hpp>
#include <gyrokit/io/table.hpp>

#include <algorithm>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

using namespace gyrokit;

namespace {

// Levenshtein distance: how many letters to insert, delete or change.
std::size_t edit_distance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diagonal = up;
        }
    }
    return row[b.size()];
}

// The nearest of `candidates` to `given` if at most two letters away (a typo), else "".
std::string nearest_name(const std::string& given, const std::vector<std::string>& candidates) {
    std::string nearest;
    std::size_t best = 3;
    for (const auto& c : candidates) {
        const std::size_t d = edit_distance(given, c);
        if (d < best) best = d, nearest = c;
    }
    return nearest;
}

// A mistyped option of the chosen command: name the nearest one it has.
std::string option_hint(const CLI::App& app, int argc, char** argv) {
    for (const CLI::App* sub : app.get_subcommands()) {
        std::vector<std::string> flags;
        for (const CLI::Option* opt : sub->get_options())
            for (const auto& name : opt->get_lnames()) flags.push_back("--" + name);
        for (int i = 2; i < argc; ++i) {
            std::string arg = argv[i];
            if (arg.rfind("--", 0) != 0 || arg == "--") continue;
            arg = arg.substr(0, arg.find('='));
            if (std::find(flags.begin(), flags.end(), arg) != flags.end()) continue;
            const std::string near = nearest_name(arg, flags);
            if (!near.empty()) return "; did you mean '" + near + "'?";
        }
    }
    return "";
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"gyrokit: Campbell diagrams, critical speeds, pervasive damping and unbalance response "
                 "of gyroscopic systems"};
    app.require_subcommand(1);
    set_field_spelling(cli::flag_words);   // tables name the options as flags
    std::vector<cli::Command> commands;
#define GYROKIT_ADD_COMMAND_GROUP(name) \
    for (auto& c : cli::add_##name##_commands(app)) commands.push_back(std::move(c));
    GYROKIT_COMMAND_GROUPS(GYROKIT_ADD_COMMAND_GROUP)
#undef GYROKIT_ADD_COMMAND_GROUP

    app.name("gyrokit");
    app.set_version_flag("--version", std::string("gyrokit ") + GYROKIT_VERSION);
    // No command: the list of commands, as --help shows it.
    if (argc == 1) {
        std::cout << app.help();
        return 0;
    }
    // A mistyped command: name the nearest one.
    if (argv[1][0] != '-') {
        const std::string given = argv[1];
        std::vector<std::string> names;
        for (const auto& c : commands) names.push_back(c.app->get_name());
        if (std::find(names.begin(), names.end(), given) == names.end()) {
            const std::string near = nearest_name(given, names);
            std::cerr << "error: unknown command '" << given << "'"
                      << (near.empty() ? "" : "; did you mean '" + near + "'?") << " (see --help)\n";
            return 2;
        }
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << "error: " << e.what() << option_hint(app, argc, argv) << " (see --help)\n";
        return 2;
    }
    try {
        // One run: every input read once, every output file claimed before any work.
        RunFiles files;
        RunScope scope(files);
        for (const auto& c : commands)
            if (c.app->parsed()) {
                cli::claim_outputs(*c.app);
                c.run(std::cout);
            }
        // Nothing counts as written until it is flushed: a full disk or a closed
        // pipe shows only here for output that fits the stream's buffer.
        std::cout.flush();
        if (!std::cout) throw Error("cannot write the output (disk full, or the reading end was closed)");
        files.check_inputs_unchanged();
    } catch (const InputError& e) {
        std::cerr << "error: " << e.message(cli::flag_words) << "\n";
        return 2;
    } catch (const SolverError& e) {
        std::cerr << "solver error: " << e.message(cli::flag_words) << "\n";
        return 3;
    } catch (const std::exception& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
