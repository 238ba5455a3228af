#include "dlmfd/scene/toml_bounds.h"

#include <cstddef>
#include <string>

#include "dlmfd/core/errors.h"

namespace dlmfd {
namespace scene {
namespace {

struct Violation {
  int line = 0;
  std::string what;  // empty: none
};

// The index just past a string that starts at i (", ', """ or '''), or text.size() when it never
// ends (the parser names that); counts the line breaks inside.
std::size_t SkipString(const std::string& text, std::size_t i, int& line) {
  const char quote = text[i];
  const bool multi = text.compare(i, 3, std::string(3, quote)) == 0;
  i += multi ? 3 : 1;
  while (i < text.size()) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      if (!multi) return i;  // an unterminated one-line string
    }
    if (c == '\\' && quote == '"') {
      i += 2;
      continue;
    }
    if (c == quote && (!multi || text.compare(i, 3, std::string(3, quote)) == 0)) {
      // A multi-line string may end with up to two more quotes of its own.
      i += multi ? 3 : 1;
      while (multi && i < text.size() && text[i] == quote) ++i;
      return i;
    }
    ++i;
  }
  return i;
}

bool IsKeyChar(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-' || c == '+';
}

// Scans the text once: the longest run of dot-separated words or strings and the bracket depth.
// Numbers and dates hold at most two dots, so a run of more than three parts is a dotted key.
Violation Scan(const std::string& text) {
  int line = 1, depth = 0, parts = 0;
  bool after_dot = false;  // the last token was a dot: the next word or string continues the run
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == '#') {
      while (i < text.size() && text[i] != '\n') ++i;
      continue;
    }
    if (c == '"' || c == '\'') {
      parts = after_dot ? parts + 1 : 1;
      after_dot = false;
      i = SkipString(text, i, line);
    } else if (IsKeyChar(c)) {
      while (i < text.size() && IsKeyChar(text[i])) ++i;
      parts = after_dot ? parts + 1 : 1;
      after_dot = false;
    } else if (c == '.') {
      after_dot = true;
      ++i;
    } else if (c == ' ' || c == '\t') {
      ++i;
      continue;
    } else {
      if (c == '\n') ++line;
      if (c == '[' || c == '{') ++depth;
      if (c == ']' || c == '}') --depth;
      if (depth > kMaxNesting) {
        return {line,
                "arrays and inline tables nested at most " + std::to_string(kMaxNesting) + " deep"};
      }
      parts = 0;
      after_dot = false;
      ++i;
    }
    if (parts > kMaxKeyParts) {
      return {line, "keys of at most " + std::to_string(kMaxKeyParts) + " dotted parts"};
    }
  }
  return {};
}

}  // namespace

bool IsBoundedToml(const std::string& text) { return Scan(text).what.empty(); }

void RequireBoundedToml(const std::string& text, const std::string& origin) {
  const Violation v = Scan(text);
  if (!v.what.empty()) throw InvalidParameter(origin, "line " + std::to_string(v.line), v.what);
}

}  // namespace scene
}  // namespace dlmfd
