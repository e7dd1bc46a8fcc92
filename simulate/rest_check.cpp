#include "simulate/rest_check.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "simulate/bullet_world.h"
#include "simulate/simulate.h"

namespace shatter {

double rest_speed_landed(const Model& model) {
    Eigen::AlignedBox3d box;
    for (const Piece& p : model.pieces)
        for (const Vec3& v : p.surface.vertices) box.extend(v);
    if (box.isEmpty()) return kRestSpeed;
    return std::max(kRestSpeed, kRestSpeedPerSize * box.diagonal().norm());
}

double rest_speed(const Model& model, double gravity) {
    return std::max(kRestSpeed, std::min(rest_speed_landed(model), kRestFall * gravity * kRestHold));
}

RestCheck::RestCheck(const Model& model, const BulletWorld& world, const std::vector<double>& radius, double fps)
    : world_(world), radius_(radius), fps_(fps), mass_(world.pieces(), 0.0) {
    for (uint32_t i = 0; i < world.pieces() && i < model.pieces.size(); ++i)
        if (world.piece_dynamic(i)) mass_[i] = model.pieces[i].mass.mass;
}

Vec3 RestCheck::centre(const Trajectory& t, uint32_t g) const {
    Vec3 c = Vec3::Zero();
    double m = 0;
    for (uint32_t i = 0; i < world_.pieces(); ++i) c += mass_[i] * t.pose(g, i).position.cast<double>(), m += mass_[i];
    return m > 0 ? Vec3(c / m) : c;
}

double RestCheck::speed(const Trajectory& t, uint32_t g, uint32_t i) const {
    return (t.pose(g, i).position - t.pose(g - 1, i).position).cast<double>().norm() * fps_;
}

double RestCheck::spread(const Trajectory& t, uint32_t g, const Vec3& c) {
    by_distance_.clear();
    double total = 0;
    for (uint32_t i = 0; i < world_.pieces(); ++i)
        if (mass_[i] > 0) by_distance_.emplace_back((t.pose(g, i).position.cast<double>() - c).norm(), mass_[i]), total += mass_[i];
    std::sort(by_distance_.begin(), by_distance_.end());
    double held = 0;
    for (const auto& [d, m] : by_distance_)
        if ((held += m) >= kRestSpreadMass * total) return 2 * d;
    return 0.0;
}

bool RestCheck::stayed(const Trajectory& t, uint32_t from, uint32_t to, double rest, bool landed) {
    std::vector<Vec3> centres;
    std::vector<double> rests;
    for (uint32_t g = from; g <= to; ++g) {
        centres.push_back(centre(t, g));
        rests.push_back(landed ? std::max(rest, kRestSpeedPerSize * spread(t, g, centres.back())) : rest);
    }
    for (uint32_t i = 0; i < world_.pieces(); ++i) {
        if (!world_.piece_dynamic(i)) continue;
        if (to > from + 1 && speed(t, to, i) > speed(t, from + 1, i) + kRestSpeed) return false;
        const BodyPose& a = t.pose(from, i);
        for (uint32_t g = from + 1; g <= to; ++g) {
            const BodyPose& b = t.pose(g, i);
            const double own = std::max(rests[g - from], kRestSpeedPerSize * (b.position.cast<double>() - centres[g - from]).norm());
            if (!(speed(t, g, i) < own)) return false;
            const double angle = 2 * std::acos(std::min(1.0, std::abs(double(a.rotation.dot(b.rotation)))));
            if (!((b.position - a.position).cast<double>().norm() + angle * radius_[i] < own * kRestHold)) return false;
        }
    }
    return true;
}

}  // namespace shatter
