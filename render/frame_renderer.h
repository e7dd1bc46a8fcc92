// Draws one frame of a trajectory into an sRGB RGBA8 buffer. Built once per render (the meshes go to
// GL once; the lights and shadow frustum are fixed from the animation's bounds, the camera path
// from the whole trajectory: render/camera_path.h), then called per frame. Each frame depends
// only on its own poses and its camera: no state carries from one frame to the next, so frame f
// is the same bytes whichever range rendered it.
//
// A piece with the input's textures (colours = "input", render/texture.h) is drawn as one item
// per texture its triangles sample (the textures uploaded once, sampled on unit 1), and casts
// its shadow once.
//
// Per frame: shadow pass (depth from the key light, front faces culled, polygon offset) ->
// scene pass (linear light, MSAA, encoded to sRGB8 by GL on write) -> resolve (glBlitFramebuffer:
// samples decoded, averaged in linear light, encoded) -> glReadPixels of sRGB bytes. Needs a
// current GlContext on the calling thread.
//
// MSAA only where there are edges: the ground (and planes) fade into the background and have no
// silhouette of their own, so only the pieces, props and colliders make edges. Their rectangle
// on screen this frame (projected bounding boxes, 2 pixels of margin) is drawn multisampled and
// resolved; the rest of the frame, ground and background only, is drawn at one sample per pixel
// straight into the buffer that is read back. A pixel that one ground triangle covers gets the
// same colour either way (the shader runs once per pixel; four equal samples average to
// themselves), so the frame is the all-MSAA frame but for a level or so along the ground's own
// triangle edges, and costs what its edges need: llvmpipe spends ~3/4 of a frame on the ground.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "render/camera.h"
#include "render/gl_program.h"
#include "render/gpu_mesh.h"
#include "render/lights.h"
#include "render/render.h"
#include "render/render_target.h"
#include "render/shadow_map.h"
#include "render/texture.h"

namespace shatter {

struct FrameTimes {
    double draw = 0;      // submit + rasterize all passes (unit: s)
    double readback = 0;  // MSAA resolve and glReadPixels (unit: s)
    double filter = 0;    // the edge filter (unit: s)
};

class FrameRenderer {
public:
    FrameRenderer(const RenderScene& scene, const RenderSettings& settings, MsaaRegion region = MsaaRegion::Edges);

    // Draws frame `frame` (< trajectory frames) and reads it back: width * height * 4 bytes,
    // sRGB-encoded RGBA, GL's bottom row first (see render/srgb_encode.h).
    void render(uint32_t frame, uint8_t* rgba);
    const FrameTimes& last_times() const { return times_; }
    // The camera of frame `frame` (the same for every frame when it does not move).
    const Camera& camera(uint32_t frame = 0) const { return cameras_[cameras_.size() > 1 ? frame : 0]; }
    bool camera_moves() const { return cameras_.size() > 1; }
    const Lights& lights() const { return lights_; }
    // Whether frames a and b draw the same picture: the same camera and every body in the same
    // pose, bit for bit (all a frame's pixels depend on: the lights, the fade and the meshes are
    // the whole render's), as at the end of a movie whose pieces rest.
    bool same_picture(uint32_t a, uint32_t b) const;

private:
    struct Item {
        std::unique_ptr<GpuMesh> mesh;
        std::unique_ptr<GpuMesh> shadow_mesh;  // drawn into the shadow map instead of `mesh`, when set
        int body = -1;  // trajectory body (pieces, then props); -1: static
        Eigen::Matrix4f model = Eigen::Matrix4f::Identity();  // for static items
        bool closed = true;   // back faces may be culled
        bool fade = false;    // fades into the background with distance (ground, planes)
        bool casts = true;    // drawn into the shadow map
        bool receives = true; // looks the shadow map up (false where no shadow can fall)
        bool shadow_clip = false;  // looks it up only within the frame's shadow rectangle (the ground)
        float specular = 0;
        int texture = -1;     // the texture it samples (textures_), -1: none
        bool interior = false;  // `texture` is the interior texture, projected (fracture faces)
        Vec3 rest_offset = Vec3::Zero();  // interior: the piece's centre in the unbroken object
    };
    void add_static_items();
    Eigen::Matrix4f model_matrix(const Item& item, uint32_t frame) const;
    void shadow_pass(uint32_t frame);
    // Draws the items (all, or only those that fade) into the bound framebuffer, within `rect`.
    void scene_pass(uint32_t frame, const PixelRect& rect, bool fading_only);
    // Where this frame's edges are: the screen rectangle of every item that does not fade.
    PixelRect edge_rect(uint32_t frame) const;
    // Where this frame's shadows can fall on the ground, on the screen: the casters' boxes carried
    // along the light onto the ground plane, padded for the lookups' filter and normal offset.
    PixelRect shadow_rect(uint32_t frame) const;
    // Draws a shadow_clip item: with lookups within shadow_rect_, without them around it.
    void draw_shadow_clipped(const Item& item, const PixelRect& rect);
    static int variant(const Item& item) {
        return (item.specular > 0 ? 1 : 0) | (item.fade ? 2 : 0) | (item.receives ? 0 : 4) |
               (item.texture >= 0 && !item.interior ? 8 : 0) | (item.interior ? 16 : 0);
    }
    void add_ground(const Vec3& origin, double extent);
    // [render] interior_texture decoded into textures_ (Error(BadInput) naming the file when it
    // cannot be), and its repeat.
    void load_interior_texture();
    // Piece `i`'s items: one per texture its triangles sample (untextured first).
    void add_piece(uint32_t i);
    void set_scene_uniforms(const GlProgram& p) const;
    void set_camera_uniforms(const GlProgram& p, const Camera& c) const;

    const RenderScene& scene_;
    RenderSettings settings_;
    MsaaRegion region_;
    Eigen::AlignedBox3d bounds_;
    std::vector<Camera> cameras_;  // one per frame, or one for all
    Lights lights_;
    std::vector<Item> items_;
    double ground_y_ = 0;        // the ground's height, when a shadow_clip item is drawn
    PixelRect shadow_rect_;      // this frame's shadow_rect
    RenderTarget target_;
    std::unique_ptr<ShadowMap> shadow_map_;
    std::vector<MaterialLook> looks_;                   // the model's materials (colours = "input"), else empty
    std::vector<std::unique_ptr<GpuTexture>> textures_;  // their decoded textures, then the interior texture
    int interior_texture_ = -1;  // its place in textures_, -1: none
    float interior_repeat_ = 0;  // its repeats per metre
    std::array<GlProgram, 32> scene_programs_;  // by variant(): highlight, fade, no shadow lookups, texture, interior (built for the items present)
    GlProgram shadow_program_;
    FrameTimes times_;
};

}  // namespace shatter
