// How prescore adapts to a mesh instead of refusing it. Real meshes have no units, thin parts
// (ears, legs, walls, tails), borders, several components and self-intersections; each of these
// used to end in an error whose fix the user had to apply by hand. Here prescore applies it:
//
//   size        a file without units is made kDefaultSize long ([mesh] size or scale to choose);
//   resolution  when Mesh_3 loses parts of the surface (the tets fall apart into more clusters
//               than the surface has components, or fill less than kMinFilled of its volume) but
//               still fill half of it (thin parts here and there), the resolution is raised by
//               kResolutionStep, twice at most, while the tets stay within kTetBudget;
//   thicken     when that does not reach the thin parts (or the tets fill less than half: thin
//               everywhere), the input is alpha-wrapped with an offset of kThickenOffset tets at
//               twice the asked resolution, which gives every wall a thickness of about 1.5 tets
//               (an open or flat sheet becomes a slab, a double-sided wrap of a thin wall one
//               solid); thicker and coarser, twice at most, when that meshing exceeds the budget
//               or makes no tets;
//   repair      a surface whose meshing does not end within the vertex budget and
//               mesh_seconds (heavy self-intersections) is alpha-wrapped first;
//   slivers     tet clusters smaller than kSliverFraction of the volume and kSliverOfLargest of
//               the largest cluster are not pieces of their own: each joins the piece nearest to
//               it (a piece may then be two clusters that move as one rigid body); a heap of
//               similar small bodies (gravel, separate voxels) keeps them all;
//   pieces      when more large clusters remain than pieces were asked for, each gets one, up
//               to kMaxBodies (the largest; smaller ones join their nearest pieces as slivers).
//
// Every choice is logged in one line and recorded in the model's settings (an "auto" list of
// what was done and why, with numbers). [mesh] adapt = false (--no-adapt) turns the
// resolution, thickening, sliver and piece choices off: such meshes are refused as before.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "core/geometry.h"
#include "core/settings.h"
#include "prescore/mesh_check.h"
#include "prescore/partition.h"
#include "prescore/tet_topology.h"

namespace shatter {

inline constexpr double kResolutionStep = 1.6;  // resolution factor per attempt
inline constexpr size_t kTetBudget = 150000;    // most tets the resolution may be raised to
inline constexpr size_t kMaxMeshVertices = 40000;  // Mesh_3 stops here (about 220,000 tets)
inline constexpr double kMinFilled = 0.85;      // tets' volume / the surface's, below which parts are lost
inline constexpr double kThickenOffset = 0.75;  // wrap offset when thickening (unit: tet sizes)
inline constexpr double kSliverFraction = 0.01;  // clusters below this share of the volume join a neighbour
inline constexpr double kSliverOfLargest = 0.1;  // ... when also below this share of the largest cluster's
inline constexpr size_t kMaxBodies = 1000;      // most separate bodies made pieces by themselves
// One Mesh_3 call is stopped past mesh_seconds(surface triangles): kMeshSeconds plus
// kMeshSecondsPerTriangle for each triangle of the surface it meshes. Its cost grows with the
// surface, for tet meshes of one size (its search tree: glmark2's bunny, 69,666 triangles, 0.36 s;
// a sphere of 6 million, 11.4 s). A deadline is only a stop for a run that does not end (heavy
// self-intersections): a surface whose meshing takes near a fixed deadline would give another
// model on a busier machine.
inline constexpr double kMeshSeconds = 15;              // (unit: s)
inline constexpr double kMeshSecondsPerTriangle = 5e-6;  // (unit: s), ~2.6 times the sphere's
double mesh_seconds(size_t surface_triangles);

struct AutoChoice {
    std::string what;  // e.g. "resolution 20 -> 32"
    std::string why;   // e.g. "the tets fell apart into 7 clusters (the surface has 1 component)"
};

// The choices made for one mesh, in order. note() logs "auto: WHAT (WHY)" and records it; warn()
// logs a warning and records it (each text once), whatever the log level: the model keeps both.
// A warning names files relative to `folder` (the mesh's, with its separator), so that the same
// inputs give the same model wherever they live.
struct AutoChoices {
    std::vector<AutoChoice> list;
    std::vector<std::string> warnings;
    std::string folder;
    void note(std::string what, std::string why);
    void warn(std::string text);
    nlohmann::ordered_json to_json() const;
};

// Metres per file unit: settings.size (the longest side), else settings.scale, else the file's
// own units, else what makes the longest side kDefaultSize (a choice, noted). Taken from the
// file's units, a size outside kPlausibleLongest is logged as a warning with units_hint's words.
double choose_scale(const TriangleMesh& mesh, double file_metres_per_unit, const MeshSettings& settings,
                    AutoChoices& choices);

// An object whose file's units make its longest side fall outside these is likely modelled in
// other units (a CAD part in millimetres exported as metres: glTF sample 2CylinderEngine is
// 743 m long by its file) (unit: m).
inline constexpr double kPlausibleLongest[2] = {1e-3, 50};
// What the longest side `longest` (unit: m, by the file's units) would be had the file been made
// in millimetres, centimetres or inches, with the settings that say so; empty within
// kPlausibleLongest.
std::string units_hint(double longest);

struct FittedTets {
    TetMesh tets;
    TriangleMesh surface;        // what Mesh_3 filled (the input, its wrap or its thickened wrap)
    MeshCheck surface_check;     // of that surface (no self-intersection search)
    double resolution = 0;       // the resolution used (cells per diagonal)
    bool wrapped = false;        // the surface is an alpha wrap of the input
    bool thickened = false;      // ... with walls given a thickness (step 3 below)
};

class IsolatedRun;

// fit_tets' first Mesh_3 call (the input itself at settings.resolution) begun in a child now, so
// that prescore counts the input's crossings while it runs (the count decides whether the input
// is wrapped first; usually it is not). A start that is not used is killed when it goes.
class EarlyTets {
public:
    EarlyTets(const TriangleMesh& surface, double diagonal, double resolution);
    ~EarlyTets();
    EarlyTets(const EarlyTets&) = delete;
    EarlyTets& operator=(const EarlyTets&) = delete;
    double resolution() const { return resolution_; }
    // Its result as the call's first attempt reads it; throws as run_isolated does. Once.
    std::string finish();

private:
    double resolution_;
    std::unique_ptr<IsolatedRun> run_;
};

// Fills `surface` (already checked: `surface_check`; `wrapped` when it is the input's wrap) with
// tets at settings.resolution, adapting as the header says when parts are lost. `input` is the
// mesh as loaded (for wrapping), `diagonal` its bounding-box diagonal (unit: m). `early`: that
// first call begun on this `surface` (unwrapped), or null. Throws Error(BadInput) when the mesh
// cannot be meshed, naming its size and the setting to change.
FittedTets fit_tets(const TriangleMesh& input, TriangleMesh surface, const MeshCheck& surface_check, bool wrapped,
                    double diagonal, const MeshSettings& mesh, const PrescoreSettings& settings,
                    const std::string& path, AutoChoices& choices, EarlyTets* early = nullptr);

// partition() over the large clusters (at least kSliverFraction of the volume or kSliverOfLargest
// of the largest cluster's; at most kMaxBodies of them); the tets of the others take the piece
// of the nearest tet (centroid to centroid) of a large one. With adapt, `pieces` is raised to
// the number of large clusters when it is smaller. When every cluster is large and there are at
// most `pieces` of them, this is exactly partition(). `density`: graded pieces (partition.h), or empty.
Partition partition_adapted(const TetMesh& mesh, const TetTopology& topology, uint32_t pieces, uint64_t seed,
                            bool adapt, AutoChoices& choices, const std::vector<double>& density = {});

}  // namespace shatter
