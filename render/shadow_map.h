// The key light's shadow map: a fixed-size depth texture (render.shadow_map texels square,
// 2048 by default) with hardware depth comparison and bilinear filtering, so that one lookup is
// a 2x2 percentage-closer filter. Outside the map (border depth 1) nothing is in shadow.
#pragma once

#include <cstdint>

namespace shatter {

class ShadowMap {
public:
    explicit ShadowMap(uint32_t size);
    ~ShadowMap();
    ShadowMap(const ShadowMap&) = delete;
    ShadowMap& operator=(const ShadowMap&) = delete;

    void bind_for_drawing() const;  // binds its framebuffer and viewport, clears depth
    unsigned texture() const { return texture_; }
    uint32_t size() const { return size_; }

private:
    uint32_t size_;
    unsigned fbo_ = 0, texture_ = 0;
};

}  // namespace shatter
