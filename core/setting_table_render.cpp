// The [render] table (core/setting_table.h): what render reads. Colours are sRGB "#rrggbb";
// camera_position, camera_target and piece_colours have their readers in core/shot_render.cpp.
#include <filesystem>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/setting_builders.h"

namespace shatter::table {

namespace {

using ojson = nlohmann::ordered_json;

Setting colour(const char* key, std::array<float, 3> RenderSettings::*member, const char* help) {
    return custom(key, "sRGB", "", "#rrggbb", help, [key, member](TomlSection& s, Shot& shot) {
               read_srgb_colour(s, key, shot.render.*member);
           })
        .shows(fmt::format("\"{}\"", srgb_hex(defaults<Shot>().render.*member)))
        .json([key, member](const Shot& s, ojson& j) { j[key] = srgb_hex(s.render.*member); });
}

}  // namespace

SettingsSection render_section() {
    return {"render",
            {whole("width", "pixels", at(&Shot::render, &RenderSettings::width), kImageSizeLimits,
                   "image width (the flag --size WxH sets both)"),
             whole("height", "pixels", at(&Shot::render, &RenderSettings::height), kImageSizeLimits, "image height"),
             custom("camera_position", "m", "framed", "finite, within 1e6", "camera position [x, y, z]",
                    [](TomlSection& s, Shot& shot) { read_render_point(s, "camera_position", shot.render.camera_position); })
                 .json([](const Shot& s, ojson& j) { put_render_point(j, "camera_position", s.render.camera_position); }),
             custom("camera_target", "m", "the animation's centre", "finite, within 1e6",
                    "the point looked at (needs camera_position)",
                    [](TomlSection& s, Shot& shot) { read_render_point(s, "camera_target", shot.render.camera_target); })
                 .json([](const Shot& s, ojson& j) { put_render_point(j, "camera_target", s.render.camera_target); }),
             choice<CameraMode>("camera", at(&Shot::render, &RenderSettings::camera),
                                {{"follow", CameraMode::Follow}, {"whole", CameraMode::Whole}},
                                "without camera_position: follow the pieces, or one fixed camera framing the whole "
                                "animation",
                                "a camera mode",
                                "use \"follow\" (moves with the pieces) or \"whole\" (fixed, frames the whole animation)")
                 .json([](const Shot& s, ojson& j) {  // what frames the shot when it places no camera
                     if (!s.render.camera_position) j["camera"] = to_string(s.render.camera);
                 })
                 .flag("--camera"),
             number("fov", "degrees", at(&Shot::render, &RenderSettings::fov), kFovLimits, "vertical field of view")
                 .flag("--fov"),
             boolean("shadows", at(&Shot::render, &RenderSettings::shadows), "the key light casts shadows (shadow map)")
                 .flag("--no-shadows", FlagKind::SetsFalse),
             whole("shadow_map", "texels", at(&Shot::render, &RenderSettings::shadow_map), kShadowMapLimits,
                   "shadow map width and height")
                 .flag("--shadow-map"),
             custom("msaa", "samples", "1", "1, 2, 4",
                    "samples per pixel: 1 (off), 2 or 4; llvmpipe draws a frame at 2 or 4 for about twice the time "
                    "of 1 (edge_filter smooths edges for a fraction of that)",
                    [](TomlSection& s, Shot& shot) {
                        if (s.integer("msaa", shot.render.msaa, Limits{1, 4, "samples"}))
                            check_msaa(s.where(s.node("msaa")), shot.render.msaa, s.from_flag());
                    })
                 .json([](const Shot& s, ojson& j) { j["msaa"] = s.render.msaa; })
                 .flag("--msaa"),
             boolean("edge_filter", at(&Shot::render, &RenderSettings::edge_filter),
                     "anti-alias the finished frame: staircase edges blended along their length with the pixels "
                     "across them (FXAA's idea, render/edge_filter.h)")
                 .flag("--no-edge-filter", FlagKind::SetsFalse),
             number("key_azimuth", "degrees", at(&Shot::render, &RenderSettings::key_azimuth), kAzimuthLimits,
                    "key light direction, from the camera's direction about +Y, positive to the right")
                 .flag("--key-azimuth"),
             number("key_elevation", "degrees", at(&Shot::render, &RenderSettings::key_elevation), kElevationLimits,
                    "key light height above the horizon")
                 .flag("--key-elevation"),
             choice<Colours>("colours", at(&Shot::render, &RenderSettings::colours),
                             {{"input", Colours::Input}, {"palette", Colours::Palette}, {"material", Colours::Material}},
                             "input: the input's materials, textures and vertex colours (material_colour when it has "
                             "none); palette: a colour by piece id, for reviewing pieces; material: material_colour",
                             "a colour source",
                             "use \"input\" (the input's materials and textures), \"palette\" (a colour by piece id) or "
                             "\"material\" (material_colour)")
                 .flag("--colours"),
             colour("material_colour", &RenderSettings::material_colour,
                    "the colour of every piece with colours = \"material\", and of inputs without materials")
                 .flag("--material-colour"),
             custom("piece_colours", "piece index, sRGB", "none", "`[{piece = 0, colour = \"#2f5fd0\"}, ...]`",
                    "these pieces in these colours whatever the mode (the chain's blue end cubes)",
                    [](TomlSection& s, Shot& shot) { read_piece_colours(s, shot.render.piece_colours); })
                 .json([](const Shot& s, ojson& j) { put_piece_colours(j, s.render.piece_colours); }),
             custom("interior_colour", "sRGB", "the outer colour, lightened by fracture_tint", "#rrggbb",
                    "fracture faces in this colour",
                    [](TomlSection& s, Shot& shot) {
                        std::array<float, 3> c{};
                        if (s.node("interior_colour")) {
                            read_srgb_colour(s, "interior_colour", c);
                            shot.render.interior_colour = c;
                        }
                    })
                 .json([](const Shot& s, ojson& j) {
                     if (s.render.interior_colour) j["interior_colour"] = srgb_hex(*s.render.interior_colour);
                 })
                 .flag("--interior-colour"),
             custom("interior_texture", "", "none", "an image file: PNG, JPEG, TGA, BMP or WebP",
                    "fracture faces drawn with this image (times interior_colour when set), projected along the "
                    "three axes of the unbroken object so that both sides of a crack show the same; relative to the "
                    "shot file's folder",
                    [](TomlSection& s, Shot& shot) {
                        std::string& path = shot.render.interior_texture;
                        if (s.text("interior_texture", path) && !path.empty() && !s.from_flag()) {
                            const std::filesystem::path p(path);
                            if (p.is_relative())
                                path = (std::filesystem::path(s.file()).parent_path() / p).lexically_normal().string();
                        }
                    })
                 .json([](const Shot& s, ojson& j) {
                     if (!s.render.interior_texture.empty()) j["interior_texture"] = s.render.interior_texture;
                 })
                 .flag("--interior-texture"),
             number("interior_texture_size", "m", at(&Shot::render, &RenderSettings::interior_texture_size),
                    kTextureSizeLimits, "the span of one repeat of interior_texture; 0: a quarter of the object's "
                    "bounding-box diagonal"),
             number("fracture_tint", "fraction", at(&Shot::render, &RenderSettings::fracture_tint), kTintLimits,
                    "fracture faces: this fraction of the way from the piece colour to white")
                 .flag("--fracture-tint"),
             number("cavity_shade", "fraction", at(&Shot::render, &RenderSettings::cavity_shade), kTintLimits,
                    "cavity faces: the piece colour times this")
                 .flag("--cavity-shade"),
             colour("background", &RenderSettings::background, "background and far ground").flag("--background")},
            [](TomlSection& s, Shot& shot) { check_render_camera(s, shot.render); }};
}

}  // namespace shatter::table
