// The input's appearance with assimp. Design notes: appearance.h.
#include "meshio/appearance.h"

#include <assimp/Importer.hpp>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <fmt/format.h>

#include "core/binary_io.h"
#include "core/error.h"
#include "core/isolated.h"
#include "core/model_io.h"
#include "core/utf8.h"
#include "meshio/assimp_input.h"
#include "meshio/companions.h"
#include "meshio/image_decode.h"
#include "meshio/mesh_load.h"

namespace shatter {
namespace {

using Mat4 = Eigen::Matrix4d;

Mat4 to_eigen(const aiMatrix4x4& m) {
    Mat4 r;
    r << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3, m.d4;
    return r;
}

constexpr int kTextureFolderUp = 3;  // folders above the mesh file's searched for a texture's written path

// The files in `dir` (not below) whose names are `wanted` in any letter case, in name order;
// its folders into `folders` when given.
std::vector<std::string> files_named(const std::filesystem::path& dir, const std::string& wanted,
                                     std::vector<std::string>* folders) {
    std::vector<std::string> found;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
        if (entry.is_directory(ec)) {
            if (folders) folders->push_back(entry.path().string());
        } else if (lower_case(entry.path().filename().string()) == wanted && entry.is_regular_file(ec)) {
            found.push_back(entry.path().string());
        }
    }
    std::sort(found.begin(), found.end());
    return found;
}

// A texture file named by a material: as written, relative to the mesh file's folder, and by its
// bare name in that folder (exporters often keep the path of the machine they ran on); then that
// bare name in any letter case (files made on Windows name "IMAGE1.JPG" for IMAGE1.jpg), in the
// mesh file's folder, then in the folders in it ("textures/", as downloads ship them), then in
// the folders beside it (models/ and textures/ side by side), the first in name order; then the
// written path's last folders and name under the folders up to kTextureFolderUp above the mesh
// file's (a project moved from where it was made: D:\...\models\OBJ\wood.jpg named by
// models/FBX/spider.fbx is models/OBJ/wood.jpg).
std::string find_texture_file(const std::string& mesh_path, std::string name) {
    std::replace(name.begin(), name.end(), '\\', '/');
    const std::filesystem::path dir = std::filesystem::path(mesh_path).parent_path();
    const std::filesystem::path bare = std::filesystem::path(name).filename();
    std::error_code ec;
    for (const std::filesystem::path& p : {dir / name, std::filesystem::path(name), dir / bare})
        if (std::filesystem::is_regular_file(p, ec)) return p.string();
    const std::string wanted = lower_case(bare.string());
    std::vector<std::string> folders;
    std::vector<std::string> found = files_named(dir.empty() ? "." : dir, wanted, &folders);
    std::sort(folders.begin(), folders.end());
    for (size_t i = 0; found.empty() && i < folders.size(); ++i) found = files_named(folders[i], wanted, nullptr);
    // The folders beside the mesh file's own (models/ and textures/ side by side, as game mods
    // and asset packs keep them), as companion_files searches them.
    if (found.empty()) {
        for (const std::filesystem::path& folder : folders_beside(dir)) {
            found = files_named(folder, wanted, nullptr);
            if (!found.empty()) break;
        }
    }
    if (!found.empty()) return found.front();
    std::vector<std::string> parts;  // the written path's folders, without a drive or root
    for (const auto& part : std::filesystem::path(name).relative_path().parent_path())
        if (part != "." && part != ".." && !part.empty()) parts.push_back(part.string());
    std::filesystem::path above = std::filesystem::absolute(dir.empty() ? "." : dir, ec);
    for (int up = 1; up <= kTextureFolderUp && above.has_relative_path(); ++up) {
        above = above.parent_path();
        std::filesystem::path tail = bare;
        for (size_t k = parts.size(); k-- > 0;) {
            tail = std::filesystem::path(parts[k]) / tail;
            if (std::filesystem::is_regular_file(above / tail, ec)) return (above / tail).string();
        }
    }
    return "";
}

std::string read_whole(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

Material read_material(const aiScene& scene, const aiMaterial& m, unsigned index, const std::string& path,
                       std::vector<std::string>& warnings) {
    Material out;
    aiString name;
    out.name = m.Get(AI_MATKEY_NAME, name) == AI_SUCCESS ? to_utf8(name.C_Str()) : fmt::format("material_{}", index);
    aiColor4D c(1, 1, 1, 1);
    // assimp's default material (grey 0.6, made for meshes that name none) is white here: such a
    // mesh shows its vertex colours as they are, or nothing beyond its shape (Appearance::plain).
    if (out.name == AI_DEFAULT_MATERIAL_NAME) {
    } else if (m.Get(AI_MATKEY_BASE_COLOR, c) == AI_SUCCESS || m.Get(AI_MATKEY_COLOR_DIFFUSE, c) == AI_SUCCESS) {
        out.base_colour = {c.r, c.g, c.b, c.a};
        for (float& x : out.base_colour) x = std::isfinite(x) ? std::clamp(x, 0.0f, 1.0f) : 1.0f;
    }
    aiString tex;
    bool found = false;
    for (aiTextureType type : {aiTextureType_BASE_COLOR, aiTextureType_DIFFUSE})
        if (m.GetTextureCount(type) > 0 && m.GetTexture(type, 0, &tex) == AI_SUCCESS && tex.length > 0) {
            found = true;
            break;
        }
    if (!found) return out;
    const std::string tex_name = tex.C_Str();
    const std::string where = fmt::format("{}: material {} ('{}')", path, index, out.name);
    if (const aiTexture* embedded = scene.GetEmbeddedTexture(tex.C_Str())) {
        if (embedded->mHeight != 0) {
            warnings.push_back(fmt::format("{}: its texture '{}' is embedded uncompressed, which shatter does not read; "
                                           "drawn in its base colour (fix: embed it as a PNG or JPEG file)",
                                           where, tex_name));
            return out;
        }
        out.texture.assign(reinterpret_cast<const char*>(embedded->pcData), embedded->mWidth);
        out.texture_name = to_utf8(tex_name);
    } else {
        const std::string file = find_texture_file(path, tex_name);
        if (file.empty()) {
            warnings.push_back(fmt::format("{}: its texture '{}' is not found beside the mesh file; drawn in its base "
                                           "colour (fix: put the image file where the material names it)",
                                           where, tex_name));
            return out;
        }
        out.texture = read_whole(file);
        out.texture_name = to_utf8(std::filesystem::path(file).filename().string());
        if (out.texture.empty()) {
            warnings.push_back(fmt::format("{}: its texture '{}' is empty or unreadable; drawn in its base colour "
                                           "(fix: re-export the image)", where, file));
            return out;
        }
    }
    if (out.texture.size() >= 12 && out.texture.compare(0, 12, "\xabKTX 20\xbb\r\n\x1a\n") == 0) {
        warnings.push_back(fmt::format("{}: its texture '{}' is a KTX2 image (Basis Universal, KHR_texture_basisu), "
                                       "which shatter does not read; drawn in its base colour (fix: export the model "
                                       "with PNG, JPEG or WebP textures)",
                                       where, tex_name));
        out.texture.clear();
        out.texture_name.clear();
        return out;
    }
    out.texture_mime = image_mime(out.texture, tex_name);
    return out;
}

class Walker {
public:
    Walker(const aiScene& scene, Appearance& out) : scene_(scene), out_(out) {}

    void add_node(const aiNode& node, const Mat4& parent) {
        const Mat4 transform = parent * to_eigen(node.mTransformation);
        for (unsigned i = 0; i < node.mNumMeshes; ++i) add_mesh(*scene_.mMeshes[node.mMeshes[i]], transform);
        for (unsigned i = 0; i < node.mNumChildren; ++i) add_node(*node.mChildren[i], transform);
    }

private:
    void add_mesh(const aiMesh& mesh, const Mat4& transform) {
        const uint32_t base = uint32_t(out_.mesh.vertices.size());
        const bool has_uv = mesh.HasTextureCoords(0), has_colour = shows_vertex_colours(mesh);
        for (unsigned i = 0; i < mesh.mNumVertices; ++i) {
            const aiVector3D& v = mesh.mVertices[i];
            const Eigen::Vector4d p = transform * Vec3(v.x, v.y, v.z).homogeneous();
            out_.mesh.vertices.push_back(p.head<3>() / p.w());
            // Non-finite values (a damaged file) become (0, 0) and white: the model holds finite numbers only.
            auto finite = [](float x, float otherwise) { return std::isfinite(x) ? x : otherwise; };
            uv.push_back(has_uv ? std::array<float, 2>{finite(mesh.mTextureCoords[0][i].x, 0), finite(mesh.mTextureCoords[0][i].y, 0)}
                                : std::array<float, 2>{0, 0});
            const float* none = kNoVertexColour;
            aiColor4D c(none[0], none[1], none[2], none[3]);
            if (has_colour && !no_vertex_colour(mesh.mColors[0][i])) c = mesh.mColors[0][i];
            colour.push_back({finite(c.r, 1), finite(c.g, 1), finite(c.b, 1), finite(c.a, 1)});
        }
        any_uv = any_uv || has_uv;
        any_colour = any_colour || has_colour;
        for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
            const aiFace& face = mesh.mFaces[f];
            if (face.mNumIndices != 3) continue;
            out_.mesh.triangles.push_back({base + face.mIndices[0], base + face.mIndices[1], base + face.mIndices[2]});
            out_.material.push_back(mesh.mMaterialIndex);
        }
    }

    const aiScene& scene_;
    Appearance& out_;

public:
    std::vector<std::array<float, 2>> uv;
    std::vector<std::array<float, 4>> colour;
    bool any_uv = false, any_colour = false;
};

Appearance import_in_process(const std::string& path) {
    Assimp::Importer importer;
    // What the surface looks like stays; what moves or lights it goes (as in load_mesh).
    importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS, aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS |
                                                            aiComponent_BONEWEIGHTS | aiComponent_ANIMATIONS |
                                                            aiComponent_LIGHTS | aiComponent_CAMERAS);
    // Made readable first where assimp would misread it (meshio/assimp_input.h).
    const aiScene* scene = read_scene(importer, path);
    const std::string fix = "check that the file is a complete mesh in a format assimp reads";
    if (scene == nullptr) throw_input_error(path, std::string("cannot read mesh: ") + importer.GetErrorString(), fix);
    scene = importer.ApplyPostProcessing(aiProcess_RemoveComponent);
    if (scene != nullptr)
        scene = importer.ApplyPostProcessing(aiProcess_ValidateDataStructure | aiProcess_Triangulate |
                                             aiProcess_GenUVCoords | aiProcess_TransformUVCoords);
    if (scene == nullptr) throw_input_error(path, std::string("corrupt mesh: ") + importer.GetErrorString(), fix);
    Appearance out;
    for (unsigned m = 0; m < scene->mNumMaterials; ++m)
        out.materials.push_back(read_material(*scene, *scene->mMaterials[m], m, path, out.warnings));
    Walker walker(*scene, out);
    if (scene->mRootNode != nullptr) walker.add_node(*scene->mRootNode, Mat4::Identity());
    if (walker.any_uv) out.uv = std::move(walker.uv);
    if (walker.any_colour) out.colour = std::move(walker.colour);
    for (uint32_t& m : out.material)
        if (m >= out.materials.size()) m = 0;
    if (out.materials.empty()) out.materials.push_back(Material{"default", {1, 1, 1, 1}, "", "", ""});
    return out;
}

std::string serialize(const Appearance& a) {
    ByteWriter w;
    w.u32(uint32_t(a.mesh.vertices.size()));
    for (const Vec3& v : a.mesh.vertices) w.vec3(v);
    w.u32(uint32_t(a.mesh.triangles.size()));
    for (size_t t = 0; t < a.mesh.triangles.size(); ++t) {
        for (uint32_t v : a.mesh.triangles[t]) w.u32(v);
        w.u32(a.material[t]);
    }
    w.u8(a.uv.empty() ? 0 : 1);
    for (const auto& uv : a.uv) w.f32(uv[0]), w.f32(uv[1]);
    w.u8(a.colour.empty() ? 0 : 1);
    for (const auto& c : a.colour)
        for (float x : c) w.f32(x);
    w.u32(uint32_t(a.materials.size()));
    for (const Material& m : a.materials) write_material(w, m);
    w.u32(uint32_t(a.warnings.size()));
    for (const std::string& s : a.warnings) w.str(s);
    return w.data();
}

Appearance deserialize(const std::string& bytes, const std::string& path) {
    ByteReader r(bytes, path + " (appearance)", 0);
    Appearance a;
    a.mesh.vertices.resize(r.count(24, "vertices"));
    for (Vec3& v : a.mesh.vertices) {
        // One read per statement: the order a function's arguments are evaluated in is unspecified
        // (read as Vec3's three arguments, GCC swapped x and z).
        const double x = r.f64(), y = r.f64(), z = r.f64();
        v = Vec3(x, y, z);
    }
    const uint32_t nt = r.count(16, "triangles");
    a.mesh.triangles.resize(nt);
    a.material.resize(nt);
    for (uint32_t t = 0; t < nt; ++t) {
        for (uint32_t& v : a.mesh.triangles[t]) v = r.u32();
        a.material[t] = r.u32();
    }
    if (r.u8()) {
        a.uv.resize(a.mesh.vertices.size());
        for (auto& uv : a.uv) uv = {r.f32(), r.f32()};
    }
    if (r.u8()) {
        a.colour.resize(a.mesh.vertices.size());
        for (auto& c : a.colour)
            for (float& x : c) x = r.f32();
    }
    a.materials.resize(r.u32());
    for (Material& m : a.materials) m = read_material(r);
    a.warnings.resize(r.u32());
    for (std::string& s : a.warnings) s = r.str();
    return a;
}

}  // namespace

bool Appearance::plain() const {
    if (!colour.empty()) return false;
    for (const Material& m : materials) {
        if (!m.texture.empty() && !uv.empty()) return false;
        const auto& c = m.base_colour;
        const bool white = c[0] == 1 && c[1] == 1 && c[2] == 1;
        const bool assimp_default = m.name == AI_DEFAULT_MATERIAL_NAME;
        if (!white && !assimp_default) return false;
    }
    return true;
}

std::string image_mime(const std::string& bytes, const std::string& name) {
    if (bytes.size() >= 8 && bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0) return "image/png";
    if (bytes.size() >= 3 && uint8_t(bytes[0]) == 0xFF && uint8_t(bytes[1]) == 0xD8 && uint8_t(bytes[2]) == 0xFF)
        return "image/jpeg";
    if (is_webp(bytes)) return "image/webp";
    const std::string ext = lower_extension(name);
    if (ext == ".tga") return "image/x-tga";
    if (ext == ".bmp") return "image/bmp";
    if (ext == ".png") return "image/png";
    if (ext == ".jpg" || ext == ".jpeg") return "image/jpeg";
    return "";
}

Appearance load_appearance(const std::string& path) {
    try {
        return deserialize(run_isolated([&] { return serialize(import_in_process(path)); },
                                        mesh_import_deadline_seconds(path)),
                           path);
    } catch (const IsolatedFailure& f) {
        throw_input_error(path, fmt::format("the mesh reader (assimp) {} on this file while reading its materials ({})",
                                            f.timed_out ? "did not finish" : "crashed", f.what()),
                          "the file is damaged or malformed");
    }
}

}  // namespace shatter
