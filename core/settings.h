// Settings of every stage: plain structs with defaults and units. They are filled from the shot
// file (core/shot.h), then from command-line flags, and every value is checked where it enters
// against the limits below, with a message that names the file:line or the flag.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace shatter {

// A closed range a setting must lie in, with the unit to print.
struct Limits {
    double min;
    double max;
    const char* unit;
};

// A length given either relative to the object's size (a fraction of its bounding-box
// diagonal; written as a plain number, e.g. 0.05) or absolute (a number with the unit m, cm or
// mm, e.g. "12mm").
struct Length {
    double value = 0;
    bool relative = true;

    double resolve(double diagonal) const { return relative ? value * diagonal : value; }
    std::string str() const;
    // Parses "0.05", "12mm", "1.5cm", "0.02m"; returns nullopt when the text is none of these.
    static std::optional<Length> parse(const std::string& text);
};

enum class RepairMode { Auto, Always, Never };
const char* to_string(RepairMode mode);

// Which way is up in the mesh file. shatter's world is y-up; a z-up file is turned by -90 degrees
// about x ((x, y, z) -> (x, z, -y): +z becomes +y). Auto: z for STL, 3MF and AMF (CAD's and 3D
// printing's convention; Blender also writes STL z-up), for Blender's own files (z-up, which
// assimp reads as they are), for an FBX file whose settings say z is up (assimp does not apply
// them) and for a PLY file Blender wrote (its header's comment); y for everything else (glTF's rule, most OBJ and PLY; assimp turns 3DS and Collada files
// to y-up as it reads them).
enum class UpAxis { Auto, Y, Z };
const char* to_string(UpAxis up);

// How big the object is: `size` (its longest bounding-box side) wins over `scale`; with neither,
// the file's own units (glTF: metres; FBX, Collada: their unit scale), and for a file without
// units (OBJ, STL, PLY, OFF, ...) the object is made kDefaultSize long.
struct MeshSettings {
    std::string path;                    // the mesh file; in a shot, relative to the shot's folder
    std::string member;                  // the mesh file in the archive `path` names; "": chosen (meshio/archive.h)
    std::optional<double> scale;         // metres per mesh unit (unit: m); unset: from the file or size
    std::optional<double> size;          // the longest side of the bounding box (unit: m); unset: scale
    RepairMode repair = RepairMode::Auto;  // auto: alpha-wrap only meshes Mesh_3 cannot take
    double wrap_alpha = 0.02;            // alpha-wrap ball radius, fraction of the diagonal
    double wrap_offset = 0.001;          // alpha-wrap offset, fraction of the diagonal
    bool adapt = true;                   // raise the resolution, thicken thin walls, merge slivers (false: refuse)
    UpAxis up = UpAxis::Auto;            // the file's up axis
};
inline constexpr double kDefaultSize = 0.3;  // (unit: m) a unitless mesh's longest side
inline constexpr Limits kScaleLimits{1e-9, 1e9, "m per mesh unit"};
inline constexpr Limits kSizeLimits{1e-6, 1e6, "m"};
inline constexpr Limits kWrapAlphaLimits{1e-4, 0.5, "of the diagonal"};
inline constexpr Limits kWrapOffsetLimits{1e-6, 0.1, "of the diagonal"};

// Where the flood fill's seeds go: "uniform": anywhere, pieces of about one size; "impact": denser
// near where the object first hits (prescore/impact.h), small pieces there and large ones far
// from it (prescore/graded_seeds.h); "points": one piece from each of the shot's seed_points
// (prescore/seed_points.h).
enum class SeedMode { Uniform, Impact, Points };

struct PrescoreSettings {
    uint32_t pieces = 10;                 // number of pieces (unit: count)
    uint64_t seed = 1;                    // seed of the random seed-tet choice
    std::optional<Length> hollow;         // shell thickness; nullopt: solid
    double resolution = 20;               // tet size = bounding-box diagonal / resolution
    double density = 2400;                // (unit: kg/m^3) glass ~2500, ceramic ~2400, plaster ~1000
    Length collision_tolerance{0.01, true};  // most mean gap between a collision part's hull and the piece's shape
    uint32_t collision_max_parts = 16;    // most convex parts per piece
    uint32_t constraints_per_pair = 0;    // most constraints joining two pieces; 0: one per shared vertex
    bool render_surface = true;           // cut the input per piece for drawing (prescore/render_surface.h)
    bool crack_fairing = true;            // render surfaces: the cracks between pieces faired (prescore/crack_fairing.h)
    bool crack_split = false;             // faired cracks: the last cut on the crack tets split 1:8 (smoother, dearer)
    double crack_roughness = 0;           // faired cracks' relief: its amplitude (unit: tet sizes); 0: smooth
    double crack_roughness_scale = 2;     // and its wavelength (unit: tet sizes)
    SeedMode seeds = SeedMode::Uniform;   // where the seeds go
    // Impact seeds: the density at the contact over far from it (unit: 1), and its fall-off radius;
    // unset: "auto", from the impact's speed and the material (prescore/graded_seeds.h).
    std::optional<double> impact_ratio;
    std::optional<Length> impact_radius;
    std::vector<std::array<double, 3>> seed_points;  // seeds = "points" (unit: m, the model's frame)
    std::string seed_points_where;        // where seed_points was given ("file:line", the flag), for messages
};
inline constexpr Limits kPiecesLimits{1, 1e6, "pieces"};
inline constexpr Limits kResolutionLimits{2, 500, "cells per diagonal"};
inline constexpr Limits kCrackRoughnessLimits{0, 1, "tet sizes"};
inline constexpr Limits kCrackRoughnessScaleLimits{0.5, 100, "tet sizes"};
inline constexpr Limits kDensityLimits{1e-3, 1e5, "kg/m^3"};
inline constexpr Limits kHollowRelativeLimits{1e-4, 0.5, "of the diagonal"};
inline constexpr Limits kHollowAbsoluteLimits{1e-7, 1e6, "m"};
inline constexpr Limits kCollisionToleranceRelativeLimits{0.0, 1.0, "of the diagonal"};
inline constexpr Limits kCollisionToleranceAbsoluteLimits{0.0, 1e6, "m"};
inline constexpr Limits kCollisionPartsLimits{1, 4096, "parts"};
inline constexpr Limits kImpactRatioLimits{1, 1000, "(density at the contact over far)"};
inline constexpr Limits kImpactRadiusRelativeLimits{1e-3, 10, "of the diagonal"};
inline constexpr Limits kImpactRadiusAbsoluteLimits{1e-7, 1e6, "m"};
inline constexpr Limits kConstraintsPerPairLimits{0, 1e6, "constraints (0: all)"};

// Throws Error(Usage or BadInput) "WHERE: KEY = VALUE is outside [MIN, MAX] UNIT" when value is
// not finite or out of range. `where` is "file:line" or "--flag".
void check_limits(const std::string& where, const std::string& key, double value, const Limits& limits,
                  bool from_flag);
// Checks a length against relative or absolute limits; `what` names it in the message.
void check_length(const std::string& where, const std::string& what, const Length& length, const Limits& relative,
                  const Limits& absolute, bool from_flag);
void check_hollow(const std::string& where, const Length& thickness, bool from_flag);
void check_collision_tolerance(const std::string& where, const Length& tolerance, bool from_flag);

nlohmann::ordered_json to_json(const MeshSettings& s);
nlohmann::ordered_json to_json(const PrescoreSettings& s);

}  // namespace shatter
