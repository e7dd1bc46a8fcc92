// The accuracy and cost study (docs/accuracy.md): what the study runs and how it scores
// a run. Shared by bench/study*.cpp.
//
// Every scene is built here from the scene generators (scenes/paper_scenes.h) and prescore with
// the study's own fixed settings (a copy of the shots in assets/ as of the study's writing), so
// that the study does not shift when the shots are tuned.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/model.h"
#include "simulate/simulate.h"

namespace shatter::study {

// ---- scenes (bench/study_scenes.cpp) -------------------------------------------------------

struct StudyCase {
    std::string scene;
    Model model;
    SimulationInput input;
    double prescore_seconds = 0;  // building the model (generate or prescore) (unit: s)
    uint32_t reference_substeps_factor = 16;  // the reference runs at h / this (the chain's CFM allows less)
};

// The model knobs a user can turn (box scenes: constraints_per_side; the bunny: the rest).
struct ModelKnobs {
    uint32_t constraints_per_side = 0;  // box scenes: n x n per shared face; 0: the scene's (2, the chain 1)
    double resolution = 20;             // bunny: tet size = diagonal / resolution
    uint32_t collision_max_parts = 16;  // bunny: convex parts per piece
    uint32_t constraints_per_pair = 0;  // bunny: most constraints per piece pair (0: all)
};

StudyCase beam_case(const ModelKnobs& k = {});
StudyCase plate_case(const ModelKnobs& k = {});
StudyCase chain_case(const ModelKnobs& k = {});
StudyCase bunny_case(const ModelKnobs& k = {});
StudyCase make_case(const std::string& scene, const ModelKnobs& k = {});

// The stability rig: three 10 x 2 x 2 cm glass bars in a row along x, 2 x 2 constraints per
// joint, piece 0 held fixed, no ground: a two-link cantilever under gravity. Its root joint
// breaks as it sags (strength = strength_fraction x the static root force); piece 2's mass (and
// inertia) is mass_ratio x piece 1's.
struct RigSettings {
    double stiffness = 1e12;      // (unit: N/m^3) ~ glass: E / l = 70 GPa / 0.1 m
    double mass_ratio = 1;        // m2 / m1
    double strength_fraction = 0.6;
    double fps = 120;
    uint32_t substeps = 8;
    double duration = 0.5;        // (unit: s)
    double alpha = 1;
};
StudyCase rig_case(const RigSettings& r);

// The stiffness rig: a 10 x 2 x 2 cm glass bar held by 2 x 2 constraints to a fixed bar, pulled
// along its axis by gravity (9.81 m/s^2 along +x), undamped, no ground, never breaking.
StudyCase stiffness_rig_case(double stiffness, uint32_t substeps, uint32_t iterations);

// ---- methods (bench/study_scenes.cpp) ------------------------------------------------------

// The breaking methods of docs/accuracy.md, applied to a case's settings.
struct Method {
    const char* name;
    const char* label;
};
const std::vector<Method>& methods();
void apply_method(const std::string& method, SimulationInput& in);

// ---- runs and metrics (bench/study_metrics.cpp) ----------------------------------------------

struct RunOutcome {
    SimulationResult sim;
    bool refused = false;   // settings refused (CFM beyond max_cfm)
    std::string message;
    double wall_seconds = 0;
    double cpu_seconds = 0;
};
RunOutcome run_case(const StudyCase& c);
// run_case `repeats` times (the runs are deterministic) keeping the least wall and CPU time: the
// machine is shared, and the least time is the least disturbed.
RunOutcome run_timed(const StudyCase& c, int repeats);

// Mean over recorded frames up to `until` (s) and over material points of the distance between a
// point's position in `run` and in `ref` (unit: m). The points: each reference piece's centre of
// mass and six points at 40% of its half-extents; in a model with other pieces, a point belongs
// to the piece of its nearest tet centroid. Infinite when the run stopped early.
double trajectory_error(const Model& run_model, const Trajectory& run, const Model& ref_model,
                        const Trajectory& ref, double until);

// The same points, root mean square over the recorded frames with from <= t <= until (unit: m).
double trajectory_rms(const Model& run_model, const Trajectory& run, const Model& ref_model, const Trajectory& ref,
                      double from, double until);

double first_break(const SimulationResult& r);  // (unit: s), NaN when nothing broke
size_t fragments(const Model& model, const SimulationResult& r);
// Max over breaks of |injected - intended| / intended, intended = what the break gives back
// (given_back: alpha E with split "total", plus held energy released, less energy held) or the
// sum of the per-body shares; 0 when nothing broke or alpha = 0.
double energy_identity_error(const SimulationResult& r, bool per_body);
// (sum injected + energy still held - alpha sum E) / (alpha sum E): how far the whole run's books
// are off alpha E.
double energy_books_error(const SimulationResult& r);
// The stiffness rig's measured stiffness over the intended one, minus 1.
double stiffness_identity_error(const StudyCase& c, const SimulationResult& r);

// Stability classes of docs/accuracy.md, in the order they are tested.
enum class Stability { Refused, NaN, EnergyGrowth, Cascade, FlyApart, Stable };
const char* to_string(Stability s);
Stability classify(const StudyCase& c, const RunOutcome& o, double* energy_growth);
// The largest number of breaks inside any window of `window` seconds (breaks in time order).
inline size_t most_breaks_within(const std::vector<BreakRecord>& breaks, double window) {
    size_t best = 0, first = 0;
    for (size_t i = 0; i < breaks.size(); ++i) {
        while (breaks[i].time - breaks[first].time > window + 1e-12) ++first;
        best = std::max(best, i - first + 1);
    }
    return best;
}

// The energy test of classify, inline so that tests built without the study's library share it:
// kinetic + potential + stored may grow by what the breaks injected, plus 10% of the larger of
// that and E_ref = the work gravity does on the dynamic pieces over 10 cm. `largest` is the
// largest growth over the run (unit: J); `grew`: it passed its allowance somewhere.
struct EnergyGrowthTest {
    double largest = -INFINITY;
    bool grew = false;
};
inline EnergyGrowthTest energy_growth_test(const StudyCase& c, const SimulationResult& r) {
    double mass = 0;
    std::vector<char> driven(c.model.pieces.size(), 0);
    for (const PieceDriveSettings& d : c.input.object.driven) driven[d.piece] = 1;
    for (size_t p = 0; p < c.model.pieces.size(); ++p)
        if (!driven[p]) mass += c.model.pieces[p].mass.mass;
    const double e_ref = mass * c.input.scene.gravity.norm() * 0.1;
    const EnergySample& e0 = r.energy.front();
    const double start = e0.kinetic + e0.potential + e0.stored;
    EnergyGrowthTest out;
    for (const EnergySample& e : r.energy) {
        const double g = e.kinetic + e.potential + e.stored - start - e.injected;
        out.largest = std::max(out.largest, g);
        out.grew = out.grew || g > 0.1 * std::max(e.injected, e_ref);
    }
    return out;
}

// ---- output ------------------------------------------------------------------------------

// A CSV file written to a temporary name and renamed into place by close().
class Csv {
public:
    Csv(const std::string& dir, const std::string& name, const std::string& header);
    ~Csv();
    void row(const std::string& line);
    void close();

private:
    std::string path_, tmp_;
    FILE* f_ = nullptr;
};

std::string fmt_double(double v);  // %.6g, "nan"/"inf" spelled out

}  // namespace shatter::study
