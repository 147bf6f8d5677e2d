#include <gyrokit/io/output_file.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/core/run_files.hpp>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <fmt/format.h>
#include <iostream>
#include <sys/stat.h>
#include <unistd.h>

namespace gyrokit {

namespace {

std::atomic<unsigned> g_temp_counter{0};

// The process's own descriptor a path names (-, /dev/stdout, /dev/fd/3, ...), or -1.
// Opening /dev/stdout anew would start at the beginning of a file the shell opened
// for appending, or fail for a pipe: the descriptor itself is written instead.
int stream_of(const std::string& path) {
    if (path == "-" || path == "/dev/stdout") return STDOUT_FILENO;
    if (path == "/dev/stderr") return STDERR_FILENO;
    for (const char* prefix : {"/dev/fd/", "/proc/self/fd/"}) {
        const std::string p(prefix);
        if (path.rfind(p, 0) == 0 && path.size() > p.size() &&
            path.find_first_not_of("0123456789", p.size()) == std::string::npos)
            return std::stoi(path.substr(p.size()));
    }
    return -1;
}

}  // namespace

int write_all(int fd, std::string_view bytes) {
    const char* p = bytes.data();
    std::size_t left = bytes.size();
    while (left > 0) {
        const ssize_t n = ::write(fd, p, left);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return errno;
        if (n == 0) return EIO;
        p += n;
        left -= static_cast<std::size_t>(n);
    }
    return 0;
}

void sync_folder_of(const std::string& path) {
    const int dfd = ::open(folder_of(path).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dfd >= 0) {
        ::fsync(dfd);
        ::close(dfd);
    }
}

OutputFile::OutputFile(const std::string& path, const std::string& option, const std::string& what)
    : path_(path), option_(option), what_(what) {
    if (RunFiles* run = current_run()) {
        run->claim_output(path, option);
    } else {
        RunFiles alone;
        alone.claim_output(path, option);
    }
    stream_ = stream_of(path);
    if (stream_ >= 0) {
        in_place_ = true;
        return;
    }
    target_ = link_target(path);
    struct stat st {};
    in_place_ = ::stat(target_.c_str(), &st) == 0 && !S_ISREG(st.st_mode);   // a device or FIFO: no entry to replace
}

OutputFile::~OutputFile() {
    if (fd_ >= 0) ::close(fd_);
    if (!committed_ && !temp_.empty()) ::unlink(temp_.c_str());
}

void OutputFile::open() {
    if (stream_ >= 0) {
        // After what the process printed there: the streams' buffers first.
        std::cout.flush();
        std::cerr.flush();
        std::fflush(nullptr);
        fd_ = ::dup(stream_);
        if (fd_ < 0) fail("open its descriptor", errno);
        return;
    }
    if (in_place_) {
        fd_ = ::open(target_.c_str(), O_WRONLY | O_CLOEXEC);
        if (fd_ < 0) fail("open", errno);
        return;
    }
    const std::string dir = folder_of(target_);
    const std::string base = target_.substr(target_.find_last_of('/') + 1);
    for (int attempt = 0; attempt < 100 && fd_ < 0; ++attempt) {
        temp_ = fmt::format("{}/.{}.{}.{}.tmp", dir, base, ::getpid(), g_temp_counter++);
        fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd_ < 0 && errno != EEXIST) break;
    }
    if (fd_ < 0) {
        const int err = errno;
        temp_.clear();
        fail("create a temporary file beside it for", err);
    }
    // A replaced file keeps its permission bits (not set-user-ID and the like).
    struct stat old {};
    if (::stat(target_.c_str(), &old) == 0) ::fchmod(fd_, old.st_mode & 0777);
}

void OutputFile::fail(const std::string& doing, int err) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    if (!temp_.empty()) ::unlink(temp_.c_str());
    temp_.clear();
    const std::string cause = err == ENOSPC ? "the disk is full" : std::strerror(err);
    throw Error(fmt::format("{} {}: cannot {} the {} ({}); the file is as it was", option_, path_, doing, what_,
                            cause));
}

void OutputFile::write(std::string_view bytes) {
    if (fd_ < 0) open();
    if (const int err = write_all(fd_, bytes)) fail("write", err);
}

void OutputFile::commit() {
    if (fd_ < 0) open();   // an empty file is a file too
    const int fd = fd_;
    fd_ = -1;
    if (in_place_) {
        committed_ = true;
        if (::close(fd) != 0 && errno != EINTR) fail("write", errno);
        return;
    }
    if (::fsync(fd) != 0) {
        const int err = errno;
        ::close(fd);
        fail("write", err);
    }
    if (::close(fd) != 0) fail("write", errno);
    if (::rename(temp_.c_str(), target_.c_str()) != 0) fail("replace", errno);
    committed_ = true;
    sync_folder_of(target_);
}

void replace_file(const std::string& path, const std::string& text, const std::string& what,
                  const std::string& option) {
    OutputFile out(path, option, what);
    out.write(text);
    out.commit();
}

}  // namespace gyrokit
