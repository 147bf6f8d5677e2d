// The Level I stability screen as tables and a figure: the summary and verdict, the
// stages' anticipated cross-coupling, the curve of the first forward mode's log
// decrement against Q, and that curve drawn with QA and Q0 marked.
#pragma once

#include <gyrokit/io/plot.hpp>
#include <gyrokit/io/table.hpp>
#include <gyrokit/analysis/level1_stability.hpp>

#include <string>
#include <vector>

namespace gyrokit {

// A log decrement's bound from its eigenvalue's: delta = -2 pi Re / Im moves by at
// most 2 pi eb (|Im| + |Re|) / Im^2 (first order).
double log_decrement_bound(const Level1Point& p);

Table level1_summary(const Level1Screen& s);
Table level1_stages(const Level1Screen& s);     // empty where QA was given directly
Table level1_curve_table(const Level1Screen& s);
// summary, stages (where there are stages), curve. With several bearing sets the summary
// and the curve lead each row with its set (a bearing_set column; the summary's first rows,
// set "all", give the verdict and the governing set), and the figure draws each set's curve.
std::vector<Table> level1_tables(const Level1Study& st);
Figure level1_figure(const Level1Study& st, const std::string& title);

}  // namespace gyrokit
