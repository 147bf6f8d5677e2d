// The API unbalance cases as tables and a figure: the summary and verdict, each case
// (its critical speeds, A1, Avl, Scc, verdict and reasons), the unbalances placed, each
// critical speed's margins, each location's largest orbit against its limit, and the
// orbits against speed with the operating range marked.
#pragma once

#include <gyrokit/io/plot.hpp>
#include <gyrokit/io/table.hpp>
#include <gyrokit/study/api_unbalance_study.hpp>

#include <string>
#include <vector>

namespace gyrokit {

Table api_unbalance_summary(const ApiUnbalanceStudy& s);
Table api_unbalance_cases(const ApiUnbalanceStudy& s);
Table api_unbalance_loads(const ApiUnbalanceStudy& s);
Table api_unbalance_margins(const ApiUnbalanceStudy& s);
Table api_unbalance_amplitudes(const ApiUnbalanceStudy& s);
// summary, cases, loads, margins, amplitudes (the last four where there are cases).
std::vector<Table> api_unbalance_tables(const ApiUnbalanceStudy& s);
// One panel per case: the peak-to-peak orbit (um) of every location against speed,
// the minimum operating speed, mcs and trip speed as vertical lines.
Figure api_unbalance_figure(const ApiUnbalanceStudy& s, const std::string& title);

}  // namespace gyrokit
