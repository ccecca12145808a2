#include "render/gl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <fmt/format.h>

#if defined(__SANITIZE_ADDRESS__)
#include <dlfcn.h>
#include <link.h>

#include <vector>
#endif

namespace vaegail::render {

namespace {

#if defined(__SANITIZE_ADDRESS__)
// In the sanitizer build (docs/sanitizers.md): every library loaded so far, Mesa's driver and the
// LLVM it draws with among them, stays loaded until the process exits. eglTerminate unloads
// them, and then LeakSanitizer's check at exit finds the memory their globals held unreachable
// and cannot name the module that allocated it. The names are collected first: dlopen must not
// run inside dl_iterate_phdr, which holds the loader's lock.
void keep_loaded_libraries() {
  std::vector<std::string> names;
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void* out) {
        if (info->dlpi_name != nullptr && info->dlpi_name[0] != '\0')
          static_cast<std::vector<std::string>*>(out)->push_back(info->dlpi_name);
        return 0;
      },
      &names);
  for (const auto& name : names) dlopen(name.c_str(), RTLD_LAZY | RTLD_NOLOAD | RTLD_NODELETE);
}
#endif

[[noreturn]] void fail(const char* call) {
  throw RenderError(fmt::format("offscreen OpenGL: {} failed (EGL error 0x{:04x}; Mesa's EGL and llvmpipe come "
                                "with libegl-mesa0 and libgl1-mesa-dri)",
                                call, static_cast<unsigned>(eglGetError())));
}

}  // namespace

GlContext::GlContext() {
  // The surfaceless platform needs neither an X server nor a GPU device node.
  const auto get_platform_display =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!get_platform_display) fail("eglGetProcAddress(eglGetPlatformDisplayEXT)");
  EGLDisplay display = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (display == EGL_NO_DISPLAY) fail("eglGetPlatformDisplayEXT(surfaceless)");
  if (!eglInitialize(display, nullptr, nullptr)) fail("eglInitialize");
  display_ = display;
  // MuJoCo's renderer is desktop OpenGL (fixed function and framebuffer objects), not GLES. It
  // draws into its own framebuffer object, so the config's surfaces go unused; the surfaceless
  // platform offers pbuffer configs only (the default, window, matches none).
  const EGLint attributes[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
  EGLConfig config;
  EGLint configs = 0;
  if (!eglChooseConfig(display, attributes, &config, 1, &configs) || configs < 1) {
    eglTerminate(display);
    fail("eglChooseConfig(desktop OpenGL)");
  }
  if (!eglBindAPI(EGL_OPENGL_API)) {
    eglTerminate(display);
    fail("eglBindAPI(EGL_OPENGL_API)");
  }
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, nullptr);
  if (context == EGL_NO_CONTEXT) {
    eglTerminate(display);
    fail("eglCreateContext");
  }
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    eglDestroyContext(display, context);
    eglTerminate(display);
    fail("eglMakeCurrent(no surface)");
  }
  context_ = context;
#if defined(__SANITIZE_ADDRESS__)
  keep_loaded_libraries();
#endif
  const auto* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  renderer_ = name ? name : "unknown";
}

GlContext::~GlContext() {
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display_, context_);
  eglTerminate(display_);
}

}  // namespace vaegail::render
