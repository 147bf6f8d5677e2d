// gyrokit: command-line front end. Parses options, calls the library, prints.
// Exit status: 0 success, 2 bad input, 3 solver failure, 1 anything else.
#include "cli/common.hpp"
#include "core/error.hpp"

#include <iostream>

using namespace gyrokit;

int main(int argc, char** argv) {
    CLI::App app{"gyrokit: Campbell diagrams, critical speeds, pervasive damping and unbalance response "
                 "of gyroscopic systems"};
    app.require_subcommand(1);
    std::vector<cli::Command> commands = cli::add_rotor_commands(app);
    // Further command groups register here, one line each.
    for (auto& c : cli::add_balancer_commands(app)) commands.push_back(std::move(c));
    for (auto& c : cli::add_fluid_commands(app)) commands.push_back(std::move(c));
    for (auto& c : cli::add_screen_commands(app)) commands.push_back(std::move(c));
    for (auto& c : cli::add_sommerfeld_commands(app)) commands.push_back(std::move(c));

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << "error: " << e.what() << " (see --help)\n";
        return 2;
    }
    try {
        for (const auto& c : commands)
            if (c.app->parsed()) c.run(std::cout);
        // Nothing counts as written until it is flushed: a full disk or a closed
        // pipe shows only here for output that fits the stream's buffer.
        std::cout.flush();
        if (!std::cout) throw Error("cannot write the output (disk full, or the reading end was closed)");
    } catch (const InputError& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 2;
    } catch (const SolverError& e) {
        std::cerr << "solver error: " << e.what() << "\n";
        return 3;
    } catch (const std::exception& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
