// What the follow camera (render/camera_path.h) shows on a finished run, without drawing it: the
// pieces in view, how large the main mass is on screen, the ground at the bottom, stillness at
// the end; with --frames, per frame (CSV). Usage:
//   camera_bench SHOT_OR_MESH OUT_DIR [--frames] [--set SECTION.KEY=VALUE ...]
// OUT_DIR is a `shatter run` output folder of that shot (its .model and .traj are read).
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "core/model_io.h"
#include "core/shot.h"
#include "core/trajectory.h"
#include "render/camera_path.h"
#include "render/render.h"

using namespace shatter;

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: camera_bench SHOT_OR_MESH OUT_DIR [--frames] [--set SECTION.KEY=VALUE ...]\n");
        return 2;
    }
    bool frames = false;
    std::vector<std::string> sets;
    for (int i = 3; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--frames") frames = true;
        else if (a == "--set" && i + 1 < argc) sets.push_back(argv[++i]);
    }
    const Shot shot = load_shot_or_mesh(argv[1], sets);
    std::string model_path, traj_path;
    for (const auto& e : std::filesystem::directory_iterator(argv[2])) {
        if (e.path().extension() == ".model") model_path = e.path().string();
        if (e.path().extension() == ".traj") traj_path = e.path().string();
    }
    if (model_path.empty() || traj_path.empty()) {
        std::fprintf(stderr, "%s: no .model or .traj\n", argv[2]);
        return 2;
    }
    const Model model = load_model(model_path);
    const Trajectory t = load_trajectory(traj_path);
    const RenderScene scene = make_render_scene(model, model_path, t, traj_path);
    const CameraCoverage c = camera_coverage(scene, shot.render);
    double total = 0;
    for (const Piece& p : model.pieces) total += p.mass.mass;
    if (frames) {
        const std::vector<Camera> cams = make_camera_path(scene, shot.render);
        std::printf("frame,in_view,fill,target_x,target_y,target_z,distance\n");
        for (uint32_t f = 0; f < t.frames(); ++f) {
            const Camera& cam = cams[cams.size() > 1 ? f : 0];
            std::printf("%u,%.3f,%.3f,%.6f,%.6f,%.6f,%.6f\n", f, c.in_view[f], c.fill[f], cam.target.x(),
                        cam.target.y(), cam.target.z(), (cam.position - cam.target).norm());
        }
        std::printf("piece,mass_share,radius,last_x,last_y,last_z\n");
        for (uint32_t i = 0; i < t.pieces; ++i) {
            const Eigen::Vector3f p = t.pose(t.frames() - 1, i).position;
            std::printf("%u,%.4f,%.3f,%.3f,%.3f,%.3f\n", i, model.pieces[i].mass.mass / total,
                        piece_radius(model.pieces[i]), p.x(), p.y(), p.z());
        }
    }
    std::printf("pieces %u, frames %u: in view first %.0f%%, least %.0f%% (frame %u); fill least %.0f%% (frame %u), "
                "median %.0f%%; %u frames without ground; %.2f s still at the end\n",
                t.pieces, t.frames(), 100 * c.first, 100 * c.least, c.least_frame, 100 * c.fill_least,
                c.fill_least_frame, 100 * c.fill_median, c.frames_without_ground, c.still_at_end);
    return 0;
}
