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
  std::size_t from = cursor_;
  if (line >= 1 && static_cast<std::size_t>(line) <= lineStarts_.size())
    from = std::max(from, lineStarts_[static_cast<std::size_t>(line) - 1]);
  const std::string needle = "<" + std::string(name);
  for (std::size_t pos = text_.find(needle, from); pos != std::string::npos; pos = text_.find(needle, pos + 1)) {
    const std::size_t end = pos + needle.size();
    if (end < text_.size() && nameEnds(text_[end])) {
      cursor_ = end;
      return pos;
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
