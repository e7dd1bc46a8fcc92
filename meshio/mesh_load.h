// Loading a surface mesh from any file format assimp reads (OBJ, PLY, STL, OFF, glTF/GLB, 3DS,
// FBX, ...) into one indexed TriangleMesh in metres.
//
// What load_mesh does, in order:
//   1. refuses a missing path or a directory before assimp sees it;
//   2. assimp imports the file, in a child process (a crash inside assimp on a malformed file
//      becomes a BadInput error, not a signal; a file that starts like a PLY has its header
//      checked first, meshio/ply_header.h); a scene without triangles or polygons is refused with a plain
//      message, then assimp validates it (ValidateDataStructure: indices in range, ...) and
//      runs Triangulate (normals, UVs, colours removed first: only positions are read);
//   3. walks the node tree depth first (children in file order, a node's meshes in file order),
//      applying each node's accumulated transform in double precision; a mesh instanced by
//      several nodes is added once per instance; the coarsest rounding of assimp's single
//      precision coordinates, against the size of the mesh it rounds, is recorded (FloatRounding);
//   4. drops points and lines (faces with fewer than 3 indices);
//   5. merges vertices with exactly equal positions, within and across meshes, keeping the first
//      occurrence's place (deterministic: the output depends only on the file);
//   6. multiplies every coordinate by `scale` (mesh units -> metres).
// Every problem a user can cause is a shatter::Error (ExitCode::BadInput) whose message names
// the file, the problem with its value, and a fix.
#pragma once

#include <cstddef>
#include <string>

#include "core/geometry.h"
#include "core/settings.h"

namespace shatter {

// assimp holds coordinates in single precision, which rounds a coordinate x to steps of about
// |x| / 2^23 (8.4 million): a mesh far from its file's origin, relative to its size, is read
// stepped (a scan kept in survey coordinates). The coarsest such step among the file's meshes
// against the size of the mesh it rounds, in the file's units, before any node transform
// (those are applied in double precision); all 0 when no mesh has a size.
struct FloatRounding {
    double step = 0;        // the spacing of single-precision numbers at `coordinate`
    double coordinate = 0;  // the mesh's largest coordinate, in magnitude
    double size = 0;        // the diagonal of the mesh's bounding box
};

struct LoadedMesh {
    TriangleMesh mesh;           // in the file's units
    double metres_per_unit = 0;  // what the file says a unit is (unit: m); 0 when its format has no units
    FloatRounding rounding;
    // The file shows nothing beyond its shape: no vertex colours, no texture, every material
    // white or assimp's default (a file that names none: an OBJ without a library, STL, most PLY).
    // Its appearance (meshio/appearance.h) would be plain, so a second reading can be skipped.
    bool plain = false;
    // An FBX file whose settings say z is up (GlobalSettings UpAxis 2, UpAxisSign 1), or a PLY file
    // whose header says Blender wrote it: assimp reads their coordinates as they are.
    bool states_z_up = false;
};

// A step of the reading's rounding past this fraction of the mesh's size is worth a warning: the
// rounding then shows (1e-3 of a 0.3 m object is 0.3 mm; at 1e-2 the stepped surface shows in a
// frame and in the tets) (unit: 1).
inline constexpr double kRoundingWarning = 1e-3;

// What the rounding `r` did and how to avoid it, for a warning; empty when its step is within
// kRoundingWarning of the mesh's size.
std::string rounding_hint(const FloatRounding& r);

// Loads `path` in the file's own units, with what the file says a unit is: glTF/GLB (metres by
// the specification) and Collada (assimp applies its <unit meter>) give 1, FBX its
// UnitScaleFactor (centimetres per unit) / 100, every other format 0. Throws as load_mesh does.
LoadedMesh load_mesh_file(const std::string& path);

// Loads `path` and returns its triangles in metres (coordinates times `scale`, which must be
// finite and > 0; unit: m per mesh unit). Throws shatter::Error(BadInput) on a missing,
// unreadable or corrupt file, a file without triangles, or NaN/Inf coordinates.
TriangleMesh load_mesh(const std::string& path, double scale);

// How long an import of `path` in a child process may take (unit: s): 15 s plus 10 s per MB, or
// SHATTER_MESH_IMPORT_TIMEOUT when set (mesh_load.cpp says why).
double mesh_import_deadline_seconds(const std::string& path);

// The first `bytes` of a file (fewer if it is shorter; empty if it cannot be read).
std::string read_file_head(const std::string& path, size_t bytes);

// `s` with its ASCII letters in lower case.
std::string lower_case(std::string s);

// The file name's extension in lower case, with its dot (".glb"); "" without one.
std::string lower_extension(const std::string& path);

// Whether the file at `path` is read as z-up with `up` ([mesh] up; Auto: an .stl, .3mf, .amf or .blend
// file, or one that states z is up: LoadedMesh::states_z_up).
bool z_up(UpAxis up, const std::string& path, bool states_z_up);

// Why `path` is z-up by its format or its own statement ("an STL file: CAD and 3D printing make z
// up"), or "" for a file read y-up.
std::string z_up_format(const std::string& path, bool states_z_up);

}  // namespace shatter
