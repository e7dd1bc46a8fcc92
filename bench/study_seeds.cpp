// The study's seeds section (docs/accuracy.md section 4): the demo shot (assets/bunny.toml) at
// 40 pieces with uniform and with impact seeds (prescore/graded_seeds.h), each prescored and
// simulated as shipped for 1.5 s: fragments, the spread 0.1 s after the first break
// (core/fragments.h) and how the pieces are graded: the mean volume of the pieces whose centres
// lie within 0.3 of the diagonal of the impact's contact over the mean volume of the rest (the
// uniform model takes the impact model's contact; scripts/impact_grading.py measures the same on
// a model file, with the render surfaces' diagonal).
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "bench/study_sections.h"
#include "core/fragments.h"
#include "core/shot.h"
#include "prescore/prescore.h"

namespace shatter::study {

namespace {

struct Grading {
    double near_over_far = NAN;
    size_t near = 0, far = 0;
};

Grading grading(const Model& m, const Vec3& contact, double within) {
    Vec3 lo = m.mesh.vertices.front(), hi = lo;
    for (const Vec3& v : m.mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    const double reach = within * (hi - lo).norm();
    double near_volume = 0, far_volume = 0;
    Grading g;
    for (const Piece& p : m.pieces) {
        const bool near = (p.mass.center - contact).norm() <= reach;
        (near ? near_volume : far_volume) += p.mass.volume;
        ++(near ? g.near : g.far);
    }
    if (g.near > 0 && g.far > 0) g.near_over_far = (near_volume / double(g.near)) / (far_volume / double(g.far));
    return g;
}

}  // namespace

bool section_seeds(const Options& opt, Headlines&) {
    Csv csv(opt.out, "seeds.csv",
            "shot,pieces,seeds,ratio,radius_m,complete,breaks,first_break_s,fragments,spread_0.1s_after_J,near,far,"
            "near_over_far_volume");
    const std::string path = std::string(SHATTER_SOURCE_DIR) + "/assets/bunny.toml";
    Vec3 contact = Vec3::Zero();
    for (const char* seeds : {"impact", "uniform"}) {  // impact first: its contact grades both
        spdlog::info("study: seeds {}", seeds);
        const Shot shot = load_shot(path, {"prescore.pieces=40", fmt::format("prescore.seeds={}", seeds),
                                           "simulate.duration=1.5"});
        StudyCase c;
        c.scene = "bunny";
        c.model = prescore_shot(shot, nullptr);
        c.input = SimulationInput{shot.scene, shot.object, shot.material, shot.simulate};
        double ratio = 1, radius = 0;
        if (std::string(seeds) == "impact") {
            const nlohmann::json settings = nlohmann::json::parse(c.model.settings_json);
            const nlohmann::json& impact = settings.at("impact");
            ratio = impact.at("ratio").get<double>(), radius = impact.at("radius_m").get<double>();
            for (const nlohmann::json& k : impact.at("contacts"))
                if (k.at("grades").get<bool>()) {
                    const auto& p = k.at("model_point_m");
                    contact = Vec3(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
                    break;
                }
        }
        const RunOutcome o = run_case(c);
        const double first = first_break(o.sim);
        const double spread = std::isnan(first) ? NAN
                                                : spread_energy(c.model, o.sim.trajectory,
                                                                uint32_t(std::lround((first + 0.1) * o.sim.trajectory.fps)));
        const Grading g = grading(c.model, contact, 0.3);
        csv.row(fmt::format("bunny,40,{},{},{},{},{},{},{},{},{},{},{}", seeds, fmt_double(ratio), fmt_double(radius),
                            o.sim.complete ? 1 : 0, o.sim.breaks.size(), fmt_double(first), fragments(c.model, o.sim),
                            fmt_double(spread), g.near, g.far, fmt_double(g.near_over_far)));
    }
    csv.close();
    return true;
}

}  // namespace shatter::study
