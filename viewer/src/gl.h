// OpenGL 3.3 core declarations: Mesa's libGL exports every core function, so the build
// defines GL_GLEXT_PROTOTYPES and links it directly; there is no loader.
#pragma once

#include <GL/glcorearb.h>
