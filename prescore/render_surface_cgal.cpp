// Render surfaces by corefinement (CGAL 5.5: Polygon_mesh_processing::
// corefine_and_compute_intersection on Surface_mesh, Epick: exact predicates, the new points
// rounded to doubles). The design is in render_surface.h. Faces of the result are told apart by
// where they lie: a face that is a cell face as it was (the same corners) is that face, with its
// kind (flat); a face within 1e-7 diagonals of an input triangle is a piece of it (Outer, smooth
// normals interpolated from that triangle's corner normals); any other face comes from the cell
// and takes the kind of the nearest cell face (flat).
#include "prescore/render_surface.h"

#include <algorithm>
#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string_view>
#include <tuple>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup_extension.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_self_intersections.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Bounded_normal_change_filter.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>
#include <spdlog/spdlog.h>

#include "core/workers.h"
#include "prescore/crack_fairing.h"
#include "prescore/tet_topology.h"
#include "prescore/triangle_tree_cgal.h"

namespace shatter {

namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Soup = std::vector<std::array<size_t, 3>>;

Vec3 vec(const Point& p) { return {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}; }

// A piece's tet boundary in mesh vertex indices, in piece_surface's order, with its kinds.
struct Cell {
    std::vector<Tri> triangles;
    std::vector<FaceKind> kinds;
};

std::vector<Cell> cells_of(const Model& model, const TetTopology& topo) {
    std::vector<Cell> cells(model.pieces.size());
    std::vector<size_t> emitted(model.pieces.size(), 0);
    for (size_t t = 0; t < model.mesh.tets.size(); ++t) {
        const uint32_t p = model.tet_piece[t];
        for (int i = 0; i < 4; ++i) {
            const int32_t u = topo.neighbour[t][i];
            if (u >= 0 && model.tet_piece[u] == p) continue;
            Tri tri;
            for (int k = 0; k < 3; ++k) tri[k] = model.mesh.tets[t][kTetFaces[i][k]];
            const PieceSurface& s = model.pieces[p].surface;
            const size_t e = emitted[p]++;
            cells[p].triangles.push_back(tri);
            cells[p].kinds.push_back(e < s.kinds.size() ? s.kinds[e] : (u >= 0 ? FaceKind::Fracture : FaceKind::Outer));
        }
    }
    return cells;
}

// What each tet face on the boundary is (Outer or Cavity), from the tet cells' kinds.
std::vector<std::array<FaceKind, 4>> boundary_kinds(const Model& model, const TetTopology& topo,
                                                    const std::vector<Cell>& tet_cells) {
    std::vector<std::array<FaceKind, 4>> kind(model.mesh.tets.size());
    std::vector<size_t> emitted(model.pieces.size(), 0);  // in cells_of's order
    for (size_t t = 0; t < model.mesh.tets.size(); ++t)
        for (int i = 0; i < 4; ++i) {
            const int32_t u = topo.neighbour[t][i];
            if (u >= 0 && model.tet_piece[u] == model.tet_piece[t]) continue;
            const uint32_t p = model.tet_piece[t];
            kind[t][i] = tet_cells[p].kinds[emitted[p]++];
        }
    return kind;
}

// A cell at `at` as a piece surface (its tet surface, with the cracks faired when `at` is).
PieceSurface cell_surface(const Cell& cell, const std::vector<Vec3>& at) {
    PieceSurface s;
    std::map<uint32_t, uint32_t> index;
    for (const Tri& t : cell.triangles) {
        Tri tri;
        for (int k = 0; k < 3; ++k) {
            auto [it, fresh] = index.emplace(t[k], uint32_t(s.vertices.size()));
            if (fresh) s.vertices.push_back(at[t[k]]);
            tri[k] = it->second;
        }
        s.triangles.push_back(tri);
    }
    s.kinds = cell.kinds;
    return s;
}

// The outer normal of every mesh vertex at `v` (zero for vertices on no outer face).
std::vector<Vec3> outer_normals(const std::vector<Vec3>& v, const std::vector<Cell>& cells) {
    std::vector<Vec3> normal(v.size(), Vec3::Zero());
    for (const Cell& c : cells)
        for (size_t f = 0; f < c.triangles.size(); ++f) {
            if (c.kinds[f] != FaceKind::Outer) continue;
            const Tri& t = c.triangles[f];
            const Vec3 n = (v[t[1]] - v[t[0]]).cross(v[t[2]] - v[t[0]]);
            for (uint32_t i : t) normal[i] += n;
        }
    for (Vec3& n : normal)
        if (n.norm() > 0) n.normalize();
    return normal;
}

// Where a piece touches itself along an edge or at a vertex (two of its tets meet only there),
// its boundary is not a manifold. Each face is paired across each edge with the opposite face
// that closes the same solid wedge (the first one turning about the edge toward the solid side),
// each vertex gets one copy per fan of faces joined by those pairs, and copies that share a
// position move by `nudge` toward their own faces, so that the sheets no longer touch.
std::vector<Vec3> separate_sheets(const std::vector<Vec3>& points, Soup& soup, double nudge) {
    using Edge = std::pair<size_t, size_t>;
    std::map<Edge, std::vector<size_t>> faces_of;  // directed edge -> faces that hold it
    for (size_t f = 0; f < soup.size(); ++f)
        for (int k = 0; k < 3; ++k) faces_of[{soup[f][k], soup[f][(k + 1) % 3]}].push_back(f);
    auto third = [&](size_t f, size_t a, size_t b) {
        for (size_t v : soup[f])
            if (v != a && v != b) return v;
        return a;
    };
    // Union-find over corners (3 f + k): corners of one vertex joined across paired edges.
    std::vector<size_t> parent(3 * soup.size());
    for (size_t i = 0; i < parent.size(); ++i) parent[i] = i;
    auto find = [&](size_t x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    };
    auto corner = [&](size_t f, size_t v) {
        for (int k = 0; k < 3; ++k)
            if (soup[f][k] == v) return 3 * f + k;
        return 3 * f;
    };
    for (size_t f = 0; f < soup.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            const size_t a = soup[f][k], b = soup[f][(k + 1) % 3];
            auto it = faces_of.find({b, a});
            if (it == faces_of.end()) continue;
            size_t g = it->second.front();
            if (it->second.size() > 1) {
                const Vec3 e = (points[b] - points[a]).normalized();
                auto perp = [&](size_t h) {
                    const Vec3 d = points[third(h, a, b)] - points[a];
                    return Vec3(d - d.dot(e) * e);
                };
                const Vec3 u = perp(f).normalized(), w = e.cross(u);
                double best = 1e300;
                for (size_t h : it->second) {
                    const Vec3 d = perp(h);
                    double theta = std::atan2(d.dot(w), d.dot(u));
                    theta = theta <= 0 ? -theta : 2 * M_PI - theta;
                    if (theta < best) best = theta, g = h;
                }
            }
            for (size_t v : {a, b}) parent[find(corner(f, v))] = find(corner(g, v));
        }
    std::vector<Vec3> out;
    std::map<size_t, size_t> copy;  // corner root -> new point
    std::vector<size_t> origin;
    for (size_t f = 0; f < soup.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            auto [it, fresh] = copy.emplace(find(3 * f + k), out.size());
            if (fresh) out.push_back(points[soup[f][k]]), origin.push_back(soup[f][k]);
        }
    std::vector<size_t> copies(points.size(), 0);
    for (size_t o : origin) ++copies[o];
    std::vector<Vec3> toward(out.size(), Vec3::Zero());
    Soup result(soup.size());
    for (size_t f = 0; f < soup.size(); ++f) {
        for (int k = 0; k < 3; ++k) result[f][k] = copy[find(3 * f + k)];
        const Vec3 c = (out[result[f][0]] + out[result[f][1]] + out[result[f][2]]) / 3;
        for (size_t v : result[f]) toward[v] += c - out[v];
    }
    for (size_t i = 0; i < out.size(); ++i)
        if (copies[origin[i]] > 1 && toward[i].norm() > 0) out[i] += nudge * toward[i].normalized();
    soup = std::move(result);
    return out;
}

// Whether `soup` is a closed, consistently oriented triangle manifold: three distinct corners per
// triangle, each directed edge once and its reverse present, and the triangles about each vertex
// one fan. What CGAL's is_polygon_soup_a_polygon_mesh and is_closed decide together, by sorted
// edge keys instead of its ordered sets (the demo bunny's 36,000 triangles made a mesh in 26 ms
// with this check against 80 ms with CGAL's).
bool closed_triangle_manifold(const Soup& soup) {
    const size_t n = soup.size();
    size_t vertices = 0;
    for (const auto& t : soup) {
        if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) return false;
        vertices = std::max({vertices, t[0] + 1, t[1] + 1, t[2] + 1});
    }
    if (vertices > (size_t(1) << 32)) return false;
    std::vector<uint64_t> edges(3 * n);
    for (size_t f = 0; f < n; ++f)
        for (int k = 0; k < 3; ++k) edges[3 * f + k] = uint64_t(soup[f][k]) << 32 | uint64_t(soup[f][(k + 1) % 3]);
    std::sort(edges.begin(), edges.end());
    if (std::adjacent_find(edges.begin(), edges.end()) != edges.end()) return false;
    for (uint64_t e : edges)
        if (!std::binary_search(edges.begin(), edges.end(), e << 32 | e >> 32)) return false;
    // Closed and edge-manifold: about each vertex the triangles' opposite edges (a -> b for a
    // triangle v, a, b) chain into cycles, each link vertex starting one such edge; one fan is one
    // cycle.
    std::vector<size_t> first(vertices + 1, 0);
    for (const auto& t : soup)
        for (size_t v : t) ++first[v + 1];
    for (size_t v = 0; v < vertices; ++v) first[v + 1] += first[v];
    std::vector<std::pair<size_t, size_t>> link(3 * n);
    std::vector<size_t> at(first.begin(), first.end() - 1);
    for (const auto& t : soup)
        for (int k = 0; k < 3; ++k) link[at[t[k]]++] = {t[(k + 1) % 3], t[(k + 2) % 3]};
    for (size_t v = 0; v < vertices; ++v) {
        const size_t begin = first[v], end = first[v + 1];
        if (begin == end) continue;
        size_t steps = 0, next = link[begin].second;
        while (next != link[begin].first && steps < end - begin) {
            size_t i = begin;
            while (i < end && link[i].first != next) ++i;
            if (i == end) return false;
            next = link[i].second;
            ++steps;
        }
        if (steps + 1 != end - begin) return false;
    }
    return true;
}

bool soup_to_mesh(const std::vector<Point>& points, const Soup& soup, Mesh& mesh) {
    if (closed_triangle_manifold(soup)) {
        PMP::polygon_soup_to_polygon_mesh(points, soup, mesh);
        return true;
    }
    if (!PMP::is_polygon_soup_a_polygon_mesh(soup)) return false;
    PMP::polygon_soup_to_polygon_mesh(points, soup, mesh);
    return CGAL::is_closed(mesh);
}

Mesh cell_mesh(const Cell& cell, const std::vector<Vec3>& pushed, double nudge, const char** why) {
    std::map<uint32_t, size_t> index;
    std::vector<Vec3> at;
    Soup soup;
    for (const Tri& t : cell.triangles) {
        std::array<size_t, 3> f;
        for (int k = 0; k < 3; ++k) {
            auto [it, fresh] = index.emplace(t[k], at.size());
            if (fresh) at.push_back(pushed[t[k]]);
            f[k] = it->second;
        }
        soup.push_back(f);
    }
    std::vector<Point> points;
    for (const Vec3& v : separate_sheets(at, soup, nudge)) points.emplace_back(v.x(), v.y(), v.z());
    Mesh mesh;
    if (!soup_to_mesh(points, soup, mesh))
        *why = "its cell is not a closed surface";
    else if (PMP::does_self_intersect(mesh))
        *why = "its cell self-intersects";
    return mesh;
}

struct Input {
    const TriangleMesh& mesh;
    std::vector<Vec3> corner_normal;
    std::vector<TreeTriangle> triangles;
    TriangleTree tree;
};

std::vector<Vec3> pushed_vertices(const std::vector<Vec3>& vertices, const std::vector<Vec3>& normal, double margin) {
    std::vector<Vec3> out = vertices;
    for (size_t i = 0; i < out.size(); ++i) out[i] += margin * normal[i];
    return out;
}


// The cut result as a render surface (see the file comment for how faces are told apart).
RenderSurface collect(const Mesh& out, const Input& in, const Cell& cell, const std::vector<Vec3>& pushed,
                      double eps) {
    RenderSurface rs;
    std::vector<TreeTriangle> cell_faces;  // the cell's faces, for the nearest one (made when first asked)
    TriangleTree cell_tree;
    std::map<std::tuple<size_t, double, double, double>, uint32_t> index;
    auto corner = [&](size_t v, const Vec3& p, const Vec3& n) {
        auto [it, fresh] = index.emplace(std::make_tuple(v, n.x(), n.y(), n.z()), uint32_t(rs.vertices.size()));
        if (fresh) {
            rs.vertices.push_back(p);
            rs.normals.push_back(n);
        }
        return it->second;
    };
    // A face of the cut that is one of the cell's faces as it was (the corefinement keeps the
    // points of the faces it does not cut, the same doubles) is that face, and takes its kind
    // without the two nearest-face searches below: most of a piece's crack faces lie inside the
    // surface, uncut (with the crack tets split, three quarters of the demo's cut faces). Keyed
    // by the corners' positions in ascending order; a position key two cell faces share is left
    // to the searches.
    using Corners = std::array<double, 9>;
    const auto corners = [](std::array<Vec3, 3> q) {
        const auto before = [](const Vec3& a, const Vec3& b) {
            return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
        };
        std::sort(q.begin(), q.end(), before);
        Corners c;
        for (int i = 0; i < 3; ++i)
            for (int d = 0; d < 3; ++d) c[size_t(3 * i + d)] = q[size_t(i)][d];
        return c;
    };
    std::vector<std::pair<Corners, int>> own;  // kind, or -1 for a key shared
    own.reserve(cell.triangles.size());
    for (size_t i = 0; i < cell.triangles.size(); ++i) {
        const Tri& t = cell.triangles[i];
        own.emplace_back(corners({pushed[t[0]], pushed[t[1]], pushed[t[2]]}), int(cell.kinds[i]));
    }
    std::sort(own.begin(), own.end());
    for (size_t i = 0; i + 1 < own.size(); ++i)
        if (own[i].first == own[i + 1].first) own[i].second = own[i + 1].second = -1;
    const auto own_kind = [&](const std::array<Vec3, 3>& p) {
        const Corners c = corners(p);
        const auto it = std::lower_bound(own.begin(), own.end(), c, [](const auto& e, const Corners& x) { return e.first < x; });
        return it != own.end() && it->first == c ? it->second : -1;
    };
    for (auto f : out.faces()) {
        std::array<size_t, 3> vi;
        std::array<Vec3, 3> p;
        int k = 0;
        for (auto v : CGAL::vertices_around_face(out.halfedge(f), out)) {
            if (k == 3) break;
            vi[k] = size_t(v);
            p[k++] = vec(out.point(v));
        }
        if (k != 3) continue;
        Tri tri;
        if (const int kind = own_kind(p); kind >= 0) {
            Vec3 n = (p[1] - p[0]).cross(p[2] - p[0]);
            n = n.norm() > 0 ? Vec3(n.normalized()) : Vec3(0, 1, 0);
            for (int c = 0; c < 3; ++c) tri[c] = corner(vi[c], p[c], n);
            rs.kinds.push_back(FaceKind(kind));
            rs.triangles.push_back(tri);
            continue;
        }
        const Vec3 centre = (p[0] + p[1] + p[2]) / 3;
        const auto hit = in.tree.closest_point_and_primitive(tree_point(centre));
        const Vec3 q(hit.first.x(), hit.first.y(), hit.first.z());
        if ((q - centre).norm() <= eps) {
            const size_t t = size_t(hit.second - in.triangles.cbegin());
            const Tri& src = in.mesh.triangles[t];
            const auto& iv = in.mesh.vertices;
            for (int c = 0; c < 3; ++c) {
                const Vec3 w = clamped(barycentric(p[c], iv[src[0]], iv[src[1]], iv[src[2]]));
                Vec3 n = w[0] * in.corner_normal[3 * t] + w[1] * in.corner_normal[3 * t + 1] +
                         w[2] * in.corner_normal[3 * t + 2];
                n = n.norm() > 0 ? Vec3(n.normalized()) : Vec3(0, 1, 0);
                tri[c] = corner(vi[c], p[c], n);
            }
            rs.kinds.push_back(FaceKind::Outer);
        } else {
            if (cell_faces.empty()) {
                for (const Tri& ct : cell.triangles)
                    cell_faces.emplace_back(tree_point(pushed[ct[0]]), tree_point(pushed[ct[1]]), tree_point(pushed[ct[2]]));
                cell_tree.rebuild(cell_faces.cbegin(), cell_faces.cend());
                cell_tree.accelerate_distance_queries();
            }
            const auto nearest = cell_tree.closest_point_and_primitive(tree_point(centre));
            const FaceKind kind = cell.kinds[size_t(nearest.second - cell_faces.cbegin())];
            Vec3 n = (p[1] - p[0]).cross(p[2] - p[0]);
            n = n.norm() > 0 ? Vec3(n.normalized()) : Vec3(0, 1, 0);
            for (int c = 0; c < 3; ++c) tri[c] = corner(vi[c], p[c], n);
            rs.kinds.push_back(kind);
        }
        rs.triangles.push_back(tri);
    }
    return rs;
}

}  // namespace

TriangleMesh simplify_surface(const TriangleMesh& surface, size_t max_triangles) {
    if (surface.triangles.size() <= max_triangles) return surface;
    // The collapses down to kRenderSurfaceQuickFactor x max_triangles are meshoptimizer's (fast;
    // it keeps input vertices where CGAL's places new ones, so it stops short of the count).
    const TriangleMesh quick = reduce_surface(surface, size_t(kRenderSurfaceQuickFactor * double(max_triangles)));
    std::vector<Point> points;
    for (const Vec3& v : quick.vertices) points.emplace_back(v.x(), v.y(), v.z());
    Soup soup;
    for (const Tri& t : quick.triangles) soup.push_back({t[0], t[1], t[2]});
    Mesh mesh;
    if (!soup_to_mesh(points, soup, mesh)) {
        // Sheets that touch along an edge or at a vertex (as a first reduction can leave them)
        // are told apart by giving each its own copies of the shared vertices; where an odd
        // number of triangles met at an edge, the border that leaves is closed with a patch.
        mesh.clear();
        PMP::orient_polygon_soup(points, soup);
        if (!PMP::is_polygon_soup_a_polygon_mesh(soup)) return surface;
        PMP::polygon_soup_to_polygon_mesh(points, soup, mesh);
        std::vector<Mesh::Halfedge_index> borders;
        PMP::extract_boundary_cycles(mesh, std::back_inserter(borders));
        for (Mesh::Halfedge_index h : borders) {
            std::vector<Mesh::Face_index> patch;
            PMP::triangulate_hole(mesh, h, std::back_inserter(patch));
        }
        if (!CGAL::is_closed(mesh)) return surface;
    }
    if (!CGAL::is_triangle_mesh(mesh)) return surface;
    // Lindstrom-Turk cost and placement (the default), no collapse that turns a face over (fewer
    // self-intersections for the cut); a closed triangle mesh has 3/2 edges per face.
    namespace SMS = CGAL::Surface_mesh_simplification;
    SMS::Count_stop_predicate<Mesh> stop(max_triangles * 3 / 2);
    SMS::edge_collapse(mesh, stop, CGAL::parameters::filter(SMS::Bounded_normal_change_filter<>()));
    mesh.collect_garbage();
    // The cut (a corefinement) needs a surface that does not cross itself: a surface reduced by
    // meshoptimizer first can (CGAL's repair smooths or refills the faces that do; on a mesh
    // without removed elements: with them it left crossings).
    if (PMP::does_self_intersect(mesh)) {
        PMP::experimental::remove_self_intersections(mesh);
        mesh.collect_garbage();
    }
    TriangleMesh out;
    out.vertices.reserve(mesh.number_of_vertices());
    for (auto v : mesh.vertices()) out.vertices.push_back(vec(mesh.point(v)));
    for (auto f : mesh.faces()) {
        Tri t;
        int k = 0;
        for (auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
            if (k < 3) t[size_t(k++)] = uint32_t(v);
        if (k == 3) out.triangles.push_back(t);
    }
    return out;
}

namespace {

// A surface to cut: its triangles for the nearest-triangle queries, corner normals, and itself as
// a CGAL mesh (`ok`: a closed polygon mesh).
struct Cuttable {
    std::unique_ptr<Input> in;
    Mesh whole;
    bool ok = false;
};

Cuttable cuttable(const TriangleMesh& input, double crease_degrees) {
    Cuttable c;
    c.in.reset(new Input{input, corner_normals(input, crease_degrees), {}, {}});
    Input& in = *c.in;
    in.triangles.reserve(input.triangles.size());
    for (const Tri& t : input.triangles)
        in.triangles.emplace_back(tree_point(input.vertices[t[0]]), tree_point(input.vertices[t[1]]), tree_point(input.vertices[t[2]]));
    in.tree.rebuild(in.triangles.cbegin(), in.triangles.cend());
    in.tree.accelerate_distance_queries();
    std::vector<Point> points;
    for (const Vec3& v : input.vertices) points.emplace_back(v.x(), v.y(), v.z());
    Soup soup;
    for (const Tri& t : input.triangles) soup.push_back({t[0], t[1], t[2]});
    c.ok = !input.triangles.empty() && soup_to_mesh(points, soup, c.whole);
    return c;
}

// corefine_and_compute_intersection(surface, cell); empty with `why` set when it fails.
Mesh cut_cell(const Mesh& whole, Mesh cell, const char** why) {
    Mesh a = whole, cut;
    try {
        if (!PMP::corefine_and_compute_intersection(a, cell, cut)) *why = "the cut failed";
        else if (cut.number_of_faces() == 0) *why = "the cut is empty";
    } catch (const std::exception&) {
        *why = "the cut threw";
    }
    return cut;
}

}  // namespace

std::optional<CrackCells> faired_crack_cells(const Model& model, bool split) {
    if (model.mesh.tets.size() < kCrackFairingTetsPerPiece * model.pieces.size()) {
        spdlog::info("render surfaces: cracks not faired (pieces of {} tets on average, fewer than {})",
                     model.mesh.tets.size() / std::max<size_t>(model.pieces.size(), 1), kCrackFairingTetsPerPiece);
        return std::nullopt;
    }
    const TetTopology topo = build_topology(model.mesh);
    CrackFairingSettings settings;
    settings.split_tets = split;
    return crack_cells(model.mesh, topo, model.tet_piece, boundary_kinds(model, topo, cells_of(model, topo)), settings);
}

std::vector<RenderSurface> render_surfaces(const TriangleMesh& input, const Model& model,
                                           const RenderSurfaceSettings& settings, const TriangleMesh* retry,
                                           const std::optional<CrackCells>* faired_given) {
    const TetTopology topo = build_topology(model.mesh);
    Workers workers(default_threads());  // the pieces' cells and cuts are independent of each other
    Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
    for (const Vec3& v : input.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    const double eps = 1e-7 * (hi - lo).norm();
    // Faired cracks (crack_fairing.h): the cells cut from the tets by the smoothed piece field,
    // their points placed from the tet vertices wherever those are (pushed out below), so that
    // the two sides of a crack stay one surface. Otherwise the cells are the tet surfaces.
    const std::vector<Cell> tet_cells = cells_of(model, topo);
    std::vector<Cell> cells = tet_cells;
    std::optional<CrackCells> faired;
    if (settings.fair_cracks && faired_given) faired = *faired_given;
    // The surface's index, and the faired cells when not given, one beside the other.
    std::optional<Cuttable> made;
    workers.both([&] { made = cuttable(input, settings.crease_degrees); },
                 [&] {
                     if (settings.fair_cracks && !faired_given) faired = faired_crack_cells(model, settings.split_cracks);
                 });
    const Cuttable first = std::move(*made);
    const bool input_ok = first.ok;
    std::optional<Cuttable> second;  // `retry`, made when first needed
    if (faired) {
        spdlog::debug("render surfaces: cracks faired: {} tets cut, {} points ({} not fixed by their name), {} rounds "
                      "of the volume fit, {} pieces held inside, {} cells open", faired->cut_tets, faired->points.size(),
                      faired->degenerate, faired->fit_rounds, faired->held, faired->open);
        if (faired->open > 0) {
            // All or none: a piece on its tet faces beside a faired neighbour would gape.
            spdlog::info("render surfaces: cracks not faired ({} of {} faired cells do not close), the tet faces "
                         "between the pieces kept", faired->open, model.pieces.size());
            faired.reset();
        } else {
            for (size_t p = 0; p < cells.size() && p < faired->triangles.size(); ++p)
                cells[p] = Cell{faired->triangles[p], faired->kinds[p]};
        }
    }
    const auto placed = [&](std::vector<Vec3> vertices) {
        if (!faired) return vertices;
        std::vector<Vec3> x = faired->place(vertices);
        roughen_cracks(*faired, x, settings.roughness, settings.roughness_scale, settings.roughness_seed);
        return x;
    };

    // The largest margin of the ladder at which every cell is a valid closed surface (fewest
    // failures otherwise, the larger margin on a tie).
    const std::vector<Vec3> normal = outer_normals(model.mesh.vertices, tet_cells);
    const double nudge = 1e-5 * (hi - lo).norm();
    std::vector<Vec3> pushed;
    std::vector<Mesh> cell(model.pieces.size());
    std::vector<const char*> why(model.pieces.size());
    size_t best_failures = SIZE_MAX;
    for (double factor : {1.0, 0.7, 0.5, 0.35}) {
        std::vector<Vec3> try_pushed = placed(pushed_vertices(model.mesh.vertices, normal, factor * settings.margin));
        std::vector<Mesh> try_cell(model.pieces.size());
        std::vector<const char*> try_why(model.pieces.size(), input_ok ? nullptr : "the input is not a closed polygon mesh");
        workers.run(model.pieces.size(), 1, [&](size_t p) {
            if (!try_why[p]) try_cell[p] = cell_mesh(cells[p], try_pushed, nudge, &try_why[p]);
        });
        const size_t failures = size_t(std::count_if(try_why.begin(), try_why.end(), [](const char* w) { return w; }));
        if (failures < best_failures) {
            best_failures = failures;
            pushed = std::move(try_pushed), cell = std::move(try_cell), why = std::move(try_why);
            if (failures > 0) spdlog::debug("render surfaces: margin {:.4g} m leaves {} bad cells", factor * settings.margin, failures);
        }
        if (failures == 0 || !input_ok) break;
    }

    // Each piece's cut on its own (on every core), then the rare second cuts one by one (they
    // share the full surface, made when first needed), then the results collected.
    std::vector<Mesh> cut(model.pieces.size());
    std::vector<const Input*> in(model.pieces.size(), first.in.get());
    workers.run(model.pieces.size(), 1, [&](size_t p) {
        if (!why[p]) cut[p] = cut_cell(first.whole, cell[p], &why[p]);
    });
    size_t retried = 0;
    for (size_t p = 0; p < model.pieces.size(); ++p) {
        if (why[p] && retry && input_ok && std::string_view(why[p]) != "its cell is not a closed surface" &&
            std::string_view(why[p]) != "its cell self-intersects") {
            // The cut failed on `input` (a simplified surface can cross itself where the cell
            // cuts it): the same cell on the surface it was simplified from.
            if (!second) second = cuttable(*retry, settings.crease_degrees);
            spdlog::debug("render surface of piece {}: {} on the simplified surface; cut again from the full one", p, why[p]);
            why[p] = nullptr;
            if (second->ok) cut[p] = cut_cell(second->whole, cell[p], &why[p]);
            else why[p] = "the full surface is not a closed polygon mesh";
            in[p] = second->in.get();
            ++retried;
        }
    }
    std::vector<RenderSurface> out(model.pieces.size());
    workers.run(model.pieces.size(), 1, [&](size_t p) {
        if (!why[p]) out[p] = collect(cut[p], *in[p], cells[p], pushed, eps);
    });
    size_t fell_back = 0;
    std::optional<std::vector<Vec3>> unpushed;  // the cells' points at the tet vertices, made when first needed
    for (size_t p = 0; p < model.pieces.size(); ++p) {
        if (!why[p]) continue;
        // Its cell, flat: the tet surface, with the faired cracks when they are (so that its
        // neighbours' cracks still meet its own).
        spdlog::debug("render surface of piece {}: the tet surface ({})", p, why[p]);
        if (!unpushed) unpushed = placed(model.mesh.vertices);
        out[p] = flat_render_surface(cell_surface(cells[p], *unpushed));
        ++fell_back;
    }
    if (retried) spdlog::info("render surfaces: {} of {} pieces cut from the full surface (the simplified one failed)", retried, out.size());
    if (fell_back && faired) {
        // All or none, as for open cells: a piece left on its cell is not the surface it stands
        // for (and its outside may be replaced by the input's triangles), where the tet faces'
        // cells may all cut.
        spdlog::info("render surfaces: cracks not faired ({} of {} pieces not cut with faired cells), the tet faces "
                     "between the pieces kept", fell_back, out.size());
        RenderSurfaceSettings unfaired = settings;
        unfaired.fair_cracks = false;
        return render_surfaces(input, model, unfaired, retry);
    }
    if (fell_back) spdlog::info("render surfaces: {} of {} pieces keep their tet surface", fell_back, out.size());
    return out;
}

}  // namespace shatter
