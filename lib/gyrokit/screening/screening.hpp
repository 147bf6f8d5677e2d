// Evaluation of the designs of a sweep against its criteria, and the run:
// parallel workers, rows written in design-index order and flushed, resume of
// an interrupted run, shards. See docs/screening.md.
#pragma once

#include <chrono>

#include <gyrokit/io/plot.hpp>
#include <gyrokit/io/table.hpp>
#include <gyrokit/screening/sweep.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace gyrokit {

enum class Verdict { Pass, Fail, Error };
std::string to_string(Verdict v);

// What one design gave. `quantities` follow quantity_columns(); unset = not
// defined (e.g. no critical speed in the scanned range).
struct DesignResult {
    std::size_t index = 0;
    std::vector<double> parameters;
    std::vector<std::optional<double>> quantities;
    std::vector<std::string> labels;   // follow label_columns(); "" = not defined
    Verdict verdict = Verdict::Pass;
    std::vector<std::string> failed;   // names of the criteria not met
    std::string reason;
};

// The computed columns of the sweep's criteria, e.g. critical_speed, separation_percent.
std::vector<std::string> quantity_columns(const Sweep& s);
// The text columns of the sweep's criteria, after the quantities: max_amplitude_probe
// (the probe that read the largest amplitude) with response probes.
std::vector<std::string> label_columns(const Sweep& s);
// design, parameters, quantities, labels, verdict, failed, reason.
std::vector<std::string> result_columns(const Sweep& s);

// Evaluates design i. Never throws for a failing design: an invalid parameter
// combination or a failed analysis gives Verdict::Error with the message.
DesignResult evaluate_design(const Sweep& s, std::size_t i);

// A result row as written: one string per column (numbers %.12g, parameters
// at round-trip precision, empty = undefined).
struct ResultRow {
    std::size_t index = 0;
    std::vector<std::string> cells;
};
ResultRow format_row(const Sweep& s, const DesignResult& r);

struct RunOptions {
    int jobs = 1;
    Shard shard;
    std::string out;          // CSV file written row by row ("" = none)
    bool resume = false;      // keep the rows already in `out` and compute the rest
    std::size_t limit = 0;    // compute at most this many designs in this run (0 = all)
    // Called from the writing thread after each row: (rows done, rows of the shard).
    std::function<void(std::size_t, std::size_t)> progress;
};

struct RunResult {
    std::vector<std::string> columns;
    std::vector<ResultRow> rows;    // design-index order
    std::size_t resumed = 0;        // rows read back from `out`
    std::size_t computed = 0;
    std::size_t shard_designs = 0;  // designs owned by the shard
};

// The last line of a result file whose run saw an input change while it ran:
// --resume and --merge refuse such a file.
constexpr const char* kInputsChangedTrailer = "# inputs changed during the run:";

// The revision of the verdicts' rules: raised where a criterion judges the same
// design differently (2: a separation criterion skips the crossings `critical` calls
// heavily damped, unless heavily_damped = "count"; 3: the response criterion is the
// study of `gyrokit response`, on the scene's solver), so that rows judged by the old
// rules are not resumed or merged with new ones.
constexpr int kScreeningRules = 3;

// The first line of a result file: "# study <16 hex digits> (…; gyrokit VERSION,
// rules N)", a 64-bit FNV-1a fingerprint of the sweep file (parameters and
// criteria), its base scene file, gyrokit's version and kScreeningRules. --resume
// and --merge refuse a file of another study: rows computed before a change are not
// this study's answers.
std::string study_identity_line(const Sweep& s);

// Seconds between syncs of a result file to the disk while rows are written.
constexpr double kResultSyncSeconds = 1.0;

// A result file held for writing: opened (created if missing) and locked
// exclusively (flock) for the object's lifetime, so a second run writing the same
// file is refused (InputError) instead of interleaving with this one. Lines are
// written whole (a kill leaves at most one partial line, which resume drops); the
// data is synced to the disk at most kResultSyncSeconds after a line and at close,
// and a new file's directory entry when it is created (docs/reliability.md).
class ResultFile {
public:
    explicit ResultFile(const std::string& path);
    ~ResultFile();
    ResultFile(const ResultFile&) = delete;
    ResultFile& operator=(const ResultFile&) = delete;
    void truncate(std::size_t bytes);   // cut to `bytes`, then write at the end
    void write(const std::string& text);
    void sync();
    void close();                       // syncs; throws Error where the data did not reach the disk
private:
    std::string path_;
    int fd_ = -1;
    bool regular_ = true;   // a device or pipe is neither cut nor synced
    std::chrono::steady_clock::time_point last_sync_;
};

// Runs the designs of the shard on `jobs` threads. Rows are written to `out`
// (a ResultFile: locked, synced) in design-index order as soon as all earlier
// rows are done, so an interrupted file is always a complete prefix plus at most
// one partial line. `out` may not be the sweep file or its base scene. With `resume`, the header must match the sweep, the rows must belong
// to this sweep and shard, a partial last line is dropped and redone.
RunResult run_screening(const Sweep& s, const RunOptions& opt);

// Reads result files (shards or one run) of `s` and returns all rows sorted
// by design index; throws InputError on a foreign header, duplicates, or
// (with `complete`) missing designs. With `out`, the rows are also written there as
// one result file (locked, synced; `option` names it in errors), which may be none
// of the files merged, the sweep or its base scene.
std::vector<ResultRow> merge_results(const Sweep& s, const std::vector<std::string>& files, bool complete,
                                     const std::string& out = "", const std::string& option = "--out");

// Rows to a table: numbers as numbers; undefined cells as "" (CSV/text) or
// null (JSON, written by write_results).
void write_results(std::ostream& os, const Sweep& s, const std::vector<ResultRow>& rows, TableFormat f);

// Verdict counts and the designs failing each criterion.
Table summary_table(const Sweep& s, const std::vector<ResultRow>& rows);

// Designs over two parameters, coloured by verdict (pass, fail, error).
Figure safe_region_figure(const Sweep& s, const std::vector<ResultRow>& rows, const std::string& x,
                          const std::string& y);

}  // namespace gyrokit
