// The files of one run: every input read once into memory and fingerprinted,
// every output claimed before anything is written. The one place that decides
// that a run never writes onto what it reads (also through a symbolic or hard
// link), never writes one file twice, and notices an input edited while it runs.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace gyrokit {

// What makes two paths the same file: the same device and inode (a hard link or a
// symbolic link to it has them), or the same absolute path once every symbolic
// link on it is followed (a file that does not exist yet, a dangling link).
struct FileIdentity {
    bool exists = false;
    bool regular = false;       // a regular file (not a device, FIFO, socket or folder)
    std::uint64_t device = 0, inode = 0;
    std::string resolved;
    bool same_file(const FileIdentity& other) const;
};
FileIdentity identify_file(const std::string& path);

// The file a path names once its symbolic links are followed, link by link
// (relative ones from their own folder); InputError for a loop.
std::string link_target(const std::string& path);
// The folder a file lies in ("." for a bare name).
std::string folder_of(const std::string& path);

// An input as it was when read: enough to tell later whether it changed.
struct InputRecord {
    std::string path, what;
    FileIdentity id;
    std::uintmax_t size = 0;
    std::int64_t mtime_ns = 0;
    std::uint64_t fingerprint = 0;   // FNV-1a of the bytes read
    std::shared_ptr<const std::string> bytes;
};

// FNV-1a, 64 bits: a fingerprint of a file's bytes, not a cryptographic hash.
std::uint64_t fingerprint_bytes(const char* data, std::size_t n, std::uint64_t h = 1469598103934665603ull);

class RunFiles {
public:
    RunFiles() = default;
    // A run whose inputs are these files (noted, not read: a result's scene files).
    explicit RunFiles(const std::vector<std::string>& inputs);
    // The bytes of an input after check_input_file, read once: a later read of the
    // same file (by any path, from any thread of the run) gets the same copy.
    // InputError if the file is an output this run claimed, or changed while the
    // run read it.
    std::shared_ptr<const std::string> read(const std::string& path, const std::string& what, std::uintmax_t max_bytes);
    // An input read by other means (a result file merged, a scene's files):
    // outputs may not be it. A path that names no file is passed over.
    void note_input(const std::string& path, const std::string& what);
    // `path` becomes an output of this run, given by `option` ("--plot", "path"):
    // InputError (nothing written) if it is an input of the run or another output
    // of it, if it is a folder or a write-protected file, or if the folder it would
    // be written in does not exist or is not writable. A path that is not a regular
    // file (-, /dev/null, a FIFO) is never refused as the same file. The same option
    // may claim the same path again.
    void claim_output(const std::string& path, const std::string& option);
    // What changed since the inputs were read ("" where nothing did): the first input
    // whose inode is another, or whose bytes differ (a size or time changed and the
    // fingerprint with them), named.
    std::string changed_inputs() const;
    // InputError with that text where something changed.
    void check_inputs_unchanged() const;
    std::vector<InputRecord> inputs() const;

private:
    struct Output {
        std::string path, option;
        FileIdentity id;
    };
    const InputRecord* find_input(const FileIdentity& id) const;
    void refuse_if_output(const FileIdentity& id, const std::string& path, const std::string& what) const;
    mutable std::mutex mutex_;
    std::vector<InputRecord> inputs_;
    std::vector<Output> outputs_;
};

// The run in progress on this thread (a command of the CLI, a Python call, a
// screening worker), or nullptr outside one.
RunFiles* current_run();

// Without an argument: joins the run in progress on this thread, else starts one of
// its own. With `files`: makes them this thread's run for its lifetime (the worker
// threads of a run, a Python call with a result's inputs), then restores the run before.
class RunScope {
public:
    RunScope();
    explicit RunScope(RunFiles& files);
    ~RunScope();
    RunScope(const RunScope&) = delete;
    RunScope& operator=(const RunScope&) = delete;
    RunFiles& files() { return *active_; }

private:
    std::unique_ptr<RunFiles> own_;
    RunFiles* active_ = nullptr;
    RunFiles* previous_ = nullptr;
    bool installed_ = false;
};

// The bytes of an input file: through the current run (read once) where there is
// one, else read now. Every reader of scene, sweep, matrix and table files calls it,
// and the paths it reads on this thread are reported to each InputCollector alive.
std::shared_ptr<const std::string> read_input(const std::string& path, const std::string& what,
                                              std::uintmax_t max_bytes);

// The paths read_input read on this thread while it lives (a scene's own inputs),
// absolute.
class InputCollector {
public:
    InputCollector();
    ~InputCollector();
    InputCollector(const InputCollector&) = delete;
    InputCollector& operator=(const InputCollector&) = delete;
    const std::vector<std::string>& paths() const { return paths_; }
    void add(const std::string& path);

private:
    std::vector<std::string> paths_;
    InputCollector* outer_ = nullptr;
};

}  // namespace gyrokit
