#include <gyrokit/core/run_files.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/core/input_file.hpp>

#include <cerrno>
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

// The current run and this thread's collectors.
std::mutex g_run_mutex;
RunFiles* g_run = nullptr;
thread_local InputCollector* t_collector = nullptr;

}  // namespace

std::uint64_t fingerprint_bytes(const char* data, std::size_t n, std::uint64_t h) {
    for (std::size_t i = 0; i < n; ++i) h = (h ^ static_cast<unsigned char>(data[i])) * 1099511628211ull;
    return h;
}

bool FileIdentity::same_file(const FileIdentity& o) const {
    if (exists && o.exists) return device == o.device && inode == o.inode;
    return !exists && !o.exists && resolved == o.resolved;
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
    id.resolved = resolved_path(path);
    return id;
}

void RunFiles::refuse_if_output(const FileIdentity& id, const std::string& path, const std::string& what) const {
    for (const auto& o : outputs_)
        if (o.id.same_file(id))
            throw InputError(fmt::format("{} {}: that file is an input of this run (the {} {}); writing it would "
                                         "destroy what the run reads; allowed: a file the run does not read",
                                         o.option, o.path, what, path));
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
        if (const InputRecord* r = find_input(id); r && r->bytes) return r->bytes;
        refuse_if_output(id, path, what);
    }
    InputRecord rec;
    rec.path = path;
    rec.what = what;
    rec.id = id;
    // Read with its state before and after: a file written while it is read is refused, not half taken.
    struct stat before {}, after {};
    const bool ok_before = ::stat(path.c_str(), &before) == 0;
    std::string bytes;
    {
        FILE* f = std::fopen(path.c_str(), "rb");
        if (!f) throw InputError(fmt::format("{}: cannot open the {} for reading ({})", path, what, std::strerror(errno)));
        char buf[1 << 16];
        std::size_t n;
        while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) bytes.append(buf, n);
        const bool bad = std::ferror(f) != 0;
        std::fclose(f);
        if (bad) throw InputError(fmt::format("{}: read error in the {}", path, what));
    }
    if (!ok_before || ::stat(path.c_str(), &after) != 0 || before.st_size != after.st_size ||
        mtime_ns(before) != mtime_ns(after) || before.st_ino != after.st_ino ||
        static_cast<std::uintmax_t>(after.st_size) != bytes.size())
        throw InputError(fmt::format("{}: the {} changed while it was read; allowed: a file no one writes during the run",
                                     path, what));
    rec.size = bytes.size();
    rec.mtime_ns = mtime_ns(after);
    rec.fingerprint = fingerprint_bytes(bytes.data(), bytes.size());
    rec.bytes = std::make_shared<const std::string>(std::move(bytes));
    std::lock_guard<std::mutex> lock(mutex_);
    // Another thread may have read it meanwhile: the first copy serves every reader.
    if (const InputRecord* r = find_input(id); r && r->bytes) return r->bytes;
    inputs_.push_back(rec);
    return rec.bytes;
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
    if (path.empty()) return;
    if (path == "-") return;   // standard output
    const FileIdentity id = identify_file(path);
    std::lock_guard<std::mutex> lock(mutex_);
    if (id.exists && !id.regular) {
        if (fs::is_directory(fs::status(path)))
            throw InputError(fmt::format("{} {}: is a folder; allowed: a file (new, or one to replace)", option, path));
        return;   // a device or FIFO is written in place; it is nobody's input
    }
    if (const InputRecord* r = find_input(id))
        throw InputError(fmt::format("{} {}: that file is an input of this run (the {} {}); writing it would destroy "
                                     "what the run reads; allowed: a file the run does not read",
                                     option, path, r->what, r->path));
    for (const auto& o : outputs_) {
        if (!o.id.same_file(id)) continue;
        if (o.option == option && o.path == path) return;
        throw InputError(fmt::format("{} {}: the same file as {} {}, another output of this run; allowed: one file "
                                     "per output",
                                     option, path, o.option, o.path));
    }
    // Before the work, not after it: a long run must not end in a file it cannot write.
    const fs::path p(path);
    const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
    std::error_code ec;
    if (!fs::is_directory(dir, ec) || ::access(dir.c_str(), W_OK) != 0)
        throw InputError(fmt::format("{} {}: the folder '{}' does not exist or is not writable; allowed: a file in a "
                                     "writable folder",
                                     option, path, dir.string()));
    outputs_.push_back({path, option, id});
}

std::string RunFiles::changed_inputs() const {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& r : inputs_) {
        struct stat st {};
        if (::stat(r.path.c_str(), &st) != 0)
            return fmt::format("{}: the {} was removed or renamed while the run read it", r.path, r.what);
        if (static_cast<std::uint64_t>(st.st_ino) != r.id.inode || static_cast<std::uint64_t>(st.st_dev) != r.id.device ||
            static_cast<std::uintmax_t>(st.st_size) != r.size || mtime_ns(st) != r.mtime_ns)
            return fmt::format("{}: the {} changed during the run (its size, time or inode is not what it was when "
                               "read); the results come from the file as it was at the start",
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

RunFiles* current_run() {
    std::lock_guard<std::mutex> lock(g_run_mutex);
    return g_run;
}

RunScope::RunScope() {
    std::lock_guard<std::mutex> lock(g_run_mutex);
    if (g_run) {
        active_ = g_run;
        return;
    }
    own_ = std::make_unique<RunFiles>();
    g_run = active_ = own_.get();
    installed_ = true;
}

RunScope::RunScope(RunFiles& files) {
    std::lock_guard<std::mutex> lock(g_run_mutex);
    if (g_run) {
        active_ = g_run;
        return;
    }
    g_run = active_ = &files;
    installed_ = true;
}

RunScope::~RunScope() {
    std::lock_guard<std::mutex> lock(g_run_mutex);
    if (installed_) g_run = nullptr;
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
