// export_glb (pipeline/export_glb.h): the trajectory as an animated binary glTF.
//
// The aiScene we hand to assimp's "glb2" exporter:
//
//   root "shatter"
//    ├─ "piece_0" … "piece_{N-1}"   meshes: the piece's surface about its centre of mass, one
//    │                              aiMesh per face kind present (outer, fracture, cavity), each
//    │                              with its own material; assimp merges them into one glTF mesh
//    │                              with one primitive per kind
//    └─ "prop_{i}[_{name}]"         the kinematic bodies of the trajectory's scene (box, sphere)
//    └─ "camera"                    with render settings: render's camera (camera_path.h); no mesh
//   animation "fracture": one channel per body (and the camera, when it moves), a translation
//   and a rotation key at every frame
//
// A node's transform is then exactly the trajectory's pose [R | p] (BodyPose: world =
// R (x - origin) + p), and its rest transform is the pose of frame 0, for viewers that do not
// play animations. Vertices are render/mesh_builder's, so that the .glb shows what render shows:
// a piece's render surface indexed with its normals (outer faces smooth, fracture faces flat,
// with texture coordinates of their own: CrackUv),
// else its tet surface, and boxes and spheres, flat; the exporter's enforced
// JoinIdenticalVertices step shares the vertices of coplanar flat neighbours again.
//
// Facts of assimp 5.2 this relies on (read in its glTF2 exporter and importer, and tested in
// tests/pipeline/glb_test.cpp):
//  - key times are written as float(mTime / mTicksPerSecond): we key in seconds (ticks per
//    second 1), computed as frame / fps in double, so each time is the float nearest f / fps;
//    the importer reads them back as milliseconds (mTicksPerSecond 1000);
//  - a channel finds its node by name, and node names must be unique: ours are by construction;
//    the animation's name is taken as an id unchecked, so it must differ from every other id
//    (node, mesh, material_N, ...), else the export fails with an empty error string;
//  - materials read AI_MATKEY_BASE_COLOR (linear RGBA), metallic and roughness factors;
//  - its buffer grows by exact reallocation on every accessor (Buffer::Grow), so an export
//    costs O(accessors x file size), 7 accessors per piece: measured (2 cores, glibc malloc)
//    0.03 s for the 10-piece bunny x 121 frames (0.3 MB), 0.12 s for 125 boxes, 2.1 s for 512,
//    6.7 s for 1,000 (7 MB), 23 s for 2,197; most of it page faults of the reallocations.
//  - its glTF2 exporter writes no cameras (aiScene::mCameras is ignored): the camera node is
//    exported and animated as an empty node, and the camera itself (glTF "cameras", the node's
//    "camera") is added to the GLB's JSON chunk afterwards; the binary chunk is left as it is.
// We export to memory (ExportToBlob) and write with write_file_atomic: a temporary name beside
// the target, fsync, rename; a failed write leaves the old file or none, never a temporary.
#include "pipeline/export_glb.h"

#include <assimp/Exporter.hpp>
#include <assimp/material.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string_view>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/render_settings.h"
#include "core/scene_settings.h"
#include "core/utf8.h"
#include "render/camera_path.h"
#include "render/mesh_builder.h"
#include "render/png_io.h"
#include "render/texture.h"

namespace shatter {

namespace {

constexpr float kRoughness = 0.6f;  // a matte plastic look; glTF's default (1) is chalk
constexpr const char* kCameraNode = "camera";

const char* kind_name(FaceKind k) {
    switch (k) {
        case FaceKind::Outer: return "outer";
        case FaceKind::Fracture: return "fracture";
        case FaceKind::Cavity: return "cavity";
    }
    return "outer";
}

aiMaterial* make_material(const std::string& name, const Colour& c) {
    auto* m = new aiMaterial();
    const aiString ai_name(name);
    m->AddProperty(&ai_name, AI_MATKEY_NAME);
    const aiColor4D rgba(c[0], c[1], c[2], 1.0f);
    m->AddProperty(&rgba, 1, AI_MATKEY_BASE_COLOR);
    m->AddProperty(&rgba, 1, AI_MATKEY_COLOR_DIFFUSE);
    const float metallic = 0.0f, roughness = kRoughness;
    m->AddProperty(&metallic, 1, AI_MATKEY_METALLIC_FACTOR);
    m->AddProperty(&roughness, 1, AI_MATKEY_ROUGHNESS_FACTOR);
    return m;
}

// Vertices as an aiMesh: a triangle soup (three vertices per triangle, as render/mesh_builder's
// flat vertices are) when `indices` is null, else the triangles `indices` names (three each).
aiMesh* make_mesh(const std::string& name, const Vertex* v, size_t count, unsigned material,
                  const uint32_t* indices = nullptr, size_t index_count = 0, bool uv = false, bool colour = false) {
    auto* m = new aiMesh();
    m->mName = aiString(name);
    m->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
    m->mMaterialIndex = material;
    m->mNumVertices = static_cast<unsigned>(count);
    m->mVertices = new aiVector3D[count];
    m->mNormals = new aiVector3D[count];
    for (size_t i = 0; i < count; ++i) {
        m->mVertices[i] = aiVector3D(v[i].position[0], v[i].position[1], v[i].position[2]);
        m->mNormals[i] = aiVector3D(v[i].normal[0], v[i].normal[1], v[i].normal[2]);
    }
    if (uv) {  // TEXCOORD_0 in assimp's convention (v up; the exporter flips it to glTF's)
        m->mNumUVComponents[0] = 2;
        m->mTextureCoords[0] = new aiVector3D[count];
        for (size_t i = 0; i < count; ++i) m->mTextureCoords[0][i] = aiVector3D(v[i].uv[0], 1.0f - v[i].uv[1], 0);
    }
    if (colour) {  // COLOR_0: the vertices' colours, linear (their material's factor is then white)
        m->mColors[0] = new aiColor4D[count];
        for (size_t i = 0; i < count; ++i) m->mColors[0][i] = aiColor4D(v[i].colour[0], v[i].colour[1], v[i].colour[2], 1.0f);
    }
    m->mNumFaces = static_cast<unsigned>((indices ? index_count : count) / 3);
    m->mFaces = new aiFace[m->mNumFaces];
    for (unsigned f = 0; f < m->mNumFaces; ++f) {
        m->mFaces[f].mNumIndices = 3;
        m->mFaces[f].mIndices = indices ? new unsigned[3]{indices[3 * f], indices[3 * f + 1], indices[3 * f + 2]}
                                        : new unsigned[3]{3 * f, 3 * f + 1, 3 * f + 2};
    }
    return m;
}

// The scene under construction; aiScene's destructor frees what its arrays point to, so the
// parts are collected here and moved into it at the end.
struct SceneParts {
    std::vector<aiMesh*> meshes;
    std::vector<aiMaterial*> materials;
    std::map<std::string, unsigned> material_index;  // by name: a material per palette colour and kind
    std::vector<aiNode*> nodes;
    std::vector<aiTexture*> textures;   // embedded images ("*0", "*1", ...), PNG or JPEG files
    std::vector<MaterialLook> looks;    // of the model's materials (render/texture.h)
    std::vector<int> texture_of;        // per model material, its embedded image, -1: none
    int interior = -1;                  // [render] interior_texture's embedded image, -1: none

    ~SceneParts() {
        for (aiMesh* m : meshes) delete m;
        for (aiTexture* t : textures) delete t;
        for (aiMaterial* m : materials) delete m;
        for (aiNode* n : nodes) delete n;
    }
    unsigned material(const std::string& name, const Colour& c) {
        auto [it, added] = material_index.try_emplace(name, static_cast<unsigned>(materials.size()));
        if (added) materials.push_back(make_material(name, c));
        return it->second;
    }
    // The glTF material of model material `m` for faces of `kind`: outer faces its base colour
    // factor and texture, fracture and cavity faces render's colours for them (untextured).
    // `vertex_colours`: the outer faces' colours are their vertices' (COLOR_0, base colour
    // included), so the outer material's factor is white.
    unsigned model_material(const Model& model, uint32_t m, FaceKind kind, const RenderSettings& look, bool vertex_colours) {
        const std::string name = fmt::format("{}_{}", model.materials[m].name.empty() ? fmt::format("material_{}", m)
                                                                                      : to_utf8(model.materials[m].name),
                                             kind_name(kind));
        auto [it, added] = material_index.try_emplace(fmt::format("{}#{}", m, kind_name(kind)), unsigned(materials.size()));
        if (!added) return it->second;
        const MaterialLook& l = looks[m];
        const Colour outer = vertex_colours ? Colour{1, 1, 1} : l.base;
        aiMaterial* mat = make_material(name, kind == FaceKind::Outer ? outer : face_colour(l.mean, kind, look));
        if (kind == FaceKind::Outer && texture_of[m] >= 0) {
            const aiString path(fmt::format("*{}", texture_of[m]));
            mat->AddProperty(&path, AI_MATKEY_TEXTURE(aiTextureType_DIFFUSE, 0));
            mat->AddProperty(&path, AI_MATKEY_TEXTURE(aiTextureType_BASE_COLOR, 0));
        }
        materials.push_back(mat);
        return it->second;
    }
    // Every piece's crack faces with [render] interior_texture: its image, in interior_colour or white.
    unsigned interior_material(const RenderSettings& look) {
        auto [it, added] = material_index.try_emplace("#interior", unsigned(materials.size()));
        if (!added) return it->second;
        aiMaterial* mat = make_material("interior_fracture", look.interior_colour.value_or(Colour{1, 1, 1}));
        const aiString path(fmt::format("*{}", interior));
        mat->AddProperty(&path, AI_MATKEY_TEXTURE(aiTextureType_DIFFUSE, 0));
        mat->AddProperty(&path, AI_MATKEY_TEXTURE(aiTextureType_BASE_COLOR, 0));
        materials.push_back(mat);
        return it->second;
    }
    aiNode* node(const std::string& name, const std::vector<unsigned>& mesh_ids) {
        auto* n = new aiNode(name);
        n->mNumMeshes = static_cast<unsigned>(mesh_ids.size());
        if (!mesh_ids.empty()) {
            n->mMeshes = new unsigned[mesh_ids.size()];
            std::copy(mesh_ids.begin(), mesh_ids.end(), n->mMeshes);
        }
        nodes.push_back(n);
        return n;
    }
};

// Whether the model's render surfaces carry the input's vertex colours (then every painted one does).
bool model_has_vertex_colours(const Model& model) {
    for (const Piece& p : model.pieces)
        if (p.render && !p.render->colour.empty()) return true;
    return false;
}

// A piece's node: one mesh per face kind present (per kind and material when its render surface
// has the input's materials), vertices about its centre of mass: its render surface with its
// normals when it has one (outer faces smooth), else its tet surface, flat.
// The crack faces' texture coordinates: a box projection of the point where it lies in the
// unbroken object (the piece's vertex plus its centre of mass), onto the plane of the two axes
// its face's normal is least along, over the object's bounding box (its diagonal is one unit; with
// [render] interior_texture, one repeat of it is: interior_texture_size, as render draws it).
// Both sides of a crack are the same points with opposite normals: they get the same
// coordinates, so that an interior texture runs on across the crack.
struct CrackUv {
    Vec3 lo = Vec3::Zero();
    double unit = 1;
    CrackUv(const Model& model, const RenderSettings& look) {
        Vec3 hi = Vec3::Constant(-1e300);
        lo = Vec3::Constant(1e300);
        for (const Vec3& v : model.mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
        if (model.mesh.vertices.empty()) lo = hi = Vec3::Zero();
        unit = look.interior_texture.empty() ? std::max((hi - lo).norm(), 1e-12) : interior_texture_span(model, look);
    }
    void set(Vertex& v, const Vec3& centre) const {
        const Vec3 x = (Vec3(v.position[0], v.position[1], v.position[2]) + centre - lo) / unit;
        const Vec3 n = Vec3(v.normal[0], v.normal[1], v.normal[2]).cwiseAbs();
        const int axis = n.x() >= n.y() && n.x() >= n.z() ? 0 : (n.y() >= n.z() ? 1 : 2);
        const int a = axis == 0 ? 1 : 0, b = axis == 2 ? 1 : 2;
        v.uv[0] = float(x[a]), v.uv[1] = float(x[b]);
    }
};

void add_piece(SceneParts& parts, const Model& model, uint32_t id, const RenderSettings& look, const CrackUv& crack_uv) {
    const Piece& piece = model.pieces[id];
    const IndexedVertices all = piece_mesh(piece, id, look, parts.looks);
    const bool by_material = !all.material.empty();
    const bool vertex_colours = by_material && model_has_vertex_colours(model);
    const std::vector<FaceKind>& kinds = piece_mesh_kinds(piece);
    const std::string name = fmt::format("piece_{}", id);
    std::vector<unsigned> mesh_ids;
    const uint32_t materials = by_material ? uint32_t(model.materials.size()) : 1;
    for (FaceKind kind : {FaceKind::Outer, FaceKind::Fracture, FaceKind::Cavity})
        for (uint32_t m = 0; m < materials; ++m) {
            // The triangles of this kind (and material), their vertices renumbered in first use.
            IndexedVertices part;
            std::vector<uint32_t> index(all.vertices.size(), UINT32_MAX);
            bool textured = false;
            for (size_t t = 0; t < kinds.size(); ++t) {
                if (kinds[t] != kind || (by_material && all.material[t] != m)) continue;
                textured = textured || (!all.texture.empty() && all.texture[t] >= 0);
                for (int k = 0; k < 3; ++k) {
                    const uint32_t v = all.indices[3 * t + size_t(k)];
                    if (index[v] == UINT32_MAX) index[v] = static_cast<uint32_t>(part.vertices.size()), part.vertices.push_back(all.vertices[v]);
                    part.indices.push_back(index[v]);
                }
            }
            if (part.indices.empty()) continue;
            if (kind == FaceKind::Fracture)
                for (Vertex& v : part.vertices) crack_uv.set(v, piece.mass.center);
            // piece_colour repeats every 36 pieces (12 hues x 3 shades): one material per repeat.
            const unsigned material =
                kind == FaceKind::Fracture && parts.interior >= 0 ? parts.interior_material(look)
                : by_material ? parts.model_material(model, m, kind, look, vertex_colours)
                            : parts.material(look.colours == Colours::Palette ? fmt::format("palette_{}_{}", id % 36, kind_name(kind))
                                                                              : fmt::format("material_{}", kind_name(kind)),
                                             face_colour(piece_base_colour(id, look), kind, look));
            mesh_ids.push_back(static_cast<unsigned>(parts.meshes.size()));
            const std::string mesh_name = by_material ? fmt::format("{}_{}_{}", name, kind_name(kind), m)
                                                      : fmt::format("{}_{}", name, kind_name(kind));
            parts.meshes.push_back(make_mesh(mesh_name, part.vertices.data(), part.vertices.size(), material,
                                             part.indices.data(), part.indices.size(), textured || kind == FaceKind::Fracture,
                                             vertex_colours && kind == FaceKind::Outer));
        }
    parts.node(name, mesh_ids);
}

aiTexture* embedded(const std::string& bytes, const std::string& hint, const std::string& name) {
    auto* tex = new aiTexture();
    tex->mWidth = unsigned(bytes.size());
    tex->mHeight = 0;
    tex->pcData = new aiTexel[(bytes.size() + sizeof(aiTexel) - 1) / sizeof(aiTexel)];
    std::copy(bytes.begin(), bytes.end(), reinterpret_cast<char*>(tex->pcData));
    std::copy(hint.begin(), hint.end(), tex->achFormatHint);
    tex->mFilename = aiString(name);
    return tex;
}

// [render] interior_texture as an embedded image, PNG or JPEG as it is, else decoded and stored as
// PNG; Error(BadInput) naming the file when it does not decode.
void add_interior_texture(SceneParts& parts, const std::string& path) {
    InteriorTexture texture = read_interior_texture(path);
    std::string& bytes = texture.bytes;
    const DecodedImage& image = texture.image;
    const bool png = bytes.rfind("\x89PNG", 0) == 0, jpeg = bytes.rfind("\xFF\xD8\xFF", 0) == 0;
    std::string name = std::filesystem::path(path).filename().string();
    if (!png && !jpeg) {
        bytes = encode_png(image.rgba.data(), image.width, image.height, 4, size_t(image.width) * 4);
        name = std::filesystem::path(path).stem().string() + ".png";
    }
    parts.interior = int(parts.textures.size());
    parts.textures.push_back(embedded(bytes, jpeg ? "jpg" : "png", to_utf8(name)));
}

// The model's textures as embedded images: PNG and JPEG files as they are, any other format
// (TGA, BMP, WebP) decoded and stored as PNG (glTF 2.0 allows those two only).
void add_textures(SceneParts& parts, const Model& model) {
    std::vector<DecodedImage> images;
    parts.looks = material_looks(model, &images);
    for (size_t m = 0; m < model.materials.size(); ++m) {
        const Material& mat = model.materials[m];
        const int32_t decoded = parts.looks[m].texture;
        if (decoded < 0) {
            parts.texture_of.push_back(-1);
            continue;
        }
        std::string bytes = mat.texture, hint = mat.texture_mime == "image/jpeg" ? "jpg" : "png";
        if (mat.texture_mime != "image/png" && mat.texture_mime != "image/jpeg") {
            const DecodedImage& image = images[size_t(decoded)];
            bytes = encode_png(image.rgba.data(), image.width, image.height, 4, size_t(image.width) * 4);
        }
        parts.texture_of.push_back(int(parts.textures.size()));
        parts.textures.push_back(embedded(bytes, hint,
                                          to_utf8(bytes == mat.texture ? mat.texture_name
                                                                       : std::filesystem::path(mat.texture_name).stem().string() +
                                                                             ".png")));
    }
}

void add_prop(SceneParts& parts, const KinematicSettings& k, uint32_t i, const std::string& where) {
    std::vector<Vertex> vertices;
    if (k.shape.kind == ShapeKind::Box)
        vertices = box_vertices(k.shape.size, k.colour);
    else if (k.shape.kind == ShapeKind::Sphere)
        vertices = sphere_vertices(k.shape.radius, k.colour);
    else
        throw_input_error(where, fmt::format("kinematic body {} ('{}') is a {}, but kinematic bodies are boxes or "
                                             "spheres", i, k.name, to_string(k.shape.kind)),
                          "simulate again with a box or sphere (docs/shot.md, [[scene.kinematic]])");
    const std::string name = k.name.empty() ? fmt::format("prop_{}", i) : fmt::format("prop_{}_{}", i, to_utf8(k.name));
    const unsigned material = parts.material(name + "_colour", k.colour);
    parts.meshes.push_back(make_mesh(name, vertices.data(), vertices.size(), material));
    parts.node(name, {static_cast<unsigned>(parts.meshes.size() - 1)});
}

// The props of the trajectory's scene (its settings JSON, key "scene": the kinematic bodies, then
// the projectiles), checked
// against the trajectory as render checks them.
std::vector<KinematicSettings> trajectory_props(const Trajectory& t, const std::string& where) {
    SceneSettings scene;
    if (!t.settings_json.empty()) {
        const nlohmann::json settings = nlohmann::json::parse(t.settings_json, nullptr, false);
        if (settings.is_discarded() || !settings.is_object())
            throw_input_error(where, "the trajectory's settings are not a JSON object", "simulate again");
        if (settings.contains("scene")) scene = scene_from_json(settings["scene"], where);
    }
    std::vector<KinematicSettings> props = scene_props(scene);
    if (t.props != props.size())
        throw_input_error(where, fmt::format("the trajectory moves {} kinematic bodies and projectiles but its scene "
                                             "describes {}", t.props, props.size()),
                          "simulate again; the file is inconsistent");
    return props;
}

aiQuaternion to_ai(const Eigen::Quaternionf& q) { return aiQuaternion(q.w(), q.x(), q.y(), q.z()); }

aiMatrix4x4 pose_matrix(const BodyPose& p) {
    aiMatrix4x4 m(to_ai(p.rotation.normalized()).GetMatrix());
    m.a4 = p.position.x();
    m.b4 = p.position.y();
    m.c4 = p.position.z();
    return m;
}

// The camera's pose: glTF cameras look down their -z with +y up; the view matrix's rows are the
// camera's right, up and backward axes in the world.
BodyPose camera_pose(const Camera& c) {
    BodyPose p;
    p.position = c.position;
    p.rotation = Eigen::Quaternionf(Eigen::Matrix3f(c.view.block<3, 3>(0, 0).transpose())).normalized();
    return p;
}

// One channel per body (and one for the camera when `cameras` has one per frame) with a key per
// frame. Quaternions are normalized and kept on one hemisphere from key to key, so that
// interpolation between frames turns the short way.
aiAnimation* make_animation(const Trajectory& t, const std::vector<aiNode*>& bodies, const std::vector<Camera>& cameras,
                            aiNode* camera) {
    const uint32_t frames = t.frames();
    const bool moving = camera && cameras.size() == frames && frames > 1;
    auto* anim = new aiAnimation();
    anim->mName = aiString("fracture");  // not "shatter": glTF ids are shared by every kind of object
    anim->mTicksPerSecond = 1.0;  // keys in seconds: the exporter writes mTime / mTicksPerSecond
    anim->mDuration = (frames - 1) / t.fps;
    const size_t channels = bodies.size() + (moving ? 1 : 0);
    anim->mNumChannels = static_cast<unsigned>(channels);
    anim->mChannels = new aiNodeAnim*[channels];
    for (uint32_t b = 0; b < channels; ++b) {
        const bool is_camera = b == bodies.size();
        auto* ch = anim->mChannels[b] = new aiNodeAnim();
        ch->mNodeName = is_camera ? camera->mName : bodies[b]->mName;
        ch->mNumPositionKeys = ch->mNumRotationKeys = frames;
        ch->mPositionKeys = new aiVectorKey[frames];
        ch->mRotationKeys = new aiQuatKey[frames];
        Eigen::Quaternionf previous = Eigen::Quaternionf::Identity();
        for (uint32_t f = 0; f < frames; ++f) {
            const BodyPose p = is_camera ? camera_pose(cameras[f]) : t.pose(f, b);
            Eigen::Quaternionf q = p.rotation.normalized();
            if (f > 0 && q.dot(previous) < 0) q.coeffs() = -q.coeffs();
            previous = q;
            const double time = f / t.fps;  // (unit: s)
            ch->mPositionKeys[f] = aiVectorKey(time, aiVector3D(p.position.x(), p.position.y(), p.position.z()));
            ch->mRotationKeys[f] = aiQuatKey(time, to_ai(q));
        }
    }
    return anim;
}

// `look`: render's colours (colours, material_colour, interior_colour, fracture_tint, cavity_shade).
std::unique_ptr<aiScene> build_scene(const Model& model, const Trajectory& t, const std::vector<Camera>& cameras,
                                     const std::string& where, const RenderSettings& look) {
    const std::vector<KinematicSettings> props = trajectory_props(t, where);
    SceneParts parts;
    add_textures(parts, model);
    if (!look.interior_texture.empty()) add_interior_texture(parts, look.interior_texture);
    const CrackUv crack_uv(model, look);
    for (uint32_t i = 0; i < model.pieces.size(); ++i) add_piece(parts, model, i, look, crack_uv);
    for (uint32_t i = 0; i < props.size(); ++i) add_prop(parts, props[i], i, where);
    for (uint32_t b = 0; b < parts.nodes.size(); ++b) parts.nodes[b]->mTransformation = pose_matrix(t.pose(0, b));
    const std::vector<aiNode*> bodies = parts.nodes;
    aiNode* camera = nullptr;
    if (!cameras.empty()) {
        camera = parts.node(kCameraNode, {});
        camera->mTransformation = pose_matrix(camera_pose(cameras.front()));
    }

    auto scene = std::make_unique<aiScene>();
    scene->mRootNode = new aiNode("shatter");
    scene->mAnimations = new aiAnimation*[1]{make_animation(t, bodies, cameras, camera)};
    scene->mNumAnimations = 1;
    scene->mRootNode->addChildren(static_cast<unsigned>(parts.nodes.size()), parts.nodes.data());
    parts.nodes.clear();
    scene->mNumMeshes = static_cast<unsigned>(parts.meshes.size());
    scene->mMeshes = new aiMesh*[parts.meshes.size()];
    std::copy(parts.meshes.begin(), parts.meshes.end(), scene->mMeshes);
    parts.meshes.clear();
    scene->mNumMaterials = static_cast<unsigned>(parts.materials.size());
    scene->mMaterials = new aiMaterial*[parts.materials.size()];
    std::copy(parts.materials.begin(), parts.materials.end(), scene->mMaterials);
    parts.materials.clear();
    if (!parts.textures.empty()) {
        scene->mNumTextures = static_cast<unsigned>(parts.textures.size());
        scene->mTextures = new aiTexture*[parts.textures.size()];
        std::copy(parts.textures.begin(), parts.textures.end(), scene->mTextures);
        parts.textures.clear();
    }
    return scene;
}

uint32_t read_u32(const std::string& b, size_t at) {
    return uint32_t(uint8_t(b[at])) | uint32_t(uint8_t(b[at + 1])) << 8 | uint32_t(uint8_t(b[at + 2])) << 16 |
           uint32_t(uint8_t(b[at + 3])) << 24;
}
void put_u32(std::string& out, uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(char((v >> (8 * i)) & 0xff));
}

// The GLB with a perspective camera attached to the node named kCameraNode: its JSON chunk
// rewritten (padded with spaces to 4 bytes, as GLB asks), the binary chunk copied.
std::string add_camera(const std::string& glb, const std::vector<Camera>& cameras, const RenderSettings& s,
                       const std::string& where) {
    auto fail = [&](const char* what) {
        return Error(ExitCode::Internal, fmt::format("{}: assimp's GLB is not as expected: {} (fix: report this as a "
                                                     "bug in shatter)", where, what));
    };
    if (glb.size() < 20 || glb.compare(0, 4, "glTF") != 0 || read_u32(glb, 16) != 0x4E4F534Au) throw fail("no JSON chunk");
    const uint32_t json_length = read_u32(glb, 12);
    if (20 + size_t(json_length) > glb.size()) throw fail("JSON chunk length");
    nlohmann::ordered_json j = nlohmann::ordered_json::parse(glb.substr(20, json_length), nullptr, false);
    if (j.is_discarded() || !j.contains("nodes")) throw fail("JSON chunk");
    // Near and far: the nearest near plane and the farthest far plane of the path.
    double znear = INFINITY, zfar = 0;
    for (const Camera& c : cameras) {
        const double a = c.projection(2, 2), b = c.projection(2, 3);
        znear = std::min(znear, b / (a - 1));
        zfar = std::max(zfar, b / (a + 1));
    }
    j["cameras"] = nlohmann::ordered_json::array({{{"name", kCameraNode},
                                                   {"type", "perspective"},
                                                   {"perspective",
                                                    {{"aspectRatio", double(s.width) / s.height},
                                                     {"yfov", s.fov * M_PI / 180},
                                                     {"zfar", zfar},
                                                     {"znear", znear}}}}});
    bool found = false;
    for (auto& node : j["nodes"])
        if (node.value("name", std::string()) == kCameraNode) node["camera"] = 0, found = true;
    if (!found) throw fail("no camera node");
    std::string text = j.dump();
    while (text.size() % 4) text.push_back(' ');
    const std::string rest = glb.substr(20 + json_length);  // the binary chunk, if any
    std::string out = "glTF";
    put_u32(out, 2);
    put_u32(out, uint32_t(12 + 8 + text.size() + rest.size()));
    put_u32(out, uint32_t(text.size()));
    put_u32(out, 0x4E4F534Au);  // "JSON"
    out += text;
    out += rest;
    return out;
}

}  // namespace

void export_glb(const Model& model, const Trajectory& trajectory, const std::string& glb_path,
                const RenderSettings* camera) {
    if (trajectory.pieces != model.pieces.size())
        throw_input_error(glb_path, fmt::format("the trajectory moves {} pieces but the model has {}",
                                                trajectory.pieces, model.pieces.size()),
                          "export a trajectory with the model it was simulated from");
    if (trajectory.frames() == 0)
        throw_input_error(glb_path, "the trajectory holds no frames", "simulate again (shatter simulate)");
    if (!(trajectory.fps > 0))
        throw_input_error(glb_path, fmt::format("the trajectory's frame rate is {} frames/s", trajectory.fps),
                          "simulate again; the file is inconsistent");
    std::vector<Camera> cameras;
    if (camera) {
        RenderScene rs;
        rs.model = &model;
        rs.trajectory = &trajectory;
        trajectory_props(trajectory, glb_path);  // the check: the props the trajectory moves are the scene's
        if (!trajectory.settings_json.empty()) {
            const nlohmann::json settings = nlohmann::json::parse(trajectory.settings_json, nullptr, false);
            if (settings.is_object() && settings.contains("scene")) rs.scene = scene_from_json(settings["scene"], glb_path);
        }
        cameras = make_camera_path(rs, *camera);
    }
    const std::unique_ptr<aiScene> scene = build_scene(model, trajectory, cameras, glb_path, camera ? *camera : RenderSettings{});

    Assimp::Exporter exporter;
    const aiExportDataBlob* blob = exporter.ExportToBlob(scene.get(), "glb2");
    if (!blob)
        throw Error(ExitCode::Internal, fmt::format("{}: assimp's glTF exporter failed: {} (fix: report this as a "
                                                    "bug in shatter)", glb_path, exporter.GetErrorString()));
    if (blob->next)  // a .glb is one file; a second blob would be a buffer we failed to embed
        throw Error(ExitCode::Internal, fmt::format("{}: assimp's glTF exporter wrote more than one file (fix: "
                                                    "report this as a bug in shatter)", glb_path));
    std::string bytes(static_cast<const char*>(blob->data), blob->size);
    if (camera) bytes = add_camera(bytes, cameras, *camera, glb_path);
    write_file_atomic(glb_path, bytes);
}

}  // namespace shatter
