// The continuum reference of the accuracy study (docs/accuracy.md, "A continuum reference"): a
// linear-elastic solid on linear tetrahedra with corotational stiffness, integrated implicitly.
// It lives in bench/ and is no part of the product's path.
//
// - Elasticity: small-strain isotropic linear elasticity (Lame mu, lambda from E, nu) per tet,
//   measured in the tet's rotated frame: f_e = -R K_e (R^T x_e - X_e), R the rotation of the
//   polar decomposition of the deformation gradient F = R S. This is the corotational ("warped
//   stiffness") method of Mueller & Gross, "Interactive Virtual Materials", GI 2004. R is
//   followed from one evaluation to the next by the iteration of Mueller, Bender, Chentanez &
//   Macklin, MIG 2016 (an inverted tet takes F's SVD, reflection removed, as Irving, Teran &
//   Fedkiw, SCA 2004). With the polar R this force is the exact gradient of the energy
//   V (mu |F - R|^2 + lambda/2 tr(R^T F - I)^2) (McAdams et al., SIGGRAPH 2011), so the solid
//   is conservative. Without corotation (R = I) it is plain linear elasticity.
// - Mass: lumped, a quarter of each tet's mass rho V on each of its vertices.
// - Time: the implicit midpoint rule (symplectic; for a linear solid it is the trapezoidal rule,
//   Newmark's average acceleration, which conserves energy exactly) or backward Euler (damps).
//   Each step solves for the end velocity by Newton's method with the tangent M + c h^2 K at the
//   step's first iterate (c = 1/4 midpoint, 1 backward Euler), K the corotated stiffness
//   R K_e R^T (the derivative of R is left out, as Mueller & Gross do), factored by Eigen's
//   SimplicialLDLT. Without corotation the tangent is exact and constant: it is factored once.
//   Each update is backtracked until the residual's norm falls; a step that does not converge
//   in max_newton iterations is taken again as two halves.
// - Boundary conditions: clamped vertices (fixed where they are) and driven vertices (constant
//   velocity); gravity; constant vertex loads; and an optional extra force (contact, in its own
//   file) with a per-vertex stiffness and damping for the tangent (refreshed within a step when
//   the stiffness changes, i.e. a contact begins or ends).
// Units: SI (m, kg, s, N, J, Pa).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/Sparse>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <functional>
#include <memory>
#include <vector>

#include "core/geometry.h"

namespace shatter::fem {

struct FemMaterial {
    double density = 2500;  // (unit: kg/m^3)
    double young = 70e9;    // Young's modulus E (unit: Pa)
    double poisson = 0.22;  // Poisson's ratio nu (unit: 1)
};

enum class FemIntegrator { Midpoint, BackwardEuler };
// How a step's linear systems are solved: a sparse LDL^T factorization (exact; cost grows with the
// fill-in), or conjugate gradients with a diagonal preconditioner, warm-started at zero (cheap
// when the step is short: M + c h^2 K is then close to its diagonal).
enum class FemLinearSolver { LDLT, CG };

struct FemSettings {
    FemMaterial material;
    Vec3 gravity = Vec3(0, -9.81, 0);  // (unit: m/s^2)
    bool corotational = true;
    FemIntegrator integrator = FemIntegrator::Midpoint;
    FemLinearSolver solver = FemLinearSolver::LDLT;
    double cg_tol = 1e-10;      // CG's relative residual
    int max_newton = 20;        // Newton iterations per step at most
    double newton_tol = 1e-10;  // stop when max |dv| <= newton_tol x (max |v| + 1e-3 m/s) + newton_floor
    double newton_floor = 1e-9; // (unit: m/s) below round-off's reach at rest, far below any motion that matters
    int max_backtracks = 6;     // halvings of a Newton update while the residual's norm does not fall
    int max_halvings = 4;       // a step whose Newton iteration does not converge is taken as two halves, down to h / 2^this
};

// An extra force evaluated at positions x and velocities v (3 per vertex): adds to f and, for the
// step's tangent, to block_k (its stiffness -df_v/dx_v) and block_c (its damping -df_v/dv_v):
// per vertex v a symmetric positive semi-definite 3 x 3 block, 9 numbers row by row.
using ExtraForce = std::function<void(const Eigen::VectorXd& x, const Eigen::VectorXd& v, Eigen::VectorXd& f,
                                      Eigen::VectorXd& block_k, Eigen::VectorXd& block_c)>;

using StepBegin = std::function<void(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v)>;

class FemSolid {
public:
    FemSolid(const TetMesh& mesh, const FemSettings& settings);
    ~FemSolid();

    // Boundary conditions; set them before the first step or solve (they fix the matrix pattern).
    void clamp(const std::vector<uint32_t>& vertices);                        // fixed where they are
    void drive(const std::vector<uint32_t>& vertices, const Vec3& velocity);  // moved at constant velocity
    void set_load(uint32_t vertex, const Vec3& force);                        // constant (unit: N)
    bool constrained(uint32_t vertex) const { return constrained_[vertex]; }  // clamped or driven
    void set_extra_force(ExtraForce f) { extra_ = std::move(f); }
    // Called at the start of every step with the time, positions and velocities there (e.g. for
    // forces that hold a value through the step).
    void set_step_begin(StepBegin f) { step_begin_ = std::move(f); }
    // Vertices that move as one: vertex v shares the degrees of freedom of group[v] (group[v] ==
    // v for a vertex of its own). The pieces' copies of an interface vertex are joined so until
    // their interface breaks (bench/fem_interfaces.h). Copies must be at the same place. A group
    // with a clamped or driven member moves with it.
    void set_vertex_groups(const std::vector<uint32_t>& group);
    // The force the rest of its group exerted on each vertex over the last step (unit: N):
    // m (v1 - v0) / h minus the vertex's own tets', gravity's, loads' and extra forces. Zero for
    // a vertex of its own, up to the Newton tolerance.
    const Eigen::VectorXd& group_forces() const { return group_force_; }

    // One step of length h (unit: s), as shorter ones where Newton's method does not converge.
    // Returns the Newton iterations it took.
    int step(double h);
    // The time the step evaluates its forces at (midpoint: t + h / 2; backward Euler: t + h), for
    // an extra force that depends on time.
    double eval_time() const { return eval_time_; }
    long halved_steps() const { return halved_steps_; }       // steps taken as two halves
    long unconverged_steps() const { return unconverged_steps_; }  // taken unconverged at the shortest step
    // Static equilibrium under gravity, loads and the boundary conditions (Newton on the
    // corotational forces; exact in one solve without corotation). Velocities are set to zero.
    int solve_static();

    double time() const { return time_; }
    void set_time(double t) { time_ = t; }
    long cg_iterations() const { return cg_iterations_; }  // total over all steps
    size_t vertex_count() const { return rest_.size() / 3; }
    size_t free_dofs() const { return n_free_; }
    Eigen::VectorXd& positions() { return x_; }  // 3 per vertex (unit: m)
    Eigen::VectorXd& velocities() { return v_; }  // (unit: m/s)
    const Eigen::VectorXd& positions_const() const { return x_; }
    const Eigen::VectorXd& velocities_const() const { return v_; }
    const Eigen::VectorXd& rest() const { return rest_; }
    const Eigen::VectorXd& lumped_mass() const { return mass_; }  // per coordinate (unit: kg)
    Vec3 position(uint32_t v) const { return x_.segment<3>(3 * v); }
    Vec3 velocity(uint32_t v) const { return v_.segment<3>(3 * v); }

    double kinetic_energy() const;
    double elastic_energy() const;            // sum over tets of 1/2 e^T K_e e, e = R^T x_e - X_e
    double gravity_energy() const;            // -sum m g . x
    double load_energy() const;               // -sum f . (x - X) of the constant loads
    double tet_elastic_energy(size_t tet) const;

    // The tangent stiffness over the free coordinates at the current positions (the corotated
    // R K_e R^T), and the free coordinates' lumped masses, for modal analysis.
    Eigen::SparseMatrix<double> free_stiffness();
    Eigen::VectorXd free_mass() const;
    const std::vector<int>& free_index() const { return free_; }  // coordinate -> free index or -1

    // The elastic force on every coordinate at positions x (unit: N), and per tet the rotation.
    void elastic_forces(const Eigen::VectorXd& x, Eigen::VectorXd& f);

private:
    void prepare_pattern();
    int step_within(double h, int depth);
    int newton_step(double h, bool& converged);
    void update_rotations(const Eigen::VectorXd& x);
    void assemble_tangent(double c_k);  // c_k R K_e R^T into tangent_'s lower triangle
    void total_forces(const Eigen::VectorXd& x, const Eigen::VectorXd& v, Eigen::VectorXd& f, Eigen::VectorXd& block_k,
                      Eigen::VectorXd& block_c);
    // c_k block_k + c_c block_c into the tangent's per-vertex 3 x 3 blocks (lower triangle).
    void add_blocks(double c_k, const Eigen::VectorXd& block_k, double c_c, const Eigen::VectorXd& block_c);

    FemSettings s_;
    std::vector<Tet> tets_;
    std::vector<double> volume_;
    std::vector<Eigen::Matrix3d> dm_inv_;
    std::vector<Eigen::Matrix<double, 12, 12>> ke_;
    std::vector<Eigen::Matrix3d> rot_;
    std::vector<Eigen::Quaterniond> quat_;  // rot_ as a quaternion, the next evaluation's start
    Eigen::VectorXd rest_, x_, v_, mass_, loads_;
    std::vector<int> free_;               // per coordinate: index among the free ones, -1 if constrained
    std::vector<Vec3> drive_velocity_;    // per vertex (zero for clamped and free)
    std::vector<bool> constrained_;       // per vertex
    std::vector<uint32_t> group_;         // per vertex: the vertex whose degrees of freedom it shares
    Eigen::VectorXd group_force_;
    size_t n_free_ = 0;
    bool pattern_ready_ = false;
    Eigen::SparseMatrix<double> tangent_;
    std::vector<int> slot_;       // per tet entry (tet, a, b, i, j) in order: index into tangent_'s values, -1 unused
    std::vector<int> diag_slot_;  // per free coordinate: its diagonal's value index
    std::vector<int> vertex_slot_;  // per vertex and (i, j) of its 3 x 3 block: value index, -1 unused
    std::unique_ptr<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>> ldlt_;
    std::unique_ptr<Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower>> cg_;
    long cg_iterations_ = 0;
    bool constant_factored_ = false;
    double factored_c_ = -1;
    Eigen::VectorXd factored_block_k_;
    ExtraForce extra_;
    StepBegin step_begin_;
    double time_ = 0, eval_time_ = 0;
    long halved_steps_ = 0, unconverged_steps_ = 0;
};

}  // namespace shatter::fem
