// The one place that includes OpenGL: OSMesa exports every gl* entry point of its GL 4.5 core
// context, so prototypes are declared directly (no loader) and only libOSMesa is linked.
#pragma once

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/osmesa.h>
#include <GL/glext.h>
