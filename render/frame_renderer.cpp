#include "render/frame_renderer.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <chrono>
#include <cstring>
#include <map>

#include <fmt/format.h>

#include "core/error.h"
#include "render/edge_filter.h"
#include "render/gl.h"
#include "render/gl_context.h"
#include "render/camera_path.h"
#include "render/scene_bounds.h"
#include "render/shaders.h"
#include "render/texture.h"

namespace shatter {

namespace {

constexpr float kPieceSpecular = 0.25f, kPropSpecular = 0.15f, kColliderSpecular = 0.1f;
const Colour kGroundColour = {0.40f, 0.39f, 0.37f};
// The ground square reaches just past the fade (kFadeStart, kFadeEnd: render/scene_bounds.h; its
// inscribed circle is the fade end): beyond, the ground would be the background colour,
// fragments for nothing. Planes keep 10: on a tilted plane the fade's horizontal distance is
// shorter than the distance in the plane.
constexpr double kGroundExtent = 8.25, kPlaneExtent = 10;  // in animation radii

Eigen::Matrix4f pose_matrix(const Mat3& rotation, const Vec3& position) {
    Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
    m.block<3, 3>(0, 0) = rotation.cast<float>();
    m.block<3, 1>(0, 3) = position.cast<float>();
    return m;
}

double seconds_since(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// The screen rectangle (pixels) of points given in clip space, two pixels wider and clamped to the
// w x h screen; the whole screen when one lies behind the eye (no safe rectangle), empty when
// there are none. S is the caller's arithmetic (float or double).
template <class S>
PixelRect screen_rect(const std::vector<Eigen::Matrix<S, 4, 1>>& clip, int w, int h) {
    S x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (const Eigen::Matrix<S, 4, 1>& p : clip) {
        if (!(p.w() > S(1e-6))) return PixelRect{0, 0, w, h};
        const S x = (p.x() / p.w() * S(0.5) + S(0.5)) * S(w), y = (p.y() / p.w() * S(0.5) + S(0.5)) * S(h);
        x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
    if (!(x0 <= x1)) return {};
    constexpr S kMargin = 2;  // pixels
    const auto clamp = [](S v, int hi) { return int(std::clamp(v, S(0), S(hi))); };
    return {clamp(std::floor(x0 - kMargin), w), clamp(std::floor(y0 - kMargin), h), clamp(std::ceil(x1 + kMargin), w),
            clamp(std::ceil(y1 + kMargin), h)};
}

}  // namespace

FrameRenderer::FrameRenderer(const RenderScene& scene, const RenderSettings& settings, MsaaRegion region)
    : scene_(scene),
      settings_(settings),
      region_(region),
      bounds_(animation_bounds(animation_balls(scene))),
      cameras_(make_camera_path(scene, settings)),
      // The lights depend on the camera's direction only, which the path keeps.
      lights_(make_lights(bounds_, cameras_.front(), settings)),
      target_(settings.width, settings.height, settings.msaa),
      shadow_program_(shaders::kShadowVertex, shaders::kShadowFragment, "shadow") {
    const Trajectory& t = *scene.trajectory;
    const std::vector<KinematicSettings> props = scene_props(scene.scene);
    assert(t.pieces == scene.model->pieces.size() && t.props == props.size());
    if (settings.shadows) shadow_map_ = std::make_unique<ShadowMap>(settings.shadow_map);
    if (settings.colours == Colours::Input && !scene.model->materials.empty()) {
        std::vector<DecodedImage> images;
        looks_ = material_looks(*scene.model, &images);
        for (const DecodedImage& image : images) textures_.push_back(std::make_unique<GpuTexture>(image));
    }
    if (!settings.interior_texture.empty()) load_interior_texture();
    for (uint32_t i = 0; i < t.pieces; ++i) add_piece(i);
    for (uint32_t k = 0; k < t.props; ++k) {
        const KinematicSettings& body = props[k];
        Item item;
        item.mesh = std::make_unique<GpuMesh>(body.shape.kind == ShapeKind::Sphere
                                                  ? sphere_vertices(body.shape.radius, body.colour)
                                                  : box_vertices(body.shape.size, body.colour));
        item.body = int(t.pieces + k);
        item.specular = kPropSpecular;
        items_.push_back(std::move(item));
    }
    add_static_items();
    const auto build = [&](const Item& item) {
        GlProgram& p = scene_programs_[size_t(variant(item))];
        if (p.id()) return;
        const std::string fragment = shaders::scene_fragment(settings.shadows && item.receives, item.specular > 0,
                                                             item.fade, item.texture >= 0 && !item.interior, item.interior);
        p = GlProgram(shaders::scene_vertex(item.interior).c_str(), fragment.c_str(), "scene");
        // Lights, shadow frustum and fade are fixed for the whole render: set once (and the
        // camera, unless it moves).
        p.use();
        set_scene_uniforms(p);
        set_camera_uniforms(p, cameras_.front());
    };
    for (const Item& item : items_) {
        build(item);
        if (!item.shadow_clip) continue;
        Item outside;  // its variant without lookups, for around the shadow rectangle
        outside.fade = item.fade, outside.specular = item.specular, outside.receives = false;
        build(outside);
    }
    check_gl("scene setup");
}

void FrameRenderer::load_interior_texture() {
    const std::string& path = settings_.interior_texture;
    const DecodedImage image = read_interior_texture(path).image;
    if (std::max(image.width, image.height) > kMaxTextureSide)
        throw_input_error(path, fmt::format("[render] interior_texture is {} x {} texels, over {} a side", image.width,
                                            image.height, kMaxTextureSide),
                          "give a smaller image (repeats cost nothing: interior_texture_size sets their span)");
    interior_texture_ = int(textures_.size());
    textures_.push_back(std::make_unique<GpuTexture>(image));
    interior_repeat_ = float(1 / interior_texture_span(*scene_.model, settings_));
}

void FrameRenderer::add_piece(uint32_t i) {
    // A render surface is drawn indexed with its smooth normals, and casts its shadow with the
    // piece's tet surface (a few thousand triangles instead of tens of thousands; the shadow
    // map holds the caster's back faces, which lie behind the drawn surface's lit side but in
    // pieces thinner than the two surfaces' gap; no acne seen in the demo); a tet surface as before.
    // With an interior texture, its fracture faces are an item of their own.
    const Piece& piece = scene_.model->pieces[i];
    if (!piece.render && interior_texture_ < 0) {
        Item item;
        item.mesh = std::make_unique<GpuMesh>(piece_vertices(piece, i, settings_));
        item.body = int(i);
        item.specular = kPieceSpecular;
        items_.push_back(std::move(item));
        return;
    }
    IndexedVertices all = piece_mesh(piece, i, settings_, looks_);
    if (interior_texture_ >= 0) {
        // Fracture faces sample the interior texture, in interior_colour or white (their vertices
        // are their own: a vertex has a copy per face kind).
        const std::vector<FaceKind>& kinds = piece_mesh_kinds(piece);
        const Colour tint = settings_.interior_colour.value_or(Colour{1, 1, 1});
        if (all.texture.empty()) all.texture.assign(all.indices.size() / 3, -1);
        for (size_t t = 0; t < all.texture.size() && t < kinds.size(); ++t) {
            if (kinds[t] != FaceKind::Fracture) continue;
            all.texture[t] = interior_texture_;
            for (size_t k = 0; k < 3; ++k)
                for (size_t c = 0; c < 3; ++c) all.vertices[all.indices[3 * t + k]].colour[c] = tint[c];
        }
    }
    // The triangles of each texture (-1 first: untextured), vertices renumbered in first use.
    std::map<int32_t, IndexedVertices> parts;
    if (all.texture.empty()) {
        parts[-1] = all;
    } else {
        std::map<int32_t, std::vector<uint32_t>> index;
        for (size_t t = 0; t < all.texture.size(); ++t) {
            IndexedVertices& part = parts[all.texture[t]];
            std::vector<uint32_t>& renumber = index[all.texture[t]];
            if (renumber.empty()) renumber.assign(all.vertices.size(), UINT32_MAX);
            for (int k = 0; k < 3; ++k) {
                const uint32_t v = all.indices[3 * t + size_t(k)];
                if (renumber[v] == UINT32_MAX) renumber[v] = uint32_t(part.vertices.size()), part.vertices.push_back(all.vertices[v]);
                part.indices.push_back(renumber[v]);
            }
        }
    }
    bool first = true;
    for (const auto& [texture, part] : parts) {
        Item item;
        item.mesh = std::make_unique<GpuMesh>(part);
        if (first && settings_.shadows) item.shadow_mesh = std::make_unique<GpuMesh>(piece_vertices(piece, i, settings_));
        item.casts = first;  // the piece's whole tet surface, once
        item.texture = texture;
        item.interior = texture >= 0 && texture == interior_texture_;
        item.rest_offset = piece.mass.center;
        item.body = int(i);
        item.specular = kPieceSpecular;
        items_.push_back(std::move(item));
        first = false;
    }
}

void FrameRenderer::add_static_items() {
    const Vec3 centre = bounds_.center();
    const double radius = bounds_.sizes().norm() / 2;
    const SceneSettings& s = scene_.scene;
    for (size_t i = 0; i < s.colliders.size(); ++i) {
        const ColliderSettings& c = s.colliders[i];
        const Mat3 r = rotation_matrix(c.pose.rotation_deg);
        Item item;
        item.specular = kColliderSpecular;
        item.model = pose_matrix(r, c.pose.position);
        switch (c.shape.kind) {
            case ShapeKind::Box: item.mesh = std::make_unique<GpuMesh>(box_vertices(c.shape.size, c.colour)); break;
            case ShapeKind::Sphere: item.mesh = std::make_unique<GpuMesh>(sphere_vertices(c.shape.radius, c.colour)); break;
            case ShapeKind::Mesh:
                item.mesh = std::make_unique<GpuMesh>(mesh_vertices(scene_.collider_meshes.at(i), c.colour));
                // The mesh's own coordinates (in metres, mesh_scale applied) placed by the pose.
                item.closed = false;
                break;
            case ShapeKind::Plane: {
                // A large square of the plane around the animation's centre, fading out.
                Vec3 local = r.transpose() * (centre - c.pose.position);
                local.y() = 0;
                item.model = pose_matrix(r, c.pose.position + r * local);
                item.mesh = std::make_unique<GpuMesh>(quad_vertices(kPlaneExtent * radius, c.colour));
                item.closed = false;
                item.fade = true;
                break;
            }
        }
        items_.push_back(std::move(item));
    }
    if (s.ground) add_ground(Vec3(centre.x(), s.ground_height, centre.z()), kGroundExtent * radius);
}

// The ground, split where the shadow map ends. Only inside the map's footprint on the ground can
// a lookup find a shadow (outside, key_visibility() returns 1): the rest is drawn without
// lookups, the same pixels for less work, since llvmpipe runs both sides of a branch. The
// footprint: the four edges of the light's orthographic box met with the ground plane, padded
// by 4 texels for the lookups' normal offset and filter taps.
void FrameRenderer::add_ground(const Vec3& origin, double extent) {
    ground_y_ = origin.y();
    double x0 = -extent, x1 = extent, z0 = -extent, z1 = extent;
    if (shadow_map_) {
        const Eigen::Matrix4f inverse = lights_.shadow_view_projection.inverse();
        auto unproject = [&](float x, float y, float z) {
            const Eigen::Vector4f p = inverse * Eigen::Vector4f(x, y, z, 1);
            return Vec3(p.head<3>().cast<double>() / double(p.w()));
        };
        x0 = z0 = extent, x1 = z1 = -extent;
        for (float sx : {-1.0f, 1.0f})
            for (float sy : {-1.0f, 1.0f}) {
                const Vec3 a = unproject(sx, sy, -1), b = unproject(sx, sy, 1);
                const Vec3 p = a + (b - a) * ((origin.y() - a.y()) / (b.y() - a.y())) - origin;
                x0 = std::min(x0, p.x()), x1 = std::max(x1, p.x()), z0 = std::min(z0, p.z()), z1 = std::max(z1, p.z());
            }
        const double pad = 4 * lights_.shadow_texel;
        x0 = std::max(x0 - pad, -extent), x1 = std::min(x1 + pad, extent);
        z0 = std::max(z0 - pad, -extent), z1 = std::min(z1 + pad, extent);
    }
    std::vector<Vertex> inner, ring;
    const double xs[4] = {-extent, x0, x1, extent}, zs[4] = {-extent, z0, z1, extent};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            add_rect(i == 1 && j == 1 ? inner : ring, xs[i], zs[j], xs[i + 1], zs[j + 1], kGroundColour);
    for (auto* part : {&inner, &ring}) {
        if (part->empty()) continue;
        Item item;
        item.model = pose_matrix(Mat3::Identity(), origin);
        item.mesh = std::make_unique<GpuMesh>(std::move(*part));
        item.fade = true;
        item.casts = false;              // nothing lies below it
        item.receives = part == &inner;  // the ring is outside the shadow map
        item.shadow_clip = part == &inner && shadow_map_;
        items_.push_back(std::move(item));
    }
}

Eigen::Matrix4f FrameRenderer::model_matrix(const Item& item, uint32_t frame) const {
    if (item.body < 0) return item.model;
    const BodyPose& p = scene_.trajectory->pose(frame, uint32_t(item.body));
    Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
    m.block<3, 3>(0, 0) = p.rotation.normalized().toRotationMatrix();
    m.block<3, 1>(0, 3) = p.position;
    return m;
}

void FrameRenderer::shadow_pass(uint32_t frame) {
    shadow_map_->bind_for_drawing();
    shadow_program_.use();
    shadow_program_.set("u_shadow_view_projection", lights_.shadow_view_projection);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.5f, 2.0f);
    glCullFace(GL_FRONT);  // closed bodies store their back faces: no acne on lit faces
    for (const Item& item : items_) {
        if (!item.casts) continue;
        if (item.closed) glEnable(GL_CULL_FACE); else glDisable(GL_CULL_FACE);
        shadow_program_.set("u_model", model_matrix(item, frame));
        (item.shadow_mesh ? item.shadow_mesh : item.mesh)->draw();
    }
    glDisable(GL_POLYGON_OFFSET_FILL);
    glCullFace(GL_BACK);
}

void FrameRenderer::set_scene_uniforms(const GlProgram& p) const {
    const auto& bg = settings_.background;
    p.set("u_shadow_view_projection", lights_.shadow_view_projection);
    p.set("u_normal_offset", 1.5f * lights_.shadow_texel);
    p.set("u_key_direction", lights_.key_direction);
    p.set("u_key_colour", lights_.key_colour);
    p.set("u_fill_direction", lights_.fill_direction);
    p.set("u_fill_colour", lights_.fill_colour);
    p.set("u_sky_colour", lights_.sky_colour);
    p.set("u_bounce_colour", lights_.bounce_colour);
    p.set("u_shadow_map", 0);
    p.set("u_texture", 1);
    p.set("u_interior_repeat", interior_repeat_);
    p.set("u_shadow_texel_uv", 1.0f / float(settings_.shadow_map));
    const float radius = float(bounds_.sizes().norm() / 2);
    p.set("u_fade_centre", Eigen::Vector3f(bounds_.center().cast<float>()));
    p.set("u_fade_start", float(kFadeStart) * radius);
    p.set("u_fade_end", float(kFadeEnd) * radius);
    p.set("u_background", Eigen::Vector3f(bg[0], bg[1], bg[2]));
}

void FrameRenderer::set_camera_uniforms(const GlProgram& p, const Camera& c) const {
    p.set("u_view_projection", Eigen::Matrix4f(c.projection * c.view));
    p.set("u_camera", c.position);
}

void FrameRenderer::scene_pass(uint32_t frame, const PixelRect& rect, bool fading_only) {
    const auto& bg = settings_.background;
    glEnable(GL_SCISSOR_TEST);
    glScissor(rect.x0, rect.y0, rect.x1 - rect.x0, rect.y1 - rect.y0);
    glEnable(GL_FRAMEBUFFER_SRGB);  // linear light in, sRGB bytes stored (clear colour included)
    glClearColor(bg[0], bg[1], bg[2], 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    if (settings_.msaa > 1) glEnable(GL_MULTISAMPLE); else glDisable(GL_MULTISAMPLE);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, shadow_map_ ? shadow_map_->texture() : 0);
    int current = -1;
    for (const Item& item : items_) {
        if (fading_only && !item.fade) continue;
        const GlProgram& p = scene_programs_[size_t(variant(item))];
        if (variant(item) != current) p.use(), current = variant(item);
        if (item.closed) glEnable(GL_CULL_FACE); else glDisable(GL_CULL_FACE);
        p.set("u_model", model_matrix(item, frame));
        p.set("u_specular", item.specular);
        if (item.interior) p.set("u_rest_offset", Eigen::Vector3f(item.rest_offset.cast<float>()));
        if (item.texture >= 0) {
            glActiveTexture(GL_TEXTURE1);
            glBindTexture(GL_TEXTURE_2D, textures_[size_t(item.texture)]->id());
            glActiveTexture(GL_TEXTURE0);
        }
        if (item.shadow_clip) {
            draw_shadow_clipped(item, rect);
            current = -1;
        } else {
            item.mesh->draw();
        }
    }
    glBindTexture(GL_TEXTURE_2D, 0);
    glDisable(GL_SCISSOR_TEST);
}

// Outside the rectangle every lookup finds the map empty and key_visibility() returns exactly 1,
// so the variant without lookups draws the same pixels there for less work (llvmpipe runs both
// sides of a branch, so a test in the shader would save nothing). The two draws are the same
// triangles under complementary scissors: each pixel is drawn once, as by one draw.
void FrameRenderer::draw_shadow_clipped(const Item& item, const PixelRect& rect) {
    const auto meet = [](const PixelRect& a, const PixelRect& b) {
        return PixelRect{std::max(a.x0, b.x0), std::max(a.y0, b.y0), std::min(a.x1, b.x1), std::min(a.y1, b.y1)};
    };
    const auto draw = [&](const PixelRect& r, int variant_of) {
        if (r.empty()) return;
        const GlProgram& p = scene_programs_[size_t(variant_of)];
        p.use();
        p.set("u_model", item.model);
        p.set("u_specular", item.specular);
        glScissor(r.x0, r.y0, r.x1 - r.x0, r.y1 - r.y0);
        item.mesh->draw();
    };
    const PixelRect in = meet(rect, shadow_rect_);
    draw(in, variant(item));
    const PixelRect e = in.empty() ? PixelRect{rect.x0, rect.y1, rect.x0, rect.y1} : in;
    for (const PixelRect& band : {PixelRect{rect.x0, rect.y0, rect.x1, e.y0}, PixelRect{rect.x0, e.y1, rect.x1, rect.y1},
                                  PixelRect{rect.x0, e.y0, e.x0, e.y1}, PixelRect{e.x1, e.y0, rect.x1, e.y1}})
        draw(band, variant(item) | 4);
    glScissor(rect.x0, rect.y0, rect.x1 - rect.x0, rect.y1 - rect.y0);
}

PixelRect FrameRenderer::shadow_rect(uint32_t frame) const {
    const int w = int(settings_.width), h = int(settings_.height);
    const PixelRect screen{0, 0, w, h};
    const Eigen::Vector3d light = lights_.key_direction.cast<double>();
    if (!(light.y() > 1e-3)) return screen;  // a grazing light: its shadows reach anywhere
    // The casters' boxes carried along the light onto the ground: a rectangle that holds every
    // point of the ground whose ray to the light meets a caster.
    double x0 = INFINITY, z0 = INFINITY, x1 = -INFINITY, z1 = -INFINITY;
    for (const Item& item : items_) {
        if (!item.casts) continue;
        const Eigen::Matrix4d m = model_matrix(item, frame).cast<double>();
        const Eigen::AlignedBox3f& b = (item.shadow_mesh ? item.shadow_mesh : item.mesh)->bounds();
        for (int c = 0; c < 8; ++c) {
            const Eigen::Vector3d p =
                (m * b.corner(Eigen::AlignedBox3f::CornerType(c)).cast<double>().homogeneous()).head<3>();
            const Eigen::Vector3d g = p - light * ((p.y() - ground_y_) / light.y());
            x0 = std::min(x0, g.x()), x1 = std::max(x1, g.x()), z0 = std::min(z0, g.z()), z1 = std::max(z1, g.z());
        }
    }
    if (!(x0 <= x1)) return {};  // nothing casts
    // The filter's reach (1.75 texels) and the normal offset (1.5 texels), each at most 1 /
    // light.y() times longer on the ground than in the map, with room to spare.
    const double pad = 8 * lights_.shadow_texel / light.y();
    x0 -= pad, z0 -= pad, x1 += pad, z1 += pad;
    const Camera& c = camera(frame);
    const Eigen::Matrix4d view_projection = (c.projection * c.view).cast<double>();
    std::vector<Eigen::Vector4d> corners;
    for (double x : {x0, x1})
        for (double z : {z0, z1}) corners.push_back(view_projection * Eigen::Vector4d(x, ground_y_, z, 1));
    return screen_rect(corners, w, h);
}

PixelRect FrameRenderer::edge_rect(uint32_t frame) const {
    const Camera& c = camera(frame);
    const Eigen::Matrix4f view_projection = c.projection * c.view;
    std::vector<Eigen::Vector4f> corners;  // of every item that does not fade (none: no edges)
    for (const Item& item : items_) {
        if (item.fade) continue;
        const Eigen::Matrix4f m = view_projection * model_matrix(item, frame);
        const Eigen::AlignedBox3f& b = item.mesh->bounds();
        for (int k = 0; k < 8; ++k) corners.push_back(m * b.corner(Eigen::AlignedBox3f::CornerType(k)).homogeneous());
    }
    return screen_rect(corners, int(settings_.width), int(settings_.height));
}

bool FrameRenderer::same_picture(uint32_t a, uint32_t b) const {
    const auto same = [](const auto& x, const auto& y) { return std::memcmp(x.data(), y.data(), sizeof(float) * x.size()) == 0; };
    if (camera_moves()) {
        const Camera &x = camera(a), &y = camera(b);
        if (!same(x.position, y.position) || !same(x.view, y.view) || !same(x.projection, y.projection)) return false;
    }
    for (const Item& item : items_) {
        if (item.body < 0) continue;
        const BodyPose& p = scene_.trajectory->pose(a, uint32_t(item.body));
        const BodyPose& q = scene_.trajectory->pose(b, uint32_t(item.body));
        if (!same(p.position, q.position) || !same(p.rotation.coeffs(), q.rotation.coeffs())) return false;
    }
    return true;
}

void FrameRenderer::render(uint32_t frame, uint8_t* rgba) {
    assert(frame < scene_.trajectory->frames());
    auto start = std::chrono::steady_clock::now();
    if (camera_moves())
        for (const GlProgram& p : scene_programs_)
            if (p.id()) p.use(), set_camera_uniforms(p, camera(frame));
    if (shadow_map_) shadow_pass(frame), shadow_rect_ = shadow_rect(frame);
    const int w = int(settings_.width), h = int(settings_.height);
    const PixelRect screen{0, 0, w, h};
    PixelRect edges;
    if (settings_.msaa > 1) {
        edges = region_ == MsaaRegion::Everywhere ? screen : edge_rect(frame);
        if (!edges.empty()) {
            target_.bind_scene();
            scene_pass(frame, edges, false);
        }
        // Around the edges' rectangle: up to four bands of ground and background, one sample.
        target_.bind_resolved();
        const PixelRect e = edges.empty() ? PixelRect{0, h, 0, h} : edges;
        for (const PixelRect& band : {PixelRect{0, 0, w, e.y0}, PixelRect{0, e.y1, w, h}, PixelRect{0, e.y0, e.x0, e.y1},
                                      PixelRect{e.x1, e.y0, w, e.y1}})
            if (!band.empty()) scene_pass(frame, band, true);
    } else {
        target_.bind_scene();
        scene_pass(frame, screen, false);
    }
    glFinish();
    times_.draw = seconds_since(start);
    start = std::chrono::steady_clock::now();
    target_.resolve(edges);
    target_.read(rgba);
    times_.readback = seconds_since(start);
    if (settings_.edge_filter) {
        start = std::chrono::steady_clock::now();
        filter_edges(rgba, settings_.width, settings_.height);
        times_.filter = seconds_since(start);
    }
}

}  // namespace shatter
