// The CLI's command groups, in the order --help lists them: one line each. A group
// is a file apps/cli/NAME_command(s).cpp that defines add_NAME_commands(app) (the
// subcommands, their options and what they run); the line below declares it and
// registers it in the gyrokit program.
#pragma once

#define GYROKIT_COMMAND_GROUPS(X)                                                         \
    X(spectrum)       /* at one speed: eig, model, modes, export */                       \
    X(tracking)       /* over speed: campbell, critical, stability, pervasive */          \
    X(response)       /* the unbalance response: response */                              \
    X(frf)            /* frequency response functions at a spin speed: frf */             \
    X(transient)      /* time integration: transient */                                   \
    X(static)         /* FE rotors at standstill: static */                               \
    X(critical_map)   /* FE rotors: critical-map */                                       \
    X(level1)         /* FE rotors: level1 (API 617 Level I stability) */                 \
    X(api_unbalance)  /* FE rotors: api-unbalance (API 617 unbalance cases) */            \
    X(mesh)           /* FE rotors: mesh (mesh convergence) */                            \
    X(report)         /* the HTML report of a scene: report */                            \
    X(balancer)       /* the auto-balancer: balancer (states, --simulate) */              \
    X(fluid)          /* the liquid-filled rotor: fluid */                                \
    X(screen)         /* design studies: screen */                                        \
    X(sommerfeld)     /* the Sommerfeld effect: sommerfeld (curves, --runup) */           \
    X(defaults)       /* the table of defaults: defaults */
