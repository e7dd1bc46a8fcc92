// Exact mass properties of a tet set by summing per-tet moments (formulas in the header).
#include "prescore/mass_properties.h"

#include <cmath>
#include <string>

#include "core/error.h"

namespace shatter {

MassProperties mass_properties(const TetMesh& mesh, const std::vector<uint32_t>& tets, double density) {
    if (!std::isfinite(density) || density <= 0) {
        throw_input_error("density", "must be a finite number > 0, got " + std::to_string(density),
                          "set the density in kg/m^3, e.g. 1000 for water");
    }
    MassProperties props;
    if (tets.empty()) return props;

    const Vec3 origin = mesh.vertices[mesh.tets[tets.front()][0]];
    double volume = 0;
    Vec3 first = Vec3::Zero();   // integral of x dV (m^4), relative to origin
    Mat3 second = Mat3::Zero();  // integral of x x^T dV (m^5), relative to origin
    for (uint32_t t : tets) {
        const Tet& tet = mesh.tets[t];
        std::array<Vec3, 4> v;
        for (int i = 0; i < 4; ++i) v[i] = mesh.vertices[tet[i]] - origin;
        const double vol = tet_volume(v[0], v[1], v[2], v[3]);
        const Vec3 s = v[0] + v[1] + v[2] + v[3];
        Mat3 outer = s * s.transpose();
        for (int i = 0; i < 4; ++i) outer += v[i] * v[i].transpose();
        volume += vol;
        first += vol / 4.0 * s;
        second += vol / 20.0 * outer;
    }
    const Vec3 d = first / volume;
    const Mat3 central = second - volume * d * d.transpose();
    props.volume = volume;
    props.mass = volume * density;
    props.center = origin + d;
    props.inertia = density * (central.trace() * Mat3::Identity() - central);
    // Symmetric by construction; remove rounding asymmetry so consumers can rely on it.
    props.inertia = 0.5 * (props.inertia + props.inertia.transpose()).eval();
    return props;
}

}  // namespace shatter
