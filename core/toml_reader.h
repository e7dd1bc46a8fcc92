// Strict reading of one table of a human-written TOML file (shot and batch files). Every key
// must be asked for: finish() turns any key nobody asked for into an error naming file:line,
// the key, and the keys allowed there (with a "did you mean"). Values are checked against their
// limits as they are read.
#pragma once

#include <set>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "core/settings.h"

namespace shatter {

// Parses a TOML file; a syntax error becomes Error(BadInput) "file:line:column: ...".
toml::table parse_toml_file(const std::string& path);

class TomlSection {
public:
    // `name` is the table's dotted name in messages ("mesh", "scene.colliders[2]"). A section
    // built from a command-line flag has `from_flag` set and the flag as `file`: its messages
    // name the flag and its errors are usage errors (exit code 2).
    TomlSection(const toml::table& table, std::string file, std::string name, bool from_flag = false);

    // Each getter leaves `out` alone and returns false when the key is absent.
    bool number(const char* key, double& out, const Limits& limits);
    bool integer(const char* key, uint32_t& out, const Limits& limits);
    bool integer(const char* key, uint64_t& out);
    bool text(const char* key, std::string& out);
    bool boolean(const char* key, bool& out);
    // The raw node for values of several possible types; marks the key as known.
    const toml::node* node(const char* key);

    // "file:line" of a node (or of the table when null).
    std::string where(const toml::node* n = nullptr) const;
    // "section.key" in messages; a section from a flag names the flag instead ("--alpha").
    std::string key_name(const char* key) const {
        return from_flag_ ? file_ : name_.empty() ? key : name_ + "." + key;
    }
    [[noreturn]] void fail(const toml::node* n, const std::string& problem, const std::string& fix) const;

    // Throws for every key that no getter asked for.
    void finish() const;

    const std::string& file() const { return file_; }
    const std::string& name() const { return name_; }
    bool from_flag() const { return from_flag_; }

private:
    const toml::table& table_;
    std::string file_;
    std::string name_;
    bool from_flag_;
    std::set<std::string> asked_;
};

// The closest of `candidates` to `word` by edit distance, or "" when none is close.
std::string closest_word(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace shatter
