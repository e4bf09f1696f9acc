#include "radiosity/gpu/egl_context.h"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "radiosity/gpu/gl.h"
#include "radiosity/gpu/shader_library.h"

namespace cpgi {
namespace {

TEST(EglContext, RunsAComputeShaderAndReadsBack) {
  Context ctx;
  std::string reported;
  ctx.setProgress([&](const Progress& p) {
    if (p.stage == "egl") reported = p.status;
  });
  EglContext context(ctx);
  EXPECT_FALSE(context.renderer().empty());
  EXPECT_NE(reported.find(context.renderer()), std::string::npos);
  EXPECT_GE(context.maxTextureSize(), 1024);
  // The device's own word on software rasterizing (EGL_MESA_device_software) agrees with what Mesa's
  // software renderers call themselves.
  const bool named = context.renderer().find("llvmpipe") != std::string::npos ||
                     context.renderer().find("softpipe") != std::string::npos;
  EXPECT_EQ(context.softwareRasterizer(), named) << context.renderer();

  const char* source = R"(#version 450 core
    layout(local_size_x = 64) in;
    layout(std430, binding = 0) buffer Data { float v[]; };
    void main() { uint i = gl_GlobalInvocationID.x; v[i] = v[i] * v[i] + float(i); })";
  GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  ASSERT_TRUE(ok);
  gl::Program program(glCreateProgram());
  glAttachShader(program.get(), shader);
  glLinkProgram(program.get());
  glDeleteShader(shader);
  glGetProgramiv(program.get(), GL_LINK_STATUS, &ok);
  ASSERT_TRUE(ok);

  std::vector<float> data(256);
  for (size_t i = 0; i < data.size(); ++i) data[i] = 0.5f * float(i);
  gl::Buffer buffer = gl::makeBuffer(data.size() * 4, data.data());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer.get());
  glUseProgram(program.get());
  glDispatchCompute(4, 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<float> out(data.size());
  glGetNamedBufferSubData(buffer.get(), 0, GLsizeiptr(out.size() * 4), out.data());
  gl::check("test");
  for (size_t i = 0; i < out.size(); ++i) EXPECT_FLOAT_EQ(out[i], data[i] * data[i] + float(i));
}

TEST(EglContext, EmbeddedShadersCompile) {
  Context ctx;
  EglContext context(ctx);
  for (const char* name : {"compact.comp", "finish_lists.comp", "shooter_pyramid.comp", "tile_stats.comp",
                           "patch_stats.comp", "select_shooter.comp", "receive.comp"})
    EXPECT_NO_THROW(buildProgram({name})) << name;
  EXPECT_NO_THROW(buildProgram({"receive.comp"}, {"HEMISPHERE"}));
  EXPECT_NO_THROW(buildProgram({"item.vert", "item.frag"}));
  EXPECT_NO_THROW(buildProgram({"item.vert", "item_hemisphere.tesc", "item_hemisphere.tese", "item.frag"},
                               {"HEMISPHERE"}));
  EXPECT_NO_THROW(buildProgram({"shot_coverage.comp"}));
  EXPECT_NO_THROW(buildProgram({"shot_coverage.comp"}, {"HEMISPHERE"}));
  EXPECT_NO_THROW(buildProgram({"rescale_shot.comp"}));
  EXPECT_NE(shaderSource("receive.comp").find("visibleFromShooter"), std::string::npos);
  EXPECT_THROW(shaderSource("missing.comp"), std::invalid_argument);
}

// Squares 64 floats on the current context by a compute shader and reads them back: whether it draws.
bool computes() {
  const char* source = R"(#version 450 core
    layout(local_size_x = 64) in;
    layout(std430, binding = 0) buffer Data { float v[]; };
    void main() { v[gl_GlobalInvocationID.x] *= v[gl_GlobalInvocationID.x]; })";
  const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) return false;
  gl::Program program(glCreateProgram());
  glAttachShader(program.get(), shader);
  glLinkProgram(program.get());
  glDeleteShader(shader);
  std::vector<float> data(64, 3.0f), out(64, 0.0f);
  gl::Buffer buffer = gl::makeBuffer(data.size() * 4, data.data());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer.get());
  glUseProgram(program.get());
  glDispatchCompute(1, 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(buffer.get(), 0, GLsizeiptr(out.size() * 4), out.data());
  return glGetError() == GL_NO_ERROR && out == std::vector<float>(64, 9.0f);
}

// A context kept from bake to bake (a cell-job server's, the bake tests' shared one) still draws after
// another one was made and closed on its thread. Every EglContext of a device shares one EGLDisplay: the
// other one, made current over the kept one, used to leave the thread with no context when it closed and
// terminate the display under the kept one (a shader compile then failed with an empty log).
TEST(EglContext, AKeptContextDrawsAfterAnotherIsMadeAndClosed) {
  Context ctx;
  EglContext kept(ctx);
  ASSERT_TRUE(computes());
  {
    EglContext other(ctx);
    EXPECT_TRUE(computes());
  }
  EXPECT_TRUE(computes());
  EXPECT_NO_THROW(buildProgram({"item.vert", "item.frag"}));
  // Closed out of order: the latest one made stays current, the kept one draws again once it goes.
  auto second = std::make_unique<EglContext>(ctx);
  auto third = std::make_unique<EglContext>(ctx);
  second.reset();
  EXPECT_TRUE(computes());
  third.reset();
  EXPECT_TRUE(computes());
  EXPECT_NO_THROW(buildProgram({"item.vert", "item.frag"}));
}

}  // namespace
}  // namespace cpgi
