#include "simulate/joined_response.h"

#include <algorithm>

#include <Eigen/Sparse>

namespace shatter {

namespace {

Mat3 skew(const Vec3& r) {
    Mat3 m;
    m << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
    return m;
}

// Each joint's penalty over the heavier of its two bodies' masses: the joints' relative pivot
// velocities come out about 1/kPenalty of the free ones.
constexpr double kPenalty = 1e8;

}  // namespace

std::vector<VelocityChange> joined_response(const std::vector<JoinedBody>& bodies,
                                            const std::vector<JoinedJoint>& joints,
                                            const std::vector<BodyImpulse>& impulses) {
    // Six unknowns per dynamic body: its change of velocity and of angular velocity.
    std::vector<int64_t> column(bodies.size(), -1);
    Eigen::Index n = 0;
    for (size_t x = 0; x < bodies.size(); ++x)
        if (bodies[x].dynamic) column[x] = n, n += 6;
    std::vector<VelocityChange> out(bodies.size());
    if (n == 0) return out;
    // (M + sum_j kappa_j G_j^T G_j) du = j: the joints as stiff penalties in the bodies' space,
    // where a pair held at more points than it needs costs nothing (no singular system).
    // Summed block by block (6 x 6 per pair of bodies), each entry in the order of the terms:
    // a body's mass and inertia, then each joint's term in turn.
    using Block = Eigen::Matrix<double, 6, 6>;
    struct Sum {
        uint32_t row, col;  // bodies
        Block value;
        bool joined;  // a joint's term added: all 36 entries stand (else a body's 12 of mass and inertia)
    };
    std::vector<Sum> sums;
    std::vector<std::vector<std::pair<uint32_t, size_t>>> sum_at(bodies.size());  // per row body: (column body, sum)
    for (size_t x = 0; x < bodies.size(); ++x) {
        if (column[x] < 0) continue;
        Block m = Block::Zero();
        m.topLeftCorner<3, 3>().diagonal().setConstant(1.0 / bodies[x].inv_mass);
        m.bottomRightCorner<3, 3>() = bodies[x].inv_inertia.inverse();
        sum_at[x].push_back({uint32_t(x), sums.size()});
        sums.push_back({uint32_t(x), uint32_t(x), m, false});
    }
    for (const JoinedJoint& joint : joints) {
        const uint32_t body[2] = {joint.a, joint.b};
        // A joint's relative pivot velocity is sum_x B_x du_x, B_x = s_x [I, -[r_x]] (s_a = -1, s_b = 1).
        Eigen::Matrix<double, 3, 6> g[2];
        double heaviest = 0;
        for (int k = 0; k < 2; ++k) {
            g[k] << Mat3::Identity(), -skew(joint.pivot - bodies[body[k]].centre);
            if (k == 0) g[k] = -g[k];
            if (bodies[body[k]].dynamic) heaviest = std::max(heaviest, 1.0 / bodies[body[k]].inv_mass);
        }
        const double kappa = kPenalty * heaviest;
        for (int k = 0; k < 2; ++k)
            for (int l = 0; l < 2; ++l) {
                if (column[body[k]] < 0 || column[body[l]] < 0) continue;
                const Block term = kappa * g[k].transpose() * g[l];
                auto& row = sum_at[body[k]];
                auto at = std::find_if(row.begin(), row.end(), [&](const auto& e) { return e.first == body[l]; });
                if (at == row.end()) {
                    row.push_back({body[l], sums.size()});
                    sums.push_back({body[k], body[l], term, true});
                    continue;
                }
                Sum& sum = sums[at->second];
                if (sum.joined) {
                    sum.value += term;
                } else {  // a body's own block: its mass and inertia entries first
                    Block first = term;
                    first.topLeftCorner<3, 3>().diagonal() = sum.value.topLeftCorner<3, 3>().diagonal() + term.topLeftCorner<3, 3>().diagonal();
                    first.bottomRightCorner<3, 3>() = sum.value.bottomRightCorner<3, 3>() + term.bottomRightCorner<3, 3>();
                    sum.value = first;
                    sum.joined = true;
                }
            }
    }
    std::vector<Eigen::Triplet<double>> entries;
    for (const Sum& sum : sums)
        for (int p = 0; p < 6; ++p)
            for (int q = 0; q < 6; ++q)
                if (sum.joined || (p < 3 && q == p) || (p >= 3 && q >= 3))
                    entries.emplace_back(column[sum.row] + p, column[sum.col] + q, sum.value(p, q));
    Eigen::SparseMatrix<double> a(n, n);
    a.setFromTriplets(entries.begin(), entries.end());
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
    for (const BodyImpulse& i : impulses) {
        if (column[i.body] < 0) continue;
        rhs.segment<3>(column[i.body]) += i.impulse;
        rhs.segment<3>(column[i.body] + 3) += (i.point - bodies[i.body].centre).cross(i.impulse);
    }
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(a);
    const Eigen::VectorXd du = ldlt.solve(rhs);
    for (size_t x = 0; x < bodies.size(); ++x)
        if (column[x] >= 0) out[x] = {du.segment<3>(column[x]), du.segment<3>(column[x] + 3)};
    // The penalties are internal forces: a group of bodies joined to nothing that stands still
    // gains exactly the impulses' momentum. The solve's round-off (1e-16 of kappa) leaves it off by
    // ~1e-8 of them; each such group's bodies share the difference.
    std::vector<uint32_t> group(bodies.size());
    for (uint32_t x = 0; x < group.size(); ++x) group[x] = x;
    auto root = [&](uint32_t x) {
        while (group[x] != x) x = group[x] = group[group[x]];
        return x;
    };
    for (const JoinedJoint& joint : joints)
        if (bodies[joint.a].dynamic && bodies[joint.b].dynamic) group[root(joint.a)] = root(joint.b);
    std::vector<bool> anchored(bodies.size(), false);
    for (const JoinedJoint& joint : joints)
        if (!bodies[joint.a].dynamic || !bodies[joint.b].dynamic)
            anchored[root(bodies[joint.a].dynamic ? joint.a : joint.b)] = true;
    std::vector<double> mass(bodies.size(), 0.0);
    std::vector<Vec3> excess(bodies.size(), Vec3::Zero());  // momentum gained - impulses, per group
    for (size_t x = 0; x < bodies.size(); ++x)
        if (column[x] >= 0) mass[root(uint32_t(x))] += 1.0 / bodies[x].inv_mass, excess[root(uint32_t(x))] += out[x].linear / bodies[x].inv_mass;
    for (const BodyImpulse& i : impulses)
        if (column[i.body] >= 0) excess[root(i.body)] -= i.impulse;
    for (size_t x = 0; x < bodies.size(); ++x) {
        const uint32_t g = root(uint32_t(x));
        if (column[x] >= 0 && !anchored[g]) out[x].linear -= excess[g] / mass[g];
    }
    return out;
}

std::vector<VelocityChange> rigid_response(const std::vector<JoinedBody>& bodies, const std::vector<BodyImpulse>& impulses) {
    std::vector<VelocityChange> out(bodies.size());
    double mass = 0;
    Vec3 moment = Vec3::Zero();
    for (const JoinedBody& b : bodies)
        if (b.dynamic) mass += 1.0 / b.inv_mass, moment += b.centre / b.inv_mass;
    if (!(mass > 0) || std::any_of(bodies.begin(), bodies.end(), [](const JoinedBody& b) { return !b.dynamic; }))
        return out;
    const Vec3 centre = moment / mass;
    Mat3 inertia = Mat3::Zero();
    for (const JoinedBody& b : bodies) {
        const Vec3 d = b.centre - centre;
        inertia += b.inv_inertia.inverse() + (1.0 / b.inv_mass) * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
    }
    Vec3 linear = Vec3::Zero(), angular = Vec3::Zero();
    for (const BodyImpulse& i : impulses) linear += i.impulse, angular += (i.point - centre).cross(i.impulse);
    const Vec3 v = linear / mass, w = inertia.inverse() * angular;
    for (size_t x = 0; x < bodies.size(); ++x) out[x] = {v + w.cross(bodies[x].centre - centre), w};
    return out;
}

}  // namespace shatter
