// A headless OpenGL 4.5 core context through EGL, with no window and no X server (design.md §2):
// a hardware EGL device first (EGL_EXT_platform_device; NVIDIA and Mesa GPUs), then Mesa's surfaceless
// platform, then a software device (llvmpipe). The context is current on the creating thread from its
// making until another EglContext is made there, and again once that one is closed: a process may keep
// one from bake to bake and let a bake open and close its own in between. The display, which every
// context on the device shares, is terminated when the last of them is closed.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "core/context.h"

namespace cpgi {

class EglContext {
 public:
  /// Makes the context current. Throws SystemError with one line naming what failed when no
  /// OpenGL 4.5 core context can be made. Reports platform, renderer and version through
  /// ctx.progress("egl", 1, ...).
  explicit EglContext(Context& ctx);
  ~EglContext();
  /// A further context on `first`'s display, made current on the calling thread: one per worker thread
  /// (a context is current on one thread at a time). Not shared with `first` (its own programs and
  /// buffers); `first` must outlive it. Throws SystemError when the driver refuses.
  static std::unique_ptr<EglContext> sibling(const EglContext& first);
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  /// GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  const std::string& renderer() const { return renderer_; }
  /// GL_VERSION.
  const std::string& version() const { return version_; }
  /// How the display was found: "device", "surfaceless" or "software device".
  const std::string& platform() const { return platform_; }
  /// Whether the device rasterizes on the CPU (its EGL device says EGL_MESA_device_software: llvmpipe,
  /// softpipe), where item buffers cost more than rays traced on the same cores.
  bool softwareRasterizer() const { return software_; }
  int maxTextureSize() const { return maxTextureSize_; }
  /// GL_MAX_SHADER_STORAGE_BLOCK_SIZE, bytes: the largest buffer a shader may address (llvmpipe: 128 MiB).
  int64_t maxStorageBlockSize() const { return maxStorageBlockSize_; }

 private:
  EglContext() = default;
  void describe();
  void release();
  void* display_ = nullptr;  // EGLDisplay
  void* context_ = nullptr;  // EGLContext
  void* config_ = nullptr;   // EGLConfig, null with EGL_KHR_no_config_context
  bool software_ = false;
  std::string renderer_, version_, platform_;
  int maxTextureSize_ = 0;
  int64_t maxStorageBlockSize_ = 0;
};

}  // namespace cpgi
