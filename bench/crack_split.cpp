// Where a model's crack creases are: its faired cells (crack_fairing.h, placed at the tet
// vertices, before the cut by the input surface) measured as crack_creases does, the creases split
// into those within one interface (both triangles facing the same other piece) and those where
// two of a piece's interfaces meet, and per piece. Prints a CSV row per piece (with its junction
// edges' length, patches and neighbours after it) and one for all, then the cells' volume over
// their tets' and the length of the within-interface edges by bend, in 10-degree bins (both in
// density units). docs/log.md has what it found.
//
//   crack_split [--split] MODEL...   (a .model file as it is; --split: the crack tets split, as
//                                    `crack_split = true` makes them)
//   crack_split --make OUT.model SHOT_OR_MESH   (prescored as crack_look does, render surfaces off)
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "core/error.h"
#include "core/log.h"
#include "core/model_io.h"
#include "core/shot.h"
#include "prescore/prescore.h"
#include "prescore/crack_creases.h"
#include "prescore/crack_fairing.h"
#include "prescore/render_surface.h"

using namespace shatter;

int main(int argc, char** argv) {
    setup_logging("warn");
    if (argc >= 3 && std::string(argv[1]) == "--surfaces") {  // the render surfaces' creases per piece
        for (int a = 2; a < argc; ++a) {
            const Model model = load_model(argv[a]);
            Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
            for (const Vec3& v : model.mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
            std::vector<RenderSurface> all;
            for (size_t p = 0; p < model.pieces.size(); ++p) {
                if (!model.pieces[p].render) continue;
                all.push_back(*model.pieces[p].render);
                const CrackCreases c = crack_creases({*model.pieces[p].render}, (hi - lo).norm());
                std::printf("%s,%zu,%.4g,%.2f,%zu triangles\n", argv[a], p, c.area, c.density, model.pieces[p].render->triangles.size());
            }
            const CrackCreases c = crack_creases(all, (hi - lo).norm());
            std::printf("%s,all,%.4g,%.2f\n", argv[a], c.area, c.density);
        }
        return 0;
    }
    if (argc == 4 && std::string(argv[1]) == "--make") {
        Shot shot = load_shot_or_mesh(argv[3]);
        shot.prescore.render_surface = false;
        PrescoreReport report;
        save_model(argv[2], prescore_shot(shot, &report));
        return 0;
    }
    std::printf("model,piece,tets,area,within,junction,density\n");
    const bool split = argc > 1 && std::string(argv[1]) == "--split";
    for (int a = split ? 2 : 1; a < argc; ++a) {
        try {
            const Model model = load_model(argv[a]);
            const auto t0 = std::chrono::steady_clock::now();
            const std::optional<CrackCells> cells = faired_crack_cells(model, split);
            const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            if (!cells) {
                std::printf("%s,none\n", argv[a]);
                continue;
            }
            const std::vector<Vec3> x = cells->place(model.mesh.vertices);
            Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
            for (const Vec3& v : model.mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
            const double diagonal = (hi - lo).norm();
            const double cos_limit = std::cos(30 * M_PI / 180);
            std::vector<size_t> tets(cells->triangles.size(), 0);
            for (uint32_t p : model.tet_piece) ++tets[p];
            double area_all = 0, within_all = 0, junction_all = 0;
            double least = 1e9, most = 0, tiny_junction = 0;
            {
                std::vector<double> own(cells->triangles.size(), 0), cell(cells->triangles.size(), 0);
                for (size_t t = 0; t < model.mesh.tets.size(); ++t) {
                    const Tet& k = model.mesh.tets[t];
                    own[model.tet_piece[t]] += tet_volume(model.mesh.vertices[k[0]], model.mesh.vertices[k[1]], model.mesh.vertices[k[2]], model.mesh.vertices[k[3]]);
                }
                for (size_t p = 0; p < cells->triangles.size(); ++p) {
                    for (const Tri& t : cells->triangles[p]) cell[p] += x[t[0]].dot(x[t[1]].cross(x[t[2]])) / 6;
                    least = std::min(least, cell[p] / own[p]), most = std::max(most, cell[p] / own[p]);
                }
            }
            std::array<double, 18> hist{};
            for (size_t p = 0; p < cells->triangles.size(); ++p) {
                double area = 0, within = 0, junction = 0;
                std::map<std::pair<uint32_t, uint32_t>, std::vector<size_t>> edges;
                std::vector<Vec3> normal(cells->triangles[p].size(), Vec3::Zero());
                for (size_t t = 0; t < cells->triangles[p].size(); ++t) {
                    if (cells->kinds[p][t] != FaceKind::Fracture) continue;
                    const Tri& tri = cells->triangles[p][t];
                    const Vec3 n = (x[tri[1]] - x[tri[0]]).cross(x[tri[2]] - x[tri[0]]);
                    area += n.norm() / 2;
                    if (n.norm() > 2e-12 * diagonal * diagonal) normal[t] = n.normalized();
                    for (int k = 0; k < 3; ++k) edges[std::minmax(tri[k], tri[(k + 1) % 3])].push_back(t);
                }
                for (const auto& [e, f] : edges) {
                    if (f.size() != 2 || normal[f[0]].isZero() || normal[f[1]].isZero()) continue;
                    if (cells->across[p][f[0]] == cells->across[p][f[1]]) {
                        const double deg = std::acos(std::clamp(normal[f[0]].dot(normal[f[1]]), -1.0, 1.0)) * 180 / M_PI;
                        hist[std::min(int(deg / 10), 17)] += (x[e.first] - x[e.second]).norm();
                    }
                    if (normal[f[0]].dot(normal[f[1]]) >= cos_limit) continue;
                    const double l = (x[e.first] - x[e.second]).norm();
                    (cells->across[p][f[0]] == cells->across[p][f[1]] ? within : junction) += l;
                }
                // Patches: crack triangles of one `across` joined by shared edges.
                std::vector<size_t> parent(cells->triangles[p].size());
                for (size_t i = 0; i < parent.size(); ++i) parent[i] = i;
                const auto root = [&](size_t i) { while (parent[i] != i) i = parent[i] = parent[parent[i]]; return i; };
                double jlen = 0;
                for (const auto& [e, f] : edges) {
                    if (f.size() != 2) continue;
                    if (cells->across[p][f[0]] == cells->across[p][f[1]]) parent[root(f[0])] = root(f[1]);
                    else jlen += (x[e.first] - x[e.second]).norm();
                }
                std::map<size_t, double> patch;
                std::map<uint32_t, int> patches_of;
                for (size_t t = 0; t < parent.size(); ++t) {
                    if (cells->kinds[p][t] != FaceKind::Fracture) continue;
                    const Tri& tri = cells->triangles[p][t];
                    auto [it, fresh] = patch.emplace(root(t), 0.0);
                    if (fresh) ++patches_of[cells->across[p][t]];
                    it->second += (x[tri[1]] - x[tri[0]]).cross(x[tri[2]] - x[tri[0]]).norm() / 2;
                }
                size_t tiny = 0;
                for (const auto& [r, ar] : patch) tiny += ar < 0.02 * area;
                for (const auto& [e, f] : edges) {
                    if (f.size() != 2 || cells->across[p][f[0]] == cells->across[p][f[1]]) continue;
                    if (patch[root(f[0])] < 0.05 * area || patch[root(f[1])] < 0.05 * area) tiny_junction += (x[e.first] - x[e.second]).norm();
                }
                std::printf("%s,%zu,%zu,%.4g,%.2f,%.2f,%.2f  junction edges %.2f, %zu patches (%zu under 2%%), neighbours %zu\n", argv[a], p, tets[p], area, within / area * diagonal,
                            junction / area * diagonal, (within + junction) / area * diagonal, jlen / area * diagonal, patch.size(), tiny, patches_of.size());
                area_all += area, within_all += within, junction_all += junction;
            }
            std::printf("%s,all,%zu,%.4g,%.2f,%.2f,%.2f  (%.3f s, %zu points, %zu held, %zu open, %zu degenerate, %zu split)\n",
                        argv[a], model.tet_piece.size(), area_all, within_all / area_all * diagonal,
                        junction_all / area_all * diagonal, (within_all + junction_all) / area_all * diagonal, secs,
                        cells->points.size(), cells->held, cells->open, cells->degenerate, cells->split_tets);
            std::printf("cell volume / tet volume %.3f to %.3f; junction edges beside patches under 5%% of their piece's crack %.2f\n", least, most, tiny_junction / area_all * diagonal);
            std::printf("within-interface edge length by angle (10-degree bins, density units):");
            for (double h : hist) std::printf(" %.2f", h / area_all * diagonal);
            std::printf("\n");
        } catch (const Error& e) {
            std::fprintf(stderr, "crack_split: %s\n", e.what());
            return 1;
        }
    }
    return 0;
}
