// The bindings of the compiled core, in the order module.cpp adds them: one line each.
// A binding is a file python/NAME.cpp that defines bind_NAME(m) (its functions and
// classes); the line below declares it and adds it to the module. The system and the
// models (system.cpp, models.cpp) come first: they define the classes the others take.
#pragma once

#include <pybind11/pybind11.h>

#define GYROKIT_BINDINGS(X)                                                    \
    X(statics)        /* static deflection, reactions, internal forces */       \
    X(critical_map)   /* the undamped critical speed map */                      \
    X(level1)         /* API 617 Level I stability */                            \
    X(api_unbalance)  /* API 617 unbalance cases */                             \
    X(mesh)           /* mesh convergence */                                    \
    X(report)         /* the HTML report */                                     \
    X(frf)            /* frequency response functions */                         \
    X(reports)        /* tables and figures of the CLI */                        \
    X(transient)      /* time integration */                                     \
    X(analyses)       /* eig, modes, campbell, critical, stability, response */  \
    X(screening)      /* design studies */                                       \
    X(balancing)      /* the auto-balancer and the Sommerfeld effect */

#define GYROKIT_DECLARE_BINDING(name) void bind_##name(pybind11::module_& m);
GYROKIT_BINDINGS(GYROKIT_DECLARE_BINDING)
#undef GYROKIT_DECLARE_BINDING
