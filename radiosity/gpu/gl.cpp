#include "radiosity/gpu/gl.h"

#include <string>

#include "core/error.h"

namespace cpgi::gl {

void check(const char* where) {
  std::string codes;
  for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError()) {
    if (!codes.empty()) codes += ", ";
    switch (e) {
      case GL_INVALID_ENUM: codes += "GL_INVALID_ENUM"; break;
      case GL_INVALID_VALUE: codes += "GL_INVALID_VALUE"; break;
      case GL_INVALID_OPERATION: codes += "GL_INVALID_OPERATION"; break;
      case GL_INVALID_FRAMEBUFFER_OPERATION: codes += "GL_INVALID_FRAMEBUFFER_OPERATION"; break;
      case GL_OUT_OF_MEMORY: codes += "GL_OUT_OF_MEMORY"; break;
      default: codes += "0x" + std::to_string(e); break;
    }
    if (codes.size() > 200) break;
  }
  if (!codes.empty()) throw SystemError(std::string("OpenGL error in ") + where + ": " + codes);
}

void deleteBuffer(GLuint id) { glDeleteBuffers(1, &id); }
void deleteTexture(GLuint id) { glDeleteTextures(1, &id); }
void deleteFramebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
void deleteVertexArray(GLuint id) { glDeleteVertexArrays(1, &id); }
void deleteProgram(GLuint id) { glDeleteProgram(id); }

Buffer makeBuffer(size_t bytes, const void* data, GLbitfield flags) {
  GLuint id = 0;
  glCreateBuffers(1, &id);
  glNamedBufferStorage(id, static_cast<GLsizeiptr>(bytes == 0 ? 16 : bytes), data, flags);
  check("buffer allocation");
  return Buffer(id);
}

Texture makeTexture2D(GLenum format, int width, int height) {
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &id);
  glTextureStorage2D(id, 1, format, width, height);
  glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  check("texture allocation");
  return Texture(id);
}

}  // namespace cpgi::gl
