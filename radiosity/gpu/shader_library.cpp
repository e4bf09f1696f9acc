#include "radiosity/gpu/shader_library.h"

#include <sstream>
#include <stdexcept>

#include "core/error.h"
#include "radiosity/gpu/embedded_shaders.h"

namespace cpgi {
namespace {

const char* findFile(const std::string& name) {
  for (const auto& f : embedded::kShaderFiles)
    if (name == f.name) return f.text;
  return nullptr;
}

std::string expand(const std::string& name, int depth) {
  const char* text = findFile(name);
  if (!text) throw std::invalid_argument("shader library: no shader named " + name);
  if (depth > 8) throw std::invalid_argument("shader library: includes nested too deep in " + name);
  std::istringstream in(text);
  std::string out, line;
  while (std::getline(in, line)) {
    const auto pos = line.find("#include \"");
    if (pos == 0) {
      const auto end = line.find('"', 10);
      out += expand(line.substr(10, end - 10), depth + 1);
    } else {
      out += line + "\n";
    }
  }
  return out;
}

GLenum stageOf(const std::string& file) {
  auto ends = [&](const char* ext) { return file.size() > 5 && file.compare(file.size() - 5, 5, ext) == 0; };
  if (ends(".vert")) return GL_VERTEX_SHADER;
  if (ends(".frag")) return GL_FRAGMENT_SHADER;
  if (ends(".comp")) return GL_COMPUTE_SHADER;
  if (ends(".tesc")) return GL_TESS_CONTROL_SHADER;
  if (ends(".tese")) return GL_TESS_EVALUATION_SHADER;
  throw std::invalid_argument("shader library: unknown stage for " + file);
}

}  // namespace

std::string shaderSource(const std::string& name) { return expand(name, 0); }

gl::Program buildProgram(const std::vector<std::string>& files, const std::vector<std::string>& defines) {
  gl::Program program(glCreateProgram());
  std::vector<GLuint> shaders;
  std::string prefix = "#version 450 core\n";
  for (const std::string& d : defines) prefix += "#define " + d + "\n";
  prefix += "#line 1\n";
  std::string failure;
  for (const std::string& file : files) {
    const std::string text = prefix + shaderSource(file);
    const GLuint s = glCreateShader(stageOf(file));
    const char* src = text.c_str();
    glShaderSource(s, 1, &src, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      char log[4096] = {};
      glGetShaderInfoLog(s, sizeof log, nullptr, log);
      failure = "compiling " + file + ": " + log;
    }
    glAttachShader(program.get(), s);
    shaders.push_back(s);
  }
  if (failure.empty()) {
    glLinkProgram(program.get());
    GLint ok = 0;
    glGetProgramiv(program.get(), GL_LINK_STATUS, &ok);
    if (!ok) {
      char log[4096] = {};
      glGetProgramInfoLog(program.get(), sizeof log, nullptr, log);
      failure = "linking " + files.front() + ": " + log;
    }
  }
  for (GLuint s : shaders) glDeleteShader(s);
  if (!failure.empty()) throw SystemError("OpenGL shader " + failure);
  gl::check("buildProgram");
  return program;
}

}  // namespace cpgi
