#pragma once
// GlContext: an offscreen OpenGL core-profile context (OSMesa, llvmpipe; no
// X, no GLX) with an RGBA colour buffer and a 24-bit depth buffer of a fixed
// size. The context is made current on the constructing thread; a GL context
// is current on one thread at a time, so create, use and destroy it on the
// thread that draws (makeCurrent() re-binds it there after another context
// was used, e.g. two renderers in one test).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace millsim {

class GlContext {
public:
  // Largest width or height accepted (also capped by the driver's limits).
  static constexpr int kMaxSize = 8192;

  // Throws GraphicsError for a size that is zero, negative or too large, when
  // OSMesa cannot create a core context, or when its GL version is below 3.3.
  GlContext(int width, int height);
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  void makeCurrent();
  int width() const { return width_; }
  int height() const { return height_; }
  // "4.5 (Core Profile) Mesa 22.3.6, llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string description() const;

  // Throws GraphicsError naming `what` if OpenGL recorded an error.
  static void check(const char* what);

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int width_, height_;
};

}  // namespace millsim
