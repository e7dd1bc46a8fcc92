// Motion of driven pieces ([[object.driven]]), declared in core/scene_settings.h.
#include "core/scene_settings.h"

namespace shatter {

Vec3 drive_offset(const PieceDriveSettings& d, double t) {
    if (d.fixed) return Vec3::Zero();
    if (d.keys.empty()) return d.velocity * t;
    if (t <= d.keys.front().time) return d.keys.front().position;
    for (size_t i = 1; i < d.keys.size(); ++i) {
        const KeyFrame& a = d.keys[i - 1];
        const KeyFrame& b = d.keys[i];
        if (t <= b.time) return a.position + (b.position - a.position) * ((t - a.time) / (b.time - a.time));
    }
    return d.keys.back().position;
}

}  // namespace shatter
