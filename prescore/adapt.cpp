// How prescore adapts to a mesh. Design notes: adapt.h.
#include "prescore/adapt.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <numeric>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "core/error.h"
#include "core/isolated.h"
#include "core/log.h"
#include "core/utf8.h"
#include "prescore/repair.h"
#include "prescore/tetrahedralize.h"

namespace shatter {

void AutoChoices::note(std::string what, std::string why) {
    spdlog::info("auto: {} ({})", what, why);
    list.push_back({std::move(what), std::move(why)});
}

void AutoChoices::warn(std::string text) {
    text = as_utf8(text);  // file and material names as files give them (core/utf8.h)
    if (!folder.empty())
        for (size_t at = text.find(folder); at != std::string::npos; at = text.find(folder, at)) text.erase(at, folder.size());
    warn_and_keep(warnings, std::move(text));
}

nlohmann::ordered_json AutoChoices::to_json() const {
    nlohmann::ordered_json j = nlohmann::ordered_json::array();
    for (const AutoChoice& c : list) j.push_back({{"what", c.what}, {"why", c.why}});
    return j;
}

double choose_scale(const TriangleMesh& mesh, double file_metres_per_unit, const MeshSettings& settings,
                    AutoChoices& choices) {
    Vec3 lo = Vec3::Constant(HUGE_VAL), hi = -lo;
    for (const Vec3& v : mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    const double longest = mesh.vertices.empty() ? 0 : (hi - lo).maxCoeff();
    if (settings.size) return longest > 0 ? *settings.size / longest : 1.0;
    if (settings.scale) return *settings.scale;
    if (file_metres_per_unit > 0) {
        const std::string hint = units_hint(longest * file_metres_per_unit);
        if (!hint.empty()) choices.warn(fmt::format("{}: {}", settings.path, hint));
        return file_metres_per_unit;
    }
    if (!(longest > 0)) return 1.0;  // flat or empty: refused later with the real reason
    const double scale = kDefaultSize / longest;
    choices.note(fmt::format("size {:g} m (scale {:.6g} m per unit)", kDefaultSize, scale),
                 fmt::format("the file has no units and the shot gives no size or scale; its longest side is {:.6g} "
                             "units (set [mesh] size or scale, --size or --scale)", longest));
    return scale;
}

std::string units_hint(double longest) {
    if (!(longest > kPlausibleLongest[1]) && !(longest < kPlausibleLongest[0])) return "";
    if (longest < kPlausibleLongest[0])
        return fmt::format("the mesh is {:.3g} m long by its file's units; if that is not meant, [mesh] size sets "
                           "its longest side, e.g. size = 0.3 (--size 0.3; with shatter run, --set mesh.size=0.3)",
                           longest);
    return fmt::format("the mesh is {:.4g} m long by its file's units, so it falls and breaks as slowly as a "
                       "building would; made in millimetres it would be {:.3g} m long ([mesh] scale = 0.001), in "
                       "centimetres {:.3g} m (scale = 0.01), in inches {:.3g} m (scale = 0.0254); or size = 0.3 "
                       "makes it 0.3 m (--scale 0.001, --size 0.3; with shatter run, --set mesh.scale=0.001)",
                       longest, longest * 1e-3, longest * 1e-2, longest * 0.0254);
}

namespace {

struct Loss {
    int32_t clusters = 0;
    double filled = 0;  // tets' volume / the surface's
    bool lost(size_t components) const { return size_t(clusters) > components || filled < kMinFilled; }
    std::string str(size_t components) const {
        return fmt::format("the tets fall apart into {} cluster(s) (the surface has {} component(s)) and fill {:.1f}% "
                           "of its volume", clusters, components, 100 * filled);
    }
};

Loss measure(const TetMesh& tets, const MeshCheck& surface) {
    Loss loss;
    if (tets.tets.empty()) return loss;
    tet_components(build_topology(tets), {}, &loss.clusters);
    double volume = 0;
    for (const Tet& t : tets.tets)
        volume += tet_volume(tets.vertices[t[0]], tets.vertices[t[1]], tets.vertices[t[2]], tets.vertices[t[3]]);
    loss.filled = surface.volume > 0 ? volume / surface.volume : 1.0;
    return loss;
}

std::string serialize(const TetMesh& m) {
    const uint64_t nv = m.vertices.size();
    std::string out("T");
    out.append(reinterpret_cast<const char*>(&nv), 8);
    for (const Vec3& v : m.vertices) out.append(reinterpret_cast<const char*>(v.data()), 24);
    out.append(reinterpret_cast<const char*>(m.tets.data()), m.tets.size() * sizeof(Tet));
    return out;
}

TetMesh deserialize(const std::string& bytes) {
    TetMesh m;
    uint64_t nv = 0;
    std::memcpy(&nv, bytes.data() + 1, 8);
    size_t at = 9;
    m.vertices.resize(nv);
    for (Vec3& v : m.vertices) std::memcpy(v.data(), bytes.data() + at, 24), at += 24;
    m.tets.resize((bytes.size() - at) / sizeof(Tet));
    std::memcpy(m.tets.data(), bytes.data() + at, m.tets.size() * sizeof(Tet));
    return m;
}

}  // namespace

double mesh_seconds(size_t surface_triangles) { return kMeshSeconds + kMeshSecondsPerTriangle * double(surface_triangles); }

namespace {

// Mesh_3's settings for a first attempt at one resolution.
TetrahedralizeSettings first_settings(double diagonal, double resolution, bool wrapped) {
    TetrahedralizeSettings ts = tetrahedralize_settings_for(diagonal, resolution);
    ts.max_vertices = kMaxMeshVertices;
    // An alpha wrap's creases are the wrap's own facets meeting, not the object's edges; protecting
    // them is where Mesh_3 crashed or stalled (lion.off, blobby_3cc.off of CGAL's data set).
    ts.protect_features = !wrapped;
    return ts;
}

// One Mesh_3 call's bytes: its tets, "B" when it hit the vertex budget, "0" when it made none.
std::function<std::string()> tet_work(const TriangleMesh& surface, const TetrahedralizeSettings& ts) {
    return [&surface, ts]() -> std::string {
        try {
            return serialize(tetrahedralize(surface, ts));
        } catch (const TetBudgetReached&) {
            return "B";
        } catch (const Error& e) {
            if (std::string(e.what()).find("made no tets") == std::string::npos) throw;
            return "0";
        }
    };
}

// Mesh_3 at one resolution, in a child process (core/isolated.h): an empty mesh when it made
// no tets, nullopt when it hit its vertex budget, ran past mesh_seconds, or crashed twice (the
// second time without protected sharp creases, where its crashes were seen: elk.off). `early`:
// the first attempt, begun already.
std::optional<TetMesh> try_tetrahedralize(const TriangleMesh& surface, bool wrapped, double diagonal,
                                          double resolution, EarlyTets* early = nullptr) {
    TetrahedralizeSettings ts = first_settings(diagonal, resolution, wrapped);
    for (int attempt = 0; attempt < 2; ++attempt, ts.protect_features = false) {
        std::string bytes;
        try {
            bytes = attempt == 0 && early ? early->finish()
                                          : run_isolated(tet_work(surface, ts), mesh_seconds(surface.triangles.size()));
        } catch (const IsolatedFailure& f) {
            spdlog::info("tetrahedralize: Mesh_3 {} at resolution {:g}{}", f.timed_out ? "did not finish" : "crashed",
                         resolution, f.timed_out ? "" : fmt::format(" ({})", f.what()));
            if (f.timed_out) return std::nullopt;
            continue;
        }
        if (bytes == "B") return std::nullopt;
        if (bytes == "0") return TetMesh{};
        return deserialize(bytes);
    }
    return std::nullopt;
}

}  // namespace

EarlyTets::EarlyTets(const TriangleMesh& surface, double diagonal, double resolution)
    : resolution_(resolution),
      run_(std::make_unique<IsolatedRun>(tet_work(surface, first_settings(diagonal, resolution, false)),
                                         mesh_seconds(surface.triangles.size()))) {}

EarlyTets::~EarlyTets() = default;

std::string EarlyTets::finish() { return run_->finish(); }

FittedTets fit_tets(const TriangleMesh& input, TriangleMesh surface, const MeshCheck& surface_check, bool wrapped,
                    double diagonal, const MeshSettings& mesh, const PrescoreSettings& settings,
                    const std::string& path, AutoChoices& choices, EarlyTets* early) {
    FittedTets fit{{}, std::move(surface), surface_check, settings.resolution, wrapped};
    const auto wrap = [&](double offset) {
        fit.surface = alpha_wrap(input, mesh.wrap_alpha * diagonal, offset);
        fit.surface_check = check_mesh(fit.surface, false);
        fit.wrapped = true;
    };
    const auto budget_why = [&](double r) {
        return fmt::format("Mesh_3 did not finish within its budget ({} vertices, {:.3g} s) at resolution {:g} on a "
                           "surface of {} triangles", kMaxMeshVertices, mesh_seconds(fit.surface.triangles.size()), r,
                           fit.surface_check.triangles);
    };
    const auto refuse_budget = [&](double r) {
        throw_input_error(path, budget_why(r) + fmt::format(" (the mesh's bounding-box diagonal is {:.4g} m)", diagonal),
                          "lower --resolution, or repair the mesh with --repair always");
    };

    // 1. The asked resolution; a surface whose meshing does not end is wrapped first.
    if (early && (fit.wrapped || early->resolution() != fit.resolution)) early = nullptr;
    std::optional<TetMesh> tets = try_tetrahedralize(fit.surface, fit.wrapped, diagonal, fit.resolution, early);
    if (!tets && !fit.wrapped && mesh.repair != RepairMode::Never) {
        choices.note("repair: alpha wrap", budget_why(fit.resolution));
        wrap(mesh.wrap_offset * diagonal);
        tets = try_tetrahedralize(fit.surface, fit.wrapped, diagonal, fit.resolution);
    }
    if (!tets && !mesh.adapt) refuse_budget(fit.resolution);
    Loss loss;
    std::string lost_why = budget_why(fit.resolution);
    if (tets) {
        loss = measure(*tets, fit.surface_check);
        lost_why = loss.str(fit.surface_check.components) + fmt::format(" at resolution {:g}", fit.resolution);
    }
    if (tets && !loss.lost(fit.surface_check.components)) {
        fit.tets = std::move(*tets);
        return fit;
    }
    if (!mesh.adapt) {
        if (tets->tets.empty())
            throw_input_error(path, fmt::format("Mesh_3 made no tets at resolution {:g}: the mesh is thinner than a "
                                                "tet", fit.resolution), "raise --resolution, or leave adapt on");
        if (size_t(loss.clusters) > fit.surface_check.components)
            throw_input_error(path, loss.str(fit.surface_check.components) + ": parts of it are thinner than a tet",
                              "raise --resolution so that tets fit in the thin parts, or leave adapt on");
        fit.tets = std::move(*tets);
        return fit;
    }

    // 2. Thin parts here and there (most of the volume is filled): a finer resolution, twice at
    // most, while the estimate stays within the tet budget.
    for (int raise = 0; raise < 2 && tets && loss.filled >= 0.5; ++raise) {
        const double next = fit.resolution * kResolutionStep;
        const double estimate = double(std::max<size_t>(tets->tets.size(), 1)) * std::pow(kResolutionStep, 3);
        if (next > kResolutionLimits.max || estimate > double(kTetBudget)) break;
        std::optional<TetMesh> finer = try_tetrahedralize(fit.surface, fit.wrapped, diagonal, next);
        if (!finer) break;
        choices.note(fmt::format("resolution {:g} -> {:g}", fit.resolution, next), loss.str(fit.surface_check.components));
        fit.resolution = next;
        tets = std::move(finer);
        loss = measure(*tets, fit.surface_check);
        lost_why = loss.str(fit.surface_check.components) + fmt::format(" at resolution {:g}", fit.resolution);
        if (!loss.lost(fit.surface_check.components)) {
            fit.tets = std::move(*tets);
            return fit;
        }
    }

    // 3. Thin everywhere, or thinner than the budget reaches: give the walls a thickness, at
    // twice the asked resolution (or the resolution reached, if finer), thicker and coarser if that
    // meshing exceeds the budget or makes no tets (a thin flat frame around a hole, CGAL's
    // triangular_hole.off, given 14 mm made none at resolution 40, given 22 mm at 25 it did).
    double r = std::max(fit.resolution, 2 * settings.resolution);
    std::string why = lost_why;
    for (int attempt = 0; attempt < 3; ++attempt) {
        if (attempt > 0) r /= kResolutionStep;
        const double offset = kThickenOffset * diagonal / r;
        choices.note(fmt::format("thicken: alpha wrap with offset {:.4g} m ({:g} of a tet) at resolution {:g}", offset,
                                 kThickenOffset, r),
                     why);
        wrap(offset);
        tets = try_tetrahedralize(fit.surface, fit.wrapped, diagonal, r);
        if (tets && !tets->tets.empty()) break;
        why = tets ? fmt::format("Mesh_3 made no tets at resolution {:g}", r) : budget_why(r);
    }
    if (!tets) refuse_budget(r);
    if (tets->tets.empty())
        throw_input_error(path, fmt::format("Mesh_3 made no tets even after thickening the mesh (diagonal {:.4g} m, "
                                            "resolution {:g})", diagonal, r),
                          "give a solid mesh, or raise --resolution");
    fit.resolution = r;
    fit.thickened = true;
    fit.tets = std::move(*tets);  // what is still apart becomes slivers or bodies (partition_adapted)
    return fit;
}

Partition partition_adapted(const TetMesh& mesh, const TetTopology& topology, uint32_t pieces, uint64_t seed,
                            bool adapt, AutoChoices& choices, const std::vector<double>& density) {
    int32_t count = 0;
    const std::vector<int32_t> cluster = tet_components(topology, {}, &count);
    std::vector<double> volume(size_t(count), 0.0);
    double total = 0;
    for (uint32_t t = 0; t < mesh.tets.size(); ++t) {
        const Tet& k = mesh.tets[t];
        const double v = tet_volume(mesh.vertices[k[0]], mesh.vertices[k[1]], mesh.vertices[k[2]], mesh.vertices[k[3]]);
        volume[size_t(cluster[t])] += v;
        total += v;
    }
    std::vector<char> large(size_t(count), 1);
    int32_t large_count = count;
    const double largest = count > 0 ? *std::max_element(volume.begin(), volume.end()) : 0.0;
    if (adapt)
        for (int32_t c = 0; c < count; ++c)
            if (volume[size_t(c)] < kSliverFraction * total && volume[size_t(c)] < kSliverOfLargest * largest)
                large[size_t(c)] = 0, --large_count;
    size_t capped = 0;  // large clusters past kMaxBodies, made slivers
    if (adapt && large_count > int32_t(kMaxBodies)) {
        // The largest kMaxBodies stay (ties: the first cluster).
        std::vector<int32_t> order;
        for (int32_t c = 0; c < count; ++c)
            if (large[size_t(c)]) order.push_back(c);
        std::stable_sort(order.begin(), order.end(),
                         [&](int32_t a, int32_t b) { return volume[size_t(a)] > volume[size_t(b)]; });
        for (size_t i = kMaxBodies; i < order.size(); ++i) large[size_t(order[i])] = 0, ++capped;
        large_count = int32_t(kMaxBodies);
    }
    if (adapt && uint32_t(large_count) > pieces) {
        choices.note(fmt::format("pieces {} -> {}", pieces, large_count),
                     fmt::format("the tets form {} separate bodies of at least {:g}% of the volume or {:g}% of the "
                                 "largest body's each{}; each needs a piece",
                                 large_count, 100 * kSliverFraction, 100 * kSliverOfLargest,
                                 capped > 0 ? fmt::format(" (the largest {} of {})", kMaxBodies, large_count + int32_t(capped)) : ""));
        pieces = uint32_t(large_count);
    }
    if (large_count == count) return partition(mesh, topology, pieces, seed, density);

    // Partition the large clusters alone.
    TetMesh kept;
    kept.vertices = mesh.vertices;
    std::vector<uint32_t> kept_index;
    std::vector<uint32_t> sliver_tets;
    std::vector<double> kept_density;
    for (uint32_t t = 0; t < mesh.tets.size(); ++t) {
        if (large[size_t(cluster[t])]) {
            kept_index.push_back(t);
            kept.tets.push_back(mesh.tets[t]);
            if (!density.empty()) kept_density.push_back(density[t]);
        } else {
            sliver_tets.push_back(t);
        }
    }
    const Partition inner = partition(kept, build_topology(kept), pieces, seed, kept_density);
    Partition out;
    out.tet_piece.assign(mesh.tets.size(), 0);
    for (size_t i = 0; i < kept_index.size(); ++i) out.tet_piece[kept_index[i]] = inner.tet_piece[i];
    // Each small cluster goes whole to the piece of the large tet nearest its centroid.
    std::vector<Vec3> cluster_centroid(size_t(count), Vec3::Zero());
    std::vector<double> cluster_tets(size_t(count), 0.0);
    for (uint32_t t : sliver_tets) {
        cluster_centroid[size_t(cluster[t])] += tet_centroid(mesh, t);
        cluster_tets[size_t(cluster[t])] += 1;
    }
    std::vector<uint32_t> cluster_piece(size_t(count), 0);
    for (int32_t c = 0; c < count; ++c) {
        if (large[size_t(c)]) continue;
        const Vec3 at = cluster_centroid[size_t(c)] / cluster_tets[size_t(c)];
        double best = std::numeric_limits<double>::infinity();
        for (size_t i = 0; i < kept_index.size(); ++i) {
            const double d = (tet_centroid(mesh, kept_index[i]) - at).squaredNorm();
            if (d < best) best = d, cluster_piece[size_t(c)] = inner.tet_piece[i];
        }
    }
    for (uint32_t t : sliver_tets) out.tet_piece[t] = cluster_piece[size_t(cluster[t])];
    for (uint32_t s : inner.seeds) out.seeds.push_back(kept_index[s]);
    out.piece_tets.assign(pieces, 0);
    for (uint32_t p : out.tet_piece) ++out.piece_tets[p];
    double sliver_volume = 0;
    for (int32_t c = 0; c < count; ++c)
        if (!large[size_t(c)]) sliver_volume += volume[size_t(c)];
    if (capped > 0)
        choices.note(fmt::format("slivers: {} of {} separate bodies ({} tets, {:.2f}% of the volume) joined their nearest "
                                 "pieces", count - large_count, count, sliver_tets.size(), 100 * sliver_volume / total),
                     fmt::format("{} of them are pieces, the most prescore makes by itself: the largest; the {} "
                                 "smaller than them{} each move with the piece nearest to it (join the mesh's parts "
                                 "into fewer bodies for more)",
                                 kMaxBodies, capped,
                                 size_t(count - large_count) > capped ? " and the clusters too small to be pieces" : ""));
    else
        choices.note(fmt::format("slivers: {} small tet clusters ({} tets, {:.2f}% of the volume) joined their nearest "
                                 "pieces", count - large_count, sliver_tets.size(), 100 * sliver_volume / total),
                     fmt::format("each is under {:g}% of the volume and under {:g}% of the largest body's: too small "
                                 "to be a piece of its own",
                                 100 * kSliverFraction, 100 * kSliverOfLargest));
    return out;
}

}  // namespace shatter
