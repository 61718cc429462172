#include "millsim/graphics/GlContext.h"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/osmesa.h>
#include <GL/gl.h>
#include <GL/glext.h>

#include "millsim/graphics/GraphicsError.h"

namespace millsim {

struct GlContext::Impl {
  OSMesaContext context = nullptr;
  std::vector<std::uint32_t> buffer;  // OSMesa's colour buffer lives in our memory
};

namespace {
std::string sizeText(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }
}  // namespace

GlContext::GlContext(int width, int height) : impl_(std::make_unique<Impl>()), width_(width), height_(height) {
  if (width <= 0 || height <= 0 || width > kMaxSize || height > kMaxSize)
    throw GraphicsError("image size " + sizeText(width, height) + " is out of range; expected 1x1 to " +
                        sizeText(kMaxSize, kMaxSize));
  const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_STENCIL_BITS, 0,
                         OSMESA_ACCUM_BITS, 0, OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION, 3, OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
  impl_->context = OSMesaCreateContextAttribs(attribs, nullptr);
  if (!impl_->context)
    throw GraphicsError("OSMesa could not create an OpenGL 3.3 core-profile context (is Mesa's llvmpipe available?)");
  int maxW = 0, maxH = 0;
  OSMesaGetIntegerv(OSMESA_MAX_WIDTH, &maxW);
  OSMesaGetIntegerv(OSMESA_MAX_HEIGHT, &maxH);
  if ((maxW > 0 && width > maxW) || (maxH > 0 && height > maxH)) {
    OSMesaDestroyContext(impl_->context);
    throw GraphicsError("image size " + sizeText(width, height) + " exceeds OSMesa's limit " + sizeText(maxW, maxH));
  }
  impl_->buffer.resize(std::size_t(width) * std::size_t(height));
  makeCurrent();
  GLint major = 0, minor = 0, maxViewport[2] = {0, 0}, maxRenderbuffer = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, maxViewport);
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxRenderbuffer);
  std::string problem;
  if (major * 10 + minor < 33)
    problem = "OpenGL " + std::to_string(major) + "." + std::to_string(minor) + " is too old; MillSim needs 3.3 core";
  else if (width > maxViewport[0] || height > maxViewport[1] || width > maxRenderbuffer || height > maxRenderbuffer)
    problem = "image size " + sizeText(width, height) + " exceeds the driver's limit " +
              sizeText(std::min(maxViewport[0], maxRenderbuffer), std::min(maxViewport[1], maxRenderbuffer));
  if (!problem.empty()) {
    OSMesaMakeCurrent(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0);
    OSMesaDestroyContext(impl_->context);
    throw GraphicsError(problem);
  }
}

GlContext::~GlContext() {
  if (OSMesaGetCurrentContext() == impl_->context) OSMesaMakeCurrent(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0);
  OSMesaDestroyContext(impl_->context);
}

void GlContext::makeCurrent() {
  if (!OSMesaMakeCurrent(impl_->context, impl_->buffer.data(), GL_UNSIGNED_BYTE, width_, height_))
    throw GraphicsError("OSMesaMakeCurrent failed for a " + sizeText(width_, height_) + " buffer");
}

std::string GlContext::description() const {
  auto str = [](GLenum e) {
    const auto* s = reinterpret_cast<const char*>(glGetString(e));
    return std::string(s ? s : "?");
  };
  return str(GL_VERSION) + ", " + str(GL_RENDERER);
}

void GlContext::check(const char* what) {
  const GLenum e = glGetError();
  if (e != GL_NO_ERROR) {
    char hex[16];
    std::snprintf(hex, sizeof hex, "0x%04X", unsigned(e));
    throw GraphicsError(std::string("OpenGL error ") + hex + " in " + what);
  }
}

}  // namespace millsim
