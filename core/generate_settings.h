// The shot's [generate] section: an object built by the project from exact boxes instead of a
// mesh (scenes/paper_scenes.h builds it; docs/shot.md and docs/scenes.md describe it). A shot has
// either [mesh] or [generate]. The three kinds are the paper's box scenes:
//
//   beam   `count` boxes of `size` in a row along x, each pair joined over their shared face
//   plate  `count` x `count` cubes of `size` in the xz plane (a plate one cube thick)
//   chain  `count` links of `size` in a row along x, lying on y = 0, between two end cubes of
//          edge `end_size`; piece 0 and piece count + 1 are the end cubes ([[object.driven]]
//          moves them)
//
// Neighbours are joined by constraints_per_side^2 point constraints at the Gauss-Legendre points
// of their shared face, each standing for its Gauss weight's share of the face's area: the
// constraints then carry a linearly varying stress (bending) with the face's exact force and
// moment (1 per side: a ball joint at the face's centre, e.g. a chain's links).
// The model's frame: x along the row, y up, centred in x and z, its lowest face on y = 0.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "core/geometry.h"
#include "core/settings.h"

namespace shatter {

enum class GenerateKind { Beam, Plate, Chain };

struct GenerateSettings {
    GenerateKind kind = GenerateKind::Beam;
    uint32_t count = 2;                 // beam: boxes along x; plate: cubes per side; chain: links (unit: count)
    Vec3 size = Vec3(0.3, 0.03, 0.03);  // full extents of one box / cube / link (unit: m)
    double end_size = 0.05;             // chain: edge of the two end cubes (unit: m)
    uint32_t constraints_per_side = 2;  // n x n constraints per shared face, at its Gauss points (unit: count)
    double density = 2400;              // (unit: kg/m^3) glass ~2500, porcelain ~2400, plaster ~1100
};
// The defaults of each kind (the paper's scenes at a size this machine simulates in seconds):
//   beam  2 boxes of 0.3 x 0.03 x 0.03 m, 2 x 2 constraints per face
//   plate 5 x 5 cubes of 0.03 m, 2 x 2 constraints per face
//   chain 10 links of 0.03 x 0.01 x 0.01 m between 0.05 m end cubes, 1 constraint per face
GenerateSettings default_generate(GenerateKind kind);

inline constexpr Limits kGenerateCountLimits{1, 1000, "count"};
inline constexpr Limits kGenerateSizeLimits{1e-4, 100, "m"};
inline constexpr Limits kConstraintsPerSideLimits{1, 5, "constraints per side"};

const char* to_string(GenerateKind kind);
std::optional<GenerateKind> parse_generate_kind(const std::string& text);
nlohmann::ordered_json to_json(const GenerateSettings& s);

}  // namespace shatter
