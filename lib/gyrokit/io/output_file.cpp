#include <gyrokit/io/output_file.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/core/run_files.hpp>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

namespace gyrokit {

namespace fs = std::filesystem;

namespace {

// The file a symbolic link leads to (followed link by link, relative links from
// their own folder); the path itself where it is no link.
fs::path link_target(const fs::path& path) {
    fs::path p = path;
    for (int hops = 0; hops < 40; ++hops) {
        std::error_code ec;
        if (!fs::is_symlink(fs::symlink_status(p, ec))) return p;
        const fs::path t = fs::read_symlink(p, ec);
        if (ec) return p;
        p = t.is_absolute() ? t : p.parent_path() / t;
    }
    throw InputError(fmt::format("{}: a symbolic link in a loop; allowed: a file or a link to one", path.string()));
}

std::atomic<unsigned> g_temp_counter{0};

}  // namespace

OutputFile::OutputFile(const std::string& path, const std::string& option, const std::string& what)
    : path_(path), option_(option), what_(what) {
    if (RunFiles* run = current_run()) {
        run->claim_output(path, option);
    } else {
        RunFiles alone;
        alone.claim_output(path, option);
    }
    if (path == "-") {
        fd_ = ::dup(STDOUT_FILENO);
        in_place_ = true;
        if (fd_ < 0) fail("open standard output", errno);
        return;
    }
    const fs::path target = link_target(path);
    target_ = target.string();
    struct stat st {};
    if (::stat(target_.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
        // A device or FIFO: no folder entry to replace; written as it is.
        in_place_ = true;
        fd_ = ::open(target_.c_str(), O_WRONLY | O_CLOEXEC);
        if (fd_ < 0) fail("open", errno);
        return;
    }
    const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
    const std::string base = target.filename().string();
    for (int attempt = 0; attempt < 100 && fd_ < 0; ++attempt) {
        temp_ = (dir / fmt::format(".{}.{}.{}.tmp", base, ::getpid(), g_temp_counter++)).string();
        fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd_ < 0 && errno != EEXIST) break;
    }
    if (fd_ < 0) {
        const int err = errno;
        temp_.clear();
        fail("create a file in its folder", err);
    }
    // A replaced file keeps its permissions.
    struct stat old {};
    if (::stat(target_.c_str(), &old) == 0) ::fchmod(fd_, old.st_mode & 07777);
}

OutputFile::~OutputFile() {
    if (fd_ >= 0) ::close(fd_);
    if (!committed_ && !temp_.empty()) ::unlink(temp_.c_str());
}

void OutputFile::fail(const std::string& doing, int err) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    if (!temp_.empty()) ::unlink(temp_.c_str());
    temp_.clear();
    const std::string cause = err == ENOSPC ? "the disk is full" : std::strerror(err);
    throw Error(fmt::format("{} {}: cannot {} the {} ({}); the file is as it was", option_, path_, doing, what_, cause));
}

void OutputFile::write(std::string_view bytes) {
    const char* p = bytes.data();
    std::size_t left = bytes.size();
    while (left > 0) {
        const ssize_t n = ::write(fd_, p, left);
        if (n < 0) {
            if (errno == EINTR) continue;
            fail("write", errno);
        }
        p += n;
        left -= static_cast<std::size_t>(n);
    }
}

void OutputFile::commit() {
    if (in_place_) {
        const int fd = fd_;
        fd_ = -1;
        committed_ = true;
        if (::close(fd) != 0 && errno != EINTR) fail("write", errno);
        return;
    }
    if (::fsync(fd_) != 0) fail("write", errno);
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) fail("write", errno);
    if (::rename(temp_.c_str(), target_.c_str()) != 0) fail("replace", errno);
    committed_ = true;
    // The new name must survive a power loss as well as the bytes.
    const fs::path dir = fs::path(target_).has_parent_path() ? fs::path(target_).parent_path() : fs::path(".");
    const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dfd >= 0) {
        ::fsync(dfd);
        ::close(dfd);
    }
}

void replace_file(const std::string& path, const std::string& text, const std::string& what,
                  const std::string& option) {
    OutputFile out(path, option, what);
    out.write(text);
    out.commit();
}

}  // namespace gyrokit
