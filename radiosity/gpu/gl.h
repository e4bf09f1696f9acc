// OpenGL for the solver: core-profile declarations from <GL/glcorearb.h>, linked against GLVND's
// libOpenGL.so. That library exports every core entry point up to 4.6 and forwards each call to the
// vendor of the current EGL context, so no loader (glad, GLEW, libepoxy) and no table of pointers from
// eglGetProcAddress is needed; the context still has to report 4.5 (checked in EglContext).
#pragma once

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>

#include <string>
#include <utility>

namespace cpgi::gl {

/// Throws SystemError naming `where` when the GL error flag is set (drains every pending error).
void check(const char* where);

/// Owns one GL object name; `Deleter` frees it. Move-only.
template <void (*Deleter)(GLuint)>
class Handle {
 public:
  Handle() = default;
  explicit Handle(GLuint id) : id_(id) {}
  ~Handle() { reset(); }
  Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) reset(), id_ = std::exchange(o.id_, 0);
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  GLuint get() const { return id_; }
  void reset() {
    if (id_) Deleter(id_);
    id_ = 0;
  }

 private:
  GLuint id_ = 0;
};

void deleteBuffer(GLuint id);
void deleteTexture(GLuint id);
void deleteFramebuffer(GLuint id);
void deleteVertexArray(GLuint id);
void deleteProgram(GLuint id);

using Buffer = Handle<deleteBuffer>;
using Texture = Handle<deleteTexture>;
using Framebuffer = Handle<deleteFramebuffer>;
using VertexArray = Handle<deleteVertexArray>;
using Program = Handle<deleteProgram>;

/// An immutable-storage buffer (glNamedBufferStorage) with optional initial data.
Buffer makeBuffer(size_t bytes, const void* data = nullptr, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT);
/// A 2D texture with one level of `format` storage.
Texture makeTexture2D(GLenum format, int width, int height);

}  // namespace cpgi::gl
