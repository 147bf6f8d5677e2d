// What a Python call asks for, as the library's request: the model it names (a
// Scene, or a System standing alone) and its keywords, None meaning "not given"
// (resolve_request then takes the scene's value, else the default).
#pragma once

#include <gyrokit/io/scene.hpp>
#include <gyrokit/study/request.hpp>

#include <pybind11/pybind11.h>

#include <optional>

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

// The keywords unit, speeds, modes, harmonics, f_cut, solver, method, target,
// target_order, lanczos, jobs (absent or None: not given); InputError naming a
// keyword of the wrong type (a count that is not whole, a list that is not numbers).
gyrokit::RotorRequest rotor_request(const pybind11::dict& keywords);

// The study of `model` for the request: resolve_request on threads, its note on
// capped jobs as a Python warning.
gyrokit::StudyOptions resolve(const ModelArg& model, const pybind11::dict& keywords,
                              gyrokit::SpeedsNeeded speeds = gyrokit::SpeedsNeeded::Yes);

}  // namespace gyrokit_python
