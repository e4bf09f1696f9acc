// Measures what one pass over N texels costs on the current GL driver, three ways: a compute dispatch
// with work groups of 8×8, 16×16 and 32×32 invocations, and a fragment pass drawing one quad over an
// RGBA32F target with additive blending. Each does the same work per texel (read a vec4, add it).
// Usage: cpgi_pass_probe [EDGE=2048] [REPEAT=5]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/context.h"
#include "radiosity/gpu/egl_context.h"
#include "radiosity/gpu/gl.h"

namespace {

GLuint compile(GLenum stage, const std::string& text) {
  GLuint s = glCreateShader(stage);
  const char* src = text.c_str();
  glShaderSource(s, 1, &src, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    std::fprintf(stderr, "%s\n", log);
    std::exit(1);
  }
  return s;
}

GLuint program(std::initializer_list<GLuint> shaders) {
  GLuint p = glCreateProgram();
  for (GLuint s : shaders) glAttachShader(p, s);
  glLinkProgram(p);
  return p;
}

double seconds(const std::chrono::steady_clock::time_point& t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

int main(int argc, char** argv) {
  const int edge = argc > 1 ? std::atoi(argv[1]) : 2048, repeat = argc > 2 ? std::atoi(argv[2]) : 5;
  cpgi::Context ctx;
  cpgi::EglContext gl(ctx);
  std::printf("# %s, %dx%d texels, best of %d\n", gl.renderer().c_str(), edge, edge, repeat);
  const size_t n = size_t(edge) * edge;
  std::vector<float> data(n * 4, 1.0f);
  cpgi::gl::Buffer in = cpgi::gl::makeBuffer(n * 16, data.data()), out = cpgi::gl::makeBuffer(n * 16, data.data());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, in.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, out.get());
  for (int local : {8, 16, 32}) {
    const std::string src = "#version 450 core\nlayout(local_size_x = " + std::to_string(local) +
                            ", local_size_y = " + std::to_string(local) + R"() in;
      layout(std430, binding = 0) readonly buffer In { vec4 a[]; };
      layout(std430, binding = 1) buffer Out { vec4 b[]; };
      uniform int uWidth;
      void main() { uint i = gl_GlobalInvocationID.y * uint(uWidth) + gl_GlobalInvocationID.x; b[i] += a[i]; })";
    GLuint p = program({compile(GL_COMPUTE_SHADER, src)});
    glProgramUniform1i(p, glGetUniformLocation(p, "uWidth"), edge);
    glUseProgram(p);
    double best = 1e9;
    for (int r = 0; r < repeat; ++r) {
      glFinish();
      const auto t = std::chrono::steady_clock::now();
      glDispatchCompute(edge / local, edge / local, 1);
      glMemoryBarrier(GL_ALL_BARRIER_BITS);
      glFinish();
      best = std::min(best, seconds(t));
    }
    std::printf("compute %2dx%-2d  %7.2f ms  %6.1f ns/texel\n", local, local, 1e3 * best, 1e9 * best / double(n));
  }
  {
    cpgi::gl::Texture a = cpgi::gl::makeTexture2D(GL_RGBA32F, edge, edge), b = cpgi::gl::makeTexture2D(GL_RGBA32F, edge, edge);
    glBindImageTexture(0, a.get(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
    glBindImageTexture(1, b.get(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    GLuint p = program({compile(GL_COMPUTE_SHADER, R"(#version 450 core
      layout(local_size_x = 8, local_size_y = 8) in;
      layout(binding = 0, rgba32f) readonly uniform image2D uA;
      layout(binding = 1, rgba32f) uniform image2D uB;
      void main() { ivec2 t = ivec2(gl_GlobalInvocationID.xy); imageStore(uB, t, imageLoad(uB, t) + imageLoad(uA, t)); })")});
    glUseProgram(p);
    double best = 1e9;
    for (int r = 0; r < repeat; ++r) {
      glFinish();
      const auto t = std::chrono::steady_clock::now();
      glDispatchCompute(edge / 8, edge / 8, 1);
      glMemoryBarrier(GL_ALL_BARRIER_BITS);
      glFinish();
      best = std::min(best, seconds(t));
    }
    std::printf("compute 8x8 images %7.2f ms  %6.1f ns/texel\n", 1e3 * best, 1e9 * best / double(n));
  }
  {
    cpgi::gl::Texture target = cpgi::gl::makeTexture2D(GL_RGBA32F, edge, edge);
    GLuint fbo = 0, vao = 0;
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, target.get(), 0);
    glCreateVertexArrays(1, &vao);
    GLuint p = program({compile(GL_VERTEX_SHADER, R"(#version 450 core
      void main() { vec2 c = vec2(gl_VertexID & 1, gl_VertexID >> 1) * 4.0 - 1.0; gl_Position = vec4(c, 0, 1); })"),
                        compile(GL_FRAGMENT_SHADER, R"(#version 450 core
      layout(std430, binding = 0) readonly buffer In { vec4 a[]; };
      uniform int uWidth;
      out vec4 colour;
      void main() { ivec2 t = ivec2(gl_FragCoord.xy); colour = a[t.y * uWidth + t.x]; })")});
    glProgramUniform1i(p, glGetUniformLocation(p, "uWidth"), edge);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, edge, edge);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glUseProgram(p);
    glBindVertexArray(vao);
    double best = 1e9;
    for (int r = 0; r < repeat; ++r) {
      glFinish();
      const auto t = std::chrono::steady_clock::now();
      glDrawArrays(GL_TRIANGLES, 0, 3);
      glFinish();
      best = std::min(best, seconds(t));
    }
    glDisable(GL_BLEND);
    std::printf("fragment+blend %7.2f ms  %6.1f ns/texel\n", 1e3 * best, 1e9 * best / double(n));
  }
  cpgi::gl::check("probe");
  return 0;
}
