// The study's sections: each runs its scenes and writes one CSV (docs/accuracy.md explains them).
#include "bench/study_sections.h"

#include <chrono>
#include <cmath>
#include <filesystem>

#include <spdlog/spdlog.h>

#include "core/error.h"
#include "core/trajectory.h"

namespace shatter::study {

namespace {

std::string d(double v) { return fmt_double(v); }

const char* precision_name() {
#ifdef SHATTER_STUDY_FLOAT
    return "float";
#else
    return "double";
#endif
}

StudyCase scene_case(const std::string& scene, const ModelKnobs& k) {
    if (scene == "rig") return rig_case(RigSettings{});
    return make_case(scene, k);
}

// The reference: the same scene at h / factor with 4x the iterations (at least 1,000); the factor is halved
// while CFM refuses it (the chain).
struct Reference {
    StudyCase c;
    RunOutcome o;
};

Reference reference_run(const std::string& scene, const Options& opt) {
    Reference r{scene_case(scene, {}), {}};
    const StudyCase base = r.c;
    const std::string path = opt.refs + "/" + scene + ".traj";
#ifdef SHATTER_STUDY_FLOAT
    // The float build compares with the double build's reference (written by `study`).
    r.o.sim.trajectory = load_trajectory(path);
    if (FILE* f = std::fopen((path + ".first_break").c_str(), "r")) {
        double t = NAN;
        if (std::fscanf(f, "%lf", &t) == 1 && std::isfinite(t)) {
            BreakRecord b;
            b.time = t;
            r.o.sim.breaks.push_back(b);
        }
        std::fclose(f);
    }
    return r;
#else
    for (uint32_t factor = base.reference_substeps_factor; factor >= 1; factor /= 2) {
        r.c = base;
        r.c.input.simulate.substeps *= factor;
        r.c.input.simulate.iterations = std::max(4 * r.c.input.simulate.iterations, 1000u);
        r.o = run_case(r.c);
        if (!r.o.refused) break;
        spdlog::warn("study: {} reference at substeps x{} refused, trying x{}", scene, factor, factor / 2);
    }
    if (r.o.refused || !r.o.sim.complete) throw Error(ExitCode::Internal, "study: no reference for " + scene);
    std::filesystem::create_directories(opt.refs);
    save_trajectory(path, r.o.sim.trajectory);
    if (FILE* f = std::fopen((path + ".first_break").c_str(), "w")) {
        std::fprintf(f, "%.17g\n", first_break(r.o.sim));
        std::fclose(f);
    }
    return r;
#endif
}

struct Knob {
    std::string name;
    std::vector<double> values;
    double fallback;  // the study default
};

std::vector<Knob> knobs_of(const std::string& scene, bool quick) {
    std::vector<Knob> k;
    (void)quick;  // the quick study runs only the rig, with every knob
    k.push_back({"substeps", {1, 2, 4, 8, 16, 32, 64}, 8});
    if (scene == "beam") k.push_back({"iterations", {30, 100, 300, 1000, 3000, 10000}, 3000});
    else k.push_back({"iterations", {2, 5, 10, 20, 50, 100}, 20});
    if (scene == "beam" || scene == "plate") k.push_back({"constraints_per_side", {1, 2, 3, 4}, 2});
    if (scene == "chain") k.push_back({"constraints_per_side", {1, 2, 3}, 1});
    if (scene == "bunny") {
        k.push_back({"constraints_per_pair", {0, 32, 16, 8, 4}, 0});
        k.push_back({"collision_parts", {1, 2, 4, 8, 16}, 16});
        k.push_back({"resolution", {10, 15, 20, 30, 40}, 20});
    }
    k.push_back({"rollback", {0, 1}, 0});
    return k;
}

StudyCase knob_case(const std::string& scene, const std::string& knob, double v) {
    ModelKnobs mk;
    if (knob == "constraints_per_side") mk.constraints_per_side = uint32_t(v);
    if (knob == "constraints_per_pair") mk.constraints_per_pair = uint32_t(v);
    if (knob == "collision_parts") mk.collision_max_parts = uint32_t(v);
    if (knob == "resolution") mk.resolution = v;
    StudyCase c = scene_case(scene, mk);
    if (knob == "substeps") c.input.simulate.substeps = uint32_t(v);
    if (knob == "iterations") c.input.simulate.iterations = uint32_t(v);
    if (knob == "rollback") c.input.simulate.rollback = v != 0;
    return c;
}

size_t collision_parts(const Model& m) {
    size_t n = 0;
    for (const Piece& p : m.pieces) n += p.collision.size();
    return n;
}

}  // namespace

// Stiffness identity (the stiffness rig's measured k over the intended one) over iterations and
// substeps; energy identity on the rig for every energized method.
bool section_identities(const Options& opt, Headlines& h) {
    Csv csv(opt.out, std::string("identities_") + precision_name() + ".csv",
            "precision,measure,stiffness,substeps,iterations,method,error");
    const std::vector<uint32_t> its = {10, 20, 50, 100, 200, 500, 1000, 2000, 5000, 10000};
    for (double stiffness : {1e10, 1e11, 1e12})
        for (uint32_t substeps : {2u, 8u, 32u})
            for (uint32_t it : its) {
                const StudyCase c = stiffness_rig_case(stiffness, substeps, it);
                const RunOutcome o = run_case(c);
                const double e = o.refused ? NAN : stiffness_identity_error(c, o.sim);
                csv.row(fmt::format("{},stiffness,{},{},{},-,{}", precision_name(), d(stiffness), substeps, it, d(e)));
                if (stiffness == 1e10 && substeps == 8 && it == 2000) h.stiffness_identity = e;
            }
    for (const char* method : {"energized", "opposed", "rollback", "paper"}) {
        StudyCase c = rig_case(RigSettings{});
        apply_method(method, c.input);
        const RunOutcome o = run_case(c);
        const bool per_body = std::string(method) == "paper";
        const double e = energy_identity_error(o.sim, per_body);
        csv.row(fmt::format("{},energy,{},{},{},{},{}", precision_name(), d(c.input.material.stiffness),
                            c.input.simulate.substeps, c.input.simulate.iterations, method, d(e)));
        if (std::string(method) == "energized") h.energy_identity = e, h.energy_identity_breaks = o.sim.breaks.size();
    }
    csv.close();
    return true;
}

// Cost against error: one knob at a time around the study default, against the scene's reference.
bool section_sweeps(const Options& opt, Headlines& h) {
    Csv csv(opt.out, std::string("sweeps_") + precision_name() + ".csv",
            "precision,scene,knob,value,is_default,refused,complete,wall_s,wall_per_sim_s,cpu_per_sim_s,steps,bodies,"
            "constraints,collision_parts,tets,breaks,first_break_s,first_break_error_s,trajectory_error_m,"
            "energy_identity_error");
    for (const std::string& scene : opt.scenes) {
        spdlog::info("study: sweeps {}", scene);
        const Reference ref = reference_run(scene, opt);
        const double until = ref.c.input.simulate.duration;
        const double t_ref = first_break(ref.o.sim);
#ifndef SHATTER_STUDY_FLOAT
        csv.row(fmt::format("{},{},reference,{},0,0,1,{},{},{},{},{},{},{},{},{},{},0,0,{}", precision_name(), scene,
                            ref.c.input.simulate.substeps, d(ref.o.wall_seconds), d(ref.o.wall_seconds / until),
                            d(ref.o.cpu_seconds / until), ref.o.sim.steps, ref.c.model.pieces.size(),
                            ref.c.model.constraints.size(), collision_parts(ref.c.model), ref.c.model.mesh.tets.size(),
                            ref.o.sim.breaks.size(), d(t_ref), d(energy_identity_error(ref.o.sim, false))));
#endif
        for (const Knob& k : knobs_of(scene, opt.quick)) {
            if (opt.precision_only && k.name != "substeps") continue;
            for (double v : k.values) {
                const StudyCase c = knob_case(scene, k.name, v);
                const RunOutcome o = run_timed(c, opt.quick ? 1 : 3);
                const double tb = first_break(o.sim);
                const double err = o.refused ? NAN
                                             : trajectory_error(c.model, o.sim.trajectory, ref.c.model,
                                                                ref.o.sim.trajectory, until);
                csv.row(fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}", precision_name(), scene,
                                    k.name, d(v), v == k.fallback, o.refused, o.sim.complete, d(o.wall_seconds),
                                    d(o.wall_seconds / until), d(o.cpu_seconds / until), o.sim.steps,
                                    c.model.pieces.size(), c.model.constraints.size(), collision_parts(c.model),
                                    c.model.mesh.tets.size(), o.sim.breaks.size(), d(tb), d(std::abs(tb - t_ref)),
                                    d(err), d(energy_identity_error(o.sim, false))));
                if (scene == "rig" && k.name == "substeps") h.rig_substeps_error.push_back({v, err});
            }
        }
        if (opt.precision_only) continue;
        // The automatic step (substeps = "auto", docs/physics.md section 7a): one point on the same
        // cost/error chart, knob "auto_step", value 1.
        StudyCase c = scene_case(scene, {});
        c.input.simulate.auto_substeps = true;
        const RunOutcome o = run_timed(c, opt.quick ? 1 : 3);
        const double tb = first_break(o.sim);
        const double err = o.refused ? NAN
                                     : trajectory_error(c.model, o.sim.trajectory, ref.c.model, ref.o.sim.trajectory, until);
        csv.row(fmt::format("{},{},auto_step,1,0,{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}", precision_name(), scene,
                            o.refused, o.sim.complete, d(o.wall_seconds), d(o.wall_seconds / until),
                            d(o.cpu_seconds / until), o.sim.steps, c.model.pieces.size(), c.model.constraints.size(),
                            collision_parts(c.model), c.model.mesh.tets.size(), o.sim.breaks.size(), d(tb),
                            d(std::abs(tb - t_ref)), d(err), d(energy_identity_error(o.sim, false))));
    }
    csv.close();
    return true;
}

}  // namespace shatter::study
