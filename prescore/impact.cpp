// The impact pre-pass (see impact.h): conservative advancement of the object's rigid flight
// against each other body of the scene, one body at a time.
#include "prescore/impact.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <utility>

namespace shatter {

namespace {

// The closest point of triangle (a, b, c) to p (Ericson, "Real-Time Collision Detection", 5.1.5).
Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return a;
    const Vec3 bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
    const Vec3 cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const double denom = 1 / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

// The gap between the object at rest and another body, and where it is smallest.
struct Gap {
    double gap = std::numeric_limits<double>::infinity();  // (unit: m) negative: overlapping
    Vec3 point = Vec3::Zero();   // on the object, world frame at rest
    Vec3 normal = Vec3::UnitY(); // the other body's outward normal there
};

// Another body: its shape at t = 0 and its displacement relative to the object's, e(t).
struct Other {
    std::string name;
    ShapeKind kind = ShapeKind::Plane;
    Vec3 centre = Vec3::Zero();  // plane: a point on it
    Mat3 rotation = Mat3::Identity();
    Vec3 half = Vec3::Zero();    // box
    double radius = 0;           // sphere
    std::function<Vec3(double)> relative;  // e(t) (unit: m)
    std::function<double(double)> speed;   // a bound of |e'(t)| (unit: m/s)
    double accel = 0;            // a bound of |e''| (unit: m/s^2)
};

struct Surface {
    const std::vector<Vec3>& points;  // world frame at rest
    const std::vector<Tri>& triangles;
    double tolerance;
};

Gap plane_gap(const Surface& s, const Vec3& n, const Vec3& on) {
    Gap g;
    for (const Vec3& x : s.points) g.gap = std::min(g.gap, n.dot(x - on));
    // Every point within the tolerance of the lowest touches: their mean is the contact point.
    Vec3 sum = Vec3::Zero();
    int count = 0;
    for (const Vec3& x : s.points)
        if (n.dot(x - on) <= g.gap + s.tolerance) sum += x, ++count;
    g.point = sum / count;
    g.point -= n * n.dot(g.point - on) - n * g.gap;  // onto the lowest level
    g.normal = n;
    return g;
}

Gap sphere_gap(const Surface& s, const Vec3& c, double r) {
    Gap g;
    for (const Tri& t : s.triangles) {
        const Vec3 q = closest_on_triangle(c, s.points[t[0]], s.points[t[1]], s.points[t[2]]);
        const double d = (q - c).norm() - r;
        if (d < g.gap) g.gap = d, g.point = q, g.normal = (q - c).normalized();
    }
    return g;
}

Gap box_gap(const Surface& s, const Vec3& c, const Mat3& rot, const Vec3& half) {
    Gap g;
    for (const Vec3& x : s.points) {
        const Vec3 local = rot.transpose() * (x - c);
        const Vec3 q = local.cwiseAbs() - half;
        const Vec3 out = q.cwiseMax(0.0);
        const double d = out.norm() > 0 ? out.norm() : q.maxCoeff();
        if (d < g.gap) {
            g.gap = d, g.point = x;
            Vec3 n = Vec3::Zero();
            if (out.norm() > 0) {
                for (int i = 0; i < 3; ++i) n[i] = std::copysign(out[i], local[i]);
            } else {
                int i = 0;
                q.maxCoeff(&i);
                n[i] = local[i] < 0 ? -1 : 1;
            }
            g.normal = (rot * n).normalized();
        }
    }
    return g;
}

Gap gap_at(const Surface& s, const Other& o, double t) {
    const Vec3 e = o.relative(t);
    switch (o.kind) {
        case ShapeKind::Plane: return plane_gap(s, o.rotation * Vec3::UnitY(), o.centre + e);
        case ShapeKind::Sphere: return sphere_gap(s, o.centre + e, o.radius);
        case ShapeKind::Box: return box_gap(s, o.centre + e, o.rotation, 0.5 * o.half);
        case ShapeKind::Mesh: break;
    }
    return {};
}

// The longest step over which a relative motion of speed <= v and acceleration <= a moves less
// than `gap`: v dt + a dt^2 / 2 = gap.
double safe_step(double gap, double v, double a) {
    if (a <= 0) return v > 0 ? gap / v : std::numeric_limits<double>::infinity();
    return 2 * gap / (v + std::sqrt(v * v + 2 * a * gap));
}

struct Found {
    double time;
    Gap gap;
};

// The first time the gap closes to the tolerance, within the horizon.
std::optional<Found> first_touch(const Surface& s, const Other& o) {
    double t = 0;
    Gap g = gap_at(s, o, t);
    for (int i = 0; i < 100000; ++i) {
        if (g.gap <= s.tolerance) return Found{t, g};
        const double dt = safe_step(g.gap, o.speed(t), o.accel);
        if (!(t + dt <= kImpactHorizon)) return std::nullopt;
        const Gap next = gap_at(s, o, t + dt);
        if (next.gap >= -s.tolerance) {
            t += dt, g = next;
            continue;
        }
        // A box's gap is a bound: the step went past the touch. Bisect back to it.
        double lo = t, hi = t + dt;
        Gap at_hi = next;
        for (int k = 0; k < 60 && at_hi.gap < -s.tolerance; ++k) {
            const double mid = 0.5 * (lo + hi);
            const Gap m = gap_at(s, o, mid);
            if (m.gap > s.tolerance) lo = mid;
            else hi = mid, at_hi = m;
        }
        return Found{hi, at_hi};
    }
    return std::nullopt;
}

// A static triangle mesh: the first time a vertex of one surface, moving with the object's
// relative displacement, crosses a triangle of the other (object vertices against the mesh's
// triangles, the mesh's vertices against the object's): each crossing is a root of a quadratic,
// n . (x + e(t) - a) = 0, the displacement being x0 + v t + g t^2 / 2. Vertex-against-face contacts
// only (an edge that first meets an edge is found when a vertex follows): the same bound as the box's.
//
// The earliest t in [0, horizon] with n . (x + d t + a t^2 / 2 - p) = 0 and the point x + d t + a t^2
// / 2 within the triangle (p, q, r); +infinity when there is none.
double crossing_time(const Vec3& x, const Vec3& d, const Vec3& acc, const Vec3& p, const Vec3& q, const Vec3& r,
                     const Vec3& n, double tolerance) {
    const double c0 = n.dot(x - p), c1 = n.dot(d), c2 = 0.5 * n.dot(acc);
    double roots[2];
    int count = 0;
    if (std::abs(c0) <= tolerance) {
        roots[count++] = 0;
    } else if (std::abs(c2) < 1e-15) {
        if (c1 != 0) roots[count++] = -c0 / c1;
    } else {
        const double disc = c1 * c1 - 4 * c2 * c0;
        if (disc >= 0) {
            const double s = std::sqrt(disc);
            const double q1 = -0.5 * (c1 + std::copysign(s, c1));  // stable roots
            roots[count++] = q1 / c2;
            if (q1 != 0) roots[count++] = c0 / q1;
            if (count == 2 && roots[1] < roots[0]) std::swap(roots[0], roots[1]);
        }
    }
    for (int i = 0; i < count; ++i) {
        const double t = roots[i];
        if (!(t >= 0 && t <= kImpactHorizon)) continue;
        const Vec3 y = x + d * t + 0.5 * acc * t * t;
        if ((closest_on_triangle(y, p, q, r) - y).norm() <= tolerance) return t;
    }
    return std::numeric_limits<double>::infinity();
}

// A static mesh collider's first contact with the object (impact.h): the earliest crossing of an
// object vertex through a mesh triangle and of a mesh vertex through an object triangle, the
// object displaced by fall(t) = v0 t + g t^2 / 2. `mesh` is in the world frame. The contact point
// is the mean of the crossings within the tolerance's time of the first, on the object at rest.
std::optional<Found> first_mesh_touch(const Surface& s, const TriangleMesh& mesh, const Vec3& v0, const Vec3& g) {
    double first = std::numeric_limits<double>::infinity();
    struct Hit {
        double time;
        Vec3 point, normal;
    };
    std::vector<Hit> hits;
    auto unit_normal = [](const Vec3& a, const Vec3& b, const Vec3& c) { return Vec3((b - a).cross(c - a).normalized()); };
    auto consider = [&](double t, const Vec3& point, const Vec3& normal) {
        if (!(t <= first + 1.0)) return;  // far later than the first: not kept
        first = std::min(first, t);
        hits.push_back({t, point, normal});
    };
    for (const Tri& tri : mesh.triangles) {  // the object's vertices through the mesh's triangles
        const Vec3 &a = mesh.vertices[tri[0]], &b = mesh.vertices[tri[1]], &c = mesh.vertices[tri[2]];
        const Vec3 n = unit_normal(a, b, c);
        if (!n.allFinite()) continue;
        for (const Vec3& x : s.points)
            if (const double t = crossing_time(x, v0, g, a, b, c, n, s.tolerance); t < kImpactHorizon) consider(t, x, n);
    }
    for (const Tri& tri : s.triangles) {  // the mesh's vertices through the object's triangles
        const Vec3 &a = s.points[tri[0]], &b = s.points[tri[1]], &c = s.points[tri[2]];
        const Vec3 n = unit_normal(a, b, c);
        if (!n.allFinite()) continue;
        for (const Vec3& y : mesh.vertices)
            if (const double t = crossing_time(y, -v0, -g, a, b, c, n, s.tolerance); t < kImpactHorizon)
                consider(t, y - v0 * t - 0.5 * g * t * t, -n);
    }
    if (hits.empty()) return std::nullopt;
    const Vec3 velocity = v0 + g * first;  // the object's, against the mesh at rest
    const double window = s.tolerance / std::max(velocity.norm(), 1e-12);
    Found f{first, {}};
    Vec3 sum = Vec3::Zero(), normal = Vec3::Zero();
    int count = 0;
    std::vector<Vec3> seen;  // a vertex on an edge crosses both triangles: counted once
    for (const Hit& h : hits)
        if (h.time <= first + window && std::find(seen.begin(), seen.end(), h.point) == seen.end()) {
            seen.push_back(h.point);
            sum += h.point, ++count;
            // The mesh's normal there, turned to face the object as it comes.
            normal += h.normal.dot(velocity) > 0 ? Vec3(-h.normal) : h.normal;
        }
    f.gap.gap = 0;
    f.gap.point = sum / count;
    f.gap.normal = normal.norm() > 0 ? Vec3(normal.normalized()) : Vec3(-velocity.normalized());
    return f;
}

}  // namespace

Vec3 object_origin(const std::vector<Vec3>& vertices, const ObjectSettings& object) {
    if (object.place == Placement::Origin || vertices.empty()) return object.pose.position;
    const Mat3 r = rotation_matrix(object.pose.rotation_deg);
    Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
    for (const Vec3& v : vertices) {
        const Vec3 x = r * v;
        lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
    }
    return object.pose.position - Vec3(0.5 * (lo.x() + hi.x()), lo.y(), 0.5 * (lo.z() + hi.z()));
}

std::vector<Contact> Impact::grading() const {
    std::vector<Contact> out;
    for (const Contact& c : contacts) {
        if (c.normal_speed < kMinImpactSpeed) continue;
        if (!out.empty() && c.time > out.front().time + kSimultaneous) break;
        out.push_back(c);
    }
    return out;
}

Impact find_impact(const TriangleMesh& surface, const SceneSettings& scene, const ObjectSettings& object,
                   double tolerance, const std::vector<TriangleMesh>* collider_meshes) {
    Impact impact;
    impact.spin_ignored = object.angular_velocity.norm() > 0;
    const Mat3 r = rotation_matrix(object.pose.rotation_deg);
    const Vec3 origin = object_origin(surface.vertices, object);
    std::vector<Vec3> points;
    points.reserve(surface.vertices.size());
    for (const Vec3& v : surface.vertices) points.push_back(r * v + origin);
    const Surface s{points, surface.triangles, tolerance};

    const Vec3 v0 = object.velocity, g = scene.gravity;
    // The object's own displacement and velocity at time t.
    auto fall = [v0, g](double t) { return Vec3(v0 * t + 0.5 * g * t * t); };
    auto fall_speed = [v0, g](double t) { return (v0 + g * t).norm(); };
    std::vector<Other> others;
    auto add_static = [&](std::string name, const ShapeSettings& shape, const Pose& pose) {
        Other o;
        o.name = std::move(name);
        o.kind = shape.kind;
        o.centre = pose.position;
        o.rotation = rotation_matrix(pose.rotation_deg);
        o.half = shape.size;
        o.radius = shape.radius;
        o.relative = [fall](double t) { return Vec3(-fall(t)); };
        o.speed = fall_speed;
        o.accel = g.norm();
        others.push_back(std::move(o));
    };
    if (scene.ground) {
        ShapeSettings plane;
        plane.kind = ShapeKind::Plane;
        Pose level;
        level.position = Vec3(0, scene.ground_height, 0);
        add_static("ground", plane, level);
    }
    std::vector<std::pair<std::string, TriangleMesh>> meshes;  // mesh colliders, world frame
    for (size_t i = 0; i < scene.colliders.size(); ++i) {
        const ColliderSettings& c = scene.colliders[i];
        const std::string name = c.name.empty() ? to_string(c.shape.kind) : c.name;
        if (c.shape.kind != ShapeKind::Mesh) {
            add_static(name, c.shape, c.pose);
        } else if (!collider_meshes || i >= collider_meshes->size()) {
            ++impact.mesh_colliders_skipped;
        } else {
            TriangleMesh m = (*collider_meshes)[i];
            const Mat3 rc = rotation_matrix(c.pose.rotation_deg);
            for (Vec3& v : m.vertices) v = rc * v + c.pose.position;
            meshes.emplace_back(name, std::move(m));
        }
    }
    for (const KinematicSettings& k : scene.kinematic) {
        add_static(k.name.empty() ? "kinematic" : k.name, k.shape, k.pose);
        Other& o = others.back();
        double fastest = k.velocity.norm();
        for (size_t i = 1; i < k.keys.size(); ++i)
            if (k.keys[i].time > k.keys[i - 1].time)
                fastest = std::max(fastest, (k.keys[i].position - k.keys[i - 1].position).norm() /
                                                (k.keys[i].time - k.keys[i - 1].time));
        o.relative = [k, fall](double t) { return Vec3(kinematic_position(k, t) - kinematic_position(k, 0) - fall(t)); };
        o.speed = [fastest, fall_speed](double t) { return fastest + fall_speed(t); };
    }
    for (const ProjectileSettings& p : scene.projectiles) {
        add_static(p.name.empty() ? "projectile" : p.name, p.shape, p.pose);
        Other& o = others.back();
        const Vec3 w = p.velocity - v0;  // both fall alike: relative to the object it flies straight
        o.relative = [w](double t) { return Vec3(w * t); };
        o.speed = [w](double) { return w.norm(); };
        o.accel = 0;
    }

    for (const Other& o : others) {
        const std::optional<Found> f = first_touch(s, o);
        if (!f) continue;
        Contact c;
        c.with = o.name;
        c.time = f->time;
        c.point = f->gap.point + fall(f->time);
        c.model_point = r.transpose() * (f->gap.point - origin);
        c.normal = f->gap.normal;
        const double h = 1e-6;
        const Vec3 rel_velocity = -(o.relative(f->time + h) - o.relative(std::max(0.0, f->time - h))) /
                                  (f->time + h - std::max(0.0, f->time - h));
        c.speed = rel_velocity.norm();
        c.normal_speed = -c.normal.dot(rel_velocity);
        impact.contacts.push_back(c);
    }
    for (const auto& [name, mesh] : meshes) {
        const std::optional<Found> f = first_mesh_touch(s, mesh, v0, g);
        if (!f) continue;
        Contact c;
        c.with = name;
        c.time = f->time;
        c.point = f->gap.point + fall(f->time);
        c.model_point = r.transpose() * (f->gap.point - origin);
        c.normal = f->gap.normal;
        const Vec3 velocity = v0 + g * f->time;
        c.speed = velocity.norm();
        c.normal_speed = -c.normal.dot(velocity);
        impact.contacts.push_back(c);
    }
    std::stable_sort(impact.contacts.begin(), impact.contacts.end(),
                     [](const Contact& a, const Contact& b) { return a.time < b.time; });
    return impact;
}

}  // namespace shatter
