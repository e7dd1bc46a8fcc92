// Faired cracks: the smoothed piece field and the cells it cuts from the tets (the design is in
// crack_fairing.h).
#include "prescore/crack_fairing.h"

#include "prescore/crack_refinement.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>
#include <utility>

#include <Eigen/LU>


namespace shatter {

namespace {

// The piece field, sparse: per vertex its pieces (ascending) and their weights.
struct Field {
    std::vector<uint32_t> start;  // vertex v's entries: [start[v], start[v + 1])
    std::vector<uint32_t> piece;
    std::vector<double> value;

    double at(uint32_t v, uint32_t p) const {
        for (uint32_t i = start[v]; i < start[v + 1]; ++i)
            if (piece[i] == p) return value[i];
        return 0;
    }
};

// (vertex, piece, value) entries summed per vertex and piece into a field; values below `drop`
// in size are left out (they decide nothing).
Field field_of(size_t vertices, std::vector<std::tuple<uint32_t, uint32_t, double>> entries, double drop) {
    std::sort(entries.begin(), entries.end(),
              [](const auto& a, const auto& b) { return std::tie(std::get<0>(a), std::get<1>(a)) < std::tie(std::get<0>(b), std::get<1>(b)); });
    Field f;
    f.start.assign(vertices + 1, 0);
    for (size_t i = 0; i < entries.size();) {
        const auto [v, p, first] = entries[i];
        double sum = first;
        size_t j = i + 1;
        for (; j < entries.size() && std::get<0>(entries[j]) == v && std::get<1>(entries[j]) == p; ++j) sum += std::get<2>(entries[j]);
        if (std::abs(sum) >= drop) f.piece.push_back(p), f.value.push_back(sum), ++f.start[v + 1];
        i = j;
    }
    for (size_t v = 0; v < vertices; ++v) f.start[v + 1] += f.start[v];
    return f;
}

// How a piece that loses too much volume is held: its vertices' fields are smoothed over sigma / 2,
// then sigma / 4; at the last level its inner vertices (whose tets are all its own) are its alone.
constexpr int kHeldLevels = 3;

// The most a piece's field scale changes in one round of the volume fit (a factor of e^0.4).
constexpr double kFitStep = 0.4;

// The Gaussian-weighted piece shares around any point: the tets reached from `start` through
// their faces (so not across a gap) whose centres lie within 2 width of x, each weighted by its
// volume times G(distance); `sums` gets (piece, weight) in first-reached order, and the total
// is returned (0 when nothing was reached).
class Neighbourhood {
public:
    Neighbourhood(const TetMesh& mesh, const TetTopology& topo, const std::vector<uint32_t>& tet_piece)
        : topo_(topo), tet_piece_(tet_piece), seen_(mesh.tets.size(), UINT32_MAX) {
        tets_of.resize(mesh.vertices.size());
        for (uint32_t t = 0; t < mesh.tets.size(); ++t)
            for (uint32_t v : mesh.tets[t]) tets_of[v].push_back(t);
        centre_.resize(mesh.tets.size());
        volume_.resize(mesh.tets.size());
        for (size_t t = 0; t < mesh.tets.size(); ++t) {
            const Tet& k = mesh.tets[t];
            centre_[t] = tet_centroid(mesh, uint32_t(t));
            volume_[t] = tet_volume(mesh.vertices[k[0]], mesh.vertices[k[1]], mesh.vertices[k[2]], mesh.vertices[k[3]]);
        }
    }

    std::vector<std::vector<uint32_t>> tets_of;  // per vertex

    // The tets reached; true when they are all one piece's.
    bool reach(const Vec3& x, const std::vector<uint32_t>& start, double width) {
        ++stamp_;
        reach_.clear();
        for (uint32_t t : start)
            if (seen_[t] != stamp_) seen_[t] = stamp_, reach_.push_back(t);
        bool alike = true;
        for (size_t k = 0; k < reach_.size(); ++k) {
            const uint32_t t = reach_[k];
            alike = alike && tet_piece_[t] == tet_piece_[reach_.front()];
            for (int i = 0; i < 4; ++i) {
                const int32_t u = topo_.neighbour[t][i];
                if (u < 0 || seen_[u] == stamp_) continue;
                seen_[u] = stamp_;
                if ((centre_[u] - x).norm() < 2 * width) reach_.push_back(uint32_t(u));
            }
        }
        return alike;
    }

    // The shares over the tets `reach` found.
    double shares(const Vec3& x, double width, std::vector<std::pair<uint32_t, double>>& sums) const {
        sums.clear();
        double total = 0;
        for (uint32_t t : reach_) {
            const double d = (centre_[t] - x).norm() / width;
            const double w = volume_[t] * std::exp(-0.5 * d * d);
            total += w;
            auto it = std::find_if(sums.begin(), sums.end(), [&](const auto& e) { return e.first == tet_piece_[t]; });
            if (it == sums.end()) sums.emplace_back(tet_piece_[t], w);
            else it->second += w;
        }
        return total;
    }

    uint32_t first_piece() const { return tet_piece_[reach_.front()]; }

private:
    const TetTopology& topo_;
    const std::vector<uint32_t>& tet_piece_;
    std::vector<Vec3> centre_;
    std::vector<double> volume_;
    std::vector<uint32_t> seen_;
    uint32_t stamp_ = 0;
    std::vector<uint32_t> reach_;
};

// The most a piece around vertex v is held (kHeldLevels), and whether its tets are all one piece's.
std::pair<int, bool> held_at(const Neighbourhood& hood, const std::vector<uint32_t>& tet_piece, uint32_t v,
                             const std::vector<char>& held_piece) {
    const uint32_t first = tet_piece[hood.tets_of[v].front()];
    bool one = true;
    int held = 0;
    for (uint32_t t : hood.tets_of[v]) {
        one = one && tet_piece[t] == first;
        held = std::max<int>(held, held_piece[tet_piece[t]]);
    }
    return {held, one};
}

// chi_p(v): the share of piece p in a Gaussian-weighted neighbourhood of v (width sigma), over
// the tets reached from v's own through their faces (so not across a gap) whose centres lie
// within 2 sigma, each weighted by its volume; narrower around the pieces `held` (kHeldLevels).
Field piece_field(const TetMesh& mesh, Neighbourhood& hood, const std::vector<uint32_t>& tet_piece, double sigma,
                  const std::vector<char>& held_piece) {
    const size_t nv = mesh.vertices.size();
    std::vector<std::tuple<uint32_t, uint32_t, double>> entries;
    std::vector<std::pair<uint32_t, double>> sums;  // per piece in reach
    for (uint32_t v = 0; v < nv; ++v) {
        if (hood.tets_of[v].empty()) continue;
        const auto [held, one] = held_at(hood, tet_piece, v, held_piece);
        if (one && held >= kHeldLevels) {
            entries.emplace_back(v, tet_piece[hood.tets_of[v].front()], 1.0);
            continue;
        }
        const double width = sigma / double(1 << held);
        // One piece within reach: chi is that piece's alone.
        if (hood.reach(mesh.vertices[v], hood.tets_of[v], width)) {
            entries.emplace_back(v, hood.first_piece(), 1.0);
            continue;
        }
        const double total = hood.shares(mesh.vertices[v], width, sums);
        for (const auto& [p, w] : sums) entries.emplace_back(v, p, w / total);
    }
    return field_of(nv, std::move(entries), 1e-9);
}

// Piece weights closer than this are tied (their difference is rounding: where the field is
// zero, a name's weights carry 1e-21 for 0).
constexpr double kTie = 1e-12;

// What defines a point of the arrangement: the simplex that holds it and the pieces tied there
// (none for a tet vertex); `alone` numbers a point its name does not fix (it is its tet's).
struct Name {
    std::array<uint32_t, 4> vertex{};
    std::array<uint32_t, 4> piece{};
    uint8_t vertices = 0, pieces = 0;
    uint32_t alone = 0;
    bool operator<(const Name& o) const {
        return std::tie(vertices, vertex, pieces, piece, alone) < std::tie(o.vertices, o.vertex, o.pieces, o.piece, o.alone);
    }
};

// A vertex of one piece's polyhedron in one tet: its point and the planes it lies on (bits 0-3:
// the tet's faces, face i opposite vertex i; bit 4 + j: the plane chi_p = chi_{labels[j]}).
struct PolyVertex {
    uint32_t point;
    uint32_t planes;
};
struct PolyFace {
    uint32_t plane;               // bit index, as above
    std::vector<uint32_t> around; // indices into the polyhedron's vertices, outward (counter-clockwise)
};

class Arrangement {
public:
    Arrangement(const CrackRefinement& fine, const std::vector<uint32_t>& tet_piece, const Field& field, size_t pieces)
        : mesh_(fine.mesh), fine_(fine), tet_piece_(tet_piece), field_(field),
          vertex_point_(fine.mesh.vertices.size(), UINT32_MAX) {
        out_.triangles.resize(pieces);
        out_.kinds.resize(pieces);
        out_.across.resize(pieces);
    }

    CrackCells run() {
        for (uint32_t t = 0; t < mesh_.tets.size(); ++t) cut_tet(t);
        return std::move(out_);
    }

private:
    const TetMesh& mesh_;
    const CrackRefinement& fine_;
    const std::vector<uint32_t>& tet_piece_;
    const Field& field_;
    CrackCells out_;
    std::map<Name, uint32_t> index_;  // the points of more than one vertex
    std::vector<Name> names_;
    std::vector<uint32_t> vertex_point_;  // per tet-mesh vertex: its point, once it has one
    uint32_t alone_ = 0;
    std::vector<std::pair<std::pair<uint32_t, uint32_t>, uint32_t>> cuts_;  // clip's, kept between calls
    std::vector<std::pair<uint32_t, uint32_t>> cap_next_;
    // The tet being cut: its vertices and the pieces positive at one of them.
    Tet tet_{};
    std::vector<uint32_t> labels_;

    double chi(uint32_t point, uint32_t p) const {
        const CrackPoint& x = out_.points[point];
        double sum = 0;
        for (int k = 0; k < x.count; ++k) sum += x.weight[k] * field_.at(x.vertex[k], p);
        return sum;
    }

    uint32_t add(const Name& name, const CrackPoint& point) {
        auto [it, fresh] = index_.emplace(name, uint32_t(out_.points.size()));
        if (fresh) out_.points.push_back(point), names_.push_back(name);
        return it->second;
    }

    // The weights its name gives a point (sum w = 1, the named pieces tied); false when they do
    // not fix one within its simplex.
    bool weights(const Name& n, CrackPoint& x) const {
        x.count = n.vertices;
        x.vertex = n.vertex;
        if (n.vertices == 1) {
            x.weight = {1, 0, 0, 0};
            return true;
        }
        const int c = n.vertices;
        Eigen::MatrixXd m(c, c);
        Eigen::VectorXd rhs = Eigen::VectorXd::Zero(c);
        rhs(0) = 1;
        for (int i = 0; i < c; ++i) {
            m(0, i) = 1;
            for (int j = 1; j < c; ++j) m(j, i) = field_.at(n.vertex[i], n.piece[0]) - field_.at(n.vertex[i], n.piece[j]);
        }
        const Eigen::FullPivLU<Eigen::MatrixXd> lu(m);
        if (!lu.isInvertible()) return false;
        const Eigen::VectorXd w = lu.solve(rhs);
        double sum = 0;
        for (int i = 0; i < c; ++i) {
            if (!std::isfinite(w(i)) || w(i) < -1e-6 || w(i) > 1 + 1e-6) return false;
            x.weight[i] = std::clamp(w(i), 0.0, 1.0);
            sum += x.weight[i];
        }
        for (int i = 0; i < c; ++i) x.weight[i] /= sum;
        return true;
    }

    uint32_t corner(int k) { return vertex_point(tet_[k]); }

    uint32_t vertex_point(uint32_t v) {
        if (vertex_point_[v] != UINT32_MAX) return vertex_point_[v];
        Name n;
        n.vertex[0] = v;
        n.vertices = 1;
        CrackPoint x;
        weights(n, x);
        vertex_point_[v] = uint32_t(out_.points.size());
        out_.points.push_back(x), names_.push_back(n);
        return vertex_point_[v];
    }

    // The point on the polyhedron edge a-b where plane `bit` cuts it, in piece p's polyhedron.
    uint32_t cut_point(const PolyVertex& a, const PolyVertex& b, uint32_t bit, uint32_t p, uint32_t r) {
        const uint32_t planes = (a.planes & b.planes) | (1u << bit);
        Name n;
        for (int k = 0; k < 4; ++k)
            if (!(planes & (1u << k))) n.vertex[n.vertices++] = tet_[k];
        std::sort(n.vertex.begin(), n.vertex.begin() + n.vertices);
        std::vector<uint32_t> tied;
        for (size_t j = 0; j < labels_.size(); ++j)
            if (planes & (1u << (4 + j))) tied.push_back(labels_[j]);
        tied.push_back(p);
        std::sort(tied.begin(), tied.end());
        CrackPoint x;
        if (tied.size() == n.vertices && n.vertices >= 2) {
            for (size_t j = 0; j < tied.size(); ++j) n.piece[j] = tied[j];
            n.pieces = uint8_t(tied.size());
            if (weights(n, x)) return add(n, x);
        }
        // Not fixed by its name: where the edge crosses the plane, this tet's own.
        const double da = chi(a.point, p) - chi(a.point, r), db = chi(b.point, p) - chi(b.point, r);
        const double s = std::abs(da - db) > 0 ? std::clamp(da / (da - db), 0.0, 1.0) : 0.5;
        std::array<double, 4> w{};
        for (const auto& [end, f] : {std::pair{a.point, 1 - s}, std::pair{b.point, s}}) {
            const CrackPoint& e = out_.points[end];
            for (int k = 0; k < e.count; ++k)
                for (int i = 0; i < 4; ++i)
                    if (tet_[i] == e.vertex[k]) w[i] += f * e.weight[k];
        }
        Name own;
        own.alone = ++alone_;
        std::array<std::pair<uint32_t, double>, 4> by_id;
        for (int i = 0; i < 4; ++i) by_id[i] = {tet_[i], w[i]};
        std::sort(by_id.begin(), by_id.end());
        x.count = 4;
        for (int i = 0; i < 4; ++i) x.vertex[i] = by_id[i].first, x.weight[i] = by_id[i].second;
        ++out_.degenerate;
        return add(own, x);
    }

    // Which side of chi_p = chi_r a vertex is on: +1 kept, 0 on it, -1 cut away. A named point is
    // tested with its lowest tied piece (the same test in every tet and piece that meets it); a
    // difference within kTie is a tie, and goes to the lower of p and r.
    int side(const PolyVertex& v, uint32_t bit, uint32_t p, uint32_t r) const {
        if (v.planes & (1u << bit)) return 0;
        const Name& n = names_[v.point];
        const uint32_t s = n.pieces > 0 ? n.piece[0] : p;
        const double d = chi(v.point, s) - chi(v.point, r);
        return d > kTie ? 1 : d < -kTie ? -1 : (p < r ? 1 : -1);
    }

    // Piece p's polyhedron clipped by chi_p >= chi_{labels_[j]}; false when nothing is left.
    bool clip(std::vector<PolyVertex>& verts, std::vector<PolyFace>& faces, size_t j, uint32_t p) {
        const uint32_t bit = uint32_t(4 + j), r = labels_[j];
        std::vector<int> sides(verts.size());
        bool any_in = false, any_out = false;
        for (size_t i = 0; i < verts.size(); ++i) {
            sides[i] = side(verts[i], bit, p, r);
            any_in |= sides[i] > 0, any_out |= sides[i] < 0;
        }
        if (!any_out) return true;
        if (!any_in) return false;
        // (A polyhedron has a dozen vertices: its small lookups are vectors searched in turn.)
        const auto local = [&](uint32_t point) {  // the index in verts of a point, or verts.size()
            size_t i = 0;
            while (i < verts.size() && verts[i].point != point) ++i;
            return uint32_t(i);
        };
        auto vertex_of = [&](uint32_t point, uint32_t planes) {
            const uint32_t i = local(point);
            if (i == verts.size()) verts.push_back({point, planes}), sides.push_back(0);
            return i;
        };
        cuts_.clear();  // (kept end, cut end) -> point: once per edge
        std::vector<PolyFace> kept;
        cap_next_.clear();  // the cap's edges, from -> to (each from once)
        bool broken = false;
        for (const PolyFace& f : faces) {
            PolyFace g{f.plane, {}};
            std::vector<char> on;
            const size_t n = f.around.size();
            for (size_t k = 0; k < n; ++k) {
                const uint32_t a = f.around[k], b = f.around[(k + 1) % n];
                if (sides[a] >= 0) g.around.push_back(a), on.push_back(sides[a] == 0);
                if ((sides[a] > 0 && sides[b] < 0) || (sides[a] < 0 && sides[b] > 0)) {
                    const PolyVertex va = verts[a], vb = verts[b];
                    const PolyVertex& in = sides[a] > 0 ? va : vb;
                    const PolyVertex& out = sides[a] > 0 ? vb : va;
                    auto cut = std::find_if(cuts_.begin(), cuts_.end(), [&](const auto& c) {
                        return c.first == std::make_pair(in.point, out.point);
                    });
                    if (cut == cuts_.end()) {
                        const uint32_t made = cut_point(in, out, bit, p, r);
                        cuts_.emplace_back(std::make_pair(in.point, out.point), made);
                        cut = cuts_.end() - 1;
                    }
                    const uint32_t x = cut->second;
                    g.around.push_back(vertex_of(x, (va.planes & vb.planes) | (1u << bit)));
                    on.push_back(1);
                }
            }
            if (g.around.size() < 3) continue;
            // The face's edge on the plane (two consecutive vertices on it) bounds the cap, the
            // other way round.
            std::vector<size_t> at;
            for (size_t k = 0; k < on.size(); ++k)
                if (on[k]) at.push_back(k);
            if (at.size() == g.around.size()) continue;  // the face lies on the plane: the cap replaces it
            if (at.size() == 2) {
                const size_t m = g.around.size();
                size_t from = at[0], to = at[1];
                if ((from + 1) % m != to) std::swap(from, to);
                if ((from + 1) % m == to) {
                    const uint32_t a = verts[g.around[to]].point;
                    if (std::any_of(cap_next_.begin(), cap_next_.end(), [&](const auto& e) { return e.first == a; }))
                        broken = true;
                    else
                        cap_next_.emplace_back(a, verts[g.around[from]].point);
                }
            } else if (at.size() > 2) {
                broken = true;
            }
            kept.push_back(std::move(g));
        }
        if (!broken && cap_next_.size() >= 3) {
            PolyFace cap{bit, {}};
            // From the lowest-numbered point.
            const uint32_t first = std::min_element(cap_next_.begin(), cap_next_.end())->first;
            uint32_t at = first;
            for (size_t k = 0; k <= cap_next_.size() && !broken; ++k) {
                const uint32_t i = local(at);
                if (i == verts.size()) throw std::out_of_range("a cap's point is not the polyhedron's");
                cap.around.push_back(i);
                auto it = std::find_if(cap_next_.begin(), cap_next_.end(), [&](const auto& e) { return e.first == at; });
                if (it == cap_next_.end()) broken = true;
                else at = it->second;
                if (at == first) break;
            }
            if (!broken && cap.around.size() == cap_next_.size()) kept.push_back(std::move(cap));
            else ++out_.degenerate;
        } else if (broken) {
            ++out_.degenerate;
        }
        faces = std::move(kept);
        return !faces.empty();
    }

    // A polygon of piece p, split into triangles from its lowest-numbered point, or from point
    // `apex` of it.
    void emit(uint32_t p, const std::vector<uint32_t>& points, FaceKind kind, uint32_t across, size_t apex = SIZE_MAX) {
        const size_t n = points.size();
        const size_t first = apex != SIZE_MAX ? apex : size_t(std::min_element(points.begin(), points.end()) - points.begin());
        for (size_t k = 1; k + 1 < n; ++k) {
            out_.triangles[p].push_back({points[first], points[(first + k) % n], points[(first + k + 1) % n]});
            out_.kinds[p].push_back(kind);
            out_.across[p].push_back(across);
        }
    }

    void cut_tet(uint32_t t) {
        tet_ = mesh_.tets[t];
        labels_.clear();
        for (uint32_t v : tet_)
            for (uint32_t i = field_.start[v]; i < field_.start[v + 1]; ++i)
                if (field_.value[i] > 0) labels_.push_back(field_.piece[i]);
        std::sort(labels_.begin(), labels_.end());
        labels_.erase(std::unique(labels_.begin(), labels_.end()), labels_.end());
        if (labels_.empty()) labels_.push_back(tet_piece_[t]);
        if (labels_.size() > 28) labels_.resize(28);  // the plane bits; never near in practice
        // The strongest competitors clip first: the parts of the tet where p is nowhere near the
        // largest go early (the result is the same in any order; what is cut on the way is not).
        std::vector<std::pair<double, size_t>> strength;
        for (size_t j = 0; j < labels_.size(); ++j) {
            double most = 0;
            for (uint32_t v : tet_) most = std::max(most, field_.at(v, labels_[j]));
            strength.emplace_back(-most, j);
        }
        std::sort(strength.begin(), strength.end());
        std::vector<size_t> order;
        for (const auto& [most, j] : strength) order.push_back(j);
        size_t parts = 0;
        for (uint32_t p : labels_) {
            std::vector<PolyVertex> verts;
            for (int k = 0; k < 4; ++k) verts.push_back({corner(k), 0xFu & ~(1u << k)});
            std::vector<PolyFace> faces;
            for (uint32_t i = 0; i < 4; ++i)
                faces.push_back({i, {uint32_t(kTetFaces[i][0]), uint32_t(kTetFaces[i][1]), uint32_t(kTetFaces[i][2])}});
            bool left = true;
            for (size_t j : order)
                if (left && labels_[j] != p) left = clip(verts, faces, j, p);
            if (!left) continue;
            ++parts;
            for (const PolyFace& f : faces) {
                if (f.plane < 4 && fine_.boundary[t][f.plane] < 0) continue;  // inside the object: the next tet's too
                std::vector<uint32_t> points;
                size_t apex = SIZE_MAX;  // the lowest midpoint taken in: the fan from a corner would
                                         // have a flat triangle
                for (size_t k = 0; k < f.around.size(); ++k) {
                    points.push_back(verts[f.around[k]].point);
                    // A whole tet's face along a split neighbour's: that edge's midpoint too.
                    const uint32_t next = verts[f.around[(k + 1) % f.around.size()]].point;
                    const Name &a = names_[points.back()], &b = names_[next];
                    if (fine_.whole[t] && f.plane < 4 && a.vertices == 1 && a.pieces == 0 && b.vertices == 1 && b.pieces == 0) {
                        const uint32_t m = fine_.midpoint(a.vertex[0], b.vertex[0]);
                        if (m == UINT32_MAX) continue;
                        points.push_back(vertex_point(m));
                        if (apex == SIZE_MAX || points.back() < points[apex]) apex = points.size() - 1;
                    }
                }
                if (f.plane < 4) emit(p, points, FaceKind(fine_.boundary[t][f.plane]), UINT32_MAX, apex);
                else emit(p, points, FaceKind::Fracture, labels_[f.plane - 4]);
            }
        }
        out_.cut_tets += parts > 1;
    }
};

}  // namespace

namespace {

// Every edge used once each way.
bool closed(const std::vector<Tri>& triangles) {
    std::vector<std::pair<uint32_t, uint32_t>> edges, back;
    for (const Tri& t : triangles)
        for (int k = 0; k < 3; ++k) edges.emplace_back(t[k], t[(k + 1) % 3]), back.emplace_back(t[(k + 1) % 3], t[k]);
    std::sort(edges.begin(), edges.end());
    std::sort(back.begin(), back.end());
    return edges == back;
}

}  // namespace

std::vector<Vec3> CrackCells::place(const std::vector<Vec3>& vertices) const {
    std::vector<Vec3> out(points.size(), Vec3::Zero());
    for (size_t i = 0; i < points.size(); ++i)
        for (int k = 0; k < points[i].count; ++k) out[i] += points[i].weight[k] * vertices[points[i].vertex[k]];
    return out;
}

double mean_tet_edge(const TetMesh& mesh) {
    double sum = 0;
    for (const Tet& t : mesh.tets)
        for (int a = 0; a < 4; ++a)
            for (int b = a + 1; b < 4; ++b) sum += (mesh.vertices[t[a]] - mesh.vertices[t[b]]).norm();
    return mesh.tets.empty() ? 0.0 : sum / (6.0 * double(mesh.tets.size()));
}

namespace {

// The field on the refined tets (crack_refinement.h). A tet is split where a crack can pass
// near it: its vertices' largest (scaled) pieces differ, or one leads the next by less than
// kSplitMargin. A split edge whose tets are all split has at its midpoint the Gaussian shares at
// its place, as a vertex does (from the tets of both ends); any other the mean of its ends' (so
// that a face between a split tet and a whole one is linear on both sides and the cracks meet).
// Next to a held piece the midpoints get the mean too: its narrower field is a few tet centres'
// shares, as ragged between the vertices as the tets are (with the Gaussian at the midpoints,
// the horse's held pieces' cracks were creased up to three times as much).
constexpr double kSplitMargin = 0.1;

struct Fine {
    CrackRefinement mesh;
    std::vector<uint32_t> piece;  // per refined tet
    Field field;                  // unscaled, per refined vertex
};

Fine refine(const TetMesh& mesh, const TetTopology& topology, const std::vector<std::array<FaceKind, 4>>& face_kind,
            Neighbourhood& hood, const std::vector<uint32_t>& tet_piece, const Field& field,
            const std::vector<double>& scale, double sigma, const std::vector<char>& held_piece) {
    const auto pure = [&](uint32_t v) { return field.start[v + 1] - field.start[v] == 1; };
    Fine f;
    // Per vertex: its largest scaled piece and by how much it leads the next.
    std::vector<uint32_t> top(mesh.vertices.size(), UINT32_MAX);
    std::vector<double> lead(mesh.vertices.size(), 0);
    for (uint32_t v = 0; v < mesh.vertices.size(); ++v) {
        double first = 0, second = 0;
        for (uint32_t i = field.start[v]; i < field.start[v + 1]; ++i) {
            const double x = field.value[i] * scale[field.piece[i]];
            if (x > first) second = first, first = x, top[v] = field.piece[i];
            else second = std::max(second, x);
        }
        lead[v] = first - second;
    }
    std::vector<char> split(mesh.tets.size(), 0);
    for (size_t t = 0; t < mesh.tets.size(); ++t)
        for (uint32_t v : mesh.tets[t]) split[t] |= top[v] != top[mesh.tets[t][0]] || lead[v] < kSplitMargin;
    f.mesh = refine_tets(mesh, topology, face_kind, split);
    for (uint32_t parent : f.mesh.parent) f.piece.push_back(tet_piece[parent]);
    std::vector<char> linear(f.mesh.ends.size(), 0);  // an edge of a whole tet
    for (size_t t = 0; t < mesh.tets.size(); ++t) {
        if (split[t]) continue;
        const Tet& k = mesh.tets[t];
        for (int a = 0; a < 4; ++a)
            for (int b = a + 1; b < 4; ++b) {
                const uint32_t m = f.mesh.midpoint(k[a], k[b]);
                if (m != UINT32_MAX) linear[m - mesh.vertices.size()] = 1;
            }
    }
    std::vector<std::tuple<uint32_t, uint32_t, double>> entries;
    for (uint32_t v = 0; v < mesh.vertices.size(); ++v)
        for (uint32_t i = field.start[v]; i < field.start[v + 1]; ++i) entries.emplace_back(v, field.piece[i], field.value[i]);
    std::vector<std::pair<uint32_t, double>> sums;
    std::vector<uint32_t> start;
    for (size_t e = 0; e < f.mesh.ends.size(); ++e) {
        const uint32_t m = uint32_t(mesh.vertices.size() + e), a = f.mesh.ends[e][0], b = f.mesh.ends[e][1];
        if (linear[e] || (pure(a) && pure(b)) || held_at(hood, tet_piece, a, held_piece).first > 0 ||
            held_at(hood, tet_piece, b, held_piece).first > 0) {
            for (uint32_t v : {a, b})
                for (uint32_t i = field.start[v]; i < field.start[v + 1]; ++i) entries.emplace_back(m, field.piece[i], field.value[i] / 2);
            continue;
        }
        const Vec3& x = f.mesh.mesh.vertices[m];
        start = hood.tets_of[a];
        start.insert(start.end(), hood.tets_of[b].begin(), hood.tets_of[b].end());
        if (hood.reach(x, start, sigma)) {
            entries.emplace_back(m, hood.first_piece(), 1.0);
            continue;
        }
        const double total = hood.shares(x, sigma, sums);
        for (const auto& [p, w] : sums) entries.emplace_back(m, p, w / total);
    }
    f.field = field_of(f.mesh.mesh.vertices.size(), std::move(entries), 1e-9);
    return f;
}

// The points' weights over the refined vertices made weights over the original ones (a midpoint
// is half of each end).
void to_original(CrackCells& cells, const CrackRefinement& fine) {
    const size_t originals = fine.originals();
    for (CrackPoint& x : cells.points) {
        std::array<std::pair<uint32_t, double>, 8> w;
        size_t n = 0;
        const auto add = [&](uint32_t v, double weight) {
            for (size_t i = 0; i < n; ++i)
                if (w[i].first == v) return void(w[i].second += weight);
            w[n++] = {v, weight};
        };
        for (int k = 0; k < x.count; ++k) {
            if (x.vertex[size_t(k)] < originals) add(x.vertex[size_t(k)], x.weight[size_t(k)]);
            else
                for (uint32_t v : fine.ends[x.vertex[size_t(k)] - originals]) add(v, x.weight[size_t(k)] / 2);
        }
        for (size_t i = 1; i < n; ++i)  // (a handful: insertion)
            for (size_t j = i; j > 0 && w[j].first < w[j - 1].first; --j) std::swap(w[j], w[j - 1]);
        assert(n <= 4);  // all in one original tet
        x = CrackPoint{};
        x.count = uint8_t(n);
        for (size_t i = 0; i < n; ++i) x.vertex[i] = w[i].first, x.weight[i] = w[i].second;
    }
}

}  // namespace

CrackCells crack_cells(const TetMesh& mesh, const TetTopology& topology, const std::vector<uint32_t>& tet_piece,
                       const std::vector<std::array<FaceKind, 4>>& face_kind, const CrackFairingSettings& settings) {
    uint32_t pieces = 0;
    for (uint32_t p : tet_piece) pieces = std::max(pieces, p + 1);
    std::vector<double> own(pieces, 0);  // each piece's tet volume
    for (size_t t = 0; t < mesh.tets.size(); ++t) {
        const Tet& k = mesh.tets[t];
        own[tet_piece[t]] += tet_volume(mesh.vertices[k[0]], mesh.vertices[k[1]], mesh.vertices[k[2]], mesh.vertices[k[3]]);
    }
    const double sigma = settings.width * mean_tet_edge(mesh);
    std::vector<char> held(pieces, 0);
    std::vector<double> scale(pieces, 1.0);  // each piece's field is scale x chi
    Neighbourhood hood(mesh, topology, tet_piece);
    Field unscaled = piece_field(mesh, hood, tet_piece, sigma, held);
    // The tets as they are, for every cut but one on split tets.
    const CrackRefinement whole = refine_tets(mesh, topology, face_kind, std::vector<char>(mesh.tets.size(), 0));
    // The cells of the field as it is scaled now, on the tets split (the last round) or not.
    const auto cut = [&](bool split) {
        const Fine fine =
            split ? refine(mesh, topology, face_kind, hood, tet_piece, unscaled, scale, sigma, held) : Fine{};
        const CrackRefinement& tets = split ? fine.mesh : whole;
        Field field = split ? fine.field : unscaled;
        for (size_t i = 0; i < field.value.size(); ++i) field.value[i] *= scale[field.piece[i]];
        CrackCells cells = Arrangement(tets, split ? fine.piece : tet_piece, field, pieces).run();
        to_original(cells, tets);
        for (const std::vector<Tri>& cell : cells.triangles) cells.open += !closed(cell);
        cells.split_tets = (tets.mesh.tets.size() - mesh.tets.size()) / 7;
        return cells;
    };
    int fits = settings.fit_rounds;
    bool split_open = false;  // the split tets' cells did not close: the whole tets' are kept
    for (;;) {
        // Once no round of the fit is left, the cut is made on the split tets: its cells are the
        // ones returned unless a piece is held again (its volume is then theirs).
        bool fine = fits <= 0 && settings.split_tets && !split_open;
        CrackCells cells = cut(fine);
        if (cells.open > 0 && fine) cells = cut(false), fine = false, split_open = true;  // (not seen)
        if (cells.open > 0) return cells;
        const std::vector<Vec3> x = cells.place(mesh.vertices);
        std::vector<double> kept(pieces, 0);  // each cell's volume over its tets'
        for (uint32_t p = 0; p < pieces; ++p) {
            for (const Tri& t : cells.triangles[p]) kept[p] += x[t[0]].dot(x[t[1]].cross(x[t[2]])) / 6;
            kept[p] /= own[p];
        }
        bool again = false;
        if (fits-- > 0) {
            // The fit: a piece whose cell keeps more or less than its tets' volume has its field
            // scaled by the square root of the ratio, at most kFitStep a round (a small piece's
            // volume jumps as its field passes its neighbours').
            for (uint32_t p = 0; p < pieces; ++p) {
                if (std::abs(kept[p] - 1) <= settings.fit_tolerance) continue;
                scale[p] *= std::exp(std::clamp(-0.5 * std::log(std::max(kept[p], 1e-3)), -kFitStep, kFitStep));
                again = true;
            }
            if (again) continue;
        }
        // Then a piece whose cell still lost too much of its tets' volume to its neighbours (a
        // thin one) is cut again, held one level more (kHeldLevels).
        for (uint32_t p = 0; p < pieces; ++p)
            if (kept[p] < settings.keep && held[p] < kHeldLevels) held[p] += 1, again = true;
        cells.held = size_t(std::count_if(held.begin(), held.end(), [](char c) { return c > 0; }));
        cells.fit_rounds = size_t(settings.fit_rounds - std::max(fits, 0));
        if (!again) {
            if (fine || split_open || !settings.split_tets) return cells;
            // The fit settled within its rounds: the same field on the split tets.
            CrackCells split = cut(true);
            if (split.open > 0) return cells;  // not seen; the cells of the whole tets close
            split.held = cells.held, split.fit_rounds = cells.fit_rounds;
            return split;
        }
        unscaled = piece_field(mesh, hood, tet_piece, sigma, held);
    }
}

}  // namespace shatter
