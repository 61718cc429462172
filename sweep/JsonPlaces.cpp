#include "sweep/JsonPlaces.h"

#include <algorithm>
#include <cctype>
#include <cstddef>
#include <iterator>
#include <string_view>

#include <nlohmann/json.hpp>

namespace millsim::sweep {
namespace {

// A character iterator that tells how far the parser has read.
struct CountingIterator {
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;
  const char* p = nullptr;
  const char* base = nullptr;
  std::size_t* consumed = nullptr;
  reference operator*() const { return *p; }
  CountingIterator& operator++() {
    ++p;
    *consumed = std::size_t(p - base);
    return *this;
  }
  CountingIterator operator++(int) {
    CountingIterator old = *this;
    ++*this;
    return old;
  }
  bool operator==(const CountingIterator& o) const { return p == o.p; }
  bool operator!=(const CountingIterator& o) const { return p != o.p; }
};

class Builder : public nlohmann::json_sax<nlohmann::json> {
public:
  Builder(const std::string& text, const std::string& file, const std::size_t& consumed)
      : text_(text), file_(file), consumed_(consumed) {
    lineStarts_.push_back(0);
    for (std::size_t i = 0; i < text.size(); ++i)
      if (text[i] == '\n') lineStarts_.push_back(i + 1);
  }

  JsonValue root;

  // Columns count characters, not bytes (a UTF-8 sequence is one).
  Place placeOf(std::size_t offset) const {
    offset = std::min(offset, text_.empty() ? 0 : text_.size() - 1);
    const auto it = std::upper_bound(lineStarts_.begin(), lineStarts_.end(), offset);
    const std::size_t line = std::size_t(it - lineStarts_.begin());
    int column = 1;
    for (std::size_t i = lineStarts_[line - 1]; i < offset; ++i)
      column += (static_cast<unsigned char>(text_[i]) & 0xC0) != 0x80;
    return {int(line), column};
  }
  [[noreturn]] void fail(Place at, const std::string& what) const {
    throw SweepError(file_ + ":" + std::to_string(at.line) + ":" + std::to_string(at.column) + ": " + what);
  }

  bool null() override { return add(scalar(JsonValue::Kind::Null, literalStart(4))); }
  bool boolean(bool v) override {
    JsonValue j = scalar(JsonValue::Kind::Bool, literalStart(v ? 4 : 5));
    j.boolean = v;
    return add(std::move(j));
  }
  bool number_integer(number_integer_t v) override { return number(double(v), true); }
  bool number_unsigned(number_unsigned_t v) override { return number(double(v), true); }
  bool number_float(number_float_t v, const string_t&) override { return number(double(v), false); }
  bool string(string_t& v) override {
    JsonValue j = scalar(JsonValue::Kind::String, stringStart());
    j.text = v;
    return add(std::move(j));
  }
  bool binary(binary_t&) override { return false; }
  bool start_object(std::size_t) override { return open(JsonValue::Kind::Object); }
  bool key(string_t& k) override {
    JsonValue& o = *stack_.back();
    const Place at = placeOf(stringStart());
    for (std::size_t i = 0; i < o.members.size(); ++i)
      if (o.members[i].first == k)
        fail(at, "\"" + k + "\" is given twice in this object (first at line " + std::to_string(o.keyPlaces[i].line) + ")");
    o.members.push_back(JsonMember{k, JsonValue{}});
    o.keyPlaces.push_back(at);
    return true;
  }
  bool end_object() override { return close(); }
  bool start_array(std::size_t) override { return open(JsonValue::Kind::Array); }
  bool end_array() override { return close(); }
  bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception& ex) override {
    std::string what = ex.what();
    // "[json.exception.parse_error.101] parse error at line 3, column 5: syntax error while parsing ..."
    if (const std::size_t colon = what.find(": ", what.find("parse error")); colon != std::string::npos)
      what = what.substr(colon + 2);
    fail(placeOf(position > 0 ? position - 1 : 0), "not JSON: " + what);
  }

private:
  // Where the token the parser has just read starts.
  std::size_t stringStart() const {
    // The closing quote was the last character read; find the opening one.
    std::size_t i = consumed_ >= 2 ? consumed_ - 2 : 0;
    while (i > 0) {
      if (text_[i] == '"') {
        std::size_t slashes = 0;
        while (i > slashes && text_[i - 1 - slashes] == '\\') ++slashes;
        if (slashes % 2 == 0) break;
      }
      --i;
    }
    return i;
  }
  std::size_t literalStart(std::size_t length) const { return consumed_ >= length ? consumed_ - length : 0; }
  std::size_t numberStart() const {
    // The lexer has read one character past the number (unless the text ended).
    std::size_t end = consumed_;
    if (end > 0 && end <= text_.size() && !std::isdigit(static_cast<unsigned char>(text_[end - 1]))) --end;
    std::size_t i = end;
    while (i > 0 && std::string_view("0123456789+-.eE").find(text_[i - 1]) != std::string_view::npos) --i;
    return i;
  }
  JsonValue scalar(JsonValue::Kind kind, std::size_t start) const {
    JsonValue j;
    j.kind = kind;
    j.at = placeOf(start);
    return j;
  }
  bool number(double v, bool integer) {
    const std::size_t start = numberStart();
    JsonValue j = scalar(JsonValue::Kind::Number, start);
    j.number = v;
    j.integer = integer;
    std::size_t end = start;
    while (end < text_.size() && std::string_view("0123456789+-.eE").find(text_[end]) != std::string_view::npos) ++end;
    j.text = text_.substr(start, end - start);
    return add(std::move(j));
  }
  bool add(JsonValue v) {
    if (stack_.empty()) {
      root = std::move(v);
      return true;
    }
    JsonValue& parent = *stack_.back();
    if (parent.kind == JsonValue::Kind::Array)
      parent.items.push_back(std::move(v));
    else
      parent.members.back().second = std::move(v);
    return true;
  }
  bool open(JsonValue::Kind kind) {
    JsonValue j = scalar(kind, consumed_ > 0 ? consumed_ - 1 : 0);
    // A sweep file nests three or four deep; the tree is freed recursively.
    if (stack_.size() >= kMaxDepth) fail(j.at, "lists and objects nested deeper than " + std::to_string(kMaxDepth));
    if (stack_.empty()) {
      root = std::move(j);
      stack_.push_back(&root);
      return true;
    }
    JsonValue& parent = *stack_.back();
    JsonValue* slot;
    if (parent.kind == JsonValue::Kind::Array) {
      parent.items.push_back(std::move(j));
      slot = &parent.items.back();
    } else {
      parent.members.back().second = std::move(j);
      slot = &parent.members.back().second;
    }
    stack_.push_back(slot);
    return true;
  }
  bool close() {
    stack_.pop_back();
    return true;
  }

  static constexpr std::size_t kMaxDepth = 64;
  const std::string& text_;
  const std::string& file_;
  const std::size_t& consumed_;
  std::vector<std::size_t> lineStarts_;
  // Pointers into the tree: safe because a container is only appended to
  // while it is the innermost open one (its children are closed by then).
  std::vector<JsonValue*> stack_;
};

}  // namespace

const char* JsonValue::kindName() const {
  switch (kind) {
    case Kind::Null: return "null";
    case Kind::Bool: return "true or false";
    case Kind::Number: return "a number";
    case Kind::String: return "a string";
    case Kind::Array: return "a list";
    case Kind::Object: return "an object";
  }
  return "?";
}

JsonValue parseJsonWithPlaces(const std::string& text, const std::string& file) {
  std::size_t consumed = 0;
  Builder builder(text, file, consumed);
  const CountingIterator first{text.data(), text.data(), &consumed},
      last{text.data() + text.size(), text.data(), &consumed};
  nlohmann::json::sax_parse(first, last, &builder);
  return std::move(builder.root);
}

}  // namespace millsim::sweep
