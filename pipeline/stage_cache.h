// What makes `shatter run` resumable and incremental: every stage's outputs are stamped with a
// key, a hash of everything the stage read (input file bytes and settings), and a stage whose
// stamp matches and whose files are intact is skipped. Stamps are written after the outputs, so
// a run killed mid-stage leaves no stamp and that stage runs again.
//
// A shared cache (batch jobs) keeps a copy of prescore and simulate outputs under their keys, so
// that an alpha sweep tetrahedralizes once: CACHE/STAGE/KEY/FILE, hard-linked when possible.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace shatter {

// The key of a stage: 16 hex digits of FNV-1a over the stage name, shatter's version, the
// running program's own bytes (a rebuilt or upgraded shatter computes its stages anew even when
// the version string is unchanged: keyed on the inputs alone, a cache handed out results of the
// previous physics) and the canonical JSON of its inputs.
std::string stage_key(std::string_view stage, const nlohmann::ordered_json& inputs);

// FNV-1a of a file's bytes as 16 hex digits; throws Error(BadInput) when it cannot be read.
std::string file_hash(const std::string& path);

// OUT_DIR/.shatter/STAGE.json: {"key": KEY, "files": {NAME: HASH}} for files in OUT_DIR.
class StageStamps {
public:
    explicit StageStamps(std::string out_dir);
    // True when STAGE's stamp has `key` and every file it lists exists with its recorded hash.
    bool current(const std::string& stage, const std::string& key) const;
    // Hashes `files` (names relative to the output directory) and writes the stamp atomically.
    void write(const std::string& stage, const std::string& key, const std::vector<std::string>& files) const;
    void remove(const std::string& stage) const;

private:
    std::string path(const std::string& stage) const;
    std::string dir_;
};

// An exclusive advisory lock (flock) on a file, held for the object's lifetime: two workers that
// need the same stage output compute it once.
class FileLock {
public:
    explicit FileLock(const std::string& path);
    ~FileLock();
    FileLock(const FileLock&) = delete;
    FileLock& operator=(const FileLock&) = delete;

private:
    int fd_ = -1;
};

// The shared cache of stage outputs. An empty root disables it.
class StageCache {
public:
    explicit StageCache(std::string root) : root_(std::move(root)) {}
    bool enabled() const { return !root_.empty(); }
    // The lock file of STAGE/KEY (held while the stage is computed).
    std::string lock_path(const std::string& stage, const std::string& key) const;
    // The files of a stage: {name in the cache, name in the output directory}, e.g.
    // {"model", "bunny.model"}: jobs with other file names share the entry.
    using Files = std::vector<std::pair<std::string, std::string>>;
    // Copies (hard links when possible) every cached file of STAGE/KEY into `out_dir`; false when
    // the cache has no complete entry.
    bool fetch(const std::string& stage, const std::string& key, const std::string& out_dir, const Files& files) const;
    // Stores the files of `out_dir` as STAGE/KEY (complete once its marker is written).
    void store(const std::string& stage, const std::string& key, const std::string& out_dir, const Files& files) const;

private:
    std::string entry(const std::string& stage, const std::string& key) const;
    std::string root_;
};

}  // namespace shatter
