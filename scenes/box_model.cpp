#include "scenes/box_model.h"

#include <algorithm>
#include <cassert>
#include <tuple>
#include <utility>
#include <vector>

namespace shatter {

Piece box_piece(const Vec3& center, const Vec3& size, double density) {
    Piece p;
    const Vec3 e = 0.5 * size;
    p.mass.volume = size.prod();
    p.mass.mass = density * p.mass.volume;
    p.mass.center = center;
    const double m = p.mass.mass;
    p.mass.inertia = Vec3(m / 3 * (e.y() * e.y() + e.z() * e.z()), m / 3 * (e.x() * e.x() + e.z() * e.z()),
                          m / 3 * (e.x() * e.x() + e.y() * e.y()))
                         .asDiagonal();
    ConvexPart part;
    for (int i = 0; i < 8; ++i)
        part.points.push_back(center + Vec3((i & 1) ? e.x() : -e.x(), (i & 2) ? e.y() : -e.y(), (i & 4) ? e.z() : -e.z()));
    part.volume = part.hull_volume = p.mass.volume;
    p.surface.vertices = part.points;
    // Corner i has bit 0: +x, bit 1: +y, bit 2: +z. Outward triangles of the six faces.
    p.surface.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                           {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    p.surface.kinds.assign(12, FaceKind::Outer);
    p.collision.push_back(part);
    return p;
}

uint32_t BoxModelBuilder::box(const Vec3& center, const Vec3& size) {
    model_.pieces.push_back(box_piece(center, size, model_.density));
    return uint32_t(model_.pieces.size() - 1);
}

void BoxModelBuilder::join(uint32_t a, uint32_t b, const Vec3& pivot, double area) {
    Constraint c;
    c.piece_a = std::min(a, b);
    c.piece_b = std::max(a, b);
    c.vertex = uint32_t(model_.constraints.size());
    c.pivot = pivot;
    c.area = area;
    model_.constraints.push_back(c);
}

BoxModelBuilder::SharedFace BoxModelBuilder::shared_face(uint32_t a, uint32_t b) const {
    const MassProperties& pa = model_.pieces[a].mass;
    const MassProperties& pb = model_.pieces[b].mass;
    const Vec3 d = pb.center - pa.center;
    SharedFace f;
    d.cwiseAbs().maxCoeff(&f.axis);
    f.u = (f.axis + 1) % 3;
    f.v = (f.axis + 2) % 3;
    // Between the two centres along `axis`, the overlap of the boxes across.
    const Vec3 ea = model_.pieces[a].collision[0].points[7] - pa.center;  // +x+y+z corner: half extents
    const Vec3 eb = model_.pieces[b].collision[0].points[7] - pb.center;
    for (int k : {f.u, f.v}) {
        f.lo[k] = std::max(pa.center[k] - ea[k], pb.center[k] - eb[k]);
        f.hi[k] = std::min(pa.center[k] + ea[k], pb.center[k] + eb[k]);
    }
    f.plane = d[f.axis] > 0 ? pa.center[f.axis] + ea[f.axis] : pa.center[f.axis] - ea[f.axis];
    return f;
}

void BoxModelBuilder::join_face(uint32_t a, uint32_t b, uint32_t per_side) {
    const SharedFace f = shared_face(a, b);
    const double area = (f.hi[f.u] - f.lo[f.u]) * (f.hi[f.v] - f.lo[f.v]) / double(per_side * per_side);
    for (uint32_t i = 0; i < per_side; ++i)
        for (uint32_t j = 0; j < per_side; ++j) {
            // 1 per side: the centre; n per side: from corner to corner.
            const double s = per_side == 1 ? 0.5 : double(i) / (per_side - 1);
            const double t = per_side == 1 ? 0.5 : double(j) / (per_side - 1);
            Vec3 p;
            p[f.axis] = f.plane;
            p[f.u] = f.lo[f.u] + s * (f.hi[f.u] - f.lo[f.u]);
            p[f.v] = f.lo[f.v] + t * (f.hi[f.v] - f.lo[f.v]);
            join(a, b, p, area);
        }
}

void BoxModelBuilder::join_face_gauss(uint32_t a, uint32_t b, uint32_t per_side) {
    // Gauss-Legendre nodes and weights on [-1, 1] (weights sum to 2), n = 1 to 5.
    static const std::vector<std::vector<std::pair<double, double>>> kRules = {
        {{0.0, 2.0}},
        {{-0.5773502691896257, 1.0}, {0.5773502691896257, 1.0}},
        {{-0.7745966692414834, 0.5555555555555556}, {0.0, 0.8888888888888888}, {0.7745966692414834, 0.5555555555555556}},
        {{-0.8611363115940526, 0.3478548451374538}, {-0.3399810435848563, 0.6521451548625461},
         {0.3399810435848563, 0.6521451548625461}, {0.8611363115940526, 0.3478548451374538}},
        {{-0.9061798459185930, 0.2369268850561891}, {-0.5384693101056831, 0.4786286704993665}, {0.0, 0.5688888888888889},
         {0.5384693101056831, 0.4786286704993665}, {0.9061798459185930, 0.2369268850561891}}};
    assert(per_side >= 1 && per_side <= kRules.size());
    const SharedFace f = shared_face(a, b);
    const double area = (f.hi[f.u] - f.lo[f.u]) * (f.hi[f.v] - f.lo[f.v]);
    const Vec3 mid = 0.5 * (f.lo + f.hi), half = 0.5 * (f.hi - f.lo);
    for (const auto& [s, ws] : kRules[per_side - 1])
        for (const auto& [t, wt] : kRules[per_side - 1]) {
            Vec3 p;
            p[f.axis] = f.plane;
            p[f.u] = mid[f.u] + s * half[f.u];
            p[f.v] = mid[f.v] + t * half[f.v];
            join(a, b, p, area * ws * wt / 4);
        }
}

Model BoxModelBuilder::take() {
    std::stable_sort(model_.constraints.begin(), model_.constraints.end(), [](const Constraint& x, const Constraint& y) {
        return std::tie(x.piece_a, x.piece_b) < std::tie(y.piece_a, y.piece_b);
    });
    return std::move(model_);
}

Model box_grid(uint32_t nx, uint32_t ny, uint32_t nz, double cell, const Vec3& origin, double density,
               uint32_t per_side) {
    BoxModelBuilder b(density);
    auto index = [&](uint32_t i, uint32_t j, uint32_t k) { return (k * ny + j) * nx + i; };
    for (uint32_t k = 0; k < nz; ++k)
        for (uint32_t j = 0; j < ny; ++j)
            for (uint32_t i = 0; i < nx; ++i)
                b.box(origin + cell * Vec3(i + 0.5, j + 0.5, k + 0.5), Vec3::Constant(cell));
    for (uint32_t k = 0; k < nz; ++k)
        for (uint32_t j = 0; j < ny; ++j)
            for (uint32_t i = 0; i < nx; ++i) {
                if (i + 1 < nx) b.join_face(index(i, j, k), index(i + 1, j, k), per_side);
                if (j + 1 < ny) b.join_face(index(i, j, k), index(i, j + 1, k), per_side);
                if (k + 1 < nz) b.join_face(index(i, j, k), index(i, j, k + 1), per_side);
            }
    return b.take();
}

}  // namespace shatter
