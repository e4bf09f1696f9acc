#include "radiosity/gpu/egl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <thread>
#include <vector>

#include "core/error.h"
#include "radiosity/gpu/gl.h"

#ifndef EGL_PLATFORM_SURFACELESS_MESA
#define EGL_PLATFORM_SURFACELESS_MESA 0x31DD
#endif

namespace cpgi {
namespace {

struct EglExtensions {
  PFNEGLQUERYDEVICESEXTPROC queryDevices = nullptr;
  PFNEGLQUERYDEVICESTRINGEXTPROC queryDeviceString = nullptr;
  PFNEGLGETPLATFORMDISPLAYEXTPROC getPlatformDisplay = nullptr;
  PFNEGLQUERYDISPLAYATTRIBEXTPROC queryDisplayAttrib = nullptr;
};

EglExtensions loadExtensions() {
  EglExtensions e;
  e.queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  e.queryDeviceString =
      reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
  e.getPlatformDisplay =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  e.queryDisplayAttrib =
      reinterpret_cast<PFNEGLQUERYDISPLAYATTRIBEXTPROC>(eglGetProcAddress("eglQueryDisplayAttribEXT"));
  return e;
}

bool hasExtension(const char* list, const char* name) {
  if (!list) return false;
  const size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

// Every live EglContext's context, for what EGL leaves to its callers. A device's EGLDisplay is one object
// for the whole process (eglGetPlatformDisplay gives the same handle each time) and eglTerminate ends it
// for every context on it, so it is terminated only when the last context on it goes. A thread has one
// current context, the latest made there, so one that goes while current hands the thread back to the
// latest other one made there, and a context kept from bake to bake draws again once another is closed.
struct LiveContext {
  EGLDisplay display;
  EGLContext context;
  std::thread::id thread;
};

struct LiveContexts {
  std::mutex mutex;
  std::vector<LiveContext> list;  // in the order they were made
  bool displayInUse(EGLDisplay d) const {
    return std::any_of(list.begin(), list.end(), [&](const LiveContext& c) { return c.display == d; });
  }
};

// Never destroyed: a context kept in a static object may go after the registry would have.
LiveContexts& liveContexts() {
  static LiveContexts* live = new LiveContexts;
  return *live;
}

void addLive(EGLDisplay d, EGLContext c) {
  LiveContexts& live = liveContexts();
  std::lock_guard lock(live.mutex);
  live.list.push_back({d, c, std::this_thread::get_id()});
}

// Terminates `d` unless a live context is on it (a failed candidate may be another context's display).
void terminateUnused(EGLDisplay d) {
  LiveContexts& live = liveContexts();
  std::lock_guard lock(live.mutex);
  if (!live.displayInUse(d)) eglTerminate(d);
}

// One candidate display to try, in order of preference.
struct Candidate {
  EGLDisplay display;
  const char* platform;
};

std::vector<Candidate> candidates(const EglExtensions& e) {
  std::vector<Candidate> hardware, software, out;
  if (e.queryDevices && e.getPlatformDisplay) {
    EGLint count = 0;
    if (e.queryDevices(0, nullptr, &count) && count > 0) {
      std::vector<EGLDeviceEXT> devices(count);
      e.queryDevices(count, devices.data(), &count);
      for (EGLint i = 0; i < count; ++i) {
        EGLDisplay d = e.getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (d == EGL_NO_DISPLAY) continue;
        const char* ext = e.queryDeviceString ? e.queryDeviceString(devices[i], EGL_EXTENSIONS) : nullptr;
        // Mesa marks its llvmpipe/softpipe device; prefer anything else.
        (hasExtension(ext, "EGL_MESA_device_software") ? software : hardware).push_back({d, "device"});
      }
    }
  }
  out = hardware;
  if (e.getPlatformDisplay) {
    EGLDisplay d = e.getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (d != EGL_NO_DISPLAY) out.push_back({d, "surfaceless"});
  }
  for (Candidate c : software) out.push_back({c.display, "software device"});
  return out;
}

// Whether the device behind display `d` rasterizes in software on the CPU (Mesa's llvmpipe or softpipe
// mark their device EGL_MESA_device_software), asked of the device itself (EGL_EXT_device_query). A
// display whose device cannot be asked counts as hardware.
bool softwareDevice(const EglExtensions& e, EGLDisplay d, const char* platform) {
  if (std::strcmp(platform, "software device") == 0) return true;
  if (!e.queryDisplayAttrib || !e.queryDeviceString ||
      !hasExtension(eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS), "EGL_EXT_device_query"))
    return false;
  EGLAttrib device = 0;
  if (!e.queryDisplayAttrib(d, EGL_DEVICE_EXT, &device) || device == 0) return false;
  return hasExtension(e.queryDeviceString(reinterpret_cast<EGLDeviceEXT>(device), EGL_EXTENSIONS),
                      "EGL_MESA_device_software");
}

// Tries one display; returns the context or EGL_NO_CONTEXT with `why` filled in.
EGLContext makeContext(EGLDisplay d, EGLConfig config, std::string& why) {
  const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                   EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                   EGL_NONE};
  EGLContext c = eglCreateContext(d, config, EGL_NO_CONTEXT, contextAttribs);
  if (c == EGL_NO_CONTEXT) {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04x", unsigned(eglGetError()));
    why = std::string("no OpenGL 4.5 core context (EGL error ") + code + ")";
    return EGL_NO_CONTEXT;
  }
  if (!eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, c)) {
    eglDestroyContext(d, c);
    why = "eglMakeCurrent without a surface failed";
    return EGL_NO_CONTEXT;
  }
  return c;
}

EGLContext tryDisplay(EGLDisplay d, EGLConfig& chosen, std::string& why) {
  EGLint major = 0, minor = 0;
  if (!eglInitialize(d, &major, &minor)) {
    why = "eglInitialize failed";
    return EGL_NO_CONTEXT;
  }
  if (!eglBindAPI(EGL_OPENGL_API)) {
    why = "no desktop OpenGL API";
    return EGL_NO_CONTEXT;
  }
  // No surface at all (surfaceless); a pbuffer-capable config as the fallback for older drivers.
  EGLConfig config = nullptr;
  EGLint n = 0;
  for (EGLint surfaceType : {0, EGL_PBUFFER_BIT}) {
    const EGLint attribs[] = {EGL_SURFACE_TYPE, surfaceType, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    if (eglChooseConfig(d, attribs, &config, 1, &n) && n > 0) break;
  }
  const bool noConfig = n == 0 && hasExtension(eglQueryString(d, EGL_EXTENSIONS), "EGL_KHR_no_config_context");
  if (n == 0 && !noConfig) {
    why = "no OpenGL-renderable EGL config";
    return EGL_NO_CONTEXT;
  }
  chosen = n > 0 ? config : EGLConfig(nullptr);
  return makeContext(d, chosen, why);
}

}  // namespace

EglContext::EglContext(Context& ctx) {
  const EglExtensions ext = loadExtensions();
  std::string failures;
  for (const Candidate& cand : candidates(ext)) {
    std::string why;
    EGLConfig config = nullptr;
    EGLContext c = tryDisplay(cand.display, config, why);
    if (c != EGL_NO_CONTEXT) {
      display_ = cand.display;
      context_ = c;
      config_ = config;
      platform_ = cand.platform;
      software_ = softwareDevice(ext, cand.display, cand.platform);
      addLive(display_, context_);
      break;
    }
    terminateUnused(cand.display);
    failures += std::string(failures.empty() ? "" : "; ") + cand.platform + ": " + why;
  }
  if (!context_)
    throw SystemError("EGL: no headless OpenGL 4.5 context (" +
                      (failures.empty() ? std::string("no EGL device or surfaceless platform") : failures) +
                      "); install Mesa (libegl-mesa0, libgl1-mesa-dri) or a GPU driver");
  describe();
  ctx.progress("egl", 1.0,
               platform_ + ": " + renderer_ + ", OpenGL " + version_ + (software_ ? " (software)" : ""));
}

std::unique_ptr<EglContext> EglContext::sibling(const EglContext& first) {
  std::unique_ptr<EglContext> c(new EglContext());
  c->display_ = first.display_;
  c->config_ = first.config_;
  c->platform_ = first.platform_;
  c->software_ = first.software_;
  // The API binding is per thread.
  if (!eglBindAPI(EGL_OPENGL_API)) throw SystemError("EGL: no desktop OpenGL API on a worker thread");
  std::string why;
  c->context_ = makeContext(first.display_, first.config_, why);
  if (!c->context_) throw SystemError("EGL: a further context for a worker thread: " + why);
  addLive(c->display_, c->context_);
  c->describe();
  return c;
}

void EglContext::describe() {
  auto str = [](GLenum name) {
    const GLubyte* s = glGetString(name);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  renderer_ = str(GL_RENDERER);
  version_ = str(GL_VERSION);
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTextureSize_);
  GLint64 storage = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &storage);
  maxStorageBlockSize_ = storage;
  if (major * 10 + minor < 45) {
    release();
    throw SystemError("EGL: the context is OpenGL " + version_ + ", 4.5 core is needed");
  }
}

EglContext::~EglContext() { release(); }

void EglContext::release() {
  if (!display_) return;
  LiveContexts& live = liveContexts();
  std::lock_guard lock(live.mutex);
  std::erase_if(live.list, [&](const LiveContext& c) { return c.context == context_; });
  if (context_ && eglGetCurrentContext() == context_) {
    const auto here = std::find_if(live.list.rbegin(), live.list.rend(), [](const LiveContext& c) {
      return c.thread == std::this_thread::get_id();
    });
    if (here != live.list.rend())
      eglMakeCurrent(here->display, EGL_NO_SURFACE, EGL_NO_SURFACE, here->context);
    else
      eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
  if (context_) eglDestroyContext(display_, context_);
  if (!live.displayInUse(display_)) eglTerminate(display_);
  display_ = context_ = nullptr;
}

}  // namespace cpgi
