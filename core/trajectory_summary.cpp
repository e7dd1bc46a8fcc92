#include "core/trajectory_summary.h"

#include <algorithm>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/stage_file.h"

namespace shatter {

namespace {

using ojson = nlohmann::ordered_json;

// Path length (m) and fastest speed between consecutive frames (m/s) of one body.
ojson body_motion(const Trajectory& t, uint32_t body) {
    double path = 0, max_speed = 0;
    const uint32_t frames = t.frames();
    for (uint32_t f = 1; f < frames; ++f) {
        const double step = (t.pose(f, body).position - t.pose(f - 1, body).position).cast<double>().norm();
        path += step;
        max_speed = std::max(max_speed, step * t.fps);
    }
    ojson end = nullptr, turn = nullptr;
    if (frames > 0) {
        const Eigen::Vector3f p = t.pose(frames - 1, body).position;
        const Eigen::Quaternionf& q = t.pose(frames - 1, body).rotation;
        end = ojson::array({p.x(), p.y(), p.z()});
        turn = ojson::array({q.x(), q.y(), q.z(), q.w()});
    }
    return {{"piece", body},           {"path_length_m", path},      {"max_speed_m_s", max_speed},
            {"final_position_m", end}, {"final_rotation_xyzw", turn}};
}

}  // namespace

ojson trajectory_summary(const Trajectory& t) {
    ojson j;
    j["kind"] = "trajectory";
    j["producer"] = t.producer;
    ojson settings = ojson::parse(t.settings_json, nullptr, false);
    j["settings"] = settings.is_discarded() ? ojson(t.settings_json) : settings;
    j["frames"] = t.frames();
    j["fps"] = t.fps;
    j["duration_s"] = t.frames() > 1 ? (t.frames() - 1) / t.fps : 0.0;  // time of the last frame
    j["pieces"] = t.pieces;
    j["props"] = t.props;
    j["complete"] = t.complete;
    ojson pieces = ojson::array();
    double fastest = 0, longest = 0;
    for (uint32_t b = 0; b < t.pieces; ++b) {
        pieces.push_back(body_motion(t, b));
        fastest = std::max(fastest, pieces.back()["max_speed_m_s"].get<double>());
        longest = std::max(longest, pieces.back()["path_length_m"].get<double>());
    }
    j["max_piece_speed_m_s"] = fastest;
    j["longest_piece_path_m"] = longest;
    j["per_piece"] = std::move(pieces);
    return j;
}

std::string trajectory_summary_text(const ojson& j) {
    std::string out;
    out += fmt::format("trajectory    {}\n", j["producer"].get<std::string>());
    out += fmt::format("frames        {} at {:g} fps ({:.6g} s)\n", j["frames"].get<uint32_t>(), j["fps"].get<double>(),
                       j["duration_s"].get<double>());
    out += fmt::format("bodies        {} pieces, {} props\n", j["pieces"].get<uint32_t>(), j["props"].get<uint32_t>());
    out += fmt::format("complete      {}\n", j["complete"].get<bool>() ? "yes" : "NO: the simulation stopped early");
    const ojson& s = j["settings"];
    if (s.is_object() && s.contains("simulate")) out += fmt::format("simulate      {}\n", s["simulate"].dump());
    out += stage_choices_text(s);
    out += fmt::format("motion        longest path {:.6g} m, fastest {:.6g} m/s\n",
                       j["longest_piece_path_m"].get<double>(), j["max_piece_speed_m_s"].get<double>());
    out += "\npiece     path(m)  max speed(m/s)  final position (m)\n";
    for (const auto& p : j["per_piece"]) {
        std::string end = "-";
        if (p["final_position_m"].is_array())
            end = fmt::format("{:.4g} {:.4g} {:.4g}", p["final_position_m"][0].get<double>(),
                              p["final_position_m"][1].get<double>(), p["final_position_m"][2].get<double>());
        out += fmt::format("{:5} {:11.6g} {:15.6g}  {}\n", p["piece"].get<uint32_t>(), p["path_length_m"].get<double>(),
                           p["max_speed_m_s"].get<double>(), end);
    }
    return out;
}

}  // namespace shatter
