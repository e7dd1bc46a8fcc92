// The [render] section's hand-written readers (camera points, sRGB colours, piece_colours; its
// keys are declared in core/setting_table_render.cpp) and the render settings' JSON
// (core/render_settings.h).
#include <cmath>
#include <cstdio>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/render_settings.h"
#include "core/setting_table.h"
#include "core/shot_sections.h"

namespace shatter {

namespace {

float srgb_to_linear(double s) {
    return static_cast<float>(s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4));
}

double linear_to_srgb(double v) {
    v = v < 0 ? 0 : (v > 1 ? 1 : v);
    return v <= 0.0031308 ? v * 12.92 : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
}

}  // namespace

bool read_render_point(TomlSection& s, const char* key, std::optional<Vec3>& out) {
    const toml::node* n = s.node(key);
    if (!n) return false;
    const auto* a = n->as_array();
    Vec3 v;
    bool ok = a && a->size() == 3;
    for (size_t i = 0; ok && i < 3; ++i) {
        auto x = (*a)[i].value<double>();
        ok = x && std::isfinite(*x) && std::abs(*x) <= 1e6;
        if (ok) v[int(i)] = *x;
    }
    if (!ok)
        s.fail(n, fmt::format("{} must be three finite numbers within 1e6 (unit: m)", s.key_name(key)),
               fmt::format("write e.g. {} = [0.5, 0.4, 1.2]", key));
    out = v;
    return true;
}

void read_srgb_colour(TomlSection& s, const char* key, std::array<float, 3>& out) {
    std::string text;
    if (!s.text(key, text)) return;
    auto c = parse_srgb_hex(text);
    if (!c)
        s.fail(s.node(key), fmt::format("{} = \"{}\" is not a colour", s.key_name(key), text),
               fmt::format("write an sRGB colour as {} = \"#rrggbb\", e.g. \"#dbd3c4\"", key));
    out = *c;
}

// piece_colours = [{piece = 0, colour = "#2f5fd0"}, ...]: each entry a table of its own.
void read_piece_colours(TomlSection& s, std::vector<std::pair<uint32_t, std::array<float, 3>>>& out) {
    const toml::node* n = s.node("piece_colours");
    if (!n) return;
    const char* fix = "write piece_colours = [{piece = 0, colour = \"#2f5fd0\"}] (piece index, sRGB colour)";
    const toml::array* a = n->as_array();
    if (!a) s.fail(n, s.key_name("piece_colours") + " must be an array of {piece, colour} tables", fix);
    out.clear();
    for (size_t i = 0; i < a->size(); ++i) {
        const toml::table* t = a->get(i)->as_table();
        const std::string name = fmt::format("{}[{}]", s.key_name("piece_colours"), i);
        if (!t) s.fail(a->get(i), name + " is not a {piece, colour} table", fix);
        const auto& file = t->source().path;
        TomlSection e(*t, file ? *file : std::string(), name);
        uint32_t piece = 0;
        std::array<float, 3> colour{};
        if (!e.integer("piece", piece, Limits{0, 1e9, "(piece index)"}) || !e.node("colour"))
            s.fail(t, name + " needs both piece and colour", fix);
        read_srgb_colour(e, "colour", colour);
        e.finish();
        out.emplace_back(piece, colour);
    }
}

void check_render_camera(TomlSection& s, const RenderSettings& r) {
    if (r.camera_target && !r.camera_position)
        s.fail(s.node("camera_target"), "render.camera_target is set without render.camera_position",
               "also give camera_position, or remove camera_target to frame the animation automatically");
    if (r.camera_position && r.camera_target && (*r.camera_position - *r.camera_target).norm() < 1e-6)
        s.fail(s.node("camera_target"), "render.camera_target equals render.camera_position",
               "place the camera away from the point it looks at");
}

const char* to_string(Colours m) {
    switch (m) {
        case Colours::Input: return "input";
        case Colours::Palette: return "palette";
        case Colours::Material: return "material";
    }
    return "input";
}

const char* to_string(CameraMode m) { return m == CameraMode::Follow ? "follow" : "whole"; }

std::optional<std::array<float, 3>> parse_srgb_hex(const std::string& text) {
    if (text.size() != 7 || text[0] != '#') return std::nullopt;
    std::array<float, 3> out{};
    for (int i = 0; i < 3; ++i) {
        unsigned v = 0;
        for (int k = 0; k < 2; ++k) {
            const char ch = text[size_t(1 + 2 * i + k)];
            int d = ch >= '0' && ch <= '9' ? ch - '0' : ch >= 'a' && ch <= 'f' ? ch - 'a' + 10
                                                     : ch >= 'A' && ch <= 'F' ? ch - 'A' + 10 : -1;
            if (d < 0) return std::nullopt;
            v = v * 16 + unsigned(d);
        }
        out[size_t(i)] = srgb_to_linear(v / 255.0);
    }
    return out;
}

std::string srgb_hex(const std::array<float, 3>& linear) {
    auto byte = [](float v) { return int(std::lround(linear_to_srgb(v) * 255)); };
    return fmt::format("#{:02x}{:02x}{:02x}", byte(linear[0]), byte(linear[1]), byte(linear[2]));
}

void check_msaa(const std::string& where, uint32_t msaa, bool from_flag) {
    if (msaa == 1 || msaa == 2 || msaa == 4) return;
    throw Error(from_flag ? ExitCode::Usage : ExitCode::BadInput,
                fmt::format("{}: msaa = {} is not a sample count render offers (fix: 1 (off), 2 or 4)", where, msaa));
}

void put_render_point(nlohmann::ordered_json& j, const char* key, const std::optional<Vec3>& point) {
    if (point) j[key] = {point->x(), point->y(), point->z()};
}

void put_piece_colours(nlohmann::ordered_json& j, const std::vector<std::pair<uint32_t, std::array<float, 3>>>& pieces) {
    if (pieces.empty()) return;
    nlohmann::ordered_json out = nlohmann::ordered_json::array();
    for (const auto& [piece, colour] : pieces) out.push_back({{"piece", piece}, {"colour", srgb_hex(colour)}});
    j["piece_colours"] = out;
}

nlohmann::ordered_json to_json(const RenderSettings& s) {
    Shot shot;
    shot.render = s;
    return settings_json("render", shot);
}

}  // namespace shatter
