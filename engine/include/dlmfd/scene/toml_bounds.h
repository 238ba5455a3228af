// The shape of TOML text bounded before toml++ parses it.
//
// toml++ 3.3 builds one nested table per part of a dotted key (`a.b.c = 1`) and walks the tree it
// built recursively: a key of 200,000 parts overflows the stack inside toml::parse, one of 20,000
// inside the recursive teardown or printing of the tree (issue 38: a scene of one such key killed
// dlmfdd and every job with it). toml++ itself bounds only the nesting of arrays and inline tables
// (TOML_MAX_NESTED_VALUES, 256). RequireBoundedToml scans the text first, skipping comments and
// the four kinds of strings, and refuses a key of more than kMaxKeyParts dotted parts or brackets
// nested more than kMaxNesting deep; the deepest tree toml++ can then build is about
// kMaxKeyParts * kMaxNesting levels. A scene's deepest key has 4 parts
// (domain.boundary.bottom.max) inside 1 bracket.
#pragma once

#include <string>

namespace dlmfd {
namespace scene {

inline constexpr int kMaxKeyParts = 16;
inline constexpr int kMaxNesting = 16;

// Throws InvalidParameter naming `origin` and the line when the text holds a longer dotted run or a
// deeper nesting; text that is not valid TOML is left for the parser to name.
void RequireBoundedToml(const std::string& text, const std::string& origin);
// The same test without the exception.
bool IsBoundedToml(const std::string& text);

}  // namespace scene
}  // namespace dlmfd
