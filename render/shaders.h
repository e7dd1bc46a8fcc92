// The GLSL 4.50 sources of render's two programs:
//   scene   - lit, shadowed, flat-shaded triangles in linear light (sRGB8 target, GL encodes);
//   shadow  - depth only, from the key light.
// There is no resolve or encoding pass: the MSAA samples are averaged by glBlitFramebuffer and
// sRGB is encoded by GL on write (GL_FRAMEBUFFER_SRGB).
#pragma once

#include <string>

namespace shatter::shaders {

extern const char* const kSceneVertex;
extern const char* const kSceneFragment;
// The scene fragment shader specialized (#define) for one kind of item: llvmpipe runs both sides
// of every branch under a mask, so a uniform `if` saves nothing; a variant without the shadow
// lookups, the highlight or the fade does. `texture`: the colour is multiplied by u_texture
// (unit 1) at the vertices' texture coordinates; `interior`: by u_texture projected from the
// unbroken object's axes (fracture faces with [render] interior_texture).
std::string scene_fragment(bool shadows, bool specular, bool fade, bool texture = false, bool interior = false);
// The scene vertex shader; `interior`: it also passes the point and normal in the unbroken
// object's frame (u_rest_offset: the piece's centre there).
std::string scene_vertex(bool interior);
extern const char* const kShadowVertex;
extern const char* const kShadowFragment;

}  // namespace shatter::shaders
