#pragma once
// Command-line checks shared by the verbs that write pictures (render, run).
#include <unistd.h>

#include <charconv>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

#include "millsim/graphics/GlContext.h"

namespace millsim::app {

// "640x480" → {640, 480}; throws std::invalid_argument naming the text.
inline std::pair<int, int> parseSize(const std::string& text) {
  const auto x = text.find_first_of("xX");
  int w = 0, h = 0;
  auto number = [](std::string_view s, int& v) {
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    return ec == std::errc() && end == s.data() + s.size() && !s.empty();
  };
  if (x == std::string::npos || !number(std::string_view(text).substr(0, x), w) ||
      !number(std::string_view(text).substr(x + 1), h))
    throw std::invalid_argument("--size '" + text + "' is not WIDTHxHEIGHT (e.g. 512x512)");
  if (w < 1 || h < 1 || w > GlContext::kMaxSize || h > GlContext::kMaxSize)
    throw std::invalid_argument("--size " + text + " is out of range; expected 1x1 to " +
                                std::to_string(GlContext::kMaxSize) + "x" + std::to_string(GlContext::kMaxSize));
  return {w, h};
}

// Refuses an output path that cannot be written, before any work is done.
inline void checkWritable(const std::filesystem::path& out, const std::string& option) {
  namespace fs = std::filesystem;
  const fs::path dir = out.has_parent_path() ? out.parent_path() : fs::path(".");
  std::error_code ec;
  if (fs::is_directory(out, ec)) throw std::invalid_argument(option + " " + out.string() + " is a directory");
  if (!fs::is_directory(dir, ec))
    throw std::invalid_argument(option + " " + out.string() + ": the folder " + dir.string() + " does not exist");
  if (::access(dir.c_str(), W_OK) != 0 || (fs::exists(out, ec) && ::access(out.c_str(), W_OK) != 0))
    throw std::invalid_argument(option + " " + out.string() + " is not writable");
}

}  // namespace millsim::app
