// Parallel run, result files (locked, synced), resume, merge and the study identity;
// the rows, tables and figure of the results are in results.cpp.
#include <gyrokit/core/error.hpp>
#include <gyrokit/core/interrupt.hpp>
#include <gyrokit/core/parallel.hpp>
#include <gyrokit/core/input_file.hpp>
#include <gyrokit/core/run_files.hpp>
#include <gyrokit/io/csv.hpp>
#include <gyrokit/io/output_file.hpp>
#include <gyrokit/screening/screening.hpp>

#include <algorithm>
#include <cmath>
#include <atomic>
#include <condition_variable>
#include <exception>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <functional>
#include <gsl/gsl_errno.h>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <utility>
#include <vector>
#include <toml++/toml.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace gyrokit {

ResultFile::ResultFile(const std::string& path) : path_(path) {
    const bool existed = std::filesystem::exists(path);
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (fd_ < 0) throw InputError(fmt::format("{}: cannot write the result file ({})", path, std::strerror(errno)));
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
        const int err = errno;
        ::close(fd_);
        fd_ = -1;
        if (err == EWOULDBLOCK)
            throw InputError(fmt::format("{}: another run is writing this result file (it holds its lock); let it "
                                         "finish, or stop it, before writing here; allowed: a file no other run writes",
                                         path));
        throw InputError(fmt::format("{}: cannot lock the result file ({})", path, std::strerror(err)));
    }
    if (!existed) sync_folder_of(path);   // the new file's name must survive a power loss as well as its lines
    struct stat st {};
    regular_ = ::fstat(fd_, &st) == 0 && S_ISREG(st.st_mode);
    last_sync_ = std::chrono::steady_clock::now();
}

ResultFile::~ResultFile() {
    if (fd_ >= 0) {
        ::fsync(fd_);
        ::close(fd_);   // releases the lock
    }
}

void ResultFile::truncate(std::size_t bytes) {
    if (!regular_) return;   // a device or a pipe (/dev/stdout): nothing to cut
    if (::ftruncate(fd_, static_cast<off_t>(bytes)) != 0 || ::lseek(fd_, 0, SEEK_END) < 0)
        throw Error(fmt::format("{}: cannot cut the result file to {} bytes ({})", path_, bytes, std::strerror(errno)));
}

void ResultFile::write(const std::string& text) {
    if (const int err = write_all(fd_, text)) throw Error(fmt::format("{}: write failed ({})", path_, std::strerror(err)));
    const auto now = std::chrono::steady_clock::now();
    if (now - last_sync_ >= std::chrono::duration<double>(kResultSyncSeconds)) sync();
}

void ResultFile::sync() {
    if (regular_ && ::fdatasync(fd_) != 0) throw Error(fmt::format("{}: cannot sync the result file ({})", path_, std::strerror(errno)));
    last_sync_ = std::chrono::steady_clock::now();
}

void ResultFile::close() {
    if (fd_ < 0) return;
    const int sync_rc = regular_ ? ::fsync(fd_) : 0;
    const int err = errno;
    const int close_rc = ::close(fd_);
    fd_ = -1;
    if (sync_rc != 0 || close_rc != 0)
        throw Error(fmt::format("{}: write failed at close ({})", path_, std::strerror(sync_rc != 0 ? err : errno)));
}

namespace {

namespace fs = std::filesystem;

// What follows a marker on a line (the files a trailer names), at most 200 characters; a
// line that ends at the marker names none.
std::string printable_rest(const std::string& line, std::size_t marker) {
    if (line.size() <= marker + 1) return "no file named";
    return line.substr(marker + 1, 200);
}

std::string header_line(const Sweep& s) {
    std::string h = csv_line(result_columns(s));
    h.pop_back();
    return h;
}

std::uint64_t fnv1a(const std::string& bytes, std::uint64_t h = 1469598103934665603ull) {
    return fingerprint_bytes(bytes.data(), bytes.size(), h);
}

// A study file's bytes as this run reads them (once: the rows are computed from the
// same copy); "" where the path names no file (a sweep built in code).
std::string file_bytes(const std::string& path, const std::string& what, std::uintmax_t max_bytes) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return "";
    return *read_input(path, what, max_bytes);
}

// Every string value of the scene file that names a regular file (relative to the
// scene's directory, as the scene readers resolve them), in document order, as
// {the value as written, the resolved path}: the value, not the path, enters the
// identity, so that a study run from another folder is the same study. A scene
// that cannot be read names none: loading it reports that.
std::vector<std::pair<std::string, std::string>> named_files(const Sweep& s) {
    std::vector<std::pair<std::string, std::string>> files;
    toml::table root;
    try {
        root = toml::parse(s.scene_text.empty() ? read_toml_text(s.scene, "scene file") : s.scene_text, s.scene);
    } catch (const std::exception&) {
        return files;
    }
    const fs::path dir = s.scene_text.empty() ? fs::path(s.scene).parent_path() : fs::path(".");
    const std::function<void(const toml::node&)> walk = [&](const toml::node& n) {
        if (const auto* t = n.as_table()) {
            for (const auto& [k, v] : *t) walk(v);
        } else if (const auto* a = n.as_array()) {
            for (const auto& v : *a) walk(v);
        } else if (const auto* str = n.as_string()) {
            const fs::path p = fs::path(str->get()).is_absolute() ? fs::path(str->get()) : dir / str->get();
            std::error_code ec;
            if (!str->get().empty() && fs::is_regular_file(p, ec)) files.emplace_back(str->get(), p.string());
        }
    };
    walk(root);
    return files;
}

// The complete lines of a result file and the byte length they occupy; a last
// line without its newline (an interrupted write) is left out.
struct ParsedFile {
    bool has_identity = false;
    bool has_header = false;
    std::vector<ResultRow> rows;
    std::size_t valid_bytes = 0;
    bool partial_tail = false;
};

ParsedFile parse_result_file(const Sweep& s, const std::string& path, const Shard* shard) {
    const std::string identity = study_identity_line(s);
    ParsedFile pf;
    check_input_file(path, "result file", kMaxDataInputBytes);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(fmt::format("{}: cannot read the result file", path));
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str();
    const std::vector<std::string> cols = result_columns(s);
    const std::string header = header_line(s);
    std::set<std::size_t> seen;
    std::size_t pos = 0, line_no = 0;
    while (pos < text.size()) {
        const std::size_t nl = text.find('\n', pos);
        if (nl == std::string::npos) {
            pf.partial_tail = true;
            break;
        }
        std::string line = text.substr(pos, nl - pos);
        if (!line.empty() && line.back() == '\r') line.pop_back();
        ++line_no;
        if (line.rfind(kInputsChangedTrailer, 0) == 0)
            throw InputError(fmt::format("{}: line {}: the run that wrote it saw an input change while it ran ({}); its "
                                         "rows may not belong to the files as they are now; allowed: a new run "
                                         "(a new --out file)",
                                         path, line_no, printable_rest(line, std::string(kInputsChangedTrailer).size())));
        if (line_no == 1) {
            // The study's identity: rows of another scene, sweep, criteria or version are not this study's answers.
            if (line.rfind("# study ", 0) != 0)
                throw InputError(fmt::format("{}: no study identity on the first line (a file of an older gyrokit, "
                                             "or not a result file); allowed: a result file of this study ({}), or "
                                             "a new file",
                                             path, s.path));
            // Another gyrokit or revision of the verdicts' rules: said as such (the fingerprint differs too).
            const std::string ours = identity.substr(identity.rfind("; gyrokit ") + 2);
            const std::size_t theirs_at = line.rfind("; gyrokit ");
            const std::string theirs = theirs_at == std::string::npos ? std::string() : line.substr(theirs_at + 2);
            if (line != identity && !theirs.empty() && theirs != ours)
                throw InputError(fmt::format("{}: written by another study: its rows were judged by {} where this run "
                                             "judges by {}; rows of other rules or versions are not resumed or merged "
                                             "with this run's; allowed: a result file of this gyrokit, or a new file",
                                             path, theirs.substr(0, std::min<std::size_t>(theirs.size() - 1, 80)),
                                             ours.substr(0, ours.size() - 1)));
            if (line != identity)
                throw InputError(fmt::format("{}: written by another study: its scene, a file the scene names, its "
                                             "sweep or criteria, the gyrokit version or the revision of the verdicts' rules (a file judged "
                                             "by older rules), changed since ('{}'; this study: '{}'); allowed: the "
                                             "result file of this study, or a new file",
                                             path, line.substr(0, 120), identity));
            pf.has_identity = true;
        } else if (line_no == 2) {
            if (line != header)
                throw InputError(fmt::format("{}: the header does not match the sweep {}; expected '{}'", path,
                                             s.path, header));
            pf.has_header = true;
        } else {
            std::vector<std::string> cells;
            try {
                cells = parse_csv_line(line);
            } catch (const Error& e) {
                throw InputError(fmt::format("{}: line {}: {}", path, line_no, e.what()));
            }
            if (cells.size() != cols.size())
                throw InputError(fmt::format("{}: line {} has {} fields; the sweep has {} columns", path, line_no,
                                             cells.size(), cols.size()));
            std::size_t idx = 0;
            try {
                std::size_t used = 0;
                const unsigned long long v = std::stoull(cells[0], &used);
                if (used != cells[0].size()) throw std::invalid_argument(cells[0]);
                idx = static_cast<std::size_t>(v);
            } catch (const std::exception&) {
                throw InputError(fmt::format("{}: line {}: design '{}' is not a design index", path, line_no, cells[0]));
            }
            if (idx >= s.design_count())
                throw InputError(fmt::format("{}: line {}: design {} is out of range; the sweep has {} designs", path,
                                             line_no, idx, s.design_count()));
            if (shard && !shard->owns(idx))
                throw InputError(fmt::format("{}: line {}: design {} belongs to another shard than {}/{}", path,
                                             line_no, idx, shard->index, shard->count));
            if (!seen.insert(idx).second)
                throw InputError(fmt::format("{}: line {}: design {} appears twice", path, line_no, idx));
            const std::vector<double> x = s.design(idx);
            for (std::size_t j = 0; j < x.size(); ++j)
                if (cells[1 + j] != fmt::format("{}", x[j]))
                    throw InputError(fmt::format("{}: line {}: design {} has {} = {}, the sweep gives {}; the file "
                                                 "belongs to another sweep",
                                                 path, line_no, idx, s.parameters[j].name, cells[1 + j], x[j]));
            pf.rows.push_back({idx, std::move(cells)});
        }
        pos = nl + 1;
        pf.valid_bytes = pos;
    }
    return pf;
}

// The results file of a run, locked: read back and cut after its last whole line
// (resume: its rows into `res`, their designs into `done`) or emptied, with the
// identity and header lines where it has none, into `out` (left empty without --out).
// The sweep and its base scene as inputs of the run (a sweep built in code names no file).
void note_study_files(RunFiles& files, const Sweep& s) {
    files.note_input(s.path, "sweep file");
    if (s.scene_text.empty()) files.note_input(s.scene, "base scene");
}

void open_results(const Sweep& s, const RunOptions& opt, RunFiles& files, RunResult& res, std::set<std::size_t>& done,
                  std::optional<ResultFile>& out) {
    note_study_files(files, s);
    files.claim_output(opt.out, opt.resume ? "--resume" : "--out");
    // Held from before the file is read back (resume) or cut (a fresh run): a second
    // writer of the same file is refused instead of interleaving with this one.
    if (opt.out.empty()) return;
    out.emplace(opt.out);
    bool need_header = true, has_identity = false;
    if (opt.resume && fs::file_size(opt.out) > 0) {
        ParsedFile pf = parse_result_file(s, opt.out, &opt.shard);
        need_header = !pf.has_header;
        has_identity = pf.has_identity;
        out->truncate(pf.valid_bytes);   // drop the partial last line before appending
        for (auto& r : pf.rows) done.insert(r.index);
        res.resumed = pf.rows.size();
        res.rows = std::move(pf.rows);
    } else {
        out->truncate(0);
    }
    if (need_header) {
        out->write((has_identity ? std::string() : study_identity_line(s) + '\n') + header_line(s) + '\n');
        out->sync();
    }
}

// The designs of one run, issued to the workers one at a time in index order (the k-th
// issued is the k-th row written), and their results handed back in that order: nothing is
// allocated per design of the grid, so a 1e8-design grid with --limit 2 costs two designs.
class DesignQueue {
public:
    // The designs first, first + step, ... (a shard) not in `done`, at most `remaining` of them.
    DesignQueue(const Sweep& s, const std::set<std::size_t>& done, std::size_t first, std::size_t step,
                std::size_t remaining)
        : s_(s), done_(done), n_(s.design_count()), step_(step), cursor_(first), remaining_(remaining) {}

    // One worker: designs until none is left or the run stops; a failure (an interrupt: a
    // design's own errors are its row) stops the run and reaches result().
    void work(RunFiles& files) {
        RunScope in_run(files);   // the designs read the study's files from the run's copies
        for (;;) {
            std::size_t k = 0, design = 0;
            {
                std::lock_guard<std::mutex> lock(mu_);
                if (!more()) return;
                k = issued_++;
                design = cursor_;
                cursor_ += step_;
            }
            try {
                throw_if_interrupted();
                DesignResult r = evaluate_design(s_, design);
                std::lock_guard<std::mutex> lock(mu_);
                ready_.emplace(k, std::move(r));
            } catch (...) {
                std::lock_guard<std::mutex> lock(mu_);
                if (!failure_) failure_ = std::current_exception();
                stop_ = true;
            }
            cv_.notify_all();
        }
    }
    // The k-th issued design's result, once there; nullopt where it will not be (every
    // issued design is handed back and no more will be issued). Rethrows a worker's failure.
    std::optional<DesignResult> result(std::size_t k) {
        std::unique_lock<std::mutex> lock(mu_);
        cv_.wait(lock, [&] { return ready_.count(k) || failure_ || (k >= issued_ && !more()); });
        const auto it = ready_.find(k);
        if (it == ready_.end()) {
            if (failure_) std::rethrow_exception(failure_);
            return std::nullopt;
        }
        DesignResult r = std::move(it->second);
        ready_.erase(it);
        return r;
    }
    void halt() {
        std::lock_guard<std::mutex> lock(mu_);
        stop_ = true;
    }

private:
    // Whether a design is left to issue (under mu_): the next one not done before, in range.
    bool more() {
        while (cursor_ < n_ && done_.count(cursor_)) cursor_ += step_;
        return !stop_ && cursor_ < n_ && issued_ < remaining_;
    }
    const Sweep& s_;
    const std::set<std::size_t>& done_;
    const std::size_t n_, step_;
    std::size_t cursor_, remaining_, issued_ = 0;
    bool stop_ = false;
    std::exception_ptr failure_;
    std::map<std::size_t, DesignResult> ready_;   // results not yet written, by issue number
    std::mutex mu_;
    std::condition_variable cv_;
};

}  // namespace

RunResult run_screening(const Sweep& s, const RunOptions& opt) {
    // One run: every design reads the base scene and the files it names from the
    // same copy, and the result file is never one of them.
    RunScope run;
    RunResult res;
    res.columns = result_columns(s);
    const std::size_t n = s.design_count();
    const std::size_t first = static_cast<std::size_t>(opt.shard.index), step = static_cast<std::size_t>(opt.shard.count);
    res.shard_designs = n > first ? (n - first + step - 1) / step : 0;

    std::set<std::size_t> done;
    std::optional<ResultFile> out;
    open_results(s, opt, run.files(), res, done, out);
    std::size_t remaining = res.shard_designs - std::min(res.shard_designs, done.size());
    if (opt.limit > 0) remaining = std::min(remaining, opt.limit);

    gsl_set_error_handler_off();   // global GSL state: set once before the workers start
    DesignQueue queue(s, done, first, step, remaining);
    const int jobs = std::max(1, static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(std::max(1, opt.jobs)),
                                                                        std::max<std::size_t>(remaining, 1))));
    std::vector<ResultRow> fresh;
    // The workers on threads of their own for the whole run; this thread writes their
    // rows in order as they come (and reports progress), so a slow disk or a progress
    // callback never holds a worker.
    run_beside(
        jobs, [&] { queue.work(run.files()); },
        [&] {
            try {
                for (std::size_t k = 0;; ++k) {
                    std::optional<DesignResult> r = queue.result(k);
                    if (!r) break;   // every issued design is written and no more will be
                    ResultRow row = format_row(s, *r);
                    if (out) out->write(csv_line(row.cells));
                    fresh.push_back(std::move(row));
                    ++res.computed;
                    if (opt.progress) opt.progress(res.resumed + res.computed, res.shard_designs);
                }
            } catch (...) {
                queue.halt();   // the workers stop after their current design
                throw;
            }
        });
    // An input edited while the run read it: the file says so, and --resume and --merge refuse it.
    if (const std::string changed = run.files().changed_inputs(); !changed.empty()) {
        if (out) {
            out->write(std::string(kInputsChangedTrailer) + " " + changed + "\n");
            out->close();
        }
        run.files().check_inputs_unchanged();
    }
    if (out) out->close();   // synced: every row of the run survives a power loss from here
    res.rows.insert(res.rows.end(), std::make_move_iterator(fresh.begin()), std::make_move_iterator(fresh.end()));
    std::stable_sort(res.rows.begin(), res.rows.end(), [](const auto& a, const auto& b) { return a.index < b.index; });
    return res;
}

std::vector<ResultRow> merge_results(const Sweep& s, const std::vector<std::string>& files, bool complete,
                                     const std::string& out, const std::string& option) {
    RunScope run;
    for (const auto& f : files) run.files().note_input(f, "merged result file");
    note_study_files(run.files(), s);
    run.files().claim_output(out, option);
    std::vector<ResultRow> rows;
    for (const auto& f : files) {
        if (!fs::exists(f)) throw InputError(fmt::format("{}: result file not found", f));
        ParsedFile pf = parse_result_file(s, f, nullptr);
        if (pf.partial_tail)
            throw InputError(fmt::format("{}: the last line is incomplete; finish that run with --resume first", f));
        rows.insert(rows.end(), std::make_move_iterator(pf.rows.begin()), std::make_move_iterator(pf.rows.end()));
    }
    std::stable_sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.index < b.index; });
    for (std::size_t k = 1; k < rows.size(); ++k)
        if (rows[k].index == rows[k - 1].index)
            throw InputError(fmt::format("design {} appears in more than one result file", rows[k].index));
    if (complete) {
        const std::size_t n = s.design_count();
        for (std::size_t k = 0; k < n; ++k)
            if (k >= rows.size() || rows[k].index != k)
                throw InputError(fmt::format("the result files miss design {} (of {})", k, n));
    }
    if (!out.empty()) {
        std::ostringstream text;
        write_results(text, s, rows, TableFormat::Csv);
        ResultFile f(out);   // locked: no other run writes it meanwhile
        f.truncate(0);
        f.write(study_identity_line(s) + '\n' + text.str());
        f.close();   // synced: a full disk shows here
    }
    return rows;
}

std::string study_identity_line(const Sweep& s) {
    std::uint64_t h = fnv1a(file_bytes(s.path, "sweep file", kMaxTextInputBytes));
    h = fnv1a("\x1f" + (s.scene_text.empty() ? file_bytes(s.scene, "scene file", kMaxTextInputBytes) : s.scene_text), h);
    // The files the scene names (bearing tables, Matrix Market matrices): a
    // bearing table edited between runs is another study too.
    for (const auto& [written, path] : named_files(s))
        h = fnv1a(file_bytes(path, "file the scene names", kMaxDataInputBytes), fnv1a("\x1f" + written + "\x1f", h));
    h = fnv1a("\x1f" GYROKIT_VERSION, h);
    h = fnv1a(fmt::format("\x1f{}", kScreeningRules), h);
    return fmt::format("# study {:016x} (sweep, base scene and criteria; gyrokit {}, rules {})", h, GYROKIT_VERSION,
                       kScreeningRules);
}

}  // namespace gyrokit
