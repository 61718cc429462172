#include "millsim/std/ImageTexture.h"

#include <array>
#include <filesystem>
#include <fstream>

#include "millsim/core/Diagnostics.h"

namespace millsim {

const NodeType& ImageTexture::type() {
  static const NodeType t = makeNodeType<ImageTexture>("ImageTexture", "texture", "Texturing", "An image (PNG or JPEG) on a Shape.");
  return t;
}

namespace {

// Why `path` is not an image MillSim can draw, or empty if it is one: the
// signature is checked here so that a wrong file is named at load, not
// discovered by the graphics thread.
std::string problemWith(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "cannot be opened";
  std::array<unsigned char, 8> head{};
  in.read(reinterpret_cast<char*>(head.data()), head.size());
  const bool png = in.gcount() == 8 && head == std::array<unsigned char, 8>{0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  const bool jpeg = in.gcount() >= 3 && head[0] == 0xFF && head[1] == 0xD8 && head[2] == 0xFF;
  return png || jpeg ? "" : "is neither a PNG nor a JPEG file";
}

}  // namespace

void ImageTexture::initialize(DiagnosticSink& sink) {
  imageFile_.clear();
  if (!load.get() || url.get().empty()) return;
  const std::filesystem::path base =
      location().file.empty() ? std::filesystem::path() : std::filesystem::path(location().file).parent_path();
  std::string why;
  for (const std::string& u : url.get()) {
    if (u.find("://") != std::string::npos) {
      why += "\n  '" + u + "': not fetched (MillSim reads local files only)";
      continue;
    }
    std::filesystem::path p(u.rfind("file:", 0) == 0 ? u.substr(5) : u);
    if (p.is_relative()) p = base / p;
    const std::string problem = problemWith(p);
    if (problem.empty()) {
      imageFile_ = std::filesystem::absolute(p).lexically_normal().string();
      return;
    }
    why += "\n  '" + u + "': " + problem;
  }
  sink.warning(location(), "ImageTexture has no usable image, so its Shape is drawn without it:" + why);
}

}  // namespace millsim
