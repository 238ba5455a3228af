// Typed, key-checked reading of one TOML table of a scene (design.md 3.1).
//
// Each getter marks its key as known; RejectUnknown() then throws for any key of the table that no
// getter asked for, so a typo is never ignored. Every failure is an InvalidParameter naming the
// dotted key, the value as TOML text, and what is allowed. Integers are accepted where a real is
// expected; reals are not accepted where an integer is.
#pragma once

#include <optional>
#include <set>
#include <string>

#include <toml++/toml.h>

#include "dlmfd/core/params.h"

namespace dlmfd {
namespace scene {

// The TOML text of a node, for messages ("1.5", "\"wave\"", "[1.0, 2.0]").
std::string NodeText(const toml::node& node);
// A string as a TOML basic string, quoted and escaped.
std::string QuotedText(const std::string& s);

class TableReader {
 public:
  // `table` may be null (an absent optional table: every getter returns its default).
  TableReader(const toml::table* table, std::string prefix);

  std::string Key(const std::string& name) const {
    return prefix_.empty() ? name : prefix_ + "." + name;
  }
  bool Has(const std::string& name) const;

  // A real (TOML float or integer); `fallback` when absent, an error when absent and !fallback.
  double Real(const std::string& name, std::optional<double> fallback);
  int Integer(const std::string& name, std::optional<int> fallback);
  std::string String(const std::string& name, std::optional<std::string> fallback);
  Vec2 Vector(const std::string& name, std::optional<Vec2> fallback);
  bool Boolean(const std::string& name, std::optional<bool> fallback);
  // A sub-table, or null when absent; an error when present but not a table.
  const toml::table* Table(const std::string& name);
  // An array, or null when absent; an error when present but not an array.
  const toml::array* Array(const std::string& name);

  // Throws for the first key that no getter asked for.
  void RejectUnknown(const std::string& allowed_keys) const;

 private:
  const toml::node* Find(const std::string& name);
  [[noreturn]] void Missing(const std::string& name, const std::string& what) const;

  const toml::table* table_;
  std::string prefix_;
  std::set<std::string> known_;
};

}  // namespace scene
}  // namespace dlmfd
