// The solver's GLSL programs, embedded at build time from shaders/ and compiled on demand.
#pragma once

#include <string>
#include <vector>

#include "radiosity/gpu/gl.h"

namespace cpgi {

/// The text of shaders/<name> with its `#include "file"` lines replaced by those files.
/// Throws std::invalid_argument for an unknown name.
std::string shaderSource(const std::string& name);

/// Compiles and links a program from shader files (stage by extension: .vert, .frag, .comp), each
/// prefixed with `#version 450 core` and the given `#define`s. Throws SystemError with the compiler's
/// log on failure.
gl::Program buildProgram(const std::vector<std::string>& files, const std::vector<std::string>& defines = {});

}  // namespace cpgi
