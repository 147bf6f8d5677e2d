// Analysis results as tables (stable column names, see docs/cli.md) and figures,
// one header per family; this one includes them all.
#pragma once

#include <gyrokit/reports/balancer_reports.hpp>
#include <gyrokit/reports/campbell_reports.hpp>
#include <gyrokit/reports/critical_map_reports.hpp>
#include <gyrokit/reports/critical_reports.hpp>
#include <gyrokit/reports/fluid_reports.hpp>
#include <gyrokit/reports/frf_reports.hpp>
#include <gyrokit/reports/api_unbalance_reports.hpp>
#include <gyrokit/reports/level1_reports.hpp>
#include <gyrokit/reports/mesh_convergence_reports.hpp>
#include <gyrokit/reports/mode_shape_reports.hpp>
#include <gyrokit/reports/model_reports.hpp>
#include <gyrokit/reports/response_reports.hpp>
#include <gyrokit/reports/sommerfeld_reports.hpp>
#include <gyrokit/reports/spectrum_reports.hpp>
#include <gyrokit/reports/static_reports.hpp>
#include <gyrokit/reports/transient_reports.hpp>
