#pragma once
// SourceText: the text of one X3D file with a way to find where an element or
// an attribute starts. libxml2 records only the line of an element, so columns
// are recovered from the text: elements are visited in document order, and a
// cursor that only moves forward finds each start tag in turn.
#include <string>
#include <string_view>
#include <vector>

#include "millsim/core/Diagnostics.h"

namespace millsim {

// Only spaces, tabs and line ends (XML's white space).
inline bool isBlank(std::string_view s) { return s.find_first_not_of(" \t\r\n") == std::string_view::npos; }

class SourceText {
public:
  SourceText(std::string fileLabel, std::string text);
  const std::string& text() const { return text_; }
  const std::string& file() const { return file_; }

  // Offset of the start tag `<name` on `line` or later, at or after the
  // cursor; advances the cursor. Returns npos if not found.
  std::size_t findStartTag(std::string_view name, long line);
  // Offset of attribute `attr` inside the start tag beginning at `tagStart`.
  std::size_t findAttribute(std::size_t tagStart, std::string_view attr) const;

  // Offset of `text` at or after the cursor (the cursor does not move).
  std::size_t findText(std::string_view text) const { return text_.find(text, cursor_); }

  SourceLocation at(std::size_t offset) const;
  SourceLocation atLine(long line) const { return {file_, static_cast<int>(line), 0}; }

private:
  std::string file_;
  std::string text_;
  std::vector<std::size_t> lineStarts_;
  std::size_t cursor_ = 0;
};

}  // namespace millsim
