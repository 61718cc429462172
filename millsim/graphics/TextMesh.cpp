#include "millsim/graphics/TextMesh.h"

#include <algorithm>

#include "millsim/graphics/FontAtlas.h"

namespace millsim {

std::u32string decodeUtf8(const std::string& text) {
  std::u32string out;
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    const int extra = c < 0x80 ? 0 : (c >> 5) == 0x6 ? 1 : (c >> 4) == 0xE ? 2 : (c >> 3) == 0x1E ? 3 : -1;
    char32_t cp = extra == 0 ? c : extra == 1 ? c & 0x1F : extra == 2 ? c & 0x0F : c & 0x07;
    bool ok = extra >= 0 && i + std::size_t(extra) < text.size() + (extra == 0 ? 1 : 0);
    for (int k = 1; ok && k <= extra; ++k) {
      const auto d = static_cast<unsigned char>(text[i + std::size_t(k)]);
      ok = (d >> 6) == 0x2;
      cp = (cp << 6) | (d & 0x3F);
    }
    out.push_back(ok ? cp : U'\uFFFD');
    i += ok ? std::size_t(extra) + 1 : 1;
  }
  return out;
}

TriangleMesh layoutText(const DrawText& text, FontAtlas& font) {
  TriangleMesh mesh;
  const float size = text.size, lineStep = text.size * text.spacing * (text.topToBottom ? -1.f : 1.f);
  const std::size_t lines = text.lines.size();
  // Where the first line's baseline sits (minor justification, X3D 15.2.2.3).
  float firstBaseline = 0.f;
  const float block = std::abs(lineStep) * float(lines == 0 ? 0 : lines - 1);
  if (text.justifyMinor == "BEGIN")
    firstBaseline = -font.ascent() * size;
  else if (text.justifyMinor == "MIDDLE")
    firstBaseline = text.topToBottom ? 0.5f * block - 0.5f * (font.ascent() - font.descent()) * size : -0.5f * block;
  else if (text.justifyMinor == "END")
    firstBaseline = text.topToBottom ? block + font.descent() * size : font.descent() * size;
  for (std::size_t l = 0; l < lines; ++l) {
    const std::u32string line = decodeUtf8(text.lines[l]);
    float width = 0.f;
    for (char32_t c : line) width += font.glyph(c).advance * size;
    // Text.length (this line) or maxExtent (every line) squeezes or stretches it along x.
    float stretch = 1.f;
    if (l < text.lengths.size() && text.lengths[l] > 0.f && width > 0.f) stretch = text.lengths[l] / width;
    if (text.maxExtent > 0.f && width * stretch > text.maxExtent) stretch = text.maxExtent / width;
    const float drawnWidth = width * stretch;
    float x = text.justifyMajor == "MIDDLE" ? -0.5f * drawnWidth : text.justifyMajor == "END" ? -drawnWidth : 0.f;
    const float y = firstBaseline + lineStep * float(l);
    for (char32_t c : line) {
      const Glyph& g = font.glyph(c);
      if (g.drawn) {
        const glm::vec3 lo(x + g.offset.x * size * stretch, y + g.offset.y * size, 0.f);
        const glm::vec3 hi(lo.x + g.size.x * size * stretch, lo.y + g.size.y * size, 0.f);
        const glm::vec3 corners[4] = {lo, {hi.x, lo.y, 0.f}, hi, {lo.x, hi.y, 0.f}};
        const glm::vec2 uvs[4] = {g.uvMin, {g.uvMax.x, g.uvMin.y}, g.uvMax, {g.uvMin.x, g.uvMax.y}};
        for (int k : {0, 1, 2, 0, 2, 3}) {
          mesh.positions.push_back(corners[k]);
          mesh.normals.emplace_back(0.f, 0.f, 1.f);
          mesh.texCoords.push_back(uvs[k]);
        }
      }
      x += g.advance * size * stretch;
    }
  }
  mesh.computeBounds();
  return mesh;
}

}  // namespace millsim
