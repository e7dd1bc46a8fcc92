#include "render/shaders.h"

namespace shatter::shaders {

const char* const kSceneVertex = R"(#version 450 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_colour;
layout(location = 3) in vec2 a_uv;
uniform mat4 u_model;
uniform mat4 u_view_projection;
uniform mat4 u_shadow_view_projection;
uniform float u_normal_offset;
#if INTERIOR
uniform vec3 u_rest_offset;  // the piece's centre in the unbroken object's frame
out vec3 v_rest;
out vec3 v_rest_normal;
#endif
out vec3 v_world;
out vec3 v_normal;
out vec3 v_colour;
out vec3 v_shadow;
out vec2 v_uv;
void main() {
    v_uv = a_uv;
#if INTERIOR
    v_rest = a_position + u_rest_offset;
    v_rest_normal = a_normal;
#endif
    vec4 world = u_model * vec4(a_position, 1.0);
    v_world = world.xyz;
    v_normal = mat3(u_model) * a_normal;
    v_colour = a_colour;
    // Normal offset: look the shadow map up a little off the surface, against acne.
    vec4 s = u_shadow_view_projection * vec4(world.xyz + normalize(v_normal) * u_normal_offset, 1.0);
    v_shadow = s.xyz / s.w * 0.5 + 0.5;
    gl_Position = u_view_projection * world;
}
)";

const char* const kSceneFragment = R"(#version 450 core
in vec3 v_world;
in vec3 v_normal;
in vec3 v_colour;
in vec3 v_shadow;
in vec2 v_uv;
uniform vec3 u_camera;
uniform vec3 u_key_direction;
uniform vec3 u_key_colour;
uniform vec3 u_fill_direction;
uniform vec3 u_fill_colour;
uniform vec3 u_sky_colour;
uniform vec3 u_bounce_colour;
uniform float u_shadow_texel_uv;
uniform sampler2DShadow u_shadow_map;
uniform vec3 u_fade_centre;
uniform float u_fade_start;
uniform float u_fade_end;
uniform vec3 u_background;
uniform float u_specular;
#if TEXTURE || INTERIOR
uniform sampler2D u_texture;  // sRGB: sampled in linear light
#endif
#if INTERIOR
in vec3 v_rest;
in vec3 v_rest_normal;
uniform float u_interior_repeat;  // repeats per metre

// The interior texture projected along the three axes of the unbroken object, blended by the
// normal's fourth powers: no seam where a crack turns, and the same on both sides of it.
vec3 interior_albedo() {
    vec3 w = pow(abs(normalize(v_rest_normal)), vec3(4.0));
    w /= w.x + w.y + w.z;
    vec3 p = v_rest * u_interior_repeat;
    return w.x * texture(u_texture, p.zy).rgb + w.y * texture(u_texture, p.xz).rgb + w.z * texture(u_texture, p.xy).rgb;
}
#endif
out vec4 o_colour;

#if SHADOWS
float key_visibility() {
    vec3 p = v_shadow;
    if (p.x <= 0.0 || p.x >= 1.0 || p.y <= 0.0 || p.y >= 1.0) return 1.0;
    p.z = min(p.z, 1.0);  // receivers beyond the map's far plane: compare with what lies in front
    // Four bilinear (2x2) comparisons 1.5 texels apart: a 16-texel percentage-closer filter.
    float d = 0.75 * u_shadow_texel_uv, sum = 0.0;
    sum += texture(u_shadow_map, vec3(p.xy + vec2(-d, -d), p.z));
    sum += texture(u_shadow_map, vec3(p.xy + vec2( d, -d), p.z));
    sum += texture(u_shadow_map, vec3(p.xy + vec2(-d,  d), p.z));
    sum += texture(u_shadow_map, vec3(p.xy + vec2( d,  d), p.z));
    return sum * 0.25;
}
#endif

void main() {
    vec3 n = normalize(v_normal);
    if (!gl_FrontFacing) n = -n;  // open meshes (mesh colliders) are lit from both sides
    float key = max(dot(n, u_key_direction), 0.0);
#if SHADOWS
    if (key > 0.0) key *= key_visibility();
#endif
    float fill = max(dot(n, u_fill_direction), 0.0);
    vec3 ambient = mix(u_bounce_colour, u_sky_colour, 0.5 + 0.5 * n.y);
    vec3 albedo = v_colour;
#if TEXTURE  // the input's texture on outer faces
    albedo *= texture(u_texture, v_uv).rgb;
#endif
#if INTERIOR  // [render] interior_texture on fracture faces
    albedo *= interior_albedo();
#endif
    vec3 colour = albedo * (u_key_colour * key + u_fill_colour * fill + ambient);
#if SPECULAR  // the ground has none: no pow()
    vec3 h = normalize(u_key_direction + normalize(u_camera - v_world));
    colour += u_key_colour * (u_specular * key * pow(max(dot(n, h), 0.0), 40.0));
#endif
#if FADE  // the ground (and planes) melt into the background far away
    float r = length((v_world - u_fade_centre).xz);
    colour = mix(colour, u_background, smoothstep(u_fade_start, u_fade_end, r));
#endif
    o_colour = vec4(colour, 1.0);
}
)";

std::string scene_fragment(bool shadows, bool specular, bool fade, bool texture, bool interior) {
    std::string s = kSceneFragment;
    const size_t line = s.find('\n') + 1;  // after #version
    s.insert(line, std::string("#define SHADOWS ") + (shadows ? "1" : "0") + "\n#define SPECULAR " + (specular ? "1" : "0") +
                       "\n#define FADE " + (fade ? "1" : "0") + "\n#define TEXTURE " + (texture ? "1" : "0") +
                       "\n#define INTERIOR " + (interior ? "1" : "0") + "\n");
    return s;
}

std::string scene_vertex(bool interior) {
    std::string s = kSceneVertex;
    s.insert(s.find('\n') + 1, std::string("#define INTERIOR ") + (interior ? "1" : "0") + "\n");
    return s;
}

const char* const kShadowVertex = R"(#version 450 core
layout(location = 0) in vec3 a_position;
uniform mat4 u_model;
uniform mat4 u_shadow_view_projection;
void main() { gl_Position = u_shadow_view_projection * (u_model * vec4(a_position, 1.0)); }
)";

const char* const kShadowFragment = R"(#version 450 core
void main() {}
)";

}  // namespace shatter::shaders
