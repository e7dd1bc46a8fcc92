// The [generate] section's defaults per kind and names (core/generate_settings.h, docs/shot.md);
// its keys are declared in core/setting_table_prescore.cpp.

#include "core/generate_settings.h"

#include <nlohmann/json.hpp>
#include "core/setting_table.h"

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

nlohmann::ordered_json to_json(const GenerateSettings& s) {  // keys: core/setting_table_prescore.cpp
    Shot shot;
    shot.generate = s;
    return settings_json("generate", shot);
}

}  // namespace shatter
