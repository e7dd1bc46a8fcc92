#include "scenes/paper_scenes.h"

#include <nlohmann/json.hpp>

#include "core/stage_file.h"
#include "scenes/box_model.h"

namespace shatter {

namespace {

// `count` boxes in a row along x, centred, bottom on y = 0, joined in order.
void beam(BoxModelBuilder& b, const GenerateSettings& g) {
    const double x0 = -0.5 * g.count * g.size.x();
    for (uint32_t i = 0; i < g.count; ++i) {
        const uint32_t p = b.box(Vec3(x0 + (i + 0.5) * g.size.x(), 0.5 * g.size.y(), 0), g.size);
        if (i > 0) b.join_face_gauss(p - 1, p, g.constraints_per_side);
    }
}

// count x count boxes in the xz plane, piece (i, k) = k * count + i.
void plate(BoxModelBuilder& b, const GenerateSettings& g) {
    const uint32_t n = g.count;
    const double x0 = -0.5 * n * g.size.x(), z0 = -0.5 * n * g.size.z();
    for (uint32_t k = 0; k < n; ++k)
        for (uint32_t i = 0; i < n; ++i)
            b.box(Vec3(x0 + (i + 0.5) * g.size.x(), 0.5 * g.size.y(), z0 + (k + 0.5) * g.size.z()), g.size);
    for (uint32_t k = 0; k < n; ++k)
        for (uint32_t i = 0; i < n; ++i) {
            if (i + 1 < n) b.join_face_gauss(k * n + i, k * n + i + 1, g.constraints_per_side);
            if (k + 1 < n) b.join_face_gauss(k * n + i, (k + 1) * n + i, g.constraints_per_side);
        }
}

// End cube (piece 0), `count` links lying on y = 0 (the ground carries the chain's weight, so a
// pull is pure tension), end cube (count + 1); the links join the cubes' faces at their foot.
void chain(BoxModelBuilder& b, const GenerateSettings& g) {
    const double half = 0.5 * g.count * g.size.x(), e = g.end_size;
    b.box(Vec3(-half - 0.5 * e, 0.5 * e, 0), Vec3::Constant(e));
    for (uint32_t i = 0; i < g.count; ++i) b.box(Vec3(-half + (i + 0.5) * g.size.x(), 0.5 * g.size.y(), 0), g.size);
    b.box(Vec3(half + 0.5 * e, 0.5 * e, 0), Vec3::Constant(e));
    for (uint32_t p = 0; p <= g.count; ++p) b.join_face_gauss(p, p + 1, g.constraints_per_side);
}

}  // namespace

Model generate_model(const GenerateSettings& g) {
    BoxModelBuilder b(g.density);
    switch (g.kind) {
        case GenerateKind::Beam: beam(b, g); break;
        case GenerateKind::Plate: plate(b, g); break;
        case GenerateKind::Chain: chain(b, g); break;
    }
    Model m = b.take();
    m.producer = producer_string();
    nlohmann::ordered_json j;
    j["generate"] = to_json(g);
    m.settings_json = j.dump();
    // The model format names each constraint's vertex: here its own pivot.
    m.mesh.vertices.resize(m.constraints.size());
    for (const Constraint& c : m.constraints) m.mesh.vertices[c.vertex] = c.pivot;
    return m;
}

}  // namespace shatter
