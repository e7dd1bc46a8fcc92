#include "simulate/recording.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace shatter {

namespace {

nlohmann::ordered_json vec(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

std::string break_log_jsonl(const std::vector<BreakRecord>& breaks) {
    std::string out;
    for (const BreakRecord& b : breaks) {
        nlohmann::ordered_json kicks = nlohmann::ordered_json::array();
        for (const Kick& k : b.kicks.kick)
            kicks.push_back({{"direction", vec(k.direction)},
                             {"random_direction", k.random_direction},
                             {"effective_mass_kg", k.effective_mass},
                             {"impulse_Ns", k.magnitude},
                             {"energy_J", k.energy}});
        nlohmann::ordered_json j = {{"time_s", b.time},
                                    {"step_s", b.step},
                                    {"constraint", b.constraint},
                                    {"pieces", {b.piece_a, b.piece_b}},
                                    {"pivot_m", vec(b.pivot)},
                                    {"force_N", vec(b.force)},
                                    {"force_norm_N", b.force.norm()},
                                    {"strength_N", b.strength},
                                    {"stiffness_N_per_m", b.stiffness},
                                    {"stored_energy_J", b.kicks.stored_energy},
                                    {"alpha", b.alpha},
                                    {"kicks", kicks},
                                    {"injected_energy_J", b.injected_energy},
                                    {"momentum_work_J", b.momentum_work}};
        if (b.held_energy > 0) j["held_energy_J"] = b.held_energy;
        if (b.released_energy > 0) j["released_energy_J"] = b.released_energy;
        if (b.overlap > 0) j["overlap_m"] = b.overlap;
        out += j.dump() + "\n";
    }
    return out;
}

std::string energy_csv(const std::vector<EnergySample>& samples) {
    std::string out =
        "time_s,kinetic_J,potential_J,stored_J,injected_J,removed_J,elastic_J,joint_residual,joints_damped_J,contacts_J,"
        "driven_J,integration_J\n";
    for (const EnergySample& e : samples)
        out += fmt::format("{:.6f},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.4g},{:.9g},{:.9g},{:.9g},{:.9g}\n", e.time,
                           e.kinetic, e.potential, e.stored, e.injected, e.removed, e.elastic, e.residual,
                           e.joints_damped, e.contacts, e.driven, e.integration);
    return out;
}

}  // namespace shatter
