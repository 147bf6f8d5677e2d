#include <gyrokit/core/run_files.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/core/input_file.hpp>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

namespace gyrokit {

namespace fs = std::filesystem;

namespace {

std::int64_t mtime_ns(const struct stat& st) {
    return static_cast<std::int64_t>(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec;
}

std::string resolved_path(const std::string& path) {
    std::error_code ec;
    const fs::path abs = fs::absolute(path, ec);
    if (ec) return path;
    const fs::path r = fs::weakly_canonical(abs, ec);
    return (ec ? abs : r).lexically_normal().string();
}

std::string input_of_run(const std::string& option, const std::string& path, const std::string& what,
                         const std::string& input) {
    return fmt::format("{} {}: that file is an input of this run (the {} {}); writing it would destroy what the run "
                       "reads; allowed: a file the run does not read",
                       option, path, what, input);
}

// The bytes of a file with its state before and after: a file written while it
// is read is refused, not half taken.
std::string read_whole(const std::string& path, const std::string& what, struct stat& after) {
    struct stat before {};
    const bool ok_before = ::stat(path.c_str(), &before) == 0;
    std::string bytes;
    FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) throw InputError(fmt::format("{}: cannot open the {} for reading ({})", path, what, std::strerror(errno)));
    if (ok_before) bytes.reserve(static_cast<std::size_t>(before.st_size));
    char buf[1 << 16];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) bytes.append(buf, n);
    const bool bad = std::ferror(f) != 0;
    std::fclose(f);
    if (bad) throw InputError(fmt::format("{}: read error in the {}", path, what));
    if (!ok_before || ::stat(path.c_str(), &after) != 0 || before.st_size != after.st_size ||
        mtime_ns(before) != mtime_ns(after) || before.st_ino != after.st_ino ||
        static_cast<std::uintmax_t>(after.st_size) != bytes.size())
        throw InputError(fmt::format("{}: the {} changed while it was read; allowed: a file no one writes during the run",
                                     path, what));
    return bytes;
}

// This thread's run and collectors: runs on other threads (another Python
// thread's call) are theirs alone.
thread_local RunFiles* t_run = nullptr;
thread_local InputCollector* t_collector = nullptr;

}  // namespace

std::uint64_t fingerprint_bytes(const char* data, std::size_t n, std::uint64_t h) {
    for (std::size_t i = 0; i < n; ++i) h = (h ^ static_cast<unsigned char>(data[i])) * 1099511628211ull;
    return h;
}

bool FileIdentity::same_file(const FileIdentity& o) const {
    if (exists && o.exists && device == o.device && inode == o.inode) return true;
    return resolved == o.resolved;
}

std::string link_target(const std::string& path) {
    fs::path p = path;
    for (int hops = 0; hops < 40; ++hops) {
        std::error_code ec;
        if (!fs::is_symlink(fs::symlink_status(p, ec))) return p.string();
        const fs::path t = fs::read_symlink(p, ec);
        if (ec) return p.string();
        p = t.is_absolute() ? t : p.parent_path() / t;
    }
    throw InputError(fmt::format("{}: a symbolic link in a loop; allowed: a file or a link to one", path));
}

std::string folder_of(const std::string& path) {
    const fs::path p(path);
    return p.has_parent_path() ? p.parent_path().string() : std::string(".");
}

FileIdentity identify_file(const std::string& path) {
    FileIdentity id;
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0) {
        id.exists = true;
        id.regular = S_ISREG(st.st_mode);
        id.device = static_cast<std::uint64_t>(st.st_dev);
        id.inode = static_cast<std::uint64_t>(st.st_ino);
    }
    std::string target = path;
    try {
        target = link_target(path);
    } catch (const InputError&) {
    }
    id.resolved = resolved_path(target);
    return id;
}

void RunFiles::refuse_if_output(const FileIdentity& id, const std::string& path, const std::string& what) const {
    for (const auto& o : outputs_)
        if (o.id.same_file(id)) throw InputError(input_of_run(o.option, o.path, what, path));
}

const InputRecord* RunFiles::find_input(const FileIdentity& id) const {
    for (const auto& r : inputs_)
        if (r.id.same_file(id)) return &r;
    return nullptr;
}

std::shared_ptr<const std::string> RunFiles::read(const std::string& path, const std::string& what,
                                                  std::uintmax_t max_bytes) {
    check_input_file(path, what, max_bytes);
    const FileIdentity id = identify_file(path);
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (const InputRecord* r = find_input(id); r && r->bytes) {
            // The copy serves while the file is still the one read; an edit since is the run's failure.
            struct stat st {};
            if (::stat(path.c_str(), &st) == 0 && static_cast<std::uintmax_t>(st.st_size) == r->size &&
                mtime_ns(st) == r->mtime_ns)
                return r->bytes;
            throw InputError(fmt::format("{}: the {} changed while the run read it; allowed: inputs left alone until "
                                         "the run ends",
                                         path, what));
        }
        refuse_if_output(id, path, what);
    }
    struct stat after {};
    std::string bytes = read_whole(path, what, after);
    InputRecord rec;
    rec.path = path;
    rec.what = what;
    rec.id = id;
    rec.size = bytes.size();
    rec.mtime_ns = mtime_ns(after);
    rec.fingerprint = fingerprint_bytes(bytes.data(), bytes.size());
    rec.bytes = std::make_shared<const std::string>(std::move(bytes));
    std::lock_guard<std::mutex> lock(mutex_);
    // Another thread of the run may have read it meanwhile: the first copy serves every reader.
    if (const InputRecord* r = find_input(id); r && r->bytes) return r->bytes;
    inputs_.push_back(rec);
    return rec.bytes;
}

RunFiles::RunFiles(const std::vector<std::string>& inputs) {
    for (const auto& in : inputs) note_input(in, "input");
}

void RunFiles::note_input(const std::string& path, const std::string& what) {
    const FileIdentity id = identify_file(path);
    if (!id.exists) return;   // a name, not a file (a sweep built in code): nothing to protect or to watch
    std::lock_guard<std::mutex> lock(mutex_);
    if (find_input(id)) return;
    refuse_if_output(id, path, what);
    InputRecord rec;
    rec.path = path;
    rec.what = what;
    rec.id = id;
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0) {
        rec.size = static_cast<std::uintmax_t>(st.st_size);
        rec.mtime_ns = mtime_ns(st);
    }
    inputs_.push_back(rec);
}

void RunFiles::claim_output(const std::string& path, const std::string& option) {
    if (path.empty() || path == "-") return;   // nothing, or standard output
    const FileIdentity id = identify_file(path);
    std::lock_guard<std::mutex> lock(mutex_);
    if (id.exists && !id.regular) {
        std::error_code ec;
        if (fs::is_directory(path, ec))
            throw InputError(fmt::format("{} {}: is a folder; allowed: a file (new, or one to replace)", option, path));
        return;   // a device or FIFO is written in place; it is nobody's input
    }
    if (const InputRecord* r = find_input(id)) throw InputError(input_of_run(option, path, r->what, r->path));
    for (const auto& o : outputs_) {
        if (!o.id.same_file(id)) continue;
        if (o.option == option && o.path == path) return;
        throw InputError(fmt::format("{} {}: the same file as {} {}, another output of this run; allowed: one file "
                                     "per output",
                                     option, path, o.option, o.path));
    }
    // Before the work, not after it: a long run must not end in a file it cannot write.
    // A link is written through, so its target's folder is the one that counts.
    const std::string target = link_target(path);
    const std::string dir = folder_of(target);
    std::error_code ec;
    if (!fs::is_directory(dir, ec) || ::access(dir.c_str(), W_OK) != 0)
        throw InputError(fmt::format("{} {}: the folder '{}' does not exist or is not writable; allowed: a file in a "
                                     "writable folder",
                                     option, path, dir));
    if (id.exists && ::access(target.c_str(), W_OK) != 0)
        throw InputError(fmt::format("{} {}: the file is write-protected; allowed: a file that may be replaced",
                                     option, path));
    outputs_.push_back({path, option, id});
}

std::string RunFiles::changed_inputs() const {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& r : inputs_) {
        struct stat st {};
        if (::stat(r.path.c_str(), &st) != 0)
            return fmt::format("{}: the {} was removed or renamed while the run read it", r.path, r.what);
        const bool same_state = static_cast<std::uintmax_t>(st.st_size) == r.size && mtime_ns(st) == r.mtime_ns;
        const bool same_file = static_cast<std::uint64_t>(st.st_ino) == r.id.inode &&
                               static_cast<std::uint64_t>(st.st_dev) == r.id.device;
        if (same_file && same_state) continue;
        // A new time alone (touch), or a rewrite with the same bytes, changes nothing the run read.
        if (r.bytes && static_cast<std::uintmax_t>(st.st_size) == r.size) {
            struct stat after {};
            try {
                const std::string now = read_whole(r.path, r.what, after);
                if (fingerprint_bytes(now.data(), now.size()) == r.fingerprint && now == *r.bytes) continue;
            } catch (const InputError&) {
            }
        }
        return fmt::format("{}: the {} changed during the run; the results come from the file as it was when read",
                           r.path, r.what);
    }
    return "";
}

void RunFiles::check_inputs_unchanged() const {
    const std::string what = changed_inputs();
    if (!what.empty())
        throw InputError(what + "; allowed: inputs left alone until the run ends (run it again to use the new file)");
}

std::vector<InputRecord> RunFiles::inputs() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return inputs_;
}

RunFiles* current_run() { return t_run; }

RunScope::RunScope() {
    if (t_run) {
        active_ = t_run;
        return;
    }
    own_ = std::make_unique<RunFiles>();
    previous_ = t_run;
    t_run = active_ = own_.get();
    installed_ = true;
}

RunScope::RunScope(RunFiles& files) : active_(&files), previous_(t_run), installed_(true) { t_run = &files; }

RunScope::~RunScope() {
    if (installed_) t_run = previous_;
}

InputCollector::InputCollector() : outer_(t_collector) { t_collector = this; }
InputCollector::~InputCollector() { t_collector = outer_; }

void InputCollector::add(const std::string& path) {
    for (const auto& p : paths_)
        if (p == path) return;
    paths_.push_back(path);
    if (outer_) outer_->add(path);
}

std::shared_ptr<const std::string> read_input(const std::string& path, const std::string& what,
                                              std::uintmax_t max_bytes) {
    std::shared_ptr<const std::string> bytes;
    if (RunFiles* run = current_run()) {
        bytes = run->read(path, what, max_bytes);
    } else {
        RunFiles once;
        bytes = once.read(path, what, max_bytes);
    }
    if (t_collector) {
        std::error_code ec;
        const fs::path abs = fs::absolute(path, ec);
        t_collector->add(ec ? path : abs.lexically_normal().string());
    }
    return bytes;
}

}  // namespace gyrokit
