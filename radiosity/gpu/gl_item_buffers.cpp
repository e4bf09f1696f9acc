// The GL engine's item buffers (gl_shot_backend.h): the scene's triangles on the device, the layered
// targets (one layer per eye), each hemicube face's culled triangle lists (shaders/item_cull.comp) and the
// draws from an eye (shaders/item.vert, item.frag).
#include <algorithm>
#include <limits>

#include "core/error.h"
#include "radiosity/gpu/gl_shot_backend.h"
#include "radiosity/gpu/item_mesh.h"

namespace cpgi::gl_engine {
namespace {

struct Face {
  glm::vec3 right, up, forward;
};
// The hemicube in shooter coordinates (z = shooter normal); must match visibility.glsl.
constexpr Face kFaces[5] = {
    {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}},   {{0, 1, 0}, {0, 0, 1}, {1, 0, 0}},
    {{0, -1, 0}, {0, 0, 1}, {-1, 0, 0}}, {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
    {{1, 0, 0}, {0, 0, 1}, {0, -1, 0}},
};

constexpr size_t kCullChunk = 32;  // triangles per invocation of item_cull.comp (its CHUNK)

}  // namespace

// Per hemicube face, the triangles that may show in it from any of `eyes` (shaders/item_cull.comp), as
// the index lists and draw commands renderItemBuffer draws.
void GlShotBackend::cullItemFaces(std::span<const glm::vec3> eyes, const glm::mat3& toShooter) {
  // The planes a·local > b beyond which item.vert's projection clips, in shooter coordinates; from every
  // eye at once, a·(toShooter p) > b + max over the eyes of a·(toShooter eye).
  std::array<glm::vec4, 26> planes;
  float scale = 0.0f;
  for (const glm::vec3& e : eyes) scale = std::max(scale, glm::length(toShooter * e));
  auto plane = [&](glm::vec3 a, float b) {
    float most = -std::numeric_limits<float>::infinity();
    for (const glm::vec3& e : eyes) most = std::max(most, glm::dot(a, toShooter * e));
    return glm::vec4(a, b + most);
  };
  planes[0] = plane(glm::vec3(0, 0, -1), 0.0f);  // behind the shooter: gl_ClipDistance[0] < 0
  for (size_t f = 0; f < 5; ++f) {
    const glm::vec3 r = kFaces[f].right, u = kFaces[f].up, w = kFaces[f].forward;
    // y as item.vert has it: v.y on the top face, 2 v.y − w on the half side faces.
    const glm::vec3 y = f == 0 ? u : 2.0f * u - w;
    planes[1 + 5 * f] = plane(r - w, 0.0f);   // x > w
    planes[2 + 5 * f] = plane(-r - w, 0.0f);  // x < −w
    planes[3 + 5 * f] = plane(y - w, 0.0f);   // y > w
    planes[4 + 5 * f] = plane(-y - w, 0.0f);  // y < −w
    planes[5 + 5 * f] = plane(-w, -near_);    // w < near
  }
  const GLuint chunks = groups(size_t(triangleCount_), kCullChunk);
  for (int pass = 0; pass < 3; ++pass) {
    const gl::Program& p = *cullPrograms_[size_t(pass)];
    if (pass == 0) {
      set(p, "uToShooter", toShooter);
      glProgramUniform4fv(p.get(), loc(p, "uPlanes"), GLsizei(planes.size()), &planes[0].x);
      set(p, "uScale", scale + near_);
    }
    glUseProgram(p.get());
    glDispatchCompute(pass == 1 ? 5 : groups(chunks, 64), 1, 1);
    glMemoryBarrier(pass < 2 ? GL_SHADER_STORAGE_BARRIER_BIT
                             : GL_ELEMENT_ARRAY_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
  }
}

void GlShotBackend::renderItemBuffer(int layer, const glm::vec3& eye, const glm::mat3& toShooter) {
  glNamedFramebufferTextureLayer(fbo_.get(), GL_COLOR_ATTACHMENT0, items_.get(), 0, layer);
  glNamedFramebufferTextureLayer(fbo_.get(), GL_COLOR_ATTACHMENT1, distances_.get(), 0, layer);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
  const GLint none = -1;
  const GLfloat far = 1.0f, nothing = 1e30f;  // a pixel showing nothing cannot shadow
  glClearNamedFramebufferiv(fbo_.get(), GL_COLOR, 0, &none);
  glClearNamedFramebufferfv(fbo_.get(), GL_COLOR, 1, &nothing);
  glClearNamedFramebufferfv(fbo_.get(), GL_DEPTH, 0, &far);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_CLIP_DISTANCE0);
  glUseProgram(itemProgram_.get());
  set(itemProgram_, "uEye", eye);
  set(itemProgram_, "uToShooter", toShooter);
  glBindVertexArray(vao_.get());
  if (params_.visibility == Visibility::Hemisphere) {
    glViewport(0, 0, itemSize_, itemSize_);
    glPatchParameteri(GL_PATCH_VERTICES, 3);
    glDrawElements(GL_PATCHES, indexCount_, GL_UNSIGNED_INT, nullptr);
  } else {
    if (culled()) glBindBuffer(GL_DRAW_INDIRECT_BUFFER, faceDraws_.get());
    const int f = itemSize_, half = f / 2;
    for (int i = 0; i < 5; ++i) {
      set(itemProgram_, "uFace", rowsOf(kFaces[i].right, kFaces[i].up, kFaces[i].forward));
      set(itemProgram_, "uHalfFace", i == 0 ? 0 : 1);
      if (i == 0)
        glViewport(0, 0, f, f);
      else
        glViewport(0, f + (i - 1) * half, f, half);
      if (culled())
        glDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT,
                               reinterpret_cast<const void*>(uintptr_t(i) * 5 * sizeof(GLuint)));
      else
        glDrawElements(GL_TRIANGLES, indexCount_, GL_UNSIGNED_INT, nullptr);
    }
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void GlShotBackend::uploadGeometry() {
  const ItemMesh mesh = buildItemMesh(scene_, atlas_);
  indexCount_ = GLsizei(mesh.indices.size());
  positionBuffer_ = gl::makeBuffer(mesh.positions.size() * sizeof(glm::vec3), mesh.positions.data(), 0);
  idBuffer_ = gl::makeBuffer(mesh.patches.size() * 4, mesh.patches.data(), 0);
  normalBuffer_ = gl::makeBuffer(mesh.normals.size() * sizeof(glm::vec3), mesh.normals.data(), 0);
  indexBuffer_ = gl::makeBuffer(mesh.indices.size() * 4, mesh.indices.data(), 0);
  triangleCount_ = indexCount_ / 3;
  GLuint vao = 0;
  glCreateVertexArrays(1, &vao);
  vao_ = gl::VertexArray(vao);
  if (!culled()) {
    glVertexArrayElementBuffer(vao, indexBuffer_.get());
  } else {  // the hemicube's faces draw the culled lists (cullItemFaces)
    const size_t chunks = groups(size_t(triangleCount_), kCullChunk);
    auto ssbo = [](gl::Buffer& b, Ssbo binding, size_t bytes) {
      b = gl::makeBuffer(std::max<size_t>(bytes, 4), nullptr);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, b.get());
    };
    ssbo(faceMasks_, kFaceMasks, size_t(triangleCount_) * 4);
    ssbo(chunkSlots_, kChunkSlots, 5 * chunks * 4);
    ssbo(faceIndices_, kFaceIndices, 5 * size_t(indexCount_) * 4);
    ssbo(faceDraws_, kFaceDraws, 5 * 5 * 4);
    if (indexCount_ > 0) {
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kItemPositions, positionBuffer_.get());
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kItemIndices, indexBuffer_.get());
    }
    glVertexArrayElementBuffer(vao, faceIndices_.get());
  }
  glVertexArrayVertexBuffer(vao, 0, positionBuffer_.get(), 0, sizeof(glm::vec3));
  glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(vao, 0, 0);
  glEnableVertexArrayAttrib(vao, 0);
  glVertexArrayVertexBuffer(vao, 1, idBuffer_.get(), 0, 4);
  glVertexArrayAttribIFormat(vao, 1, 1, GL_INT, 0);
  glVertexArrayAttribBinding(vao, 1, 1);
  glEnableVertexArrayAttrib(vao, 1);
  glVertexArrayVertexBuffer(vao, 2, normalBuffer_.get(), 0, sizeof(glm::vec3));
  glVertexArrayAttribFormat(vao, 2, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(vao, 2, 2);
  glEnableVertexArrayAttrib(vao, 2);

  const Bounds b = scene_.bounds();
  const float diagonal = std::max(glm::length(b.size()), 1e-3f);
  far_ = 2.0f * diagonal;
  // Drawn eyes (pick_eyes.comp) may sit a few millimetres from a wall (a lamp's edge texel in its
  // housing): a near plane of 1e-3 × diagonal (9 mm in spot-door) cut such walls open and let the lamp
  // light the room through them (global rel. RMSE 128 %).
  near_ = 1e-4f * diagonal;
  eyeOffset_ = 1e-4f * diagonal;
}

void GlShotBackend::makeItemBuffer() {
  int w, h;
  if (params_.visibility == Visibility::Hemisphere) {
    itemSize_ = params_.itemBuffer;
    w = h = itemSize_;
  } else {
    itemSize_ = params_.itemBuffer / 2 + (params_.itemBuffer / 2) % 2;  // face edge, even
    w = itemSize_;
    h = itemSize_ * 3;  // top face, then four half-height side faces
  }
  // One layer per shooter region.
  GLuint items = 0;
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &items);
  items_ = gl::Texture(items);
  const int layers = mostEyes();
  glTextureStorage3D(items, 1, GL_R32I, w, h, layers);
  glTextureParameteri(items, GL_TEXTURE_MIN_FILTER, GL_NEAREST);  // else incomplete for texelFetch
  glTextureParameteri(items, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  // The distance from the eye of what each pixel shows (item.frag), for the receivers' plane test.
  GLuint distances = 0;
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &distances);
  distances_ = gl::Texture(distances);
  glTextureStorage3D(distances, 1, GL_R32F, w, h, layers);
  glTextureParameteri(distances, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(distances, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  depth_ = gl::makeTexture2D(GL_DEPTH_COMPONENT32F, w, h);
  GLuint fbo = 0;
  glCreateFramebuffers(1, &fbo);
  fbo_ = gl::Framebuffer(fbo);
  glNamedFramebufferTextureLayer(fbo, GL_COLOR_ATTACHMENT0, items, 0, 0);
  glNamedFramebufferTextureLayer(fbo, GL_COLOR_ATTACHMENT1, distances, 0, 0);
  const GLenum outputs[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(fbo, 2, outputs);
  glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, depth_.get(), 0);
  if (glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw SystemError("OpenGL: the item-buffer framebuffer (R32I + R32F + depth) is incomplete");
  glBindTextureUnit(0, items_.get());
  glBindTextureUnit(1, distances_.get());
}

}  // namespace cpgi::gl_engine
