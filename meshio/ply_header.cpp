// The PLY header check. Why it exists: ply_header.h.
#include "meshio/ply_header.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <sstream>
#include <vector>

#include "core/error.h"

namespace shatter {

namespace {

constexpr size_t kMaxHeaderBytes = 64 * 1024;

bool scalar_type(const std::string& t) {
    static const std::array<const char*, 16> types = {"char",  "uchar",  "short",  "ushort", "int",    "uint",
                                                      "float", "double", "int8",   "uint8",  "int16",  "uint16",
                                                      "int32", "uint32", "float32", "float64"};
    return std::find(types.begin(), types.end(), t) != types.end();
}

bool count(const std::string& s) {
    unsigned long long v = 0;
    auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    return ec == std::errc() && end == s.data() + s.size();
}

// The problem with one header line, or "" when it is well formed.
std::string line_problem(const std::vector<std::string>& w, bool* elements_seen) {
    const std::string& key = w[0];
    if (key == "comment" || key == "obj_info") return "";
    if (key == "format") {
        if (w.size() != 3 || (w[1] != "ascii" && w[1] != "binary_little_endian" && w[1] != "binary_big_endian"))
            return "a format line must be 'format ascii|binary_little_endian|binary_big_endian 1.0'";
        return "";
    }
    if (key == "element") {
        *elements_seen = true;
        return w.size() == 3 && count(w[2]) ? "" : "an element line must be 'element NAME COUNT'";
    }
    if (key == "property") {
        if (!*elements_seen) return "a property before any element";
        if (w.size() == 3 && scalar_type(w[1])) return "";
        if (w.size() == 5 && w[1] == "list" && scalar_type(w[2]) && scalar_type(w[3])) return "";
        return "a property line must be 'property TYPE NAME' or 'property list TYPE TYPE NAME'";
    }
    // Any other line of printable text ("Created by ...", an exporter's own note) is skipped, as
    // assimp's reader skips it: only the lines that define the layout can mislead the reader.
    return "";
}

}  // namespace

bool looks_like_ply(std::string_view bytes) { return bytes.substr(0, 3) == "ply"; }

void check_ply_header(std::string_view bytes, const std::string& path) {
    const std::string fix = "re-export the PLY file; its header is damaged";
    const std::string_view head = bytes.substr(0, kMaxHeaderBytes);
    size_t pos = 0, line_no = 0;
    bool elements_seen = false, format_seen = false;
    while (pos < head.size()) {
        const size_t end = head.find('\n', pos);
        if (end == std::string_view::npos) break;
        std::string line(head.substr(pos, end - pos));
        pos = end + 1;
        ++line_no;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        const std::string where = path + ":" + std::to_string(line_no);
        if (std::any_of(line.begin(), line.end(), [](char c) { return (c < 32 && c != '\t') || c == 127; }))
            throw_input_error(where, "the PLY header has a control or binary byte", fix);
        std::istringstream words(line);
        std::vector<std::string> w;
        for (std::string word; words >> word;) w.push_back(word);
        if (line_no == 1) {
            if (line != "ply") throw_input_error(where, "a PLY file's first line must be 'ply'", fix);
            continue;
        }
        if (w.empty()) continue;
        if (w[0] == "end_header") {
            if (!format_seen) throw_input_error(where, "the PLY header has no format line", fix);
            return;
        }
        if (w[0] == "format") format_seen = true;
        const std::string problem = line_problem(w, &elements_seen);
        if (!problem.empty()) throw_input_error(where, "PLY header: " + problem, fix);
    }
    throw_input_error(path, "the PLY header has no end_header line (in its first 64 kB)", fix);
}

}  // namespace shatter
