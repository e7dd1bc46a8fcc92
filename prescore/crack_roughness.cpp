// Rough cracks: the faired crack points moved by a seeded relief (crack_fairing.h,
// roughen_cracks and crack_relief).
#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "prescore/crack_fairing.h"

#include "core/rng.h"

namespace shatter {

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

}  // namespace shatter
