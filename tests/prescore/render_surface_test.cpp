// Render surfaces: on a sphere of 5,120 triangles cut into 6 pieces by prescore (which makes them
// by default; none with render_surface = false), the pieces' render surfaces follow the input (99% of its vertices within 0.05% of the diagonal, normals within
// 10 degrees on 95% of it), each is closed, none falls back to its tet surface, and two runs
// give the same surfaces. The tet surfaces miss both by far (the test says by how much). An
// input prescore wraps for its tets (open, or crossing itself) is drawn with its own triangles,
// unless meshoptimizer leaves it too large to draw.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "meshio/mesh_load.h"
#include "prescore/adapt.h"
#include "prescore/mesh_check.h"
#include "prescore/prescore.h"
#include "prescore/render_surface.h"
#include "prescore/surface_agreement.h"
#include "prescore/tet_test_meshes.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

using test::icosphere;

// Closed: every edge (by vertex positions, since vertices are split where normals differ) is
// used once in each direction.
bool closed(const RenderSurface& s) {
    std::map<std::array<double, 6>, int> edges;
    for (const Tri& t : s.triangles)
        for (int k = 0; k < 3; ++k) {
            const Vec3 &a = s.vertices[t[k]], &b = s.vertices[t[(k + 1) % 3]];
            edges[{a.x(), a.y(), a.z(), b.x(), b.y(), b.z()}] += 1;
            edges[{b.x(), b.y(), b.z(), a.x(), a.y(), a.z()}] -= 1;
        }
    for (const auto& [edge, balance] : edges)
        if (balance != 0) return false;
    return !s.triangles.empty();
}

struct Cut {
    TriangleMesh input;
    Model model;
    double diagonal = 0;
    std::vector<RenderSurface> surfaces;
};

Cut cut_sphere(const testing_support::TempDir& dir, std::optional<Length> hollow) {
    MeshSettings mesh;
    mesh.path = dir.write("sphere.obj", test::obj_text(icosphere(4)));
    mesh.scale = 0.1;
    PrescoreSettings settings;
    settings.pieces = 6;
    settings.resolution = 12;
    settings.hollow = hollow;
    PrescoreReport report;
    Cut cut;
    cut.model = prescore(mesh, settings, &report);
    cut.input = load_mesh(mesh.path, 0.1);
    if (check_mesh(cut.input, false).volume < 0) orient_outward(cut.input);
    cut.diagonal = report.input.diagonal;
    // prescore made them (by default), from the surface it tetrahedralized: the input here.
    EXPECT_EQ(report.surface.vertices, cut.input.vertices);
    EXPECT_EQ(report.render_surfaces, cut.model.pieces.size());
    for (const Piece& p : cut.model.pieces) {
        EXPECT_TRUE(p.render);
        if (p.render) cut.surfaces.push_back(*p.render);
    }
    return cut;
}

void expect_follows_the_input(const Cut& cut) {
    ASSERT_EQ(cut.surfaces.size(), cut.model.pieces.size());
    for (size_t p = 0; p < cut.surfaces.size(); ++p) {
        EXPECT_FALSE(cut.surfaces[p].fell_back) << "piece " << p;
        EXPECT_TRUE(closed(cut.surfaces[p])) << "piece " << p;
    }
    const SurfaceAgreement a = surface_agreement(cut.input, cut.surfaces, 40, 10);
    EXPECT_LE(a.distance_p99, 0.0005 * cut.diagonal);
    EXPECT_GE(a.normals_within, 0.95);
    EXPECT_GT(a.smooth_samples, cut.input.vertices.size() * 9 / 10);  // a sphere is smooth everywhere

    std::vector<RenderSurface> tet;
    for (const Piece& p : cut.model.pieces) tet.push_back(flat_render_surface(p.surface));
    const SurfaceAgreement before = surface_agreement(cut.input, tet, 40, 10);
    EXPECT_GT(before.distance_p99, 0.0005 * cut.diagonal) << "the tet surfaces should miss the input";
    ::testing::Test::RecordProperty("tet_p99_pct", std::to_string(100 * before.distance_p99 / cut.diagonal));
    ::testing::Test::RecordProperty("render_p99_pct", std::to_string(100 * a.distance_p99 / cut.diagonal));
}

TEST(RenderSurface, SolidSphereCutFollowsTheInputWithin005PercentAndNormalsWithin10Degrees) {
    testing_support::TempDir dir;
    const Cut cut = cut_sphere(dir, std::nullopt);
    expect_follows_the_input(cut);
    size_t fracture = 0;
    for (const RenderSurface& s : cut.surfaces)
        for (FaceKind k : s.kinds) fracture += k == FaceKind::Fracture;
    EXPECT_GT(fracture, 0u);
}

TEST(RenderSurface, HollowSphereKeepsItsCavityFacesAndFollowsTheInput) {
    testing_support::TempDir dir;
    const Cut cut = cut_sphere(dir, Length{0.1, true});
    expect_follows_the_input(cut);
    size_t cavity = 0;
    for (const RenderSurface& s : cut.surfaces)
        for (FaceKind k : s.kinds) cavity += k == FaceKind::Cavity;
    EXPECT_GT(cavity, 0u);
}

// An icosphere of `levels` and radius 0.1 m (dir/sphere.obj) prescored into `pieces`.
Model prescore_sphere(const testing_support::TempDir& dir, int levels, uint32_t pieces, double resolution,
                      bool render_surface, PrescoreReport* report) {
    MeshSettings mesh;
    mesh.path = dir.write("sphere.obj", test::obj_text(icosphere(levels)));
    mesh.scale = 0.1;
    PrescoreSettings settings;
    settings.pieces = pieces;
    settings.resolution = resolution;
    settings.render_surface = render_surface;
    return prescore(mesh, settings, report);
}

TEST(RenderSurface, PrescoreMakesNoneWhenTheSettingIsOff) {
    testing_support::TempDir dir;
    PrescoreReport report;
    const Model m = prescore_sphere(dir, 2, 3, 8, false, &report);
    for (const Piece& p : m.pieces) EXPECT_FALSE(p.render);
    EXPECT_EQ(report.render_surfaces, 0u);
    EXPECT_NE(m.settings_json.find("\"render_surface\":false"), std::string::npos) << m.settings_json;
}

// The surface a cut starts from: kRenderSurfaceTriangles (or fewer when the surface has fewer)
// up to kRenderSurfaceWork / kRenderSurfaceTriangles pieces; then what keeps pieces x triangles
// within kRenderSurfaceWork, down to kRenderSurfaceFewest (beyond which the work is over budget).
TEST(RenderSurface, ManyPiecesGetASurfaceSimplifiedToTheCutsBudget) {
    EXPECT_EQ(render_surface_triangles(10, 69666), kRenderSurfaceTriangles);
    EXPECT_EQ(render_surface_triangles(10, 5000), 5000u);
    EXPECT_EQ(render_surface_triangles(333, 69666), kRenderSurfaceTriangles);  // 3,996,000 <= 4e6
    EXPECT_EQ(render_surface_triangles(1000, 69666), 4000u);
    EXPECT_EQ(render_surface_triangles(1000, 3000), 3000u);
    EXPECT_EQ(render_surface_triangles(4000, 69666), 1000u);
    EXPECT_EQ(render_surface_triangles(8000, 69666), kRenderSurfaceFewest);  // 8 million: over budget
    EXPECT_EQ(render_surface_triangles(8000, 600), 600u);                    // 4.8 million: over budget
    EXPECT_EQ(render_surface_triangles(0, 69666), kRenderSurfaceTriangles);
}

// 500 pieces of a sphere of 20,480 triangles: each piece is cut from the sphere simplified to
// 4e6 / 500 = 8,000 triangles (a choice, noted), and still follows the sphere.
TEST(RenderSurface, FiveHundredPiecesAreCutFromTheSurfaceSimplifiedTo8000Triangles) {
    testing_support::TempDir dir;
    PrescoreReport report;
    const Model m = prescore_sphere(dir, 5, 500, 40, true, &report);
    ASSERT_EQ(m.pieces.size(), 500u);
    EXPECT_EQ(report.render_surfaces, 500u);
    bool noted = false;
    for (const AutoChoice& c : report.choices.list)
        noted = noted || c.what == "render surfaces: the surface simplified to 8000 triangles";
    EXPECT_TRUE(noted) << m.settings_json;
    std::vector<RenderSurface> surfaces;
    for (const Piece& p : m.pieces)
        if (p.render) surfaces.push_back(*p.render);
    TriangleMesh input = load_mesh(dir.file("sphere.obj"), 0.1);
    if (check_mesh(input, false).volume < 0) orient_outward(input);
    const SurfaceAgreement a = surface_agreement(input, surfaces, 40, 10);
    // An 8,000-triangle sphere of radius 0.1 m lies within r (1 - cos(edge angle / 2)) ~ 0.05 mm of
    // the 20,480-triangle one: 0.05% of the diagonal.
    EXPECT_LE(a.distance_p99, 0.0005 * report.input.diagonal);
    EXPECT_GE(a.normals_within, 0.95);
}

// A torus (ring radius R, tube radius r) of 2 nu nv triangles, outward.
TriangleMesh torus(double R, double r, uint32_t nu, uint32_t nv) {
    TriangleMesh m;
    for (uint32_t i = 0; i < nu; ++i)
        for (uint32_t j = 0; j < nv; ++j) {
            const double u = 2 * M_PI * i / nu, v = 2 * M_PI * j / nv;
            m.vertices.push_back({(R + r * std::cos(v)) * std::cos(u), r * std::sin(v), (R + r * std::cos(v)) * std::sin(u)});
        }
    for (uint32_t i = 0; i < nu; ++i)
        for (uint32_t j = 0; j < nv; ++j) {
            const uint32_t a = i * nv + j, b = (i + 1) % nu * nv + j, c = (i + 1) % nu * nv + (j + 1) % nv,
                           d = i * nv + (j + 1) % nv;
            m.triangles.push_back({a, c, b});
            m.triangles.push_back({a, d, c});
        }
    return m;
}

// A surface over kRenderSurfaceSimplifyLimit (a torus of 600,000 triangles, whose first reduction
// folds triangle pairs, makes tubes touch along edges and crosses itself) is reduced by
// meshoptimizer to about kRenderSurfaceReduced triangles of its own vertices, and CGAL's
// simplification of that is closed, does not cross itself, is within kRenderSurfaceTriangles, on
// the torus within 0.05% of its diagonal and encloses its volume 2 pi^2 R r^2 within 1%.
TEST(RenderSurface, ASurfaceTooLargeForCgalIsReducedFirstAndStaysClosedOnTheTorus) {
    const double R = 1, r = 0.35;
    const TriangleMesh big = torus(R, r, 1000, 300);
    ASSERT_GT(big.triangles.size(), kRenderSurfaceSimplifyLimit);
    const auto off_torus = [&](const Vec3& p) { return std::abs(std::hypot(std::hypot(p.x(), p.z()) - R, p.y()) - r); };
    const TriangleMesh reduced = reduce_surface(big, kRenderSurfaceReduced);
    EXPECT_LE(reduced.triangles.size(), kRenderSurfaceReduced);
    EXPECT_GT(reduced.triangles.size(), kRenderSurfaceReduced * 9 / 10);
    for (const Vec3& v : reduced.vertices) ASSERT_LT(off_torus(v), 1e-12) << "a vertex not of the input";
    const TriangleMesh cut = simplify_surface(reduced, kRenderSurfaceTriangles);
    EXPECT_LE(cut.triangles.size(), kRenderSurfaceTriangles);
    EXPECT_GT(cut.triangles.size(), kRenderSurfaceTriangles * 9 / 10);
    const MeshCheck check = check_mesh(cut);
    EXPECT_TRUE(check.closed() && check.manifold() && check.oriented()) << describe(check);
    EXPECT_EQ(check.self_intersections, 0u) << "the cut needs a surface that does not cross itself";
    double worst = 0;
    for (const Vec3& v : cut.vertices) worst = std::max(worst, off_torus(v));
    const double volume = check.volume;
    const double diagonal = std::sqrt(2 * std::pow(2 * (R + r), 2) + std::pow(2 * r, 2));
    EXPECT_LT(worst, 0.0005 * diagonal);  // as the cut sphere's render surfaces (above)
    EXPECT_NEAR(volume, 2 * M_PI * M_PI * R * r * r, 0.01 * 2 * M_PI * M_PI * R * r * r);
    ::testing::Test::RecordProperty("worst_off_torus_of_r", std::to_string(worst / r));
}

TEST(RenderSurface, TwoRunsGiveTheSameSurfaces) {
    testing_support::TempDir dir;
    const Cut a = cut_sphere(dir, std::nullopt), b = cut_sphere(dir, std::nullopt);
    ASSERT_EQ(a.surfaces.size(), b.surfaces.size());
    for (size_t p = 0; p < a.surfaces.size(); ++p) {
        EXPECT_EQ(a.surfaces[p].vertices, b.surfaces[p].vertices);
        EXPECT_EQ(a.surfaces[p].normals, b.surfaces[p].normals);
        EXPECT_EQ(a.surfaces[p].triangles, b.surfaces[p].triangles);
        EXPECT_EQ(a.surfaces[p].kinds, b.surfaces[p].kinds);
    }
}

// A piece whose cut failed (prescore gives it the cut surface's triangles, use_input_faces with
// `only`): on the cut sphere, piece 0 put back on its tet surface and given the input's triangles
// has every outer face within the input's own sag of the sphere (its tet faces' chords sag up to
// ten times more), keeps its tet fracture faces, and the other pieces are left as they were.
TEST(RenderSurface, APieceWhoseCutFailedTakesTheInputsTrianglesAndTheOthersStay) {
    testing_support::TempDir dir;
    const Cut cut = cut_sphere(dir, std::nullopt);
    std::vector<RenderSurface> surfaces = cut.surfaces;
    surfaces[0] = flat_render_surface(cut.model.pieces[0].surface);
    size_t tet_fracture = 0;
    for (FaceKind k : surfaces[0].kinds) tet_fracture += k != FaceKind::Outer;
    std::vector<char> only(surfaces.size(), 0);
    only[0] = 1;
    const InputFacesReport r = use_input_faces(surfaces, cut.input, cut.model, cut.diagonal / 12, 40, false, 0.0, &only);
    EXPECT_EQ(r.pieces, 1u);
    for (size_t p = 1; p < surfaces.size(); ++p) {
        EXPECT_EQ(surfaces[p].vertices, cut.surfaces[p].vertices) << "piece " << p;
        EXPECT_EQ(surfaces[p].triangles, cut.surfaces[p].triangles) << "piece " << p;
    }
    const double radius = 0.1, sag = radius * (1 - std::cos(0.06));
    size_t outer = 0, fracture = 0;
    for (size_t t = 0; t < surfaces[0].triangles.size(); ++t) {
        const Tri& tri = surfaces[0].triangles[t];
        if (surfaces[0].kinds[t] != FaceKind::Outer) {
            ++fracture;
            continue;
        }
        ++outer;
        const auto& v = surfaces[0].vertices;
        EXPECT_GE(((v[tri[0]] + v[tri[1]] + v[tri[2]]) / 3).norm(), radius - sag);
    }
    EXPECT_GT(outer, 0u);
    EXPECT_EQ(fracture, tet_fracture);
    // The tet surface itself fails that: its outer chords cut deeper.
    const RenderSurface tet = flat_render_surface(cut.model.pieces[0].surface);
    double deepest = radius;
    for (size_t t = 0; t < tet.triangles.size(); ++t)
        if (tet.kinds[t] == FaceKind::Outer) {
            const Tri& tri = tet.triangles[t];
            deepest = std::min(deepest, ((tet.vertices[tri[0]] + tet.vertices[tri[1]] + tet.vertices[tri[2]]) / 3).norm());
        }
    EXPECT_LT(deepest, radius - sag);
}

// An input that prescore alpha-wraps for its tets is drawn with its own triangles
// (use_input_faces): every outer vertex lies on an input triangle (within the sag of an
// icosphere of radius r: the wrap's lie `offset` outside it, 1e-3 of the diagonal), the
// outer faces cover the input's area once (a closed input) or twice (an open one, drawn from both
// sides), and the fracture faces come from the wrap's cut, their rims moved in under the input.
struct Wrapped {
    Model model;
    PrescoreReport report;
    double input_area = 0;
};

Wrapped prescore_wrapped(const testing_support::TempDir& dir, const std::string& name, const TriangleMesh& input) {
    MeshSettings mesh;
    mesh.path = dir.write(name, test::obj_text(input));
    mesh.scale = 1;
    PrescoreSettings settings;
    settings.pieces = 6;
    settings.resolution = 12;
    Wrapped w;
    w.model = prescore(mesh, settings, &w.report);
    for (const Tri& t : input.triangles)
        w.input_area += (input.vertices[t[1]] - input.vertices[t[0]]).cross(input.vertices[t[2]] - input.vertices[t[0]]).norm() / 2;
    return w;
}

double outer_area(const Model& m) {
    double area = 0;
    for (const Piece& p : m.pieces)
        for (size_t t = 0; t < p.render->triangles.size(); ++t) {
            if (p.render->kinds[t] != FaceKind::Outer) continue;
            const Tri& tri = p.render->triangles[t];
            const auto& v = p.render->vertices;
            area += (v[tri[1]] - v[tri[0]]).cross(v[tri[2]] - v[tri[0]]).norm() / 2;
        }
    return area;
}

bool chose_input_faces(const PrescoreReport& r) {
    for (const AutoChoice& c : r.choices.list)
        if (c.what.find("render surfaces: the input's own triangles") == 0) return true;
    return false;
}

TEST(RenderSurface, AnOpenInputWrappedForItsTetsIsDrawnWithItsOwnTrianglesFromBothSides) {
    testing_support::TempDir dir;
    // An icosphere of radius 0.1 m without its topmost triangle: open, so prescore wraps it; the
    // hole (a triangle of about 7 mm sides, its inscribed circle 2 mm in radius) does not let the
    // wrap's ball (alpha 6.9 mm) in, so the wrap closes it and the tets fill the ball (a larger
    // hole makes the sphere a shell, which is thickened).
    const double r = 0.1;
    TriangleMesh open = icosphere(4);
    for (Vec3& v : open.vertices) v *= r;
    const auto centre_y = [&](const Tri& t) {
        return (open.vertices[t[0]].y() + open.vertices[t[1]].y() + open.vertices[t[2]].y()) / 3;
    };
    const auto top = std::max_element(open.triangles.begin(), open.triangles.end(),
                                      [&](const Tri& a, const Tri& b) { return centre_y(a) < centre_y(b); });
    const Tri hole = *top;
    open.triangles.erase(top);
    const Wrapped w = prescore_wrapped(dir, "open_sphere.obj", open);
    EXPECT_TRUE(w.report.repaired);
    EXPECT_TRUE(chose_input_faces(w.report));
    ASSERT_EQ(w.report.render_surfaces, w.model.pieces.size());
    // A level-4 icosphere's triangles lie within r (1 - cos(rho)) of the sphere, rho the angle of
    // their circumradius (under 0.06 rad).
    const double sag = r * (1 - std::cos(0.06));
    size_t fracture = 0, outer_vertices = 0;
    for (const Piece& p : w.model.pieces) {
        ASSERT_TRUE(p.render);
        std::vector<char> outer(p.render->vertices.size(), 0);
        for (size_t t = 0; t < p.render->triangles.size(); ++t) {
            fracture += p.render->kinds[t] == FaceKind::Fracture;
            if (p.render->kinds[t] == FaceKind::Outer)
                for (uint32_t v : p.render->triangles[t]) outer[v] = 1;
            else  // the fracture faces end under the input: the intact ball shows no seams
                for (uint32_t v : p.render->triangles[t]) EXPECT_LT(p.render->vertices[v].norm(), r);
        }
        for (size_t v = 0; v < outer.size(); ++v) {
            if (!outer[v]) continue;
            ++outer_vertices;
            const Vec3& x = p.render->vertices[v];
            // (assimp reads the input in single precision.)
            EXPECT_LE(x.norm(), r * (1 + 1e-6)) << "outside the input, as the wrap is";
            EXPECT_GE(x.norm(), r - sag);
            // Seen from the centre, no outer vertex lies within the hole.
            const Vec3 &a = open.vertices[hole[0]], &b = open.vertices[hole[1]], &c = open.vertices[hole[2]];
            const bool within = x.dot(a.cross(b)) > 0 && x.dot(b.cross(c)) > 0 && x.dot(c.cross(a)) > 0;
            EXPECT_FALSE(within) << "an outer face over the hole: the wrap's cap is drawn";
        }
    }
    EXPECT_GT(outer_vertices, open.vertices.size() / 2);
    EXPECT_GT(fracture, 0u);
    EXPECT_NEAR(outer_area(w.model), 2 * w.input_area, 1e-6 * w.input_area);
}

TEST(RenderSurface, AClosedInputThatCrossesItselfIsDrawnWithItsOwnTrianglesOnce) {
    testing_support::TempDir dir;
    // Two spheres of radius 0.1 m that overlap: closed, outward, crossing along a circle (more
    // crossings than prescore meshes as they are), so prescore wraps them.
    TriangleMesh two = icosphere(3);
    for (Vec3& v : two.vertices) v *= 0.1;
    const size_t n = two.vertices.size();
    for (size_t i = 0; i < n; ++i) two.vertices.push_back(two.vertices[i] + Vec3(0.12, 0, 0));
    const size_t nt = two.triangles.size();
    for (size_t t = 0; t < nt; ++t) {
        const Tri f = two.triangles[t];
        two.triangles.push_back({f[0] + uint32_t(n), f[1] + uint32_t(n), f[2] + uint32_t(n)});
    }
    const Wrapped w = prescore_wrapped(dir, "two_spheres.obj", two);
    EXPECT_TRUE(w.report.repaired);
    EXPECT_TRUE(chose_input_faces(w.report));
    EXPECT_NEAR(outer_area(w.model), w.input_area, 1e-6 * w.input_area);
}

// An input that stays over kInputFaceMostTriangles after meshoptimizer's reduction keeps the
// wrap's outer faces, a choice said with its reason. Here a sphere of 81,920 triangles with a fin
// on each of its edges: every edge carries three triangles, so meshoptimizer moves no vertex.
TEST(RenderSurface, AnInputTooLargeToDrawAsItsOwnKeepsTheWrapsOuterFaces) {
    testing_support::TempDir dir;
    TriangleMesh apart = icosphere(6);
    for (Vec3& v : apart.vertices) v *= 0.1;
    const size_t faces = apart.triangles.size();
    std::map<std::pair<uint32_t, uint32_t>, bool> finned;
    for (size_t t = 0; t < faces; ++t)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = apart.triangles[t][size_t(k)], b = apart.triangles[t][size_t(k + 1) % 3];
            if (!finned.emplace(std::minmax(a, b), true).second) continue;
            apart.vertices.push_back((apart.vertices[a] + apart.vertices[b]) * 0.505);
            apart.triangles.push_back({a, b, uint32_t(apart.vertices.size() - 1)});
        }
    ASSERT_GT(reduce_surface(apart, kRenderSurfaceTriangles).triangles.size(), kInputFaceMostTriangles);
    const Wrapped w = prescore_wrapped(dir, "finned.obj", apart);
    EXPECT_TRUE(w.report.repaired);
    EXPECT_FALSE(chose_input_faces(w.report));
    bool said = false;
    for (const AutoChoice& c : w.report.choices.list) said = said || c.what == "render surfaces: the wrap's outer faces";
    EXPECT_TRUE(said);
    ASSERT_EQ(w.report.render_surfaces, w.model.pieces.size());
    size_t outside = 0;
    for (const Piece& p : w.model.pieces)
        for (size_t t = 0; t < p.render->triangles.size(); ++t)
            if (p.render->kinds[t] == FaceKind::Outer)
                for (uint32_t v : p.render->triangles[t]) outside += p.render->vertices[v].norm() > 0.1;
    EXPECT_GT(outside, 0u) << "the wrap lies outside the input";
}

}  // namespace
}  // namespace shatter
