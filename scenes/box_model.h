// Models built from boxes, without tetrahedralization: exact masses and known geometry for the
// physics tests, the benchmarks and the built-in scenes whose pieces are boxes (plate, beam,
// chain). Each piece is one box; its collision shape is the box itself; its surface is the
// box's 12 triangles (all outer).
#pragma once

#include <cstdint>

#include "core/model.h"

namespace shatter {

// One box piece of full extents `size` centred at `center` (unit: m), at `density` (kg/m^3).
Piece box_piece(const Vec3& center, const Vec3& size, double density);

class BoxModelBuilder {
public:
    explicit BoxModelBuilder(double density = 1000) { model_.density = density; }
    uint32_t box(const Vec3& center, const Vec3& size);
    // A constraint between pieces a and b at `pivot` standing for `area` (m^2).
    void join(uint32_t a, uint32_t b, const Vec3& pivot, double area = 1.0);
    // Joins two boxes that share a face with `per_side` x `per_side` constraints spread over
    // the face (1: its centre; 2: its four corners), sharing the face's area equally.
    void join_face(uint32_t a, uint32_t b, uint32_t per_side);
    // Joins two boxes that share a face with `per_side` x `per_side` constraints (1 to 5) at the
    // face's Gauss-Legendre points, each standing for its weight's share of the face's area: a
    // stress varying linearly over the face (bending) then gives the face's exact force and
    // moment (second moment of area A h^2 / 12 per axis, not the corners' A h^2 / 4).
    void join_face_gauss(uint32_t a, uint32_t b, uint32_t per_side);
    Model& model() { return model_; }
    Model take();  // sorted constraints, as prescore writes them

private:
    // The face boxes a and b share: its normal axis, the two axes across it, its plane and extent.
    struct SharedFace {
        int axis = 0, u = 1, v = 2;
        double plane = 0;
        Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
    };
    SharedFace shared_face(uint32_t a, uint32_t b) const;
    Model model_;
};

// nx x ny x nz boxes of edge `cell` (unit: m) with their minimum corner at `origin`, every pair
// of face neighbours joined by join_face(per_side).
Model box_grid(uint32_t nx, uint32_t ny, uint32_t nz, double cell, const Vec3& origin, double density,
               uint32_t per_side);

}  // namespace shatter
