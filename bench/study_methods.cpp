// The study's methods, continuum and speed sections (docs/accuracy.md).
#include <chrono>
#include <cmath>
#include <filesystem>

#include <spdlog/spdlog.h>

#include "bench/study_sections.h"
#ifndef SHATTER_STUDY_FLOAT
#include "render/render.h"
#endif

namespace shatter::study {

namespace {

std::string d(double v) { return fmt_double(v); }

StudyCase scene_case(const std::string& scene) {
    if (scene == "rig") return rig_case(RigSettings{});
    return make_case(scene);
}

const EnergySample& sample_at(const std::vector<EnergySample>& e, double t) {
    for (const EnergySample& s : e)
        if (s.time >= t - 1e-9) return s;
    return e.back();
}

}  // namespace

// Every method on the same scenes: speed, energy books and what the result looks like.
bool section_methods(const Options& opt, Headlines& h) {
    Csv csv(opt.out, "methods.csv",
            "scene,method,complete,wall_s,wall_per_sim_s,steps,breaks,first_break_s,stored_J,injected_J,books_error,"
            "identity_error,fragments,kinetic_0.1s_after_J,difference_from_plain_m,momentum_work_J,world_books_error");
    for (const std::string& scene : opt.scenes) {
        spdlog::info("study: methods {}", scene);
        StudyCase plain_case;
        RunOutcome plain;
        for (const Method& m : methods()) {
            StudyCase c = scene_case(scene);
            apply_method(m.name, c.input);
            const RunOutcome o = run_timed(c, opt.quick ? 1 : 3);
            const std::string name = m.name;
            if (name == "plain") plain_case = c, plain = o;
            // injected: in each broken pair's frame (what exact_energy controls); momentum work: what the
            // kicks' net momentum adds on top in the world's frame (docs/physics.md section 4).
            double stored = 0, injected = 0, work = 0;
            for (const BreakRecord& b : o.sim.breaks)
                stored += b.kicks.stored_energy, injected += b.injected_energy, work += b.momentum_work;
            const double alpha_e = c.input.material.alpha * stored;
            const double world_books = alpha_e > 0 ? (injected + work - alpha_e) / alpha_e : 0.0;
            const double t0 = first_break(o.sim), until = c.input.simulate.duration;
            const double ke = std::isnan(t0) ? NAN : sample_at(o.sim.energy, t0 + 0.1).kinetic;
            const double diff = trajectory_error(c.model, o.sim.trajectory, plain_case.model, plain.sim.trajectory, until);
            csv.row(fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}", scene, name, o.sim.complete,
                                d(o.wall_seconds), d(o.wall_seconds / until), o.sim.steps, o.sim.breaks.size(), d(t0),
                                d(stored), d(injected), d(energy_books_error(o.sim)),
                                d(energy_identity_error(o.sim, name == "paper")), fragments(c.model, o.sim), d(ke),
                                d(diff), d(work), d(world_books)));
            if (scene == "rig") {
                if (name == "plain") h.plain_injected = injected;
                if (name == "energized") h.energized_books = energy_books_error(o.sim);
                if (name == "paper") h.paper_books = energy_books_error(o.sim);
            }
        }
    }
    csv.close();
    return true;
}

// The beam against Euler-Bernoulli theory: the energy its constraints store at the break against
// the elastic energy M^2 L / (6 E I) of a simply supported beam of span L under the central load
// that makes the same moment M at the score (docs/accuracy.md section 5).
bool section_continuum(const Options& opt, Headlines&) {
    Csv csv(opt.out, "continuum.csv",
            "iterations,substeps,wall_s,first_break_s,breaks_at_first,moment_Nm,stored_J,euler_bernoulli_J,ratio,"
            "euler_bernoulli_s,rupture_moment_Nm,rupture_energy_J");
    const double E = 70e9, L = 0.4, side = 0.03, I = side * side * side * side / 12, sigma = 40e6;
    const double m_rupture = sigma * I / (0.5 * side);
    const std::vector<uint32_t> its = opt.quick ? std::vector<uint32_t>{} : std::vector<uint32_t>{300, 1000, 3000, 10000};
    for (uint32_t it : its) {
        StudyCase c = beam_case();
        c.input.simulate.iterations = it;
        apply_method("energized", c.input);
        const RunOutcome o = run_case(c);
        const double t0 = first_break(o.sim);
        Vec3 centre = Vec3::Zero();
        size_t n = 0;
        double stored = 0;
        for (const BreakRecord& b : o.sim.breaks)
            if (std::abs(b.time - t0) < 1e-9) centre += b.pivot, stored += b.kicks.stored_energy, ++n;
        if (n) centre /= double(n);
        Vec3 moment = Vec3::Zero();
        for (const BreakRecord& b : o.sim.breaks)
            if (std::abs(b.time - t0) < 1e-9) moment += (b.pivot - centre).cross(b.force);
        const double M = moment.norm();
        const auto s0 = std::chrono::steady_clock::now();
        volatile double u = 0;
        for (int i = 0; i < 1000; ++i) u = M * M * L / (6 * E * I);
        const double eb_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - s0).count() / 1000;
        const double eb = u;
        csv.row(fmt::format("{},{},{},{},{},{},{},{},{},{},{},{}", it, c.input.simulate.substeps, d(o.wall_seconds),
                            d(t0), n, d(M), d(stored), d(eb), d(eb > 0 ? stored / eb : NAN), d(eb_s), d(m_rupture),
                            d(m_rupture * m_rupture * L / (6 * E * I))));
    }
    csv.close();
    return true;
}

// Wall time per simulated second by stage: building the model, simulating (energizing apart),
// rendering (1280 x 720, shadows, the default edge filter for anti-aliasing; 8 frames timed after 2
// warm-up frames).
bool section_speed(const Options& opt, Headlines&) {
    Csv csv(opt.out, "speed.csv",
            "scene,bodies,constraints,prescore_s,simulate_per_sim_s,energize_per_sim_s,render_per_sim_s,"
            "total_per_sim_s,steps_per_s");
    for (const std::string& scene : opt.scenes) {
        const StudyCase c = scene_case(scene);
        const RunOutcome o = run_case(c);
        const double dur = c.input.simulate.duration;
        double render = NAN;
#ifndef SHATTER_STUDY_FLOAT
        if (opt.render) {
            RenderScene rs;
            rs.model = &c.model;
            rs.trajectory = &o.sim.trajectory;
            rs.scene = c.input.scene;
            rs.collider_meshes.resize(c.input.scene.colliders.size());
            RenderOptions ro;
            ro.progress = false;
            const std::string dir = opt.refs + "/render-" + scene;
            std::filesystem::remove_all(dir);
            render_frames(rs, RenderSettings{}, {0, 2}, dir, ro);
            std::filesystem::remove_all(dir);
            const uint32_t frames = std::min<uint32_t>(8, o.sim.trajectory.frames());
            const RenderReport r = render_frames(rs, RenderSettings{}, {0, frames}, dir, ro);
            render = r.seconds / frames * c.input.simulate.fps;
            std::filesystem::remove_all(dir);
        }
#endif
        const double sim = o.wall_seconds / dur;
        csv.row(fmt::format("{},{},{},{},{},{},{},{},{}", scene, c.model.pieces.size(), c.model.constraints.size(),
                            d(c.prescore_seconds), d(sim), d(o.sim.energize_seconds / dur), d(render),
                            d(c.prescore_seconds / dur + sim + (std::isnan(render) ? 0 : render)),
                            d(double(o.sim.steps) / o.wall_seconds)));
    }
    csv.close();
    return true;
}

}  // namespace shatter::study
