// The cracks before and after fairing, side by side: a shot or a mesh (with the default shot) is
// prescored three times, `crack_fairing = false` (the tet faces between the pieces), the default
// (faired) and with `crack_split = true` (faired on the crack tets split), and each is drawn at
// the same frame of the render benchmark's synthetic trajectory (the pieces flown apart and
// turned, so that their crack faces show), at 960x540 with the defaults' look. Writes OUT.png
// (left to right in that order) and prints one CSV row per variant with the crack faces' crease
// density (prescore/crack_creases.h). `make refresh` runs it for
// docs/render.md's images.
//
//   crack_look OUT.png SHOT_OR_MESH [FRAME]   (FRAME of 60, default 45)
#include <cstdio>
#include <filesystem>
#include <string>

#include "core/error.h"
#include "core/log.h"
#include "core/shot.h"
#include "prescore/crack_creases.h"
#include "prescore/prescore.h"
#include "render/png_io.h"
#include "render/render.h"
#include "scenes/render_test_scene.h"

using namespace shatter;

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: crack_look OUT.png SHOT_OR_MESH [FRAME]\n");
        return 2;
    }
    setup_logging("warn");  // standard output is the CSV
    const std::string out = argv[1];
    const uint32_t frames = 60, frame = argc > 3 ? uint32_t(std::stoul(argv[3])) : 45;
    try {
        const Shot shot = load_shot_or_mesh(argv[2]);
        const std::string work = out + ".tmp.d";
        std::filesystem::remove_all(work);
        Image side_by_side;
        std::printf("mesh,cracks,pieces,crack_area_m2,crease_density,crease_share\n");
        const char* const names[] = {"tet faces", "faired", "faired (crack_split)"};
        for (int look = 0; look < 3; ++look) {
            Shot variant = shot;
            variant.prescore.crack_fairing = look > 0;
            variant.prescore.crack_split = look == 2;
            PrescoreReport report;
            const Model model = prescore_shot(variant, &report);  // the shot's flight grades impact seeds
            std::vector<RenderSurface> surfaces;
            for (const Piece& p : model.pieces)
                if (p.render) surfaces.push_back(*p.render);
            const CrackCreases c = crack_creases(surfaces, report.input.diagonal);
            std::printf("%s,%s,%zu,%.5g,%.2f,%.3f\n", std::filesystem::path(shot.mesh.path).filename().c_str(),
                        names[look], model.pieces.size(), c.area, c.density, c.share);
            SceneSettings scene_settings;  // the ground only
            const Trajectory trajectory = testing_support::test_trajectory(model, scene_settings, frames);
            RenderScene scene;
            scene.model = &model;
            scene.trajectory = &trajectory;
            scene.scene = scene_settings;
            RenderSettings rs;
            rs.width = 960;
            rs.height = 540;
            RenderOptions options;
            options.progress = false;
            const std::string dir = work + "/" + std::to_string(look);
            render_frames(scene, rs, {frame, frame + 1}, dir, options);
            const Image image = load_png(dir + "/" + frame_file_name(frame));
            if (side_by_side.width == 0) side_by_side = Image(3 * image.width, image.height);
            for (uint32_t y = 0; y < image.height; ++y)
                for (uint32_t x = 0; x < image.width; ++x) {
                    const uint8_t* from = image.pixel(x, y);
                    uint8_t* to = side_by_side.pixel(x + uint32_t(look) * image.width, y);
                    to[0] = from[0], to[1] = from[1], to[2] = from[2];
                }
        }
        save_png(out, side_by_side);
        std::filesystem::remove_all(work);
    } catch (const Error& e) {
        std::fprintf(stderr, "crack_look: %s\n", e.what());
        return 1;
    }
    return 0;
}
