#include "core/toml_reader.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/error.h"

namespace shatter {

namespace {

const char* type_name(const toml::node& n) {
    if (n.is_string()) return "a string";
    if (n.is_integer()) return "an integer";
    if (n.is_floating_point()) return "a number";
    if (n.is_boolean()) return "a boolean";
    if (n.is_array()) return "an array";
    if (n.is_table()) return "a table";
    return "a date or time";
}

// Keys that were renamed: a shot file written before the rename gets the new name and how to
// write its value instead of "unknown key".
struct RenamedKey {
    const char* section;
    const char* old_name;
    const char* fix;
};
constexpr RenamedKey kRenamedKeys[] = {
    {"render", "colour_mode",
     "colour_mode was renamed colours: write colours = \"palette\" for colour_mode = \"pieces\", colours = "
     "\"material\" for \"material\", or colours = \"input\" (the default: the input mesh's own colours and "
     "textures)"},
};

}  // namespace

toml::table parse_toml_file(const std::string& path) {
    std::string text = read_file(path, "shot file");
    try {
        return toml::parse(text, path);
    } catch (const toml::parse_error& e) {
        const auto& src = e.source();
        throw_input_error(fmt::format("{}:{}:{}", path, src.begin.line, src.begin.column),
                          fmt::format("TOML syntax error: {}", e.description()),
                          "see docs/shot.md for the shot file syntax");
    }
}

TomlSection::TomlSection(const toml::table& table, std::string file, std::string name, bool from_flag)
    : table_(table), file_(std::move(file)), name_(std::move(name)), from_flag_(from_flag) {}

std::string TomlSection::where(const toml::node* n) const {
    if (from_flag_) return file_;
    const auto& src = n ? n->source() : table_.source();
    if (src.path && *src.path != file_) return *src.path;  // a value given on the command line (--set)
    if (src.begin.line == 0) return file_;
    return fmt::format("{}:{}", file_, src.begin.line);
}

void TomlSection::fail(const toml::node* n, const std::string& problem, const std::string& fix) const {
    if (from_flag_) {  // "--alpha = -1 is outside ...": the problem names the flag already
        const std::string prefix = problem.rfind(file_, 0) == 0 ? "" : where(n) + ": ";
        throw Error(ExitCode::Usage, fmt::format("{}{} (fix: {})", prefix, problem, fix));
    }
    throw_input_error(where(n), problem, fix);
}

const toml::node* TomlSection::node(const char* key) {
    asked_.insert(key);
    return table_.get(key);
}

bool TomlSection::number(const char* key, double& out, const Limits& limits) {
    const toml::node* n = node(key);
    if (!n) return false;
    if (auto v = n->value<double>()) {  // integers convert too
        check_limits(where(n), key_name(key), *v, limits, from_flag_);
        out = *v;
        return true;
    }
    fail(n, fmt::format("{} must be a number ({}), not {}", key_name(key), limits.unit, type_name(*n)),
         fmt::format("write e.g. {} = {:g}", key, limits.min));
}

bool TomlSection::integer(const char* key, uint32_t& out, const Limits& limits) {
    const toml::node* n = node(key);
    if (!n) return false;
    if (!n->is_integer())
        fail(n, fmt::format("{} must be a whole number ({})", key_name(key), limits.unit),
             fmt::format("write e.g. {} = {:g}", key, limits.min));
    const double v = static_cast<double>(n->as_integer()->get());
    check_limits(where(n), key_name(key), v, limits, from_flag_);
    out = static_cast<uint32_t>(v);
    return true;
}

bool TomlSection::integer(const char* key, uint64_t& out) {
    const toml::node* n = node(key);
    if (!n) return false;
    if (!n->is_integer() || n->as_integer()->get() < 0)
        fail(n, fmt::format("{} must be a whole number >= 0", key_name(key)), fmt::format("write e.g. {} = 1", key));
    out = static_cast<uint64_t>(n->as_integer()->get());
    return true;
}

bool TomlSection::text(const char* key, std::string& out) {
    const toml::node* n = node(key);
    if (!n) return false;
    if (!n->is_string()) fail(n, fmt::format("{} must be a string in quotes", key_name(key)), "put the value in quotes");
    out = n->as_string()->get();
    return true;
}

bool TomlSection::boolean(const char* key, bool& out) {
    const toml::node* n = node(key);
    if (!n) return false;
    if (!n->is_boolean()) fail(n, fmt::format("{} must be true or false", key_name(key)), "write true or false");
    out = n->as_boolean()->get();
    return true;
}

void TomlSection::finish() const {
    std::vector<std::string> allowed(asked_.begin(), asked_.end());
    for (auto&& [k, v] : table_) {
        const std::string key(k.str());
        if (asked_.count(key)) continue;
        std::string hint = closest_word(key, allowed);
        std::string fix = hint.empty() ? "" : fmt::format("did you mean '{}'? ", hint);
        fix += fmt::format("keys allowed in [{}]: {}", name_, fmt::join(allowed, ", "));
        for (const RenamedKey& r : kRenamedKeys)
            if (name_ == r.section && key == r.old_name) fix = r.fix;
        const auto& src = k.source();
        std::string at = src.begin.line ? fmt::format("{}:{}", file_, src.begin.line) : where(&v);
        throw_input_error(at, fmt::format("unknown key '{}'", key_name(key.c_str())), fix);
    }
}

std::string closest_word(const std::string& word, const std::vector<std::string>& candidates) {
    size_t best = 3;  // at most two edits away
    std::string found;
    for (const std::string& c : candidates) {
        std::vector<size_t> prev(c.size() + 1), cur(c.size() + 1);
        for (size_t j = 0; j <= c.size(); ++j) prev[j] = j;
        for (size_t i = 1; i <= word.size(); ++i) {
            cur[0] = i;
            for (size_t j = 1; j <= c.size(); ++j)
                cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (word[i - 1] != c[j - 1])});
            std::swap(prev, cur);
        }
        if (prev[c.size()] < best) best = prev[c.size()], found = c;
    }
    return found;
}

}  // namespace shatter
