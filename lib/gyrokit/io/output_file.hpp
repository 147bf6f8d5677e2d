// Every file gyrokit writes passes here. A file is claimed in the current run
// first (never an input of the run, a link to one, or another output of it: see
// core/run_files.hpp), then written whole or not at all: into a temporary file in
// the target's folder, synced, and renamed over the target, so that a reader, a
// crash or a full disk never leaves half a file and the old file stays until the
// new one is complete. A symbolic link is written through to its target (the
// link kept). A path that is not a regular file is written in place: `-`,
// /dev/stdout, /dev/stderr and /dev/fd/N on the process's own descriptor (after
// what the process printed there), /dev/null or a FIFO opened as it is.
#pragma once

#include <string>
#include <string_view>

namespace gyrokit {

class OutputFile {
public:
    // Claims `path` for `option` (the run's word for it: "--out", "path"); the
    // temporary file is made at the first write, so a long run leaves none behind
    // before it has something to write. InputError naming the path where it is refused.
    OutputFile(const std::string& path, const std::string& option, const std::string& what);
    ~OutputFile();   // not committed: the temporary file is removed, the target untouched
    OutputFile(const OutputFile&) = delete;
    OutputFile& operator=(const OutputFile&) = delete;

    void write(std::string_view bytes);
    // Synced and renamed over the target. Error naming the file and the cause (disk full, ...).
    void commit();
    const std::string& path() const { return path_; }

private:
    void open();
    [[noreturn]] void fail(const std::string& doing, int err);
    std::string path_, option_, what_, target_, temp_;
    int fd_ = -1;
    int stream_ = -1;   // the descriptor a /dev/stdout-like path names, else -1
    bool in_place_ = false, committed_ = false;
};

// `text` written to `path` through an OutputFile.
void replace_file(const std::string& path, const std::string& text, const std::string& what,
                  const std::string& option = "path");

// All of `bytes` written to `fd` (EINTR retried): 0, or the errno of the failure.
int write_all(int fd, std::string_view bytes);
// The folder of `path` synced: a new or renamed entry survives a power loss.
void sync_folder_of(const std::string& path);

}  // namespace gyrokit
