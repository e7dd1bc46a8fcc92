// Conversions between Bullet's and Eigen's vectors, matrices and transforms.
#pragma once

#include <btBulletDynamicsCommon.h>

#include "core/geometry.h"

namespace shatter {

inline Vec3 to_eigen(const btVector3& v) { return Vec3(v.x(), v.y(), v.z()); }
inline btVector3 to_bullet(const Vec3& v) { return btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z())); }
inline Mat3 to_eigen(const btMatrix3x3& m) {
    Mat3 out;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) out(r, c) = m[r][c];
    return out;
}
inline btMatrix3x3 to_bullet_matrix(const Mat3& m) {
    return btMatrix3x3(btScalar(m(0, 0)), btScalar(m(0, 1)), btScalar(m(0, 2)), btScalar(m(1, 0)), btScalar(m(1, 1)),
                       btScalar(m(1, 2)), btScalar(m(2, 0)), btScalar(m(2, 1)), btScalar(m(2, 2)));
}

inline btTransform make_transform(const Mat3& r, const Vec3& p) { return btTransform(to_bullet_matrix(r), to_bullet(p)); }

}  // namespace shatter
