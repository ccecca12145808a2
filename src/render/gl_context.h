// An OpenGL context with no display and no GPU: Mesa's software renderer (llvmpipe) through
// EGL's surfaceless platform. MuJoCo's renderer draws into its own offscreen framebuffer
// (mjr_setBuffer(mjFB_OFFSCREEN)), so the context needs no window and no pbuffer surface.
// Only the render stage creates one: the rest of the project never touches OpenGL.
#pragma once

#include <stdexcept>
#include <string>

namespace vaegail::render {

// Every failure to get a context or to draw: one line naming what failed.
class RenderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Creates the context and makes it current on the calling thread; the destructor releases it.
// Render on the thread that created it. Throws RenderError naming the EGL call and its error
// code when Mesa's EGL is missing (scripts/setup.sh installs it) or refuses.
class GlContext {
 public:
  GlContext();
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  // "Mesa/X.org llvmpipe (LLVM ...)": which renderer drew, for reports.
  const std::string& renderer() const { return renderer_; }

 private:
  void* display_ = nullptr;  // EGLDisplay
  void* context_ = nullptr;  // EGLContext
  std::string renderer_;
};

}  // namespace vaegail::render
