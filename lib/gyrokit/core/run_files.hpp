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

// What makes two paths the same file: device and inode where the file exists (a
// hard link or a symbolic link to it has the same), else the absolute path with
// the symbolic links of its existing part resolved.
struct FileIdentity {
    bool exists = false;
    bool regular = false;       // a regular file (not a device, FIFO, socket or folder)
    std::uint64_t device = 0, inode = 0;
    std::string resolved;
    bool same_file(const FileIdentity& other) const;
};
FileIdentity identify_file(const std::string& path);

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
    // The bytes of an input after check_input_file, read once: a later read of the
    // same file (by any path, from any thread) gets the same copy. InputError if the
    // file is an output this run claimed, or changed while it was read.
    std::shared_ptr<const std::string> read(const std::string& path, const std::string& what, std::uintmax_t max_bytes);
    // An input read by other means (a result file merged): outputs may not be it.
    void note_input(const std::string& path, const std::string& what);
    // `path` becomes an output of this run, given by `option` ("--plot", "path"):
    // InputError (nothing written) if it is an input of the run or another output
    // of it, or if its folder does not exist or is not writable. A path that is not
    // a regular file (-, /dev/null, a FIFO) is never refused as the same file. The
    // same option may claim the same path again.
    void claim_output(const std::string& path, const std::string& option);
    // What changed since the inputs were read ("" where nothing did): the first input
    // whose size, modification time or inode is no longer what it was, named.
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

// The run in progress in this process (a command of the CLI, a Python call), or
// nullptr outside one.
RunFiles* current_run();

// Makes `files` the current run for its lifetime; inside a run already in
// progress it joins that one (the outer run decides). Without an argument: a run
// of its own unless one is in progress.
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
    bool installed_ = false;
};

// The bytes of an input file: through the current run (read once) where there is
// one, else read now. Every reader of scene, sweep, matrix and table files calls it,
// and the paths it reads on this thread are reported to each InputCollector alive.
std::shared_ptr<const std::string> read_input(const std::string& path, const std::string& what,
                                              std::uintmax_t max_bytes);

// The paths read_input read on this thread while it lives (a scene's own inputs).
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
