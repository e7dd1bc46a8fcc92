// assimp-testmodels' duck (Collada, its TGA texture beside it): the textured input the pipeline
// tests pre-score, 20 cm across in 6 pieces at resolution 12 (a second or two).
#pragma once

#include <string>

#include "prescore/prescore.h"

namespace shatter::testing_support {

inline const std::string kDuck = "/usr/share/assimp/models/Collada/duck.dae";

inline Model prescore_duck(const std::string& path = kDuck) {
    MeshSettings mesh;
    mesh.path = path;
    mesh.size = 0.2;
    PrescoreSettings settings;
    settings.pieces = 6;
    settings.resolution = 12;
    return prescore(mesh, settings, nullptr);
}

}  // namespace shatter::testing_support
