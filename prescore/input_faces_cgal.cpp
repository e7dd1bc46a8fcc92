// The input's own triangles as the pieces' outer faces (render_surface.h, use_input_faces): each
// input triangle goes to the piece whose tet holds its centre (a uniform grid over the tets), or,
// outside every tet, to the piece of the nearest boundary face of the tet mesh (a CGAL AABB tree:
// the one CGAL feature of this file). A triangle whose corners and centre do not all lie in one
// piece is split at its edges' midpoints until they do or it is smaller than a fraction of a tet,
// level by level over all triangles, within a budget.
#include <cmath>
#include <map>
#include <tuple>

#include "prescore/render_surface.h"
#include "prescore/tet_topology.h"
#include "prescore/triangle_tree_cgal.h"

namespace shatter {

namespace {

// Which piece a point lies in: the tet that holds it, else the nearest boundary face's piece.
class PieceLocator {
public:
    explicit PieceLocator(const Model& model) : model_(model) {
        const TetMesh& mesh = model.mesh;
        lo_ = Vec3::Constant(1e300);
        Vec3 hi = Vec3::Constant(-1e300);
        for (const Vec3& v : mesh.vertices) lo_ = lo_.cwiseMin(v), hi = hi.cwiseMax(v);
        const Vec3 size = (hi - lo_).cwiseMax(1e-12);
        // About one tet per grid cell.
        cell_ = std::cbrt(size.prod() / double(std::max<size_t>(mesh.tets.size(), 1)));
        cell_ = std::max(cell_, size.maxCoeff() / 256);
        for (int a = 0; a < 3; ++a) n_[a] = std::max(1, int(std::ceil(size[a] / cell_)));
        bins_.resize(size_t(n_[0]) * size_t(n_[1]) * size_t(n_[2]));
        inverse_.resize(mesh.tets.size());
        for (uint32_t t = 0; t < mesh.tets.size(); ++t) {
            const Tet& k = mesh.tets[t];
            const Vec3& a = mesh.vertices[k[0]];
            Mat3 e;
            e.col(0) = mesh.vertices[k[1]] - a, e.col(1) = mesh.vertices[k[2]] - a, e.col(2) = mesh.vertices[k[3]] - a;
            inverse_[t] = e.inverse();
            Vec3 tlo = a, thi = a;
            for (int i = 1; i < 4; ++i) tlo = tlo.cwiseMin(mesh.vertices[k[i]]), thi = thi.cwiseMax(mesh.vertices[k[i]]);
            const std::array<int, 3> b0 = bin(tlo), b1 = bin(thi);
            for (int x = b0[0]; x <= b1[0]; ++x)
                for (int y = b0[1]; y <= b1[1]; ++y)
                    for (int z = b0[2]; z <= b1[2]; ++z) bins_[index(x, y, z)].push_back(t);
        }
        const TetTopology topo = build_topology(mesh);
        for (uint32_t t = 0; t < mesh.tets.size(); ++t)
            for (int f = 0; f < 4; ++f) {
                if (topo.neighbour[t][f] >= 0) continue;
                const Tet& k = mesh.tets[t];
                const auto& face = kTetFaces[size_t(f)];
                outer_.emplace_back(tree_point(mesh.vertices[k[size_t(face[0])]]),
                                    tree_point(mesh.vertices[k[size_t(face[1])]]),
                                    tree_point(mesh.vertices[k[size_t(face[2])]]));
                outer_piece_.push_back(model.tet_piece[t]);
            }
        tree_.rebuild(outer_.cbegin(), outer_.cend());
        tree_.accelerate_distance_queries();
    }

    uint32_t piece(const Vec3& p) const {
        const TetMesh& mesh = model_.mesh;
        const std::array<int, 3> b = bin(p);
        constexpr double kInside = -1e-9;  // barycentric slack: a point on a shared face takes the lower tet
        for (uint32_t t : bins_[index(b[0], b[1], b[2])]) {
            const Vec3 w = inverse_[t] * (p - mesh.vertices[mesh.tets[t][0]]);
            if (w.minCoeff() >= kInside && 1 - w.sum() >= kInside) return model_.tet_piece[t];
        }
        const auto hit = tree_.closest_point_and_primitive(tree_point(p));
        return outer_piece_[size_t(hit.second - outer_.cbegin())];
    }

private:
    std::array<int, 3> bin(const Vec3& p) const {
        std::array<int, 3> b;
        for (int a = 0; a < 3; ++a) b[size_t(a)] = std::clamp(int(std::floor((p[a] - lo_[a]) / cell_)), 0, n_[a] - 1);
        return b;
    }
    size_t index(int x, int y, int z) const { return (size_t(z) * size_t(n_[1]) + size_t(y)) * size_t(n_[0]) + size_t(x); }

    const Model& model_;
    Vec3 lo_;
    double cell_ = 1;
    std::array<int, 3> n_{};
    std::vector<std::vector<uint32_t>> bins_;
    std::vector<Mat3> inverse_;
    std::vector<TreeTriangle> outer_;
    std::vector<uint32_t> outer_piece_;
    TriangleTree tree_;
};

// A piece's render surface under construction: vertices shared by position and normal.
struct Builder {
    RenderSurface rs;
    std::map<std::tuple<double, double, double, double, double, double>, uint32_t> index;

    uint32_t vertex(const Vec3& p, const Vec3& n) {
        auto [it, fresh] = index.emplace(std::make_tuple(p.x(), p.y(), p.z(), n.x(), n.y(), n.z()),
                                         uint32_t(rs.vertices.size()));
        if (fresh) rs.vertices.push_back(p), rs.normals.push_back(n);
        return it->second;
    }
    void triangle(const std::array<Vec3, 3>& p, const std::array<Vec3, 3>& n, FaceKind kind) {
        rs.triangles.push_back({vertex(p[0], n[0]), vertex(p[1], n[1]), vertex(p[2], n[2])});
        rs.kinds.push_back(kind);
    }
};

Vec3 unit_or(const Vec3& v, const Vec3& fallback) { return v.norm() > 0 ? Vec3(v.normalized()) : fallback; }

}  // namespace

InputFacesReport use_input_faces(std::vector<RenderSurface>& surfaces, const TriangleMesh& input, const Model& model,
                                 double tet_size, double crease_degrees, bool double_sided, double rim_inset,
                                 const std::vector<char>* only) {
    InputFacesReport report;
    if (input.triangles.empty() || model.mesh.tets.empty() || surfaces.size() != model.pieces.size()) return report;
    if (only && only->size() != surfaces.size()) return report;
    const auto wanted = [&](uint32_t piece) { return !only || (*only)[piece]; };
    const PieceLocator locate(model);
    const std::vector<Vec3> corner_normal = corner_normals(input, crease_degrees);
    std::vector<Builder> built(surfaces.size());
    const double smallest = kInputFaceSplit * tet_size;
    // The triangles are split level by level, every one that straddles pieces at once, while the
    // parts stay within this many (a budget: past it, the rest go whole by their centre).
    const size_t budget = kInputFaceBudget * std::max<size_t>(input.triangles.size(), kRenderSurfaceTriangles);

    struct Node {
        std::array<Vec3, 3> p, n;
        uint32_t piece = 0;     // of its centre
        bool straddles = false; // a corner lies in another piece, and it is larger than `smallest`
    };
    const auto examine = [&](Node& node) {
        node.piece = locate.piece((node.p[0] + node.p[1] + node.p[2]) / 3);
        double longest = 0;
        bool one = true, any = wanted(node.piece);
        for (int c = 0; c < 3; ++c) {
            longest = std::max(longest, (node.p[(c + 1) % 3] - node.p[c]).norm());
            const uint32_t corner = locate.piece(node.p[c]);
            one = one && corner == node.piece;
            any = any || wanted(corner);
        }
        node.straddles = !one && any && longest > smallest;
    };
    const auto place = [&](const Node& node) {
        if (!wanted(node.piece)) return;
        ++report.leaves;
        built[node.piece].triangle(node.p, node.n, FaceKind::Outer);
        if (double_sided)
            built[node.piece].triangle({node.p[0], node.p[2], node.p[1]},
                                       {Vec3(-node.n[0]), Vec3(-node.n[2]), Vec3(-node.n[1])}, FaceKind::Outer);
    };

    std::vector<Node> level;
    for (size_t t = 0; t < input.triangles.size(); ++t) {
        const Tri& tri = input.triangles[t];
        Node node;
        for (int c = 0; c < 3; ++c) node.p[c] = input.vertices[tri[c]], node.n[c] = corner_normal[3 * t + size_t(c)];
        if (!((node.p[1] - node.p[0]).cross(node.p[2] - node.p[0]).norm() > 0)) continue;  // no area
        examine(node);
        level.push_back(node);
    }
    std::vector<Node> next;
    while (!level.empty()) {
        size_t straddling = 0;
        for (const Node& node : level) straddling += node.straddles;
        const bool split = report.leaves + level.size() + 3 * straddling <= budget;
        next.clear();
        for (const Node& node : level) {
            if (!split || !node.straddles) {
                place(node);
                continue;
            }
            std::array<Vec3, 3> mp, mn;
            for (int c = 0; c < 3; ++c) {
                const int d = (c + 1) % 3;
                mp[c] = (node.p[c] + node.p[d]) / 2;
                mn[c] = unit_or(node.n[c] + node.n[d], node.n[c]);
            }
            const std::array<Node, 4> four = {Node{{node.p[0], mp[0], mp[2]}, {node.n[0], mn[0], mn[2]}},
                                              Node{{mp[0], node.p[1], mp[1]}, {mn[0], node.n[1], mn[1]}},
                                              Node{{mp[2], mp[1], node.p[2]}, {mn[2], mn[1], node.n[2]}},
                                              Node{{mp[0], mp[1], mp[2]}, {mn[0], mn[1], mn[2]}}};
            for (Node part : four) {
                examine(part);
                next.push_back(part);
            }
            ++report.split;
        }
        level.swap(next);
    }

    // The outer faces of every piece, for the fracture vertices near them (below; only when the
    // rims move in).
    std::vector<TreeTriangle> outer;
    std::vector<Vec3> outer_normal;
    for (const RenderSurface& rs : surfaces)
        for (size_t t = 0; t < rs.triangles.size() && rim_inset > 0; ++t) {
            if (rs.kinds[t] != FaceKind::Outer) continue;
            const Vec3 &a = rs.vertices[rs.triangles[t][0]], &b = rs.vertices[rs.triangles[t][1]],
                       &c = rs.vertices[rs.triangles[t][2]];
            outer.emplace_back(tree_point(a), tree_point(b), tree_point(c));
            outer_normal.push_back(unit_or((b - a).cross(c - a), Vec3::Zero()));
        }
    TriangleTree outer_tree(outer.cbegin(), outer.cend());
    if (!outer.empty()) outer_tree.accelerate_distance_queries();

    for (size_t p = 0; p < surfaces.size(); ++p) {
        Builder& b = built[p];
        if (!wanted(uint32_t(p))) continue;
        if (b.rs.triangles.empty()) {  // no input triangle lies in this piece: it keeps its outer faces
            ++report.kept;
            continue;
        }
        const RenderSurface& old = surfaces[p];
        // The fracture faces' rim (their vertices on the wrap's outer faces) moves in along the
        // wrap's normal there, under the input.
        std::map<std::tuple<double, double, double>, Vec3> rim;
        for (size_t t = 0; t < old.triangles.size(); ++t)
            if (old.kinds[t] == FaceKind::Outer)
                for (uint32_t v : old.triangles[t]) {
                    const Vec3& x = old.vertices[v];
                    rim.emplace(std::make_tuple(x.x(), x.y(), x.z()), old.normals[v]);
                }
        for (size_t t = 0; t < old.triangles.size(); ++t) {
            if (old.kinds[t] == FaceKind::Outer) continue;
            const Tri& o = old.triangles[t];
            std::array<Vec3, 3> x;
            for (int c = 0; c < 3; ++c) {
                x[c] = old.vertices[o[c]];
                const auto it = rim.find(std::make_tuple(x[c].x(), x[c].y(), x[c].z()));
                if (it != rim.end()) {
                    x[c] -= rim_inset * it->second;
                } else if (!outer.empty()) {
                    // A fracture vertex inside the wrap but nearer its outer faces than the rim's
                    // inset (a crack that runs close under them) goes as deep, so that it too
                    // stays under the input; both sides of the crack move it alike.
                    const auto hit = outer_tree.closest_point_and_primitive(tree_point(x[c]));
                    const Vec3 q(hit.first.x(), hit.first.y(), hit.first.z());
                    const double d = (x[c] - q).norm();
                    if (d < rim_inset) x[c] -= (rim_inset - d) * outer_normal[size_t(hit.second - outer.cbegin())];
                }
            }
            b.triangle(x, {old.normals[o[0]], old.normals[o[1]], old.normals[o[2]]}, old.kinds[t]);
        }
        b.rs.fell_back = old.fell_back;
        surfaces[p] = std::move(b.rs);
        ++report.pieces;
    }
    return report;
}

}  // namespace shatter
