// The GLSL 4.50 sources of render's two programs:
//   scene   - lit, shadowed, flat-shaded triangles in linear light (RGBA16F target);
//   shadow  - depth only, from the key light.
// There is no resolve or encoding pass: the MSAA samples are averaged by glBlitFramebuffer and
// sRGB is encoded on the CPU (render/srgb_encode.h).
#pragma once

namespace shatter::shaders {

extern const char* const kSceneVertex;
extern const char* const kSceneFragment;
extern const char* const kShadowVertex;
extern const char* const kShadowFragment;

}  // namespace shatter::shaders
