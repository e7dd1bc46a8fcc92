// The shot's [generate] section (core/generate_settings.h, docs/shot.md): strict like the other
// sections. `kind` is required and chooses the defaults of the other keys; a key that the kind
// does not use (end_size on a beam) is an error.
#include <fmt/format.h>

#include "core/error.h"
#include "core/generate_settings.h"
#include "core/shot_sections.h"

namespace shatter {

GenerateSettings default_generate(GenerateKind kind) {
    GenerateSettings g;
    g.kind = kind;
    switch (kind) {
        case GenerateKind::Beam: break;  // the struct's defaults
        case GenerateKind::Plate:
            g.count = 5;
            g.size = Vec3::Constant(0.03);
            break;
        case GenerateKind::Chain:
            g.count = 10;
            g.size = Vec3(0.03, 0.01, 0.01);
            g.constraints_per_side = 1;
            break;
    }
    return g;
}

const char* to_string(GenerateKind kind) {
    switch (kind) {
        case GenerateKind::Beam: return "beam";
        case GenerateKind::Plate: return "plate";
        case GenerateKind::Chain: return "chain";
    }
    return "?";
}

std::optional<GenerateKind> parse_generate_kind(const std::string& text) {
    for (GenerateKind k : {GenerateKind::Beam, GenerateKind::Plate, GenerateKind::Chain})
        if (text == to_string(k)) return k;
    return std::nullopt;
}

nlohmann::ordered_json to_json(const GenerateSettings& s) {
    nlohmann::ordered_json j;
    j["kind"] = to_string(s.kind);
    j["count"] = s.count;
    j["size"] = {s.size.x(), s.size.y(), s.size.z()};
    if (s.kind == GenerateKind::Chain) j["end_size"] = s.end_size;
    j["constraints_per_side"] = s.constraints_per_side;
    j["density"] = s.density;
    return j;
}

void read_generate_section(TomlSection& s, GenerateSettings& g) {
    std::string kind_text;
    if (!s.text("kind", kind_text))
        s.fail(nullptr, "[generate] has no kind", "add kind = \"beam\", \"plate\" or \"chain\"");
    const auto kind = parse_generate_kind(kind_text);
    if (!kind)
        s.fail(s.node("kind"), fmt::format("generate.kind = \"{}\" is not a generated object", kind_text),
               "use \"beam\", \"plate\" or \"chain\"");
    g = default_generate(*kind);
    s.integer("count", g.count, kGenerateCountLimits);
    read_numbers(s, "size", g.size.data(), 3, kGenerateSizeLimits, "[0.3, 0.03, 0.03]");
    const bool end_size = s.number("end_size", g.end_size, kGenerateSizeLimits);
    if (end_size && g.kind != GenerateKind::Chain)
        s.fail(s.node("end_size"), fmt::format("generate.end_size does not apply to kind = \"{}\"", kind_text),
               "remove end_size (only a chain has end cubes)");
    s.integer("constraints_per_side", g.constraints_per_side, kConstraintsPerSideLimits);
    s.number("density", g.density, kDensityLimits);
    s.finish();
}

}  // namespace shatter
