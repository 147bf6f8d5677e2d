// A TOML syntax error in any file a reader parses: an InputError naming the file, the line
// and the column (one parse for scenes, balancer scenes and sweeps).
#include <gyrokit/core/error.hpp>
#include <gyrokit/scene/balancer_scene.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/screening/sweep.hpp>

#include <catch2/catch.hpp>
#include <cstdio>
#include <fstream>
#include <string>

using namespace gyrokit;

TEST_CASE("a TOML syntax error names the file, the line and the column in every reader", "[scene][errors]") {
    const std::string text = "title = \"x\"\n[model\ntype = \"gyrostat\"\n";   // line 2: unclosed table header
    CHECK_THROWS_MATCHES(parse_scene(text, "inline.toml"), InputError,
                         Catch::Matchers::Predicate<InputError>([](const InputError& e) {
                             return std::string(e.what()).rfind("inline.toml: line 2, column", 0) == 0;
                         }));
    const std::string path = "toml_syntax_test.toml";
    {
        std::ofstream f(path);
        f << text;
    }
    const auto names_line = [&](const InputError& e) {
        return std::string(e.what()).rfind(path + ": line 2, column", 0) == 0;
    };
    CHECK_THROWS_MATCHES(load_scene(path), InputError, Catch::Matchers::Predicate<InputError>(names_line));
    CHECK_THROWS_MATCHES(load_balancer_scene(path), InputError, Catch::Matchers::Predicate<InputError>(names_line));
    CHECK_THROWS_MATCHES(read_sweep(path, "", ""), InputError, Catch::Matchers::Predicate<InputError>(names_line));
    std::remove(path.c_str());
}
