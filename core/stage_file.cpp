#include "core/stage_file.h"

#include <cassert>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/binary_io.h"
#include "core/error.h"
#include "core/version.h"

namespace shatter {

std::string producer_string() { return std::string("shatter ") + kVersion; }

std::string pack_stage_file(const StageHeader& header, std::string_view payload) {
    assert(header.magic.size() == kMagicSize);
    ByteWriter w;
    w.bytes(header.magic);
    w.u32(header.version);
    w.u32(kByteOrderMark);
    w.str(header.producer);
    w.str(header.settings_json);
    w.u64(payload.size());
    w.u64(fnv1a64(payload));
    w.bytes(payload);
    return std::move(w.data());
}

std::string stage_file_magic(std::string_view bytes) {
    if (bytes.size() < kMagicSize || bytes.substr(0, 3) != "SHT") return "";
    return std::string(bytes.substr(0, kMagicSize));
}

StageFile unpack_stage_file(std::string_view bytes, const std::string& source, std::string_view magic,
                            const char* kind, uint32_t min_version, uint32_t max_version) {
    const std::string k(kind);
    if (bytes.size() < kMagicSize || bytes.substr(0, kMagicSize) != magic) {
        std::string found = stage_file_magic(bytes);
        throw_input_error(source,
                          found.empty() ? "not a shatter " + k + " file (no " + std::string(magic) + " signature)"
                                        : "is a " + found + " file, not a " + k + " file",
                          "pass the " + k + " file written by the stage that makes it");
    }
    ByteReader r(bytes.substr(kMagicSize), source, kMagicSize);
    StageFile f;
    f.header.magic = std::string(magic);
    f.header.version = r.u32();
    if (f.header.version < min_version || f.header.version > max_version) {
        const bool newer = f.header.version > max_version;
        throw_input_error(source,
                          k + " format version " + std::to_string(f.header.version) + " is " +
                              (newer ? "newer" : "older") + " than this shatter reads (" +
                              std::to_string(min_version) + " to " + std::to_string(max_version) + ")",
                          newer ? "update shatter" : "make the file again with this shatter");
    }
    if (r.u32() != kByteOrderMark) r.fail("byte-order mark mismatch (written on a big-endian machine?)");
    f.header.producer = r.str(4096);
    f.header.settings_json = r.str();
    uint64_t size = r.u64();
    uint64_t sum = r.u64();
    if (size != r.remaining())
        r.fail("the payload should have " + std::to_string(size) + " bytes but " + std::to_string(r.remaining()) +
               " follow (truncated or padded)");
    f.payload_offset = r.offset();
    f.payload = r.bytes(size);
    if (fnv1a64(f.payload) != sum) r.fail("checksum mismatch: the " + k + " payload is damaged");
    return f;
}

nlohmann::ordered_json stage_choices(const nlohmann::ordered_json& settings) {
    if (!settings.is_object()) return nlohmann::ordered_json::array();
    return settings.value("auto", nlohmann::ordered_json::array());
}

nlohmann::ordered_json stage_warnings(const nlohmann::ordered_json& settings) {
    if (!settings.is_object()) return nlohmann::ordered_json::array();
    return settings.value("warnings", nlohmann::ordered_json::array());
}

std::string stage_choices_text(const nlohmann::ordered_json& settings) {
    std::string out;
    for (const auto& c : stage_choices(settings))
        out += fmt::format("chosen        {}; why: {}\n", c.value("what", std::string()), c.value("why", std::string()));
    for (const auto& w : stage_warnings(settings))
        if (w.is_string()) out += fmt::format("warning       {}\n", w.get<std::string>());
    return out;
}

}  // namespace shatter
