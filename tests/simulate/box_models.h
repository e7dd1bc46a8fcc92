// Small models built from boxes, for physics tests that need exact masses and known geometry
// (no tetrahedralization): each piece is one box, its collision shape the box itself.
#pragma once

#include <vector>

#include "core/model.h"

namespace shatter::test {

struct BoxSpec {
    Vec3 center;
    Vec3 size;  // full extents (unit: m)
};

inline Piece box_piece(const BoxSpec& b, double density) {
    Piece p;
    const Vec3 e = 0.5 * b.size;
    p.mass.volume = b.size.prod();
    p.mass.mass = density * p.mass.volume;
    p.mass.center = b.center;
    const double m = p.mass.mass;
    p.mass.inertia = Vec3(m / 3 * (e.y() * e.y() + e.z() * e.z()), m / 3 * (e.x() * e.x() + e.z() * e.z()),
                          m / 3 * (e.x() * e.x() + e.y() * e.y()))
                         .asDiagonal();
    ConvexPart part;
    for (int i = 0; i < 8; ++i)
        part.points.push_back(b.center + Vec3((i & 1) ? e.x() : -e.x(), (i & 2) ? e.y() : -e.y(), (i & 4) ? e.z() : -e.z()));
    part.volume = part.hull_volume = p.mass.volume;
    p.collision.push_back(part);
    return p;
}

// A model of boxes with density 1000 kg/m^3 and the given constraints (pivot, area).
struct ModelBuilder {
    Model model;
    ModelBuilder() { model.density = 1000; }
    uint32_t box(const Vec3& center, const Vec3& size) {
        model.pieces.push_back(box_piece({center, size}, model.density));
        return uint32_t(model.pieces.size() - 1);
    }
    void join(uint32_t a, uint32_t b, const Vec3& pivot, double area = 1.0) {
        Constraint c;
        c.piece_a = std::min(a, b);
        c.piece_b = std::max(a, b);
        c.pivot = pivot;
        c.area = area;
        model.constraints.push_back(c);
    }
};

}  // namespace shatter::test
