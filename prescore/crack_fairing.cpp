// Faired cracks: the smoothed piece field and the cells it cuts from the tets (the design is in
// crack_fairing.h).
#include "prescore/crack_fairing.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <utility>

#include <Eigen/LU>

#include "core/rng.h"

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

// chi_p(v): the share of piece p in a Gaussian-weighted neighbourhood of v (width sigma), over
// the tets reached from v's own through their faces (so not across a gap) whose centres lie
// within 2 sigma, each weighted by its volume; narrower around the pieces `held` (kHeldLevels).
Field piece_field(const TetMesh& mesh, const TetTopology& topo, const std::vector<uint32_t>& tet_piece, double sigma,
                  const std::vector<char>& held_piece) {
    const size_t nv = mesh.vertices.size();
    std::vector<std::vector<uint32_t>> tets_of(nv);
    for (uint32_t t = 0; t < mesh.tets.size(); ++t)
        for (uint32_t v : mesh.tets[t]) tets_of[v].push_back(t);
    std::vector<Vec3> centre(mesh.tets.size());
    std::vector<double> volume(mesh.tets.size());
    for (size_t t = 0; t < mesh.tets.size(); ++t) {
        const Tet& k = mesh.tets[t];
        centre[t] = tet_centroid(mesh, uint32_t(t));
        volume[t] = tet_volume(mesh.vertices[k[0]], mesh.vertices[k[1]], mesh.vertices[k[2]], mesh.vertices[k[3]]);
    }
    std::vector<std::tuple<uint32_t, uint32_t, double>> entries;
    std::vector<uint32_t> seen(mesh.tets.size(), UINT32_MAX);
    std::vector<uint32_t> reach;
    std::vector<std::pair<uint32_t, double>> sums;  // per piece in reach
    for (uint32_t v = 0; v < nv; ++v) {
        if (tets_of[v].empty()) continue;
        const uint32_t first = tet_piece[tets_of[v].front()];
        bool one = true;
        for (uint32_t t : tets_of[v]) one = one && tet_piece[t] == first;
        int held = 0;  // the most a piece around v is held
        for (uint32_t t : tets_of[v]) held = std::max<int>(held, held_piece[tet_piece[t]]);
        if (one && held >= kHeldLevels) {
            entries.emplace_back(v, first, 1.0);
            continue;
        }
        const double width = sigma / double(1 << held);
        // The tets within reach; one piece among them: chi is that piece's alone.
        reach.assign(tets_of[v].begin(), tets_of[v].end());
        for (uint32_t t : reach) seen[t] = v;
        bool alike = true;
        for (size_t k = 0; k < reach.size(); ++k) {
            const uint32_t t = reach[k];
            alike = alike && tet_piece[t] == first;
            for (int i = 0; i < 4; ++i) {
                const int32_t u = topo.neighbour[t][i];
                if (u < 0 || seen[u] == v) continue;
                seen[u] = v;
                if ((centre[u] - mesh.vertices[v]).norm() < 2 * width) reach.push_back(uint32_t(u));
            }
        }
        if (alike) {
            entries.emplace_back(v, first, 1.0);
            continue;
        }
        sums.clear();
        double total = 0;
        for (uint32_t t : reach) {
            const double d = (centre[t] - mesh.vertices[v]).norm() / width;
            const double w = volume[t] * std::exp(-0.5 * d * d);
            total += w;
            auto it = std::find_if(sums.begin(), sums.end(), [&](const auto& e) { return e.first == tet_piece[t]; });
            if (it == sums.end()) sums.emplace_back(tet_piece[t], w);
            else it->second += w;
        }
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
    Arrangement(const TetMesh& mesh, const TetTopology& topo, const std::vector<uint32_t>& tet_piece,
                const std::vector<std::array<FaceKind, 4>>& face_kind, const Field& field, size_t pieces)
        : mesh_(mesh), topo_(topo), tet_piece_(tet_piece), face_kind_(face_kind), field_(field) {
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
    const TetTopology& topo_;
    const std::vector<uint32_t>& tet_piece_;
    const std::vector<std::array<FaceKind, 4>>& face_kind_;
    const Field& field_;
    CrackCells out_;
    std::map<Name, uint32_t> index_;
    std::vector<Name> names_;
    uint32_t alone_ = 0;
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

    uint32_t corner(int k) {
        Name n;
        n.vertex[0] = tet_[k];
        n.vertices = 1;
        CrackPoint x;
        weights(n, x);
        return add(n, x);
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
        std::map<uint32_t, uint32_t> local;  // point -> index in verts
        for (size_t i = 0; i < verts.size(); ++i) local.emplace(verts[i].point, uint32_t(i));
        auto vertex_of = [&](uint32_t point, uint32_t planes) {
            auto [it, fresh] = local.emplace(point, uint32_t(verts.size()));
            if (fresh) verts.push_back({point, planes}), sides.push_back(0);
            return it->second;
        };
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> cuts;  // (kept end, cut end) -> point: once per edge
        std::vector<PolyFace> kept;
        std::map<uint32_t, uint32_t> cap_next;  // the cap's edges, from -> to
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
                    auto [cut, fresh] = cuts.emplace(std::make_pair(in.point, out.point), 0);
                    if (fresh) cut->second = cut_point(in, out, bit, p, r);
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
                if ((from + 1) % m == to) broken |= !cap_next.emplace(verts[g.around[to]].point, verts[g.around[from]].point).second;
            } else if (at.size() > 2) {
                broken = true;
            }
            kept.push_back(std::move(g));
        }
        if (!broken && cap_next.size() >= 3) {
            PolyFace cap{bit, {}};
            uint32_t at = cap_next.begin()->first;
            for (size_t k = 0; k <= cap_next.size() && !broken; ++k) {
                cap.around.push_back(local.at(at));
                auto it = cap_next.find(at);
                if (it == cap_next.end()) broken = true;
                else at = it->second;
                if (at == cap_next.begin()->first) break;
            }
            if (!broken && cap.around.size() == cap_next.size()) kept.push_back(std::move(cap));
            else ++out_.degenerate;
        } else if (broken) {
            ++out_.degenerate;
        }
        faces = std::move(kept);
        return !faces.empty();
    }

    // A polygon of piece p, split into triangles from its lowest-numbered point.
    void emit(uint32_t p, const std::vector<uint32_t>& points, FaceKind kind, uint32_t across) {
        const size_t n = points.size();
        const size_t first = size_t(std::min_element(points.begin(), points.end()) - points.begin());
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
                if (f.plane < 4 && topo_.neighbour[t][f.plane] >= 0) continue;  // inside the object: the next tet's too
                std::vector<uint32_t> points;
                for (uint32_t v : f.around) points.push_back(verts[v].point);
                if (f.plane < 4) emit(p, points, face_kind_[t][f.plane], UINT32_MAX);
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

namespace {

// Perlin's gradient noise at x (lattice spacing 1): one of the 12 cube-edge directions per lattice
// point, chosen by a hash of the point and the seed; quintic fade. Within about [-1, 1].
double gradient_noise(const Vec3& x, uint64_t seed) {
    static constexpr int kGradient[12][3] = {{1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0}, {1, 0, 1}, {-1, 0, 1},
                                             {1, 0, -1}, {-1, 0, -1}, {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1}};
    const Vec3 floor(std::floor(x.x()), std::floor(x.y()), std::floor(x.z()));
    const Vec3 f = x - floor;
    const auto fade = [](double t) { return t * t * t * (t * (t * 6 - 15) + 10); };
    const Vec3 w(fade(f.x()), fade(f.y()), fade(f.z()));
    double sum = 0;
    for (int corner = 0; corner < 8; ++corner) {
        const int dx = corner & 1, dy = (corner >> 1) & 1, dz = (corner >> 2) & 1;
        uint64_t h = seed;
        h = mix64(h ^ uint64_t(int64_t(floor.x()) + dx));
        h = mix64(h ^ uint64_t(int64_t(floor.y()) + dy));
        h = mix64(h ^ uint64_t(int64_t(floor.z()) + dz));
        const int* g = kGradient[h % 12];
        const double dot = g[0] * (f.x() - dx) + g[1] * (f.y() - dy) + g[2] * (f.z() - dz);
        sum += dot * (dx ? w.x() : 1 - w.x()) * (dy ? w.y() : 1 - w.y()) * (dz ? w.z() : 1 - w.z());
    }
    return sum;
}

// Two octaves of gradient noise (wavelength and half of it at half the height), in [-1, 1].
double relief_channel(const Vec3& x, double wavelength, uint64_t seed) {
    const Vec3 u = x / wavelength;
    const double n = gradient_noise(u, seed) + 0.5 * gradient_noise(2 * u + Vec3(17.1, 5.3, 11.7), mix64(seed + 1));
    return std::clamp(n / 1.5, -1.0, 1.0);
}

}  // namespace

Vec3 crack_relief(const Vec3& x, double wavelength, uint64_t seed) {
    return Vec3(relief_channel(x, wavelength, mix64(seed ^ 1)), relief_channel(x, wavelength, mix64(seed ^ 2)),
                relief_channel(x, wavelength, mix64(seed ^ 3))) /
           std::sqrt(3.0);
}

void roughen_cracks(const CrackCells& cells, std::vector<Vec3>& placed, double amplitude, double wavelength,
                    uint64_t seed) {
    if (!(amplitude > 0) || !(wavelength > 0) || placed.empty()) return;
    // Which points lie on a crack, and which on the object's boundary (they stay).
    std::vector<char> on_crack(placed.size(), 0), on_boundary(placed.size(), 0);
    for (size_t p = 0; p < cells.triangles.size(); ++p)
        for (size_t t = 0; t < cells.triangles[p].size(); ++t)
            for (uint32_t i : cells.triangles[p][t])
                (cells.kinds[p][t] == FaceKind::Fracture ? on_crack : on_boundary)[i] = 1;
    // The boundary points in a grid of cells `wavelength` wide, for each crack point's distance
    // to the nearest (the move fades in over one wavelength from the boundary).
    Vec3 lo = placed.front();
    for (const Vec3& x : placed) lo = lo.cwiseMin(x);
    const auto cell = [&](const Vec3& x) {
        return std::array<int64_t, 3>{int64_t(std::floor((x.x() - lo.x()) / wavelength)),
                                      int64_t(std::floor((x.y() - lo.y()) / wavelength)),
                                      int64_t(std::floor((x.z() - lo.z()) / wavelength))};
    };
    std::map<std::array<int64_t, 3>, std::vector<uint32_t>> grid;
    for (uint32_t i = 0; i < placed.size(); ++i)
        if (on_boundary[i]) grid[cell(placed[i])].push_back(i);
    std::vector<Vec3> moved = placed;
    for (size_t i = 0; i < placed.size(); ++i) {
        if (!on_crack[i] || on_boundary[i]) continue;
        const Vec3& x = placed[i];
        double nearest = wavelength;
        const auto c = cell(x);
        for (int64_t dx = -1; dx <= 1; ++dx)
            for (int64_t dy = -1; dy <= 1; ++dy)
                for (int64_t dz = -1; dz <= 1; ++dz) {
                    const auto it = grid.find({c[0] + dx, c[1] + dy, c[2] + dz});
                    if (it == grid.end()) continue;
                    for (uint32_t j : it->second) nearest = std::min(nearest, (placed[j] - x).norm());
                }
        moved[i] = x + amplitude * (nearest / wavelength) * crack_relief(x, wavelength, seed);
    }
    placed = std::move(moved);
}

double mean_tet_edge(const TetMesh& mesh) {
    double sum = 0;
    for (const Tet& t : mesh.tets)
        for (int a = 0; a < 4; ++a)
            for (int b = a + 1; b < 4; ++b) sum += (mesh.vertices[t[a]] - mesh.vertices[t[b]]).norm();
    return mesh.tets.empty() ? 0.0 : sum / (6.0 * double(mesh.tets.size()));
}

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
    Field unscaled = piece_field(mesh, topology, tet_piece, sigma, held);
    int fits = settings.fit_rounds;
    for (;;) {
        Field field = unscaled;
        for (size_t i = 0; i < field.value.size(); ++i) field.value[i] *= scale[field.piece[i]];
        CrackCells cells = Arrangement(mesh, topology, tet_piece, face_kind, field, pieces).run();
        for (const std::vector<Tri>& cell : cells.triangles) cells.open += !closed(cell);
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
        if (!again) return cells;
        unscaled = piece_field(mesh, topology, tet_piece, sigma, held);
    }
}

}  // namespace shatter
