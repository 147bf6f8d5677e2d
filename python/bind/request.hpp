// What a Python call asks for, as the library's request: the model it names (a
// Scene, or a System standing alone) and its keywords, None meaning "not given"
// (resolve_request then takes the scene's value, else the default).
#pragma once

#include <gyrokit/scene/scene.hpp>
#include <gyrokit/study/request.hpp>

#include <pybind11/pybind11.h>

#include <optional>
#include <string>

namespace gyrokit_python {

// A Scene, or a System as a scene of the system alone; InputError for anything else.
class ModelArg {
public:
    explicit ModelArg(const pybind11::object& model);
    const gyrokit::Scene& scene() const { return *scene_; }
    const gyrokit::GyroscopicSystem& system() const { return scene_->system; }

private:
    std::optional<gyrokit::Scene> owned_;
    const gyrokit::Scene* scene_ = nullptr;
};

// One keyword of a call (absent or None: not given), InputError naming it where its
// type is wrong: a number; a whole number (an int, or a float with no fraction: 6.0),
// |n| < limit, named `field` where given; a name.
pybind11::object given(const pybind11::dict& keywords, const char* name);
std::optional<double> given_number(const pybind11::dict& keywords, const char* name);
std::optional<long long> given_count(const pybind11::dict& keywords, const char* name, const char* field, double limit);
std::optional<int> given_whole(const pybind11::dict& keywords, const char* name, const char* field = nullptr);
std::optional<std::string> given_text(const pybind11::dict& keywords, const char* name);

// The keywords unit, speeds, modes, harmonics, f_cut, solver, method, target,
// target_order, lanczos, jobs (absent or None: not given); InputError naming a
// keyword of the wrong type (a count that is not whole, a list that is not numbers).
gyrokit::RotorRequest rotor_request(const pybind11::dict& keywords);

// The study of `model` for the request: resolve_request on threads, its note on
// capped jobs as a Python warning.
gyrokit::StudyOptions resolve(const ModelArg& model, const pybind11::dict& keywords,
                              gyrokit::SpeedsNeeded speeds = gyrokit::SpeedsNeeded::Yes);

}  // namespace gyrokit_python
