#include <gyrokit/core/solver_kind.hpp>

#include <gyrokit/core/error.hpp>

#include <fmt/format.h>

namespace gyrokit {

SolverKind parse_solver_kind(const std::string& name) {
    if (name == "auto") return SolverKind::Auto;
    if (name == "dense") return SolverKind::Dense;
    if (name == "sparse") return SolverKind::Sparse;
    throw InputError(fmt::format("{} '{}': allowed: auto, dense, sparse", option_field("solver"), name));
}

std::string to_string(SolverKind k) {
    switch (k) {
    case SolverKind::Auto: return "auto";
    case SolverKind::Dense: return "dense";
    case SolverKind::Sparse: return "sparse";
    }
    return "auto";
}

EigenMethod parse_eigen_method(const std::string& name) {
    if (name == "auto") return EigenMethod::Auto;
    if (name == "qz") return EigenMethod::ScaledQZ;
    if (name == "qz-classic") return EigenMethod::ClassicQZ;
    if (name == "state") return EigenMethod::StateMatrix;
    throw InputError(fmt::format("eigen method '{}' is unknown; allowed: auto, qz, qz-classic, state", name));
}

std::string to_string(EigenMethod m) {
    switch (m) {
    case EigenMethod::Auto: return "auto";
    case EigenMethod::ScaledQZ: return "qz";
    case EigenMethod::ClassicQZ: return "qz-classic";
    case EigenMethod::StateMatrix: break;
    }
    return "state";
}

}  // namespace gyrokit
