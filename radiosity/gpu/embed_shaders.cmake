# Writes OUT: a C++ header with every file of FILES as a raw string literal, keyed by file name.
# Run at build time (radiosity/CMakeLists.txt), so editing a shader rebuilds only what includes it.
set(body "// Generated from shaders/*.glsl by radiosity/gpu/embed_shaders.cmake; do not edit.\n#pragma once\n\n")
string(APPEND body "namespace cpgi::embedded {\nstruct ShaderFile { const char* name; const char* text; };\n")
string(APPEND body "inline constexpr ShaderFile kShaderFiles[] = {\n")
foreach(file IN LISTS FILES)
  get_filename_component(name "${file}" NAME)
  file(READ "${file}" text)
  string(APPEND body "  {\"${name}\", R\"cpgi_glsl(${text})cpgi_glsl\"},\n")
endforeach()
string(APPEND body "};\n}  // namespace cpgi::embedded\n")
file(WRITE "${OUT}.tmp" "${body}")
file(COPY_FILE "${OUT}.tmp" "${OUT}" ONLY_IF_DIFFERENT)
