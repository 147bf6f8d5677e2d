// defaults: the table of defaults every command and the Python module use
// (study/defaults.hpp), as docs/defaults.md lists it.
#include "cli/common.hpp"

#include <gyrokit/study/defaults.hpp>

#include <memory>

namespace gyrokit::cli {

std::vector<Command> add_defaults_commands(CLI::App& app) {
    auto format = std::make_shared<std::string>("table");
    auto* cmd = app.add_subcommand("defaults", "the defaults of every command and Python call (docs/defaults.md)");
    cmd->add_option("--format", *format, "output format: table, csv or json")->capture_default_str();
    return {{cmd, [format](std::ostream& out) {
                 const TableFormat f = parse_table_format(*format);
                 Table t({"name", "value", "meaning", "option", "keyword", "command", "function"});
                 t.title = "defaults (a value left empty is a rule, stated beside it)";
                 for (const defaults::Entry& e : defaults::table()) t.add_row({e.name, e.value, e.meaning, e.option, e.keyword, e.command, e.function});
                 write_table(out, t, f);
             }}};
}

}  // namespace gyrokit::cli
