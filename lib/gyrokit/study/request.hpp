// What a caller asks of a rotor study, and how it meets the scene: every front end
// (the CLI's options, Python's keywords) fills a RotorRequest with what the user
// gave and nothing else; resolve_request decides the rest once, here: the request
// where given, else the scene's [speeds] and [analysis], else the table of defaults
// (study/defaults.hpp). Speeds and frequencies are in the request's unit, which is
// the scene's [speeds] units unless the call names one: the results come back in it.
#pragma once

#include <gyrokit/scene/scene.hpp>
#include <gyrokit/study/rotor_study.hpp>

#include <optional>
#include <string>
#include <vector>

namespace gyrokit {

struct RotorRequest {
    std::optional<std::string> unit;              // rad/s, Hz or rpm (any case)
    std::optional<std::vector<double>> speeds;    // in unit
    std::optional<int> modes;                     // 0: every mode; K: the K lowest shown
    std::optional<std::vector<int>> harmonics;    // excitation lines k x speed
    std::optional<double> f_cut;                  // in unit: the modes judged
    std::optional<std::string> solver;            // auto, dense or sparse
    std::optional<std::string> method;            // qz, qz-classic or state
    std::optional<double> target;                 // in unit: the sparse search's centre
    std::optional<double> target_order;           // the centre moves as target + order x speed
    std::optional<int> lanczos;                   // Arnoldi vectors, 0: automatic
    std::optional<int> jobs;                      // workers, 0: every core
};

// Whether a study sweeps speeds (campbell, critical, ...) or solves at one (eig).
enum class SpeedsNeeded { Yes, No };

// The study's options: unit, speeds (rad/s), modes, harmonics, f_cut (rad/s), the
// solver options and the worker count, each from the request, else the scene, else
// the default. InputError naming the field (option_field) and its allowed range for
// a value out of range, and for a sweep without speeds (none given, no [speeds]).
// `notes`: what the worker rule has to say (more jobs than cores).
StudyOptions resolve_request(const Scene& scene, const RotorRequest& request, SpeedsNeeded speeds = SpeedsNeeded::Yes,
                             std::vector<std::string>* notes = nullptr);

// A speed or frequency given in `u`, in rad/s: InputError naming `field` unless it is
// finite and >= 0 (> 0 where `positive`), the range stated for a `what` ("speed", "number").
double to_rad_s(double value, const char* field, const char* what, const SpeedUnit& u, bool positive = false);

// The unit alone: the request's, else the scene's [speeds] units.
SpeedUnit resolve_unit(const Scene& scene, const std::optional<std::string>& unit);

// A scene holding only `system` (no [speeds], no [analysis]): a model built in
// code meets the same rules as one read from a file.
Scene scene_of(const GyroscopicSystem& system);

}  // namespace gyrokit
