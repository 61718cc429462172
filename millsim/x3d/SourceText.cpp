#include "millsim/x3d/SourceText.h"

#include <algorithm>

namespace millsim {

SourceText::SourceText(std::string fileLabel, std::string text) : file_(std::move(fileLabel)), text_(std::move(text)) {
  lineStarts_.push_back(0);
  for (std::size_t i = 0; i < text_.size(); ++i)
    if (text_[i] == '\n') lineStarts_.push_back(i + 1);
}

namespace {
bool nameEnds(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '/' || c == '>'; }
}  // namespace

std::size_t SourceText::findStartTag(std::string_view name, long line) {
  // libxml2 gives the line where the start tag ends, so the tag begins on that
  // line or before it. Scan forward from the cursor over markup that is not a
  // start tag (comments, CDATA, declarations, end tags).
  auto skipTo = [&](std::size_t from, std::string_view terminator) {
    std::size_t e = text_.find(terminator, from);
    return e == std::string::npos ? text_.size() : e + terminator.size();
  };
  std::size_t pos = cursor_;
  while ((pos = text_.find('<', pos)) != std::string::npos) {
    if (text_.compare(pos, 4, "<!--") == 0) {
      pos = skipTo(pos + 4, "-->");
    } else if (text_.compare(pos, 9, "<![CDATA[") == 0) {
      pos = skipTo(pos + 9, "]]>");
    } else if (text_.compare(pos, 2, "<?") == 0) {
      pos = skipTo(pos + 2, "?>");
    } else if (text_.compare(pos, 2, "<!") == 0 || text_.compare(pos, 2, "</") == 0) {
      pos = skipTo(pos + 2, ">");
    } else {
      const std::size_t end = pos + 1 + name.size();
      if (text_.compare(pos + 1, name.size(), name) == 0 && end < text_.size() && nameEnds(text_[end])) {
        if (line > 0 && at(pos).line > line) return std::string::npos;  // out of step: give the line only
        cursor_ = end;
        return pos;
      }
      ++pos;
    }
  }
  return std::string::npos;
}

std::size_t SourceText::findAttribute(std::size_t tagStart, std::string_view attr) const {
  if (tagStart == std::string::npos) return std::string::npos;
  char quote = 0;
  for (std::size_t i = tagStart + 1; i < text_.size(); ++i) {
    char c = text_[i];
    if (quote) {
      if (c == quote) quote = 0;
      continue;
    }
    if (c == '"' || c == '\'') {
      quote = c;
      continue;
    }
    if (c == '>') return std::string::npos;
    // An attribute name starts after whitespace and is followed by optional space and '='.
    if ((text_[i - 1] == ' ' || text_[i - 1] == '\t' || text_[i - 1] == '\n' || text_[i - 1] == '\r') &&
        text_.compare(i, attr.size(), attr) == 0) {
      std::size_t j = i + attr.size();
      while (j < text_.size() && (text_[j] == ' ' || text_[j] == '\t' || text_[j] == '\n' || text_[j] == '\r')) ++j;
      if (j < text_.size() && text_[j] == '=') return i;
    }
  }
  return std::string::npos;
}

SourceLocation SourceText::at(std::size_t offset) const {
  if (offset == std::string::npos || offset > text_.size()) return {file_, 0, 0};
  auto it = std::upper_bound(lineStarts_.begin(), lineStarts_.end(), offset);
  const std::size_t lineIndex = static_cast<std::size_t>(it - lineStarts_.begin()) - 1;
  return {file_, static_cast<int>(lineIndex + 1), static_cast<int>(offset - lineStarts_[lineIndex] + 1)};
}

}  // namespace millsim
