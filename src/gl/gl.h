// The only header that includes GL. Everything GL in penumbra goes through src/gl/: the
// context backends, the entry-point table and the RAII object wrappers.
//
// Entry points are function pointers penumbra::glX (C++-mangled, so they never clash with the
// gl* symbols libOSMesa exports), loaded from the active backend's GetProcAddress. Code in
// namespace penumbra calls them as plain glX(...). glcorearb.h declares no prototypes unless
// GL_GLEXT_PROTOTYPES is defined, so there is no ambiguity with the C symbols.
#pragma once

#include <GL/glcorearb.h>

// glcorearb.h has no pointer types for these GL 1.1 entry points.
typedef void(APIENTRYP PENUMBRA_PFNGLPOLYGONOFFSETPROC)(GLfloat factor, GLfloat units);
typedef void(APIENTRYP PENUMBRA_PFNGLDELETETEXTURESPROC)(GLsizei n, const GLuint* textures);
typedef void(APIENTRYP PENUMBRA_PFNGLDRAWARRAYSPROC)(GLenum mode, GLint first, GLsizei count);
typedef void(APIENTRYP PENUMBRA_PFNGLDRAWELEMENTSPROC)(GLenum mode, GLsizei count, GLenum type, const void* indices);

namespace penumbra {
#define X(type, name) extern type name;
#include "gl/functions.inl"
#undef X
}  // namespace penumbra
