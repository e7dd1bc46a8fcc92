// Loads a mesh with assimp and merges it into one TriangleMesh. Design notes: mesh_load.h.
#include "meshio/mesh_load.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>


#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unordered_map>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/error.h"
#include "core/find_program.h"
#include "core/isolated.h"
#include "meshio/assimp_input.h"
#include "meshio/gltf_extensions.h"
#include "meshio/ply_header.h"

namespace shatter {
namespace {

namespace fs = std::filesystem;

using Mat4 = Eigen::Matrix4d;

Mat4 to_eigen(const aiMatrix4x4& m) {
    Mat4 r;
    r << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3,
        m.d4;
    return r;
}

std::string format_vec(const Vec3& v) {
    std::ostringstream s;
    s.precision(17);
    s << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
    return s.str();
}

// Hash of an exact position; -0.0 is normalised to +0.0 by the caller so equal keys hash equal.
struct PositionHash {
    size_t operator()(const Vec3& p) const {
        std::hash<double> h;
        size_t seed = h(p.x());
        seed ^= h(p.y()) + 0x9e3779b97f4a7c15ULL + (seed << 6) + (seed >> 2);
        seed ^= h(p.z()) + 0x9e3779b97f4a7c15ULL + (seed << 6) + (seed >> 2);
        return seed;
    }
};
struct PositionEqual {
    bool operator()(const Vec3& a, const Vec3& b) const { return a == b; }
};

// Accumulates the scene's triangles, merging exactly equal positions (first occurrence wins).
class Merger {
public:
    explicit Merger(const std::string& path) : path_(path) {}

    void add_mesh(const aiMesh& mesh, unsigned mesh_index, const Mat4& transform) {
        std::vector<uint32_t> remap(mesh.mNumVertices);
        Vec3 lo = Vec3::Constant(HUGE_VAL), hi = -lo;
        for (unsigned i = 0; i < mesh.mNumVertices; ++i) {
            const aiVector3D& v = mesh.mVertices[i];
            const Vec3 raw(v.x, v.y, v.z);
            if (!raw.allFinite()) {
                throw_input_error(path_, "vertex " + std::to_string(i) + " of mesh " +
                                             std::to_string(mesh_index) + " ('" + mesh.mName.C_Str() +
                                             "') has a non-finite coordinate " + format_vec(raw),
                                  "remove or fix the NaN/Inf coordinates in the file");
            }
            lo = lo.cwiseMin(raw), hi = hi.cwiseMax(raw);
            Eigen::Vector4d p = transform * raw.homogeneous();
            Vec3 q = p.head<3>() / p.w();
            if (!q.allFinite()) {
                throw_input_error(path_, "vertex " + std::to_string(i) + " of mesh " +
                                             std::to_string(mesh_index) + " ('" + mesh.mName.C_Str() +
                                             "') becomes " + format_vec(q) + " under its node transform",
                                  "fix the node transforms in the file (scale 0 or Inf)");
            }
            q += Vec3::Zero();  // -0.0 + 0.0 == +0.0: one key per position
            auto [it, inserted] = index_.try_emplace(q, uint32_t(out_.vertices.size()));
            if (inserted) out_.vertices.push_back(q);
            remap[i] = it->second;
        }
        if (mesh.mNumVertices > 0) note_rounding(lo, hi);
        for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
            const aiFace& face = mesh.mFaces[f];
            if (face.mNumIndices != 3) continue;  // points and lines carry no volume
            out_.triangles.push_back(
                {remap[face.mIndices[0]], remap[face.mIndices[1]], remap[face.mIndices[2]]});
        }
    }

    void add_node(const aiScene& scene, const aiNode& node, const Mat4& parent) {
        Mat4 transform = parent * to_eigen(node.mTransformation);
        for (unsigned i = 0; i < node.mNumMeshes; ++i) {
            unsigned m = node.mMeshes[i];
            add_mesh(*scene.mMeshes[m], m, transform);
        }
        for (unsigned i = 0; i < node.mNumChildren; ++i) add_node(scene, *node.mChildren[i], transform);
    }

    // The merged mesh without the vertices only points or lines used (order kept).
    TriangleMesh take() {
        std::vector<uint32_t> new_index(out_.vertices.size(), kUnused);
        for (const Tri& t : out_.triangles)
            for (uint32_t v : t) new_index[v] = 0;
        TriangleMesh mesh;
        for (size_t v = 0; v < out_.vertices.size(); ++v) {
            if (new_index[v] == kUnused) continue;
            new_index[v] = uint32_t(mesh.vertices.size());
            mesh.vertices.push_back(out_.vertices[v]);
        }
        mesh.triangles = std::move(out_.triangles);
        for (Tri& t : mesh.triangles)
            for (uint32_t& v : t) v = new_index[v];
        return mesh;
    }

    const FloatRounding& rounding() const { return rounding_; }

private:
    // Keeps the mesh with bounds [lo, hi] (as read) if its rounding step is the coarsest so far
    // against its size.
    void note_rounding(const Vec3& lo, const Vec3& hi) {
        const double size = (hi - lo).norm(), coordinate = lo.cwiseAbs().cwiseMax(hi.cwiseAbs()).maxCoeff();
        if (!(size > 0)) return;
        const float x = float(coordinate);
        const double step = double(std::nextafter(x, HUGE_VALF)) - double(x);
        if (rounding_.size > 0 && !(step * rounding_.size > rounding_.step * size)) return;
        rounding_ = {step, coordinate, size};
    }

    static constexpr uint32_t kUnused = UINT32_MAX;
    FloatRounding rounding_;
    std::string path_;
    TriangleMesh out_;
    std::unordered_map<Vec3, uint32_t, PositionHash, PositionEqual> index_;
};

// Faces with three or more corners, read before assimp validates the scene.
size_t count_surface_faces(const aiScene& scene) {
    size_t count = 0;
    for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
        const aiMesh* mesh = scene.mMeshes[m];
        if (mesh == nullptr || mesh->mFaces == nullptr) continue;
        if (mesh->mPrimitiveTypes & (aiPrimitiveType_TRIANGLE | aiPrimitiveType_POLYGON)) count += mesh->mNumFaces;
    }
    return count;
}

void check_path(const std::string& path) {
    std::error_code ec;
    auto status = std::filesystem::status(path, ec);
    if (!std::filesystem::exists(status)) {
        throw_input_error(path, "mesh file does not exist", "check the path (and the shot's mesh.path)");
    }
    if (std::filesystem::is_directory(status)) {
        throw_input_error(path, "mesh path is a directory, not a file", "name the mesh file itself");
    }
    if (!std::filesystem::is_regular_file(status)) {
        // A FIFO with no writer would block the first read, and the mesh is read more than once.
        throw_input_error(path, "mesh path is not a regular file (a FIFO, socket or device)",
                          "save the mesh to a file and name that");
    }
    if (std::filesystem::file_size(path, ec) == 0 && !ec) {
        throw_input_error(path, "mesh file is empty (0 bytes)", "give a file with a surface mesh; re-export it");
    }
}

void check_scale(const std::string& path, double scale) {
    if (!std::isfinite(scale) || scale <= 0) {
        std::ostringstream s;
        s << "mesh scale = " << scale << " must be finite and > 0";
        throw_input_error(path, s.str(), "set the scale to the size of one mesh unit in metres, e.g. 1 or 0.01");
    }
}


// Formats users bring that assimp 5.2 does not read, by extension: what the file is and where a
// mesh comes from.
struct ForeignFormat {
    std::vector<std::string> extensions;
    const char* what;
    const char* fix;
};
const std::vector<ForeignFormat>& foreign_formats() {
    static const std::vector<ForeignFormat> formats = {
        {{".usd", ".usda", ".usdc", ".usdz"}, "a USD file (Universal Scene Description; .usdz is Apple's AR format)",
         "export it as glTF 2.0 (.glb), OBJ or STL from the program that made it; Blender's own builds from 3.0 on "
         "import USD (File > Import > Universal Scene Description; Debian's is built without it) and export glTF 2.0"},
        {{".step", ".stp", ".iges", ".igs", ".brep", ".sat", ".x_t"}, "a CAD file (exact surfaces, not a mesh)",
         "export a mesh from the CAD program (STL, OBJ or glTF); FreeCAD opens STEP and IGES files and exports STL "
         "and OBJ (File > Export)"},
        {{".skp"}, "a SketchUp model", "export it from SketchUp as COLLADA (.dae) or OBJ"},
        {{".max"}, "a 3ds Max scene", "export it from 3ds Max as FBX, OBJ or glTF"},
        {{".ma", ".mb"}, "a Maya scene", "export it from Maya as FBX or OBJ"},
        {{".c4d"}, "a Cinema 4D scene", "export it from Cinema 4D as FBX, OBJ or glTF"},
        {{".3dm"}, "a Rhino model", "export it from Rhino as OBJ, STL or FBX"},
        {{".wrl", ".vrml"}, "a VRML file", "convert it to OBJ, STL or glTF, e.g. in MeshLab (File > Export Mesh As)"},
        {{".dwg"}, "an AutoCAD drawing", "export its 3D solids from AutoCAD as STL, or the drawing as DXF"},
        {{".vox"}, "a MagicaVoxel model", "export it from MagicaVoxel as OBJ or PLY"},
    };
    return formats;
}

// What to do about a file assimp cannot read. Blender's own files are read only as Blender 2.4 to
// 2.7x saved them (their header: "BLENDER", a pointer size, an endianness, three version digits);
// a newer one, or one saved compressed by Blender 3 and later (zstd), is exported from Blender.
std::string format_fix(const std::string& path) {
    const std::string head = read_file_head(path, 12);
    const std::string ext = lower_extension(path);
    const bool blend = ext == ".blend" || head.rfind("BLENDER", 0) == 0;
    if (ext == ".3mf" && head.rfind("PK\x03\x04", 0) != 0)
        return "a 3MF file is a ZIP package holding its model (3D/3dmodel.model), and this one is not a ZIP" +
               std::string(head.rfind("<?xml", 0) == 0 ? " (it is XML: the model alone?)" : "") +
               ": save it as 3MF again from the program that made it, or as STL";
    if (!blend) {
        for (const ForeignFormat& f : foreign_formats())
            if (std::find(f.extensions.begin(), f.extensions.end(), ext) != f.extensions.end())
                return fmt::format("this is {}, which the mesh reader (assimp) does not read: {}", f.what, f.fix);
        return "check that the file is a complete mesh in a format assimp reads (OBJ, PLY, STL, OFF, glTF/GLB, 3DS, "
               "FBX, ...)";
    }
    std::string export_it = "in Blender, File > Export > glTF 2.0 (.glb) or Wavefront (.obj), and give shatter that file";
    // With Blender installed, the command that does it (for a name the quotes below can hold).
    const fs::path glb = fs::path(path).replace_extension(".glb");
    if (find_program("blender") && path.find_first_of("'\"\\\n") == std::string::npos)
        export_it += fmt::format("; here: blender -b '{}' --python-expr \"import bpy; "
                                 "bpy.ops.export_scene.gltf(filepath='{}')\"",
                                 path, glb.string());
    const auto digit = [&head](size_t i) { return head.size() > i && std::isdigit(static_cast<unsigned char>(head[i])); };
    std::string newer;
    if (head.rfind("BLENDER", 0) == 0 && digit(9) && digit(10) && digit(11) && head.substr(9, 3) >= "280")
        newer = fmt::format("Blender {}.{}", head[9],
                            head[9] >= '3' ? std::to_string(std::stoi(head.substr(10, 2))) : head.substr(10, 2));
    else if (head.rfind("\x28\xb5\x2f\xfd", 0) == 0)
        newer = "Blender 3 or later, compressed";
    if (!newer.empty())
        return "the mesh reader (assimp) reads .blend files only as Blender 2.4 to 2.7x saved them, and this one was "
               "saved by " + newer + ": " + export_it;
    return "check that the file is complete; or " + export_it +
           " (the mesh reader, assimp, reads .blend files as Blender 2.4 to 2.7x saved them)";
}

// The metres per unit a file states, or 0 when its format has no units. glTF is in metres by
// its specification; assimp applies a Collada file's <unit meter> to the root node, so its
// coordinates arrive in metres; an FBX file records its unit in centimetres (UnitScaleFactor).
double file_units(const aiScene& scene, const std::string& path) {
    const std::string ext = lower_extension(path);
    if (ext == ".gltf" || ext == ".glb" || ext == ".dae" || ext == ".zae") return 1.0;
    if (ext == ".fbx") {
        double factor = 0;
        float factor_f = 0;
        if (scene.mMetaData != nullptr) {
            if (!scene.mMetaData->Get("UnitScaleFactor", factor) && scene.mMetaData->Get("UnitScaleFactor", factor_f))
                factor = factor_f;
        }
        return std::isfinite(factor) && factor > 0 ? factor * 0.01 : 0.01;
    }
    return 0;
}

// LoadedMesh::states_z_up: an FBX file's GlobalSettings, which assimp keeps as metadata, or a PLY
// header's comment that Blender wrote it (Blender writes PLY z-up; Stanford's scans, the usual PLY
// files, are y-up).
bool states_z_up(const aiScene& scene, const std::string& path) {
    if (const std::string head = read_file_head(path, 4096); looks_like_ply(head)) {
        const size_t end = head.find("end_header");
        return head.substr(0, end).find("\ncomment Created by Blender") != std::string::npos;
    }
    int32_t axis = -1, sign = 0;
    return lower_extension(path) == ".fbx" && scene.mMetaData != nullptr && scene.mMetaData->Get("UpAxis", axis) &&
           scene.mMetaData->Get("UpAxisSign", sign) && axis == 2 && sign == 1;
}

// LoadedMesh::plain, from the scene as read, by Appearance::plain's rule as read_material reads
// a material (meshio/appearance.cpp): no mesh with vertex colours, no material with a texture
// (found or not: one not found is a warning), and every material assimp's default or white.
bool shows_only_its_shape(const aiScene& scene) {
    for (unsigned i = 0; i < scene.mNumMeshes; ++i)
        if (shows_vertex_colours(*scene.mMeshes[i])) return false;
    for (unsigned i = 0; i < scene.mNumMaterials; ++i) {
        const aiMaterial& m = *scene.mMaterials[i];
        for (aiTextureType type : {aiTextureType_BASE_COLOR, aiTextureType_DIFFUSE})
            if (m.GetTextureCount(type) > 0) return false;
        aiString name;
        if (m.Get(AI_MATKEY_NAME, name) == AI_SUCCESS && std::string(name.C_Str()) == AI_DEFAULT_MATERIAL_NAME) continue;
        aiColor4D c(1, 1, 1, 1);
        if (m.Get(AI_MATKEY_BASE_COLOR, c) != AI_SUCCESS) m.Get(AI_MATKEY_COLOR_DIFFUSE, c);
        const auto white = [](float x) { return !std::isfinite(x) || x >= 1; };  // read_material clamps
        if (!white(c.r) || !white(c.g) || !white(c.b)) return false;
    }
    return true;
}

// assimp's import and our merge, in this process.
LoadedMesh import_in_process(const std::string& path) {
    Assimp::Importer importer;
    // Every per-vertex attribute but the position goes: only the shape is read here. The
    // vertices that share a position are joined by the merge (Merger), not by assimp's
    // JoinIdenticalVertices: the OBJ loader un-shares them (the bunny has 208,998 for 34,835
    // positions), and assimp's join took 0.06 of the bunny's 0.15 s of reading. Over the corpus
    // the merge alone gives the same meshes (553 of 554 files to the byte; one renumbered:
    // assimp-testmodels' glTF2/IndexOutOfRange). It joins equal positions only, where assimp's
    // join also took those within 4 units in the last place of a float.
    importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS,
                                aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS |
                                    aiComponent_COLORS | aiComponent_TEXCOORDS | aiComponent_BONEWEIGHTS |
                                    aiComponent_ANIMATIONS | aiComponent_TEXTURES | aiComponent_LIGHTS |
                                    aiComponent_CAMERAS | aiComponent_MATERIALS);
    // Made readable first where assimp would misread it (meshio/assimp_input.h).
    const aiScene* scene = read_scene(importer, path);
    if (scene == nullptr) {
        throw_input_error(path, std::string("cannot read mesh: ") + importer.GetErrorString(), format_fix(path));
    }
    // Before validation (which rejects a scene without meshes or faces with a message about
    // assimp's data structures), say plainly when there is nothing to fill.
    if (count_surface_faces(*scene) == 0) {
        throw_input_error(path,
                          "mesh file has no triangles or polygons (" + std::to_string(scene->mNumMeshes) +
                              " meshes)",
                          "give a file with a surface mesh; points and lines are ignored");
    }
    // Read before the pass below removes colours and materials.
    const bool plain = shows_only_its_shape(*scene);
    // The components shatter does not use (animations, bones, cameras, ...) go first, in a pass of
    // their own: assimp's validation refuses some animated or skinned files (.b3d, .fbx, .dae)
    // for their animation data alone, and only the static mesh matters here.
    scene = importer.ApplyPostProcessing(aiProcess_RemoveComponent);
    if (scene != nullptr)
        scene = importer.ApplyPostProcessing(aiProcess_ValidateDataStructure | aiProcess_Triangulate);
    if (scene == nullptr) {
        throw_input_error(path, std::string("corrupt mesh: ") + importer.GetErrorString(), format_fix(path));
    }

    Merger merger(path);
    if (scene->mRootNode != nullptr) merger.add_node(*scene, *scene->mRootNode, Mat4::Identity());
    LoadedMesh loaded{merger.take(), file_units(*scene, path), merger.rounding(), plain, states_z_up(*scene, path)};
    if (loaded.mesh.triangles.empty()) {
        throw_input_error(path, "mesh file has no triangles (only points and lines)",
                          "give a file with a surface mesh; points and lines are ignored");
    }
    return loaded;
}

// The import runs in a child process (core/isolated.h): Debian's assimp 5.2 crashes (SIGSEGV)
// on some malformed files (found by tests/fuzz/mesh_fuzz.cpp: an OFF face with an index far out
// of range; PLY headers, see ply_header.h), and its PLY reader spun for ever on a header with no
// end_header. A child that dies or passes its deadline is a bad file (exit code 3) whose message
// says the reader crashed or did not finish.
std::string serialize(const LoadedMesh& loaded) {
    const TriangleMesh& m = loaded.mesh;
    const uint64_t nv = m.vertices.size(), nt = m.triangles.size();
    std::string out;
    out.append(reinterpret_cast<const char*>(&loaded.metres_per_unit), 8);
    for (const double* x : {&loaded.rounding.step, &loaded.rounding.coordinate, &loaded.rounding.size})
        out.append(reinterpret_cast<const char*>(x), 8);
    out.push_back(loaded.plain ? 1 : 0);
    out.push_back(loaded.states_z_up ? 1 : 0);
    out.append(reinterpret_cast<const char*>(&nv), 8);
    for (const Vec3& v : m.vertices) out.append(reinterpret_cast<const char*>(v.data()), 24);
    out.append(reinterpret_cast<const char*>(&nt), 8);
    out.append(reinterpret_cast<const char*>(m.triangles.data()), nt * sizeof(Tri));
    return out;
}

LoadedMesh deserialize(const std::string& bytes) {
    LoadedMesh loaded;
    TriangleMesh& m = loaded.mesh;
    uint64_t nv = 0, nt = 0;
    size_t at = 0;
    std::memcpy(&loaded.metres_per_unit, bytes.data() + at, 8);
    at += 8;
    for (double* x : {&loaded.rounding.step, &loaded.rounding.coordinate, &loaded.rounding.size})
        std::memcpy(x, bytes.data() + at, 8), at += 8;
    loaded.plain = bytes[at++] != 0;
    loaded.states_z_up = bytes[at++] != 0;
    std::memcpy(&nv, bytes.data() + at, 8);
    at += 8;
    m.vertices.resize(nv);
    for (Vec3& v : m.vertices) std::memcpy(v.data(), bytes.data() + at, 24), at += 24;
    std::memcpy(&nt, bytes.data() + at, 8);
    at += 8;
    m.triangles.resize(nt);
    std::memcpy(m.triangles.data(), bytes.data() + at, nt * sizeof(Tri));
    return loaded;
}

// How long the reader may take: 15 s plus 10 s per MB, far beyond any real import (the bunny,
// 3 MB: ~0.1 s; two million triangles: a few seconds), so that prescore of any file ends within
// 20 s plus its size's share (assimp-testmodels' invalid/OutOfMemory.off, 309 bytes, kept the
// reader busy for 44 s before it failed). Under ASan imports are ~20x slower: scripts/asan.sh
// sets SHATTER_MESH_IMPORT_TIMEOUT (seconds), which overrides this, as the test that proves the
// deadline does.
}  // namespace

double mesh_import_deadline_seconds(const std::string& path) {
    if (const char* env = std::getenv("SHATTER_MESH_IMPORT_TIMEOUT")) {
        char* end = nullptr;
        const double s = std::strtod(env, &end);
        if (end != env && *end == '\0' && s > 0) return s;
    }
    std::error_code ec;
    const auto bytes = std::filesystem::file_size(path, ec);
    return 15.0 + 10.0 * (ec ? 0.0 : double(bytes) / 1e6);
}

namespace {

LoadedMesh import_isolated(const std::string& path) {
    const double limit = mesh_import_deadline_seconds(path);
    try {
        return deserialize(run_isolated([&] { return serialize(import_in_process(path)); }, limit));
    } catch (const IsolatedFailure& f) {
        if (f.timed_out)
            throw_input_error(path, fmt::format("the mesh reader (assimp) did not finish within {:.3g} s on this file", limit),
                              "the file is damaged or malformed; " + format_fix(path));
        throw_input_error(path, std::string("the mesh reader (assimp) crashed on this file (") + f.what() + ")",
                          "the file is damaged or malformed; " + format_fix(path));
    }
}

}  // namespace

LoadedMesh load_mesh_file(const std::string& path) {
    check_path(path);
    // assimp crashes on some malformed PLY headers (meshio/ply_header.h): check them first.
    // The first 64 kB: what a PLY header may take.
    if (const std::string head = read_file_head(path, 64 * 1024); looks_like_ply(head)) check_ply_header(head, path);
    if (const std::string ext = unreadable_gltf_extension(path); !ext.empty())
        spdlog::info("mesh: {} uses {} (as gltfpack writes it): decoded before it is read", path, ext);

    return import_isolated(path);
}

std::string lower_case(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

std::string lower_extension(const std::string& path) { return lower_case(std::filesystem::path(path).extension().string()); }

bool z_up(UpAxis up, const std::string& path, bool states_z_up) {
    if (up != UpAxis::Auto) return up == UpAxis::Z;
    return !z_up_format(path, states_z_up).empty();
}

std::string z_up_format(const std::string& path, bool states_z_up) {
    const std::string ext = lower_extension(path);
    if (states_z_up && ext == ".fbx") return "an FBX file whose settings make z up (UpAxis), which the reader does not turn";
    if (states_z_up) return "a PLY file Blender wrote (its header says so): Blender makes z up";
    if (ext == ".stl") return "an STL file: CAD and 3D printing make z up";
    if (ext == ".3mf") return "a 3MF file: 3D printing makes z up";
    if (ext == ".amf") return "an AMF file: 3D printing makes z up";
    if (ext == ".blend") return "a Blender file: Blender makes z up";
    return "";
}

std::string rounding_hint(const FloatRounding& r) {
    if (!(r.size > 0) || !(r.step > kRoundingWarning * r.size)) return "";
    return fmt::format("its coordinates reach {:.4g} units from the file's origin, {:.3g} times the size of the mesh "
                       "they belong to ({:.3g} units across); the reader (assimp) holds coordinates in single "
                       "precision, which there rounds them to steps of {:.2g} units, {:.2g}% of that size, so the "
                       "surface comes out stepped. Move the object to the origin before exporting it (in Blender: "
                       "Object > Set Origin > Origin to Geometry, then Object > Clear > Location)",
                       r.coordinate, r.coordinate / r.size, r.size, r.step, 100 * r.step / r.size);
}

TriangleMesh load_mesh(const std::string& path, double scale) {
    check_scale(path, scale);
    TriangleMesh mesh = load_mesh_file(path).mesh;
    for (Vec3& v : mesh.vertices) v *= scale;
    return mesh;
}

std::string read_file_head(const std::string& path, size_t bytes) {
    std::ifstream in(path, std::ios::binary);
    // No more than the file holds: callers ask for up to kCompanionSearchBytes (256 MB), and
    // filling that much for a small file cost a tenth of a second per call.
    std::error_code ec;
    const uintmax_t size = fs::file_size(path, ec);
    if (!ec && size < bytes) bytes = size_t(size);
    std::string head(bytes, '\0');
    in.read(head.data(), std::streamsize(head.size()));
    head.resize(size_t(in.gcount()));
    return head;
}

}  // namespace shatter
