#include "pipeline/instability_record.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "simulate/simulate.h"

namespace shatter {

using json = nlohmann::ordered_json;

namespace {

json id_or_null(int64_t id) { return id >= 0 ? json(id) : json(nullptr); }

// One event: where simulate's guard found the run unstable (simulate.h, InstabilityWhere) and
// its message.
json instability_event(const InstabilityWhere& at, const std::string& what) {
    return {{"time_s", at.time >= 0 ? json(at.time) : json(nullptr)},
            {"piece", id_or_null(at.piece)},
            {"constraint", id_or_null(at.constraint)},
            {"last_broken_constraint", id_or_null(at.last_broken)},
            {"what", what}};
}

// Throws json::exception unless `e` is an event (or null, when not `required`).
void check_event(const json& e, bool required) {
    if (e.is_null() && !required) return;
    (void)e.at("what").get<std::string>();  // throws for null too
    if (!e.at("time_s").is_null()) (void)e.at("time_s").get<double>();
    for (const char* k : {"piece", "constraint", "last_broken_constraint"})
        if (!e.at(k).is_null()) (void)e.at(k).get<uint64_t>();
}

}  // namespace

json instability_record(InstabilityMode mode, const SimulationResult& sim) {
    return {{"on_instability", to_string(mode)},
            {"clamps", sim.clamps},
            {"first_clamp", sim.clamps ? instability_event(sim.first_clamp_at, sim.first_clamp) : json(nullptr)},
            {"stopped", sim.complete ? json(nullptr) : instability_event(sim.stopped_at, sim.stop_reason)}};
}

json parse_instability_record(std::string_view bytes, const std::string& source) {
    try {
        json r = json::parse(bytes);
        (void)r.at("on_instability").get<std::string>();
        check_event(r.at("first_clamp"), r.at("clamps").get<uint64_t>() > 0);
        check_event(r.at("stopped"), false);
        return r;
    } catch (const json::exception& e) {
        throw Error(ExitCode::BadInput, fmt::format("{}: not an instability record: {} (fix: run simulate again: "
                                                    "shatter run SHOT --stages simulate --force)", source, e.what()));
    }
}

std::string instability_where(const json& e) {
    std::string s = e.at("time_s").is_number() ? fmt::format("at t = {:.4f} s", e.at("time_s").get<double>()) : "";
    for (const char* k : {"piece", "constraint"})
        if (e.at(k).is_number()) s += fmt::format("{}{} {}", s.empty() ? "" : ", ", k, e.at(k).get<uint64_t>());
    return s;
}

std::string clamped_steps(uint64_t n) { return fmt::format("velocities clamped in {} step{}", n, n == 1 ? "" : "s"); }

std::string format_instability(const json& r) {
    const uint64_t clamps = r.at("clamps").get<uint64_t>();
    std::string out;
    if (clamps > 0)
        out += fmt::format("stability: {} (on_instability = clamp), the first {} (summary.json: instability)\n",
                           clamped_steps(clamps), instability_where(r.at("first_clamp")));
    else if (r.at("on_instability") == "clamp")
        out += "stability: no clamp was needed (on_instability = clamp)\n";
    if (r.at("stopped").is_object())
        out += fmt::format("stability: STOPPED {} (the full message: run.log, summary.json: instability)\n",
                           instability_where(r.at("stopped")));
    return out;
}

}  // namespace shatter
