// The envelope every stage file shares (model, trajectory, ...), described in docs/formats.md:
//
//   offset  size  field
//   0       8     magic, e.g. "SHTMODEL" (names the kind of file)
//   8       4     format version (u32); a reader accepts a range and refuses others
//   12      4     byte-order mark 0x01020304 (u32), refuses a file from a big-endian writer
//   16      4+n   producer (u32 length + UTF-8), e.g. "shatter 0.1.0"
//   ...     4+n   settings (u32 length + canonical JSON): the settings and inputs that made it
//   ...     8     payload size in bytes (u64)
//   ...     8     FNV-1a 64 of the payload (u64): detects truncation and flipped bits
//   ...           payload, little-endian, as the kind's own section of docs/formats.md says
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

namespace shatter {

constexpr size_t kMagicSize = 8;
constexpr uint32_t kByteOrderMark = 0x01020304u;

struct StageHeader {
    std::string magic;     // exactly kMagicSize characters
    uint32_t version = 0;
    std::string producer;
    std::string settings_json;
};

// Header + payload, ready for write_file_atomic.
std::string pack_stage_file(const StageHeader& header, std::string_view payload);

struct StageFile {
    StageHeader header;
    std::string_view payload;  // points into the bytes given to unpack_stage_file
    size_t payload_offset = 0;
};

// Checks magic, version range, byte order, size and checksum; throws Error(BadInput) naming
// `source` and what is wrong. `kind` names the file kind in messages ("model").
StageFile unpack_stage_file(std::string_view bytes, const std::string& source, std::string_view magic,
                            const char* kind, uint32_t min_version, uint32_t max_version);

// The magic of a stage file, or "" when the bytes do not start like one.
std::string stage_file_magic(std::string_view bytes);

// "shatter <version>": the producer written into every stage file.
std::string producer_string();

// What a stage chose by itself, kept in its file's settings (parsed) under "auto": prescore's in
// a model, simulate's in a trajectory, {"what", "why"} each; an empty array when none.
nlohmann::ordered_json stage_choices(const nlohmann::ordered_json& settings);
// Those choices as `shatter info` lists them, a line each: "chosen        WHAT; why: WHY"; then
// the stage's warnings, a line each: "warning       TEXT".
std::string stage_choices_text(const nlohmann::ordered_json& settings);
// What a stage warned of, kept in its file's settings under "warnings" (texts, in order; files
// named relative to the mesh's folder); an empty array when none.
nlohmann::ordered_json stage_warnings(const nlohmann::ordered_json& settings);

}  // namespace shatter
