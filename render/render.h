// The render stage: draws every frame of a simulation to PNG with OpenGL 4.5 core on OSMesa
// (llvmpipe, CPU only), and compares images (`shatter diff`). docs/render.md has the design.
//
//   load model + trajectory ──► RenderScene (scene from the trajectory's settings, checked)
//        ──► FrameRenderer per frame: shadow pass ─► scene pass (4x MSAA, linear light
//                                     encoded by GL into sRGB8) ─► resolve ─► RGBA8 readback
//        ──► FrameWriter thread: row flip, PNG encode (zlib 1, SUB, RLE) ─► FRAMES/frame_NNNNN.png
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/geometry.h"
#include "core/model.h"
#include "core/render_settings.h"
#include "core/scene_settings.h"
#include "core/trajectory.h"
#include "render/frame_writer.h"

namespace shatter {

// Everything a frame is drawn from. `model` and `trajectory` are borrowed.
struct RenderScene {
    const Model* model = nullptr;
    const Trajectory* trajectory = nullptr;
    SceneSettings scene;                      // colliders, kinematic bodies, ground
    std::vector<TriangleMesh> collider_meshes;  // per collider: its triangles when a mesh collider, else empty
};

// The scene of a trajectory (its settings JSON key "scene"; the default scene when absent),
// checked against the model: same piece count, same model file (when the trajectory names its
// hash), one prop per kinematic body. Mesh colliders are loaded. Throws Error(BadInput) naming
// the files and the fix.
RenderScene make_render_scene(const Model& model, const std::string& model_path, const Trajectory& trajectory,
                              const std::string& trajectory_path);

// Checks the settings against what the GL context allows; `where` names the source of the size
// ("--size" or "shot.toml:[render]"). Throws Error(Usage).
void check_render_limits(const RenderSettings& s, int max_image_size, int max_samples, const std::string& where);

struct FrameRange {
    uint32_t first = 0;  // first frame rendered
    uint32_t end = 0;    // one past the last
};

struct RenderReport {
    uint32_t frames = 0;
    uint32_t repeated = 0;       // of them, the same picture as the frame before: its PNG written again
    double seconds = 0;          // wall time of the whole loop (unit: s)
    double draw_seconds = 0;     // submitting and rasterizing (main thread; unit: s)
    double readback_seconds = 0; // glReadPixels (unit: s)
    double filter_seconds = 0;   // the edge filter (main thread; unit: s)
    double encode_seconds = 0;   // PNG encoding (writer thread; unit: s)
    double write_seconds = 0;    // atomic file writes (writer thread; unit: s)
    std::string renderer;        // GL_RENDERER
};

// Where MSAA samples are taken: only around the edges (the default; render/frame_renderer.h), or
// over the whole frame (the same image within a level, slower; for the benchmark and the test
// that compares the two).
enum class MsaaRegion { Edges, Everywhere };

struct RenderOptions {
    bool progress = true;  // a progress bar on stderr
    bool overlap = true;   // encode PNGs on a second thread while the next frame renders
    std::string size_source = "--size";  // where the image size came from, for error messages
    // Frames whose file exists are not drawn again (a resumed run: every frame file was written
    // atomically, and a frame's bytes do not depend on which run drew it).
    bool skip_existing = false;
    MsaaRegion msaa_region = MsaaRegion::Edges;
    // Each frame's sRGB RGB bytes (top row first), drawn or repeated, before its file is written:
    // on the writer's thread, frames in order (what `shatter run` hands ffmpeg without a PNG).
    FramePixelsSink on_pixels;
};

// The file name of frame f: frame_00012.png (five digits, more when f >= 100000).
std::string frame_file_name(uint32_t frame);

// Renders frames [range.first, range.end) to `out_dir`/frame_NNNNN.png (each written atomically;
// the directory is created). A frame's bytes do not depend on the range or the thread count.
RenderReport render_frames(const RenderScene& scene, const RenderSettings& settings, FrameRange range,
                           const std::string& out_dir, const RenderOptions& options = {});

}  // namespace shatter
