// The model: what prescore writes and simulate, render and `shatter info` read. A tet mesh split
// into pieces, each with its surface, mass properties and collision parts, and the point
// constraints that join neighbouring pieces. Stored as a versioned binary (docs/formats.md).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry.h"

namespace shatter {

// What a surface triangle of a piece borders.
enum class FaceKind : uint8_t {
    Outer = 0,     // the object's outside surface
    Fracture = 1,  // a face shared with another piece: becomes visible when they part
    Cavity = 2,    // the inside wall left by hollowing
};

struct PieceSurface {
    std::vector<Vec3> vertices;  // (unit: m, model frame)
    std::vector<Tri> triangles;  // outward oriented
    std::vector<FaceKind> kinds; // one per triangle
};

// What a piece looks like, apart from what it simulates with (tets, mass, collision parts): the
// surface prescore's tets were made from, cut along the piece's fracture faces
// (prescore/render_surface.h). Render, the .glb and OUT.pieces.ply draw it instead of the tet
// surface when a piece has one: indexed, outer faces with smooth per-vertex normals, fracture and
// cavity faces flat (their vertices carry the face normal).
struct RenderSurface {
    std::vector<Vec3> vertices;  // (unit: m, model frame)
    std::vector<Vec3> normals;   // unit, one per vertex
    std::vector<Tri> triangles;  // outward oriented
    std::vector<FaceKind> kinds; // one per triangle
    bool fell_back = false;      // the cut failed for this piece: its fracture faces are its tet faces, flat
                                 // (its outer faces too, unless the input's own triangles took their place)
    // The input's appearance (model version 3; each empty when the input has none): texture
    // coordinates (channel 0, assimp's convention: v up, (0, 0) the image's bottom left) and
    // colours (linear RGBA) per vertex, taken on outer faces from the input triangle nearest to
    // the face (vertices are split where a UV seam or a material boundary runs; fracture and
    // cavity faces carry (0, 0) and white), and per triangle an index into Model::materials: on
    // outer faces the nearest input triangle's material, on fracture and cavity faces the
    // material of the input nearest to them (the piece's inside is drawn from it).
    std::vector<std::array<float, 2>> uv;
    std::vector<std::array<float, 4>> colour;
    std::vector<uint32_t> material;
};

// One material of the input (meshio/appearance.h): what its outer faces are drawn with.
struct Material {
    std::string name;
    std::array<float, 4> base_colour = {1, 1, 1, 1};  // linear RGBA, multiplies the texture
    std::string texture;       // the base colour texture as the encoded image file (PNG, JPEG, TGA, ...); empty: none
    std::string texture_mime;  // "image/png", "image/jpeg", ... (by the file's first bytes)
    std::string texture_name;  // where it came from (a file name, or "*0" for an embedded one), for messages
};

struct MassProperties {
    double volume = 0;             // (unit: m^3)
    double mass = 0;               // (unit: kg) volume * density
    Vec3 center = Vec3::Zero();    // centre of mass (unit: m, model frame)
    Mat3 inertia = Mat3::Zero();   // inertia tensor about the centre of mass, model axes (unit: kg m^2)
};

// One convex part of a piece's collision shape: the convex hull of `points`.
struct ConvexPart {
    std::vector<Vec3> points;  // hull vertices (unit: m, model frame)
    double volume = 0;         // volume of the tets the part stands for (unit: m^3)
    double hull_volume = 0;    // volume of the hull (unit: m^3); >= volume
};

struct Piece {
    std::vector<uint32_t> tets;  // indices into Model::mesh.tets, ascending
    PieceSurface surface;
    MassProperties mass;
    std::vector<ConvexPart> collision;
    bool connected = true;       // its tets form one face-connected component
    std::optional<RenderSurface> render;  // how it is drawn; none: its tet surface, flat (model version 1)
};

// A point constraint joining two pieces at a vertex of a face they share.
struct Constraint {
    uint32_t piece_a = 0;  // piece_a < piece_b
    uint32_t piece_b = 0;
    uint32_t vertex = 0;   // index into Model::mesh.vertices
    Vec3 pivot = Vec3::Zero();  // (unit: m, model frame)
    double area = 0;       // the share of the shared-face area this constraint stands for (unit: m^2)
};

struct Model {
    std::string producer;       // e.g. "shatter 0.1.0"
    std::string settings_json;  // the settings (and input) that made the model, canonical JSON
    double density = 0;         // (unit: kg/m^3) the density the masses were computed with
    TetMesh mesh;               // every tet of the object (after hollowing)
    std::vector<uint32_t> tet_piece;  // piece of each tet
    std::vector<Piece> pieces;
    std::vector<Constraint> constraints;  // sorted by (piece_a, piece_b, vertex)
    std::vector<Material> materials;      // the input's, named by RenderSurface::material (version 3)
};

// The radius of a piece's surface about its centre of mass (unit: m): the farthest any point of
// it is from the point it turns about.
double piece_radius(const Piece& piece);

// Per piece, one piece of its group: the groups of pieces that the constraints not `broken` (one
// flag per constraint; none when empty) hold together, the fragments. A piece joined to nothing
// is its own group; two pieces are in one group when they name the same piece.
std::vector<uint32_t> fragment_of(const Model& model, const std::vector<bool>& broken = {});

// How many fragments (fragment_of) the constraints that are not `broken` leave.
size_t count_fragments(const Model& model, const std::vector<bool>& broken);

}  // namespace shatter
