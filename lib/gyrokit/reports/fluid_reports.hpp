// The liquid-filled rotor as tables and figures: critical speeds of the three
// liquid models, the sloshing coefficients, the liquid's inertias, and the sweep
// over the fill level (the paper's Bild 2). Speeds in the chosen unit.
#pragma once

#include <gyrokit/analysis/fluid_critical_speeds.hpp>
#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/io/plot.hpp>
#include <gyrokit/io/table.hpp>

#include <string>

namespace gyrokit {

// Per liquid model, its critical speeds numbered from 1.
Table fluid_critical_table(const FluidCriticalSpeeds& cs, const SpeedUnit& u);
// The sloshing modes; the decay time tau at the first critical speed with moving
// undamped liquid, or at the rotor's sqrt(gamma / m) when it has none.
Table sloshing_modes_table(const FluidRotor& f, const FluidCriticalSpeeds& cs, const SpeedUnit& u);
// Effective masses and inertias of the liquid, the rotor's stiffness coefficients.
Table liquid_table(const FluidRotor& f, const FluidCriticalSpeeds& cs);

Table fill_sweep_table(const FillSweep& s, const SpeedUnit& u);
// Critical speeds against R0, one point series per liquid model; `title` heads the panel.
Figure fill_sweep_figure(const FillSweep& s, const SpeedUnit& u, const std::string& title);

}  // namespace gyrokit
