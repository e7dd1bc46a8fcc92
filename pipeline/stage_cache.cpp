#include "pipeline/stage_cache.h"

#include <fcntl.h>
#include <nlohmann/json.hpp>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/binary_io.h"
#include "core/error.h"
#include "core/version.h"

namespace shatter {

namespace fs = std::filesystem;

namespace {

// FNV-1a of the running executable (/proc/self/exe names the image that runs, even when the file
// was replaced since), once per process: ~10 ms.
const std::string& program_hash() {
    static const std::string hash = file_hash("/proc/self/exe");
    return hash;
}

}  // namespace

std::string stage_key(std::string_view stage, const nlohmann::ordered_json& inputs) {
    nlohmann::ordered_json j;
    j["stage"] = stage;
    j["version"] = kVersion;
    j["program"] = program_hash();
    j["inputs"] = inputs;
    return fmt::format("{:016x}", fnv1a64(j.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace)));
}

std::string file_hash(const std::string& path) { return fmt::format("{:016x}", fnv1a64(read_file(path))); }

StageStamps::StageStamps(std::string out_dir) : dir_(std::move(out_dir)) {}

std::string StageStamps::path(const std::string& stage) const { return (fs::path(dir_) / ".shatter" / (stage + ".json")).string(); }

bool StageStamps::current(const std::string& stage, const std::string& key) const {
    std::error_code ec;
    if (!fs::exists(path(stage), ec)) return false;
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(read_file(path(stage), "stage stamp"));
        if (j.at("key").get<std::string>() != key) return false;
        for (const auto& [name, hash] : j.at("files").items()) {
            const fs::path f = fs::path(dir_) / name;
            if (!fs::exists(f, ec) || file_hash(f.string()) != hash.get<std::string>()) return false;
        }
    } catch (const std::exception&) {
        return false;  // a damaged stamp: run the stage again
    }
    return true;
}

void StageStamps::write(const std::string& stage, const std::string& key, const std::vector<std::string>& files) const {
    nlohmann::ordered_json j;
    j["key"] = key;
    j["files"] = nlohmann::ordered_json::object();
    for (const std::string& name : files) j["files"][name] = file_hash((fs::path(dir_) / name).string());
    make_directories((fs::path(dir_) / ".shatter").string());
    write_file_atomic(path(stage), j.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n");
}

void StageStamps::remove(const std::string& stage) const {
    std::error_code ec;
    fs::remove(path(stage), ec);
}

FileLock::FileLock(const std::string& path) {
    make_directories(fs::path(path).parent_path().string());
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw_io_error(path, std::strerror(errno));
    while (::flock(fd_, LOCK_EX) != 0) {
        if (errno != EINTR) throw_io_error(path, std::strerror(errno));
    }
}

FileLock::~FileLock() {
    if (fd_ >= 0) ::close(fd_);  // releases the lock
}

std::string StageCache::entry(const std::string& stage, const std::string& key) const {
    return (fs::path(root_) / stage / key).string();
}

std::string StageCache::lock_path(const std::string& stage, const std::string& key) const {
    return (fs::path(root_) / stage / (key + ".lock")).string();
}

namespace {

// Links `from` to `to` (replacing it), copying when a hard link is impossible (another file
// system); through a temporary name, so `to` is never half there.
void link_or_copy(const fs::path& from, const fs::path& to) {
    const fs::path tmp = to.string() + fmt::format(".tmp.{}", ::getpid());
    std::error_code ec;
    fs::remove(tmp, ec);
    fs::create_hard_link(from, tmp, ec);
    if (ec) {
        ec.clear();
        fs::copy_file(from, tmp, fs::copy_options::overwrite_existing, ec);
        if (ec) throw_io_error(tmp.string(), ec.message());
    }
    fs::rename(tmp, to, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw_io_error(to.string(), "cannot rename into place");
    }
}

}  // namespace

bool StageCache::fetch(const std::string& stage, const std::string& key, const std::string& out_dir,
                       const Files& files) const {
    if (!enabled()) return false;
    const fs::path e = entry(stage, key);
    std::error_code ec;
    if (!fs::exists(e / ".complete", ec)) return false;
    for (const auto& [cached, name] : files)
        if (!fs::exists(e / cached, ec)) return false;
    make_directories(out_dir);
    for (const auto& [cached, name] : files) link_or_copy(e / cached, fs::path(out_dir) / name);
    return true;
}

void StageCache::store(const std::string& stage, const std::string& key, const std::string& out_dir,
                       const Files& files) const {
    if (!enabled()) return;
    const fs::path e = entry(stage, key);
    make_directories(e.string());
    for (const auto& [cached, name] : files) link_or_copy(fs::path(out_dir) / name, e / cached);
    write_file_atomic((e / ".complete").string(), key + "\n");
}

}  // namespace shatter
