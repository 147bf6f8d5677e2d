// Load a scene file and print its critical speeds (1x line), refined by root
// finding on the tracked branches. Usage: critical_speeds SCENE.toml
#include <gyrokit/gyrokit.hpp>

#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s SCENE.toml\n", argv[0]);
        return 2;
    }
    try {
        const gyrokit::Scene scene = gyrokit::load_scene(argv[1]);
        if (!scene.speeds) {
            std::fprintf(stderr, "%s: the scene has no [speeds]\n", argv[1]);
            return 2;
        }
        const gyrokit::CampbellDiagram cd = gyrokit::campbell(scene.system, scene.speed_points());
        for (const auto& c : gyrokit::critical_speeds(scene.system, cd, {1}))
            std::printf("%10.4f rad/s  branch %d  %s\n", c.speed, c.branch, gyrokit::to_string(c.mode.whirl).c_str());
    } catch (const std::exception& e) {   // gyrokit::InputError: one line naming the file and key
        std::fprintf(stderr, "%s\n", e.what());
        return 2;
    }
    return 0;
}
