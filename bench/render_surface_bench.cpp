// Render surfaces on a real mesh: prescore time (without them), the cut's time, fallbacks, and
// how closely the pieces' render surfaces follow the surface the tets were made from (the input,
// or its wrap when prescore wrapped it; prescore/surface_agreement.h), unsimplified. The cut time
// includes the simplification, as in prescore. Prints one CSV row.
//   render_surface_bench MESH [scale 0: automatic] [pieces 10] [resolution 20] [hollow 0: solid]
//                        [margin, in tet sizes 0.15] [most surface triangles cut: kRenderSurfaceTriangles, 0: all]
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <spdlog/spdlog.h>

#include "core/error.h"
#include "prescore/prescore.h"
#include "prescore/render_surface.h"
#include "prescore/surface_agreement.h"

using namespace shatter;

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: render_surface_bench MESH [scale] [pieces] [resolution] [hollow] [margin]\n");
        return 2;
    }
    auto arg = [&](int i, double fallback) { return argc > i ? std::atof(argv[i]) : fallback; };
    MeshSettings mesh;
    mesh.path = argv[1];
    if (arg(2, 0) > 0) mesh.scale = arg(2, 0);
    PrescoreSettings settings;
    settings.pieces = static_cast<uint32_t>(arg(3, 10));
    settings.resolution = arg(4, 20);
    if (arg(5, 0) > 0) settings.hollow = Length{arg(5, 0), true};
    const double margin_tets = arg(6, kRenderSurfaceMargin);
    const size_t max_triangles = argc > 7 && arg(7, 0) > 0 ? size_t(arg(7, 0)) : argc > 7 ? SIZE_MAX : kRenderSurfaceTriangles;
    if (std::getenv("SHATTER_DEBUG")) spdlog::set_level(spdlog::level::debug);
    try {
        using Clock = std::chrono::steady_clock;
        // prescore without its render surfaces (timed), then the cut as prescore makes it, from
        // the surface the tets were made from (the input, its wrap or its thickened wrap).
        settings.render_surface = false;
        auto t0 = Clock::now();
        PrescoreReport report;
        const Model model = prescore(mesh, settings, &report);
        auto t1 = Clock::now();
        const TriangleMesh& input = report.surface;
        const double diagonal = report.input.diagonal;
        RenderSurfaceSettings rs;
        rs.margin = margin_tets * diagonal / report.resolution;
        auto t2 = Clock::now();
        // As prescore: a surface too large for CGAL's simplification is reduced first.
        const std::optional<TriangleMesh> first = first_reduction(input);
        const TriangleMesh& reduced = first ? *first : input;
        const TriangleMesh simplified = simplify_surface(reduced, max_triangles);
        auto t_simplified = Clock::now();
        const std::vector<RenderSurface> surfaces = render_surfaces(
            simplified, model, rs, simplified.triangles.size() < reduced.triangles.size() ? &reduced : nullptr);
        auto t3 = Clock::now();
        size_t fell_back = 0, triangles = 0, tet_triangles = 0;
        for (const RenderSurface& s : surfaces) fell_back += s.fell_back, triangles += s.triangles.size();
        for (const Piece& p : model.pieces) tet_triangles += p.surface.triangles.size();
        std::vector<RenderSurface> tet;
        for (const Piece& p : model.pieces) tet.push_back(flat_render_surface(p.surface));
        const SurfaceAgreement before = surface_agreement(input, tet, rs.crease_degrees, 10);
        const SurfaceAgreement after = surface_agreement(input, surfaces, rs.crease_degrees, 10);
        auto s = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
        std::printf("mesh,input_triangles,wrapped,tets,pieces,prescore_s,render_surface_s,fell_back,tet_triangles,"
                    "render_triangles,simplify_s,tet_p99_pct,tet_max_pct,tet_normals_within_10deg,p99_pct,max_pct,"
                    "normals_within_10deg,smooth_samples\n");
        std::printf("%s,%zu,%d,%zu,%zu,%.2f,%.2f,%zu,%zu,%zu,%.2f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%zu\n", argv[1],
                    input.triangles.size(), int(report.repaired), model.mesh.tets.size(), model.pieces.size(),
                    s(t0, t1), s(t2, t3), fell_back, tet_triangles, triangles, s(t2, t_simplified), 100 * before.distance_p99 / diagonal,
                    100 * before.distance_max / diagonal, before.normals_within, 100 * after.distance_p99 / diagonal,
                    100 * after.distance_max / diagonal, after.normals_within, after.smooth_samples);
    } catch (const Error& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }
    return 0;
}
