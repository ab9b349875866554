#pragma once
// OpenGL 4.5 core entry points. Through glvnd's libOpenGL every core function is
// exported directly, so no loader library is needed; EGL and GLX contexts both dispatch.
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>
