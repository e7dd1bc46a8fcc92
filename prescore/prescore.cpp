#include "prescore/prescore.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <exception>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string_view>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/atomic_file.h"
#include "core/binary_io.h"
#include "core/error.h"
#include "core/isolated.h"
#include "core/model_io.h"
#include "core/progress.h"
#include "core/stage_file.h"
#include "core/utf8.h"
#include "meshio/appearance.h"
#include "meshio/mesh_load.h"
#include "prescore/adapt.h"
#include "prescore/appearance_transfer.h"
#include "prescore/collision_parts.h"
#include "prescore/constraint_reduction.h"
#include "prescore/constraints.h"
#include "prescore/graded_seeds.h"
#include "prescore/hollow.h"
#include "prescore/mass_properties.h"
#include "prescore/partition.h"
#include "prescore/piece_surface.h"
#include "prescore/pieces_ply.h"
#include "prescore/render_surface.h"
#include "prescore/repair.h"
#include "prescore/seed_points.h"
#include "prescore/tet_topology.h"
#include "prescore/tetrahedralize.h"
#include "scenes/paper_scenes.h"

namespace shatter {

namespace {

// A mesh file larger than this is said to be read and checked, since both take a while (unit: bytes).
constexpr size_t kLargeMeshFileBytes = 50'000'000;

class PhaseTimer {
public:
    explicit PhaseTimer(PrescoreReport& report) : report_(report), start_(std::chrono::steady_clock::now()) {}
    void lap(const char* phase) {
        auto now = std::chrono::steady_clock::now();
        report_.phase_seconds.emplace_back(phase, std::chrono::duration<double>(now - start_).count());
        start_ = now;
    }

private:
    PrescoreReport& report_;
    std::chrono::steady_clock::time_point start_;
};

// Mesh_3's predicates underflow on a mesh far below a nanometre (a 1e-20 m cube crashed inside
// CGAL's refinement: found by tests/bad_inputs), and nothing this tool simulates is that small
// or beyond a million kilometres, so the size (after --scale) must lie within these bounds.
constexpr double kMinDiagonal = 1e-9, kMaxDiagonal = 1e9;  // (unit: m)
bool in_scale(double diagonal) { return diagonal >= kMinDiagonal && diagonal <= kMaxDiagonal; }
void refuse_out_of_scale(double diagonal, const std::string& path) {
    if (in_scale(diagonal)) return;
    throw_input_error(path,
                      fmt::format("the mesh's bounding-box diagonal is {:.4g} m, outside {:g} to {:g} m", diagonal,
                                  kMinDiagonal, kMaxDiagonal),
                      "set the mesh's size (--size or [mesh] size, the longest side in metres) or its scale");
}

// A mesh whose triangles are all degenerate (its points on a line or at one point) has no surface
// to give a thickness to.
bool without_area(const MeshCheck& c) { return c.diagonal > 0 && c.area <= 1e-12 * c.diagonal * c.diagonal; }
void refuse_without_area(const MeshCheck& c, const std::string& path) {
    if (without_area(c)) {
        const Vec3 extent = c.bbox_max - c.bbox_min;
        throw_input_error(path,
                          fmt::format("the mesh has no area: every triangle is degenerate (bounding box {:.4g} x {:.4g} x "
                                      "{:.4g} m)", extent.x(), extent.y(), extent.z()),
                          "give a mesh with a surface: a solid, or a sheet (which is given a thickness)");
    }
}

// The mesh Mesh_3 will see: the input when it can be tetrahedralized as it is, else its alpha
// wrap when the repair mode allows. The crossings are counted last (about 0.2 s on glmark2's
// bunny): when nothing but their count could send the input to the wrap, Mesh_3 begins on the
// surface it would then see, at `resolution`, beside the count (`early`, for fit_tets; reset when
// the input is wrapped after all).
TriangleMesh prepare_surface(const TriangleMesh& input, const MeshSettings& settings, double resolution,
                             PrescoreReport& report, std::unique_ptr<EarlyTets>& early) {
    report.input = check_mesh(input, false);
    TriangleMesh mesh = input;
    // Flipping every triangle changes nothing the check counts but the volume's sign.
    MeshCheck oriented = report.input;
    if (report.input.closed() && report.input.volume < 0 && orient_outward(mesh)) oriented.volume = -oriented.volume;
    if (settings.repair != RepairMode::Always && in_scale(report.input.diagonal) && !without_area(report.input) &&
        meshes_as_it_is(report.input, oriented, false, nullptr))
        early = std::make_unique<EarlyTets>(mesh, report.input.diagonal, resolution);
    report.input.self_intersections = oriented.self_intersections = count_self_intersections(input);
    spdlog::info("mesh: {}", describe(report.input));
    refuse_out_of_scale(report.input.diagonal, settings.path);
    refuse_without_area(report.input, settings.path);
    std::string why;
    // With repair "never", crossings are the user's to answer for: Mesh_3 is tried on them.
    const bool usable = meshes_as_it_is(report.input, oriented, settings.repair != RepairMode::Never, &why);
    if (settings.repair == RepairMode::Never && !usable)
        throw_input_error(settings.path, "the mesh cannot be tetrahedralized as it is: " + why,
                          "allow repair with --repair auto (alpha wrapping), or fix the mesh");
    if (settings.repair == RepairMode::Always || !usable) {
        const double d = report.input.diagonal;
        const std::string what =
            fmt::format("repair: alpha wrap (alpha {:.4g} m, offset {:.4g} m)", settings.wrap_alpha * d, settings.wrap_offset * d);
        if (usable)
            spdlog::info("{} (repair = \"always\")", what);
        else
            report.choices.note(what, why);
        early.reset();  // (killed: the wrap is meshed instead)
        mesh = alpha_wrap(mesh, settings.wrap_alpha * d, settings.wrap_offset * d);
        report.repaired = true;
    }
    report.tetrahedralized_from = report.repaired ? check_mesh(mesh, false) : report.input;
    if (report.repaired) {
        const double before = report.input.volume, after = report.tetrahedralized_from.volume;
        spdlog::info("repair: {} triangles, volume {:.6g} m^3 ({:+.2f}% of the input's {:.6g} m^3)",
                     report.tetrahedralized_from.triangles, after, before > 0 ? 100 * (after / before - 1) : 0.0,
                     before);
    }
    return mesh;
}

std::string settings_json(const MeshSettings& mesh, const PrescoreSettings& settings, uint64_t mesh_hash,
                          const AutoChoices& choices, const nlohmann::ordered_json& impact) {
    // The mesh is named by its file name and content hash, not its path: the same inputs give
    // the same bytes wherever they live (caching, pinned hashes).
    nlohmann::ordered_json j;
    j["mesh"] = to_json(mesh);
    j["mesh"]["path"] = as_utf8(std::filesystem::path(mesh.path).filename().string());
    j["mesh"]["fnv1a64"] = fmt::format("{:016x}", mesh_hash);
    j["prescore"] = to_json(settings);
    if (!choices.list.empty()) j["auto"] = choices.to_json();  // what prescore chose, and why
    if (!choices.warnings.empty()) j["warnings"] = choices.warnings;  // and what it warned of
    if (!impact.is_null()) j["impact"] = impact;  // seeds = "impact": where the object hits
    return j.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);  // (names are as_utf8's)
}

// Each piece's tets, surface and whether it is connected: what the render surfaces need.
void build_piece_shapes(Model& model, const TetTopology& topo, const std::vector<std::array<bool, 4>>* cavity) {
    const uint32_t n = static_cast<uint32_t>(model.pieces.size());
    for (uint32_t t = 0; t < model.tet_piece.size(); ++t) model.pieces[model.tet_piece[t]].tets.push_back(t);
    for (uint32_t p = 0; p < n; ++p) {
        Piece& piece = model.pieces[p];
        piece.surface = piece_surface(model.mesh, topo, model.tet_piece, p, cavity);
        std::vector<char> mask(model.mesh.tets.size(), 0);
        for (uint32_t t : piece.tets) mask[t] = 1;
        int32_t components = 0;
        tet_components(topo, mask, &components);
        piece.connected = components == 1;
    }
}

// Each piece's mass and collision parts (after build_piece_shapes).
void build_piece_bodies(Model& model, const PrescoreSettings& settings, double diagonal) {
    CollisionSettings cs;
    cs.max_gap = settings.collision_tolerance.resolve(diagonal);
    cs.max_parts = settings.collision_max_parts;
    Progress progress("pieces", model.pieces.size());
    for (Piece& piece : model.pieces) {
        piece.mass = mass_properties(model.mesh, piece.tets, settings.density);
        piece.collision = collision_parts(model.mesh, piece.tets, cs);
        progress.advance();
    }
}

std::string mesh_bytes(const TriangleMesh& mesh) {
    ByteWriter w;
    w.u32(uint32_t(mesh.vertices.size()));
    for (const Vec3& v : mesh.vertices) w.vec3(v);
    w.u32(uint32_t(mesh.triangles.size()));
    for (const Tri& t : mesh.triangles)
        for (uint32_t i : t) w.u32(i);
    return std::move(w.data());
}

TriangleMesh mesh_from_bytes(std::string_view bytes) {
    ByteReader r(bytes, "the simplified surface");
    TriangleMesh mesh;
    mesh.vertices.resize(r.count(24, "vertices"));
    for (Vec3& v : mesh.vertices) v = r.finite_vec3("vertex");
    mesh.triangles.resize(r.count(12, "triangles"));
    for (Tri& t : mesh.triangles)
        for (uint32_t& i : t) i = r.index(uint32_t(mesh.vertices.size()), "triangle corner");
    return mesh;
}

// The render surfaces' first half: the surface they are cut from, simplified for drawing. A
// surface too large for CGAL's simplification is first reduced by meshoptimizer's, here; CGAL's
// then runs in a child process (core/isolated.h: a crash or a run past the deadline leaves the
// pieces their tet surfaces instead of ending prescore), begun as soon as the input is read so
// that it works beside the check and the tetrahedralization. Made for one surface and piece
// count: the surface the tets come from may turn out another (a repair's wrap, a thickening) or
// the pieces more (a piece per separate body), and it is then made again.
struct SurfaceSimplification {
    SurfaceSimplification(const TriangleMesh& surface, size_t pieces);
    bool made_for(const TriangleMesh& s, size_t n) const {
        return n == pieces && s.vertices == surface.vertices && s.triangles == surface.triangles;
    }
    TriangleMesh surface;                  // what it was begun on
    size_t pieces = 0;                     // and for how many pieces
    std::optional<TriangleMesh> reduced;   // meshoptimizer's first reduction (first_reduction)
    double reduce_seconds = 0;
    size_t at_most = 0;                    // the triangles the cut gets (render_surface_triangles)
    std::unique_ptr<IsolatedRun> run;      // simplify_surface (none when the budget is passed)
    const TriangleMesh& from() const { return reduced ? *reduced : surface; }
};

SurfaceSimplification::SurfaceSimplification(const TriangleMesh& s, size_t n) : surface(s), pieces(n) {
    const auto start = std::chrono::steady_clock::now();
    reduced = first_reduction(surface);
    reduce_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (reduced && reduced->triangles.size() > kRenderSurfaceSimplifyLimit) return;
    at_most = render_surface_triangles(pieces, from().triangles.size());
    if (double(pieces) * double(at_most) > kRenderSurfaceWork) return;
    // CGAL's simplification: ~20 us per triangle it removes (render_surface.h).
    const double deadline = kRenderSurfaceSeconds + 2e-5 * double(from().triangles.size() - at_most);
    run = std::make_unique<IsolatedRun>([this] { return mesh_bytes(simplify_surface(from(), at_most)); }, deadline);
}

// Render surfaces (prescore/render_surface.h) for every piece, from `surface` (what the tets were
// made from) simplified to kRenderSurfaceTriangles, within kRenderSurfaceWork; over it, the
// pieces keep their tet surfaces (a choice, noted). `early`, when given, is the simplification
// begun before the tets (used when it was made for this surface and piece count). `own`, when
// given (the input, which `surface` wraps), gives the outer faces instead (use_input_faces;
// reduced to kRenderSurfaceTriangles by meshoptimizer first; not when more than
// kInputFaceMostTriangles remain, a choice noted), drawn from both sides unless `own_closed`, the
// fracture faces' rims moved `rim_inset` in. Without `own`, a piece whose cut fails takes the cut
// surface's triangles as its outer faces. `looks`: crack_fairing (the cracks between pieces
// faired, crack_fairing.h) and their roughness, seeded by its seed. `beside` runs while the
// cut works in its child (on the model as it was before: the cut must not need what `beside`
// does); not at all when no cut is made. One log line says what was done.
void add_render_surfaces(Model& model, const TriangleMesh& surface, std::unique_ptr<SurfaceSimplification> early,
                         double tet_size, const TriangleMesh* own, bool own_closed, double rim_inset,
                         const PrescoreSettings& looks,
                         const std::function<void()>& beside, PrescoreReport& report) {
    const auto start = std::chrono::steady_clock::now();
    if (!early || !early->made_for(surface, model.pieces.size()))
        early = std::make_unique<SurfaceSimplification>(surface, model.pieces.size());
    const SurfaceSimplification& simplification = *early;
    const TriangleMesh* from = &simplification.from();
    if (simplification.reduced) {
        if (simplification.reduced->triangles.size() > kRenderSurfaceSimplifyLimit) {
            report.choices.note("render surfaces: none, the pieces keep their tet surfaces",
                                fmt::format("the surface has {} triangles, and {} after a first simplification, more "
                                            "than the {} that are simplified for drawing within a few seconds; "
                                            "[prescore] render_surface = false to say so",
                                            surface.triangles.size(), simplification.reduced->triangles.size(),
                                            kRenderSurfaceSimplifyLimit));
            return;
        }
        spdlog::info("render surfaces: the surface's {} triangles first reduced to {} (meshoptimizer) in {:.2f} s",
                     surface.triangles.size(), simplification.reduced->triangles.size(), simplification.reduce_seconds);
    }
    RenderSurfaceSettings rs;
    rs.margin = kRenderSurfaceMargin * tet_size;
    rs.fair_cracks = looks.crack_fairing;
    rs.split_cracks = looks.crack_split;
    rs.roughness = looks.crack_roughness * tet_size;
    rs.roughness_scale = looks.crack_roughness_scale * tet_size;
    rs.roughness_seed = looks.seed;
    const auto over_budget = [&](size_t triangles) {
        const double work = double(model.pieces.size()) * double(triangles);
        if (!(work > kRenderSurfaceWork)) return false;
        report.choices.note(
            "render surfaces: none, the pieces keep their tet surfaces",
            fmt::format("{} pieces x {} surface triangles = {:.3g} million, over the budget of {:.3g} million (about "
                        "{:.0f} s); fewer pieces, or [prescore] render_surface = false to say so",
                        model.pieces.size(), triangles, work / 1e6, kRenderSurfaceWork / 1e6, kRenderSurfaceWork * 2e-6));
        return true;
    };
    // Many pieces: the surface is simplified further, to what the cut's budget allows for them.
    const size_t at_most = simplification.at_most;
    if (over_budget(at_most)) return;
    if (at_most < std::min(from->triangles.size(), kRenderSurfaceTriangles))
        report.choices.note(fmt::format("render surfaces: the surface simplified to {} triangles", at_most),
                            fmt::format("{} pieces are each cut from the whole surface, within a budget of {:.3g} "
                                        "million pieces x triangles (about {:.0f} s); at most {} pieces keep {} "
                                        "triangles; [prescore] render_surface = false draws the tet surfaces instead",
                                        model.pieces.size(), kRenderSurfaceWork / 1e6, kRenderSurfaceWork * 2e-6,
                                        size_t(kRenderSurfaceWork) / kRenderSurfaceTriangles, kRenderSurfaceTriangles));
    // CGAL's corefinement in a child process too. The child sends back six counts (the simplified
    // surface's triangles; use_input_faces' four; the input triangles it was given) and, within
    // the budget, the model with its render surfaces (the model format carries them).
    Model cut_model;
    std::array<uint64_t, 6> head{};
    try {
        // While the simplification finishes (it began before the tets): the faired cracks' cells,
        // which need the pieces' tets and surfaces alone.
        std::optional<CrackCells> faired;
        try {
            if (rs.fair_cracks) faired = faired_crack_cells(model, rs.split_cracks);
        } catch (const std::exception& e) {
            spdlog::info("render surfaces: cracks not faired ({})", e.what());
        }
        const TriangleMesh cut = mesh_from_bytes(early->run->finish());
        spdlog::debug("render surfaces: the simplification ready {:.3f} s after this stage began",
                      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        // meshoptimizer's reduction: ~1 us per input triangle.
        const double deadline = kRenderSurfaceSeconds + kRenderSurfaceWork * 2e-6 +
                                (own ? 1e-6 * double(own->triangles.size()) : 0.0);
        IsolatedRun cutting(
            [&] {
                std::array<uint64_t, 6> h{cut.triangles.size(), 0, 0, 0, 0, 0};
                const auto reply = [&h] { return std::string(reinterpret_cast<const char*>(h.data()), sizeof h); };
                if (double(model.pieces.size()) * double(h[0]) > kRenderSurfaceWork) return reply();
                Model m = model;
                std::vector<RenderSurface> found =
                    render_surfaces(cut, m, rs, cut.triangles.size() < from->triangles.size() ? from : nullptr, &faired);
                if (own) {
                    const TriangleMesh drawn = reduce_surface(*own, kRenderSurfaceTriangles);
                    h[5] = drawn.triangles.size();
                    if (h[5] <= kInputFaceMostTriangles) {
                        const InputFacesReport r =
                            use_input_faces(found, drawn, m, tet_size, rs.crease_degrees, !own_closed, rim_inset);
                        h[1] = r.pieces, h[2] = r.kept, h[3] = r.split, h[4] = r.leaves;
                    }
                } else {
                    // The input itself was cut: a piece whose cut failed takes the input's triangles
                    // as its outer faces instead of its tet faces (its fracture faces stay the tets').
                    std::vector<char> failed(found.size(), 0);
                    for (size_t p = 0; p < found.size(); ++p) failed[p] = found[p].fell_back;
                    if (std::count(failed.begin(), failed.end(), 1) > 0) {
                        const InputFacesReport r =
                            use_input_faces(found, cut, m, tet_size, rs.crease_degrees, false, 0.0, &failed);
                        h[1] = r.pieces, h[2] = r.kept, h[3] = r.split, h[4] = r.leaves, h[5] = cut.triangles.size();
                    }
                }
                for (size_t p = 0; p < found.size(); ++p) m.pieces[p].render = std::move(found[p]);
                return reply() + encode_model(m);
            },
            deadline);
        // The cut's child has its copy of the model: `beside` (the pieces' masses and collision
        // parts, which the cut does not use) works on this one meanwhile.
        beside();
        const std::string bytes = cutting.finish();
        if (bytes.size() < sizeof head) throw IsolatedFailure("no reply");
        std::memcpy(head.data(), bytes.data(), sizeof head);
        if (over_budget(head[0])) return;
        cut_model = decode_model(bytes.substr(sizeof head), "render surfaces");
    } catch (const IsolatedFailure& f) {
        report.choices.note("render surfaces: none, the pieces keep their tet surfaces",
                            fmt::format("CGAL's simplification or corefinement {} ({}); [prescore] render_surface = "
                                        "false to say so",
                                        f.timed_out ? "did not finish in time" : "crashed", f.what()));
        return;
    }
    for (size_t p = 0; p < model.pieces.size() && p < cut_model.pieces.size(); ++p) {
        if (!cut_model.pieces[p].render) continue;
        report.render_fell_back += cut_model.pieces[p].render->fell_back;
        report.render_triangles += cut_model.pieces[p].render->triangles.size();
        model.pieces[p].render = std::move(cut_model.pieces[p].render);
        ++report.render_surfaces;
    }
    const uint64_t cut_triangles = head[0];
    if (own && head[5] > kInputFaceMostTriangles)
        report.choices.note("render surfaces: the wrap's outer faces",
                            fmt::format("the input has {} triangles after meshoptimizer's simplification (which "
                                        "does not move a vertex on a border or on an edge of three triangles), "
                                        "more than the {} drawn as its own",
                                        head[5], kInputFaceMostTriangles));
    if (!own && head[1] > 0)
        spdlog::info("render surfaces: {} whose cut failed drawn with the surface's own triangles outside ({} parts, "
                     "{} split in four)", head[1] == 1 ? "1 piece" : fmt::format("{} pieces", head[1]), head[4], head[3]);
    if (own && head[1] > 0) {
        report.choices.note(
            fmt::format("render surfaces: the input's own triangles outside ({} pieces), the wrap's fracture faces "
                        "inside", head[1]),
            "the tets were made from an alpha wrap of the input, which bridges gaps narrower than its alpha; "
            "[prescore] render_surface = false draws the tet surfaces instead");
        spdlog::info("render surfaces: {} of the input's triangles ({}) placed as {} outer faces ({} split in four){}, "
                     "{}; {} pieces without one keep the wrap's",
                     head[5], own->triangles.size(), head[4], head[3], own_closed ? "" : ", each drawn from both sides",
                     head[1] == 1 ? "1 piece" : fmt::format("{} pieces", head[1]), head[2]);
    }
    const std::string simplified =
        cut_triangles < surface.triangles.size() ? fmt::format(", simplified from {}", surface.triangles.size()) : "";
    spdlog::info("render surfaces: {} pieces cut from {} surface triangles{} (margin {:g} tet sizes, {:.4g} m) in "
                 "{:.2f} s: {} triangles, {} on their tet surface",
                 report.render_surfaces, cut_triangles, simplified, kRenderSurfaceMargin, rs.margin,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                 report.render_triangles, report.render_fell_back);
}

// The input's materials, textures, texture coordinates and colours on the render surfaces
// (prescore/appearance_transfer.h), when it has any beyond its shape. Never fatal: a file whose
// appearance cannot be read is drawn in the material colour, with a warning.
void add_appearance(Model& model, const std::string& path, double scale, bool turn_up, AutoChoices& choices) {
    Appearance look;
    try {
        look = load_appearance(path);
    } catch (const Error& e) {
        choices.warn(fmt::format("appearance: not read, the pieces are drawn in one colour ({})", e.what()));
        return;
    }
    for (const std::string& w : look.warnings) choices.warn("appearance: " + w);
    if (look.plain()) return;
    if (turn_up) stand_up(look.mesh.vertices);
    for (Vec3& v : look.mesh.vertices) {
        v *= scale;
        if (!v.allFinite()) {  // load_mesh refuses such a file; a second reading must not differ
            choices.warn("appearance: not used, a vertex is not finite; the pieces are drawn in one colour");
            return;
        }
    }
    transfer_appearance(model, look);
    size_t textures = 0;
    for (const Material& m : model.materials) textures += !m.texture.empty();
    spdlog::info("appearance: {} materials ({} textured), {} texture coordinates, {} vertex colours, from {} triangles",
                 model.materials.size(), textures, look.uv.empty() ? "no" : "with", look.colour.empty() ? "no" : "with",
                 look.mesh.triangles.size());
}

}  // namespace

InputMesh read_input_mesh(const MeshSettings& settings, AutoChoices& choices) {
    InputMesh in;
    in.path = settings.path;
    if (std::optional<MeshArchive> archive = MeshArchive::open(settings.path, settings.member)) {
        in.archive = std::make_shared<const MeshArchive>(std::move(*archive));
        in.path = in.archive->mesh_path();
        const std::vector<std::string>& others = in.archive->other_meshes();
        std::string why = "the one mesh file in it";
        if (!settings.member.empty()) {
            why = "[mesh] member";
        } else if (!others.empty()) {
            why = fmt::format("of its {} mesh files the likeliest to hold the model whole ({}); the others:",
                              others.size() + 1, kArchiveChoice);
            for (size_t i = 0; i < others.size() && i < 5; ++i) why += (i ? ", " : " ") + others[i];
            if (others.size() > 5) why += fmt::format(" and {} more", others.size() - 5);
        }
        choices.note(fmt::format("mesh: {} from the archive", in.archive->mesh_name()), why);
    } else if (!settings.member.empty()) {
        throw_input_error(settings.path, fmt::format("mesh.member = \"{}\" names a file in an archive, and this is no "
                                                     "archive (.zip, .7z, .rar, .tar.gz)", settings.member),
                          "remove member, or give the archive as the mesh path");
    }
    try {
        in.loaded = load_mesh_file(in.path);
    } catch (const Error& e) {
        if (!in.archive) throw;
        // The message names the archive and the file in it, not the temporary folder it was unpacked to.
        std::string message = e.what();
        const std::string named = fmt::format("{} (its {})", settings.path, in.archive->mesh_name());
        for (size_t at = message.find(in.path); at != std::string::npos; at = message.find(in.path, at + named.size()))
            message.replace(at, in.path.size(), named);
        throw Error(e.code(), message);
    }
    LoadedMesh& loaded = in.loaded;
    if (const std::string hint = rounding_hint(loaded.rounding); !hint.empty())
        choices.warn(fmt::format("{}: {}", settings.path, hint));
    if (!settings.size) {
        // Numbers this far from a metre lose precision whatever the size asked for: check them
        // in the units given (or the file's) before any automatic size.
        const double given = settings.scale ? *settings.scale
                                            : (loaded.metres_per_unit > 0 ? loaded.metres_per_unit : 1.0);
        refuse_out_of_scale(bounding_diagonal(loaded.mesh) * given, settings.path);
    }
    in.turned = z_up(settings.up, in.path, loaded.states_z_up);
    if (in.turned) {
        stand_up(loaded.mesh.vertices);
        const std::string what = "up: the file's +z turned to +y (-90 degrees about x)";
        if (settings.up == UpAxis::Auto)
            choices.note(what, z_up_format(in.path, loaded.states_z_up) + "; [mesh] up = \"y\" keeps the file's axes");
        else
            spdlog::info("{} ([mesh] up = \"z\")", what);
    }
    in.scale = choose_scale(loaded.mesh, loaded.metres_per_unit, settings, choices);
    for (Vec3& v : loaded.mesh.vertices) v *= in.scale;
    return in;
}

namespace {

// seeds = "points": one piece from each of the shot's points (prescore/seed_points.h), `reach`
// a tet's size.
Partition partition_points(const TetMesh& mesh, const TetTopology& topology, const PrescoreSettings& settings,
                           double reach, AutoChoices& choices) {
    const std::string where = settings.seed_points_where.empty() ? "prescore.seed_points" : settings.seed_points_where;
    if (settings.seed_points.empty())
        throw_input_error(where, "prescore.seeds = \"points\" but seed_points is empty",
                          "give seed_points = [[x, y, z], ...] (m, the model's frame), or seeds = \"uniform\"");
    const std::vector<uint32_t> seeds = seed_tets_of_points(mesh, settings.seed_points, reach, where);
    if (settings.pieces != seeds.size())
        choices.note(fmt::format("pieces {} -> {}", settings.pieces, seeds.size()),
                     "seeds = \"points\": one piece per seed point");
    Partition part = partition_from_seeds(mesh, topology, seeds);
    if (part.joined_components > 0)
        choices.note(fmt::format("{} separate bodies without a seed point joined their nearest pieces",
                                 part.joined_components),
                     "seeds = \"points\": a body of the object that holds no point is not a piece of its own");
    return part;
}

}  // namespace

Model prescore(const MeshSettings& mesh_settings, const PrescoreSettings& settings, PrescoreReport* report_out,
               const FlightScene* flight) {
    PrescoreReport local;
    PrescoreReport& report = report_out ? *report_out : local;
    PhaseTimer timer(report);
    AutoChoices& choices = report.choices;
    if (const std::filesystem::path folder = std::filesystem::path(mesh_settings.path).parent_path();
        !folder.empty() && folder != folder.root_path())  // (a root, "/", would strip every slash)
        choices.folder = (folder / "").string();

    uint64_t mesh_hash = 0;
    size_t mesh_file_bytes = 0;
    {
        const std::string bytes = read_file(mesh_settings.path, "mesh file");
        mesh_hash = fnv1a64(bytes);
        mesh_file_bytes = bytes.size();
    }
    // A large file is read and checked for tens of seconds (6 million triangles, 240 MB: ~20 s
    // each): say what is happening before it.
    const bool large = mesh_file_bytes > kLargeMeshFileBytes;
    if (large) spdlog::info("mesh: reading {} ({:.0f} MB)", mesh_settings.path, double(mesh_file_bytes) / 1e6);
    InputMesh read = read_input_mesh(mesh_settings, choices);
    LoadedMesh& loaded = read.loaded;
    if (large)
        spdlog::info("mesh: {} triangles read; checking them (closed, manifold, oriented, crossing)",
                     loaded.mesh.triangles.size());
    report.scale = read.scale;
    timer.lap("load");
    const TriangleMesh& input = loaded.mesh;
    // The render surfaces' simplification works beside the check and the tetrahedralization, on
    // the input (made again if the tets come from another surface: a repair's wrap, a thickening;
    // or if the pieces turn out more). With seeds = "points" the pieces are the points.
    const size_t pieces = settings.seeds == SeedMode::Points && !settings.seed_points.empty()
                              ? settings.seed_points.size()
                              : size_t(settings.pieces);
    std::unique_ptr<SurfaceSimplification> simplification;
    if (settings.render_surface) simplification = std::make_unique<SurfaceSimplification>(input, pieces);
    std::unique_ptr<EarlyTets> early;  // the tets begun while the input's crossings are counted
    TriangleMesh surface = prepare_surface(input, mesh_settings, settings.resolution, report, early);
    timer.lap(report.repaired ? "check+repair" : "check");

    Model model;
    model.producer = producer_string();
    model.density = settings.density;
    FittedTets fit = fit_tets(input, std::move(surface), report.tetrahedralized_from, report.repaired,
                              report.input.diagonal, mesh_settings, settings, mesh_settings.path, choices, early.get());
    early.reset();
    model.mesh = std::move(fit.tets);
    report.resolution = fit.resolution;
    report.repaired = fit.wrapped;
    report.tetrahedralized_from = fit.surface_check;
    report.tets_meshed = model.mesh.tets.size();
    spdlog::info("tetrahedralize: {} tets, {} vertices", model.mesh.tets.size(), model.mesh.vertices.size());
    timer.lap("tetrahedralize");

    TetTopology topo = build_topology(model.mesh);
    std::vector<std::array<bool, 4>> cavity;
    if (settings.hollow) {
        report.hollow_thickness = settings.hollow->resolve(report.input.diagonal);
        HollowResult h = hollow(model.mesh, topo, report.hollow_thickness);
        model.mesh = std::move(h.mesh);
        cavity = std::move(h.cavity_face);
        report.tets_removed = h.removed;
        report.tets_restored = h.restored;
        topo = build_topology(model.mesh);
        spdlog::info("hollow: shell {:.4g} m thick, {} tets removed, {} kept ({} restored to keep the shell connected)",
                     report.hollow_thickness, h.removed, model.mesh.tets.size(), h.restored);
        timer.lap("hollow");
    }

    std::vector<double> density;  // empty: uniform seeds
    if (settings.seeds == SeedMode::Impact) {
        SceneSettings none;
        none.ground = false;
        const ObjectSettings still;
        const MaterialSettings material;
        GradedSeeds graded = grade_by_impact(model.mesh, topo, settings, flight ? flight->scene : none,
                                             flight ? flight->object : still, flight ? flight->material : material,
                                             report.input.diagonal, choices);
        report.impact = graded.record();
        density = std::move(graded.density);
        timer.lap("impact");
    }
    Partition part = settings.seeds == SeedMode::Points
                         ? partition_points(model.mesh, topo, settings, report.input.diagonal / report.resolution, choices)
                         : partition_adapted(model.mesh, topo, settings.pieces, settings.seed, mesh_settings.adapt,
                                             choices, density);
    model.tet_piece = std::move(part.tet_piece);
    model.pieces.resize(part.piece_tets.size());
    timer.lap("partition");
    model.constraints = reduce_constraints(place_constraints(model.mesh, topo, model.tet_piece),
                                           settings.constraints_per_pair);
    timer.lap("constraints");
    build_piece_shapes(model, topo, settings.hollow ? &cavity : nullptr);
    // The pieces' masses and collision parts are made while the render surfaces' cut works.
    bool bodies = false;
    const auto build_bodies = [&] {
        build_piece_bodies(model, settings, report.input.diagonal);
        bodies = true;
    };
    if (settings.render_surface) {
        // An alpha wrap made for the tets alone (not one that gave thin walls a thickness) is not
        // what the user modelled: the outer faces come from the input itself.
        const bool own = fit.wrapped && !fit.thickened;
        add_render_surfaces(model, fit.surface, std::move(simplification), report.input.diagonal / report.resolution,
                            own ? &input : nullptr,
                            report.input.closed() && report.input.volume > 0,
                            kInputFaceRimInset * mesh_settings.wrap_offset * report.input.diagonal,
                            settings, build_bodies, report);
        if (!bodies) build_bodies();
        timer.lap("pieces + render surfaces");
        // A file that shows nothing beyond its shape is not read a second time (a 6-million-triangle
        // scan: 8.7 s).
        if (report.render_surfaces > 0 && !loaded.plain) {
            add_appearance(model, read.path, report.scale, read.turned, choices);
            timer.lap("appearance");
        }
    } else {
        build_bodies();
        timer.lap("pieces");
    }
    report.surface = std::move(fit.surface);
    model.settings_json = settings_json(mesh_settings, settings, mesh_hash, choices, report.impact);
    return model;
}

Model prescore_shot(const Shot& shot, PrescoreReport* report_out) {
    if (!shot.generate) {
        if (shot.mesh.path.empty())
            throw_input_error(shot.path, "the shot has neither [mesh] nor [generate]",
                              "add [mesh] with path = \"your.obj\", or [generate] with kind = \"beam\", \"plate\" or "
                              "\"chain\" (docs/shot.md)");
        const FlightScene flight{shot.scene, shot.object, shot.material};
        return prescore(shot.mesh, shot.prescore, report_out, &flight);
    }
    PrescoreReport local;
    PrescoreReport& report = report_out ? *report_out : local;
    PhaseTimer timer(report);
    Model model = generate_model(*shot.generate);
    timer.lap("generate");
    return model;
}

std::string save_prescore_outputs(const Model& model, const std::string& model_path) {
    const std::filesystem::path path(model_path);
    const std::string ply = (path.parent_path() / (path.stem().string() + ".pieces.ply")).string();
    save_model(model_path, model);
    write_file_atomic(ply, pieces_ply(model));
    return ply;
}

}  // namespace shatter
