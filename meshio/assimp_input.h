// What the mesh reader (assimp) is given: the user's file, made readable first where Debian's
// assimp 5.2 would misread it. The mesh loader (meshio/mesh_load.h) and the appearance reader
// (meshio/appearance.h) both read a file through read_scene, so they see the same scene.
//
// Made readable, in this order:
//   - a glTF file with extensions assimp cannot read or gets wrong: decoded to a plain GLB
//     (meshio/gltf_extensions.h);
//   - glmark2's .jobj (its jellyfish: OBJ's vertex lines, then one "i N" line per index, three
//     per triangle, counted from 0): written as OBJ faces;
//   - a text file saved as UTF-16 (a byte-order mark FF FE or FE FF, as Windows tools save text):
//     assimp 5.2 reads its bytes as if they were ASCII (an OBJ or ASE gave no triangles, a
//     Collada file "malformed XML"); it is given the same text in UTF-8, and so are the files it
//     names (an OBJ's material library);
//   - an AMF file compressed as a ZIP of its XML (the specification allows it; OpenSCAD writes
//     it): unpacked, assimp reads only the XML;
//   - an OFF file with comments, or colours of three components: assimp's OFF reader reads a
//     comment line between the numbers in place of a face (CGAL writes "# vertices" and "#
//     facets" lines: its cube_poly.off came out with 10 of its 12 triangles), takes a comment
//     after the numbers ("1 -1 0 0.9 0 0 #red") for a number, and reads four colour components
//     (RGBA), taking the next line's first number for alpha; the comments go, and a colour of
//     three gets an alpha of 1.
#pragma once

#include <optional>
#include <string>

#include <assimp/Importer.hpp>
#include <assimp/scene.h>

namespace shatter {

// Whether `mesh` shows vertex colours: it has a first colour set in which some vertex is not
// (0, 0, 0, 0). assimp's AMF reader gives every mesh a colour set, with (0, 0, 0, 0) (transparent
// black) where the file gives no colour: drawn as colours, an AMF without any came out black.
// Where a set has colours, a vertex of (0, 0, 0, 0) is drawn in its material's colour
// (kNoVertexColour).
bool shows_vertex_colours(const aiMesh& mesh);

// What a vertex without a colour of its own is drawn in: white, which leaves its material's colour.
inline constexpr float kNoVertexColour[4] = {1, 1, 1, 1};

// Whether a vertex colour is the (0, 0, 0, 0) that stands for none.
inline bool no_vertex_colour(const aiColor4D& c) { return c.r == 0 && c.g == 0 && c.b == 0 && c.a == 0; }

// Reads `path` with `importer` (its properties already set), made readable as above; nullptr
// when assimp cannot read it (importer.GetErrorString() says why). Throws Error(BadInput) naming
// the file, the line and the fix for a .jobj whose numbers or indices do not hold together.
const aiScene* read_scene(Assimp::Importer& importer, const std::string& path);

// glmark2's .jobj text as OBJ text (vertices and faces; its normals, texture coordinates and
// colours are left out: glmark2 draws the jellyfish with a texture of its own scene). Throws
// Error(BadInput) for an index past the vertices, an index count not a multiple of 3, or a
// line that does not parse, naming `path` and the line.
std::string jobj_as_obj(const std::string& text, const std::string& path);

// `bytes` decoded from UTF-16 to UTF-8 when they start with a byte-order mark (FF FE: little
// endian; FE FF: big endian) and hold text (an even count, no NUL, no unpaired surrogate); else
// nullopt. The mark itself is dropped.
std::optional<std::string> utf16_as_utf8(const std::string& bytes);

// An OFF file's text with every comment ('#' to the end of its line) and empty line taken out,
// and an alpha of 1 after each vertex colour of three components; nullopt when that changes
// nothing.
std::optional<std::string> off_for_assimp(const std::string& text);

}  // namespace shatter
