#include "scene_overrides.h"

#include <cctype>
#include <string>
#include <utility>
#include <vector>

#include "dlmfd/core/errors.h"
#include "dlmfd/scene/toml_bounds.h"
#include "toml_reader.h"

namespace dlmfd {
namespace scene {
namespace {

std::vector<std::string> SplitKey(const std::string& key) {
  std::vector<std::string> parts;
  std::string current;
  for (char c : key) {
    if (c == '.') {
      parts.push_back(current);
      current.clear();
    } else {
      current += c;
    }
  }
  parts.push_back(current);
  return parts;
}

bool IsIndex(const std::string& s) {
  if (s.empty() || s.size() > 9) return false;
  for (char c : s) {
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  }
  return true;
}

// The override's value as a TOML node: a TOML value when the text is one, else a string.
toml::table ParseValue(const std::string& text) {
  // Text deeper than a scene may be (toml_bounds.h) is kept as a string, as unparsable text is.
  if (IsBoundedToml(text)) {
    try {
      toml::table wrapper = toml::parse("value = " + text);
      if (wrapper.size() == 1 && wrapper.contains("value")) return wrapper;
    } catch (const toml::parse_error&) {}
  }
  toml::table wrapper;
  wrapper.insert_or_assign("value", text);
  return wrapper;
}

bool IsSideTypeKey(const std::vector<std::string>& parts) {
  return parts.size() == 4 && parts[0] == "domain" && parts[1] == "boundary" && parts[3] == "type";
}

void ApplyOne(toml::table& root, const SceneOverride& o) {
  const std::vector<std::string> parts = SplitKey(o.key);
  if (parts.size() > static_cast<std::size_t>(kMaxKeyParts)) {
    throw InvalidParameter(o.key.substr(0, 64) + "... (" + std::to_string(parts.size()) + " parts)",
                           o.value,
                           "a dotted key of at most " + std::to_string(kMaxKeyParts) +
                               " parts (e.g. fluid.viscosity)");
  }
  for (const auto& p : parts) {
    if (p.empty())
      throw InvalidParameter(o.key, o.value,
                             "a dotted key of non-empty names (e.g. fluid.viscosity)");
  }
  toml::table value_holder = ParseValue(o.value);
  toml::node& value = *value_holder.get("value");

  toml::node* node = &root;
  std::string walked;
  for (std::size_t k = 0; k + 1 < parts.size(); ++k) {
    const std::string& part = parts[k];
    walked += (walked.empty() ? "" : ".") + part;
    if (auto* table = node->as_table()) {
      toml::node* next = table->get(part);
      if (next == nullptr) {
        table->insert_or_assign(part, toml::table{});
        next = table->get(part);
      }
      node = next;
    } else if (auto* array = node->as_array()) {
      if (!IsIndex(part) || std::stoul(part) >= array->size()) {
        throw InvalidParameter(walked, part,
                               "an index below " + std::to_string(array->size()) +
                                   " (the number of entries in the scene)");
      }
      node = array->get(std::stoul(part));
    } else {
      throw InvalidParameter(walked, NodeText(*node),
                             "a table or an array to set " + o.key + " in");
    }
  }
  const std::string& leaf = parts.back();
  if (auto* table = node->as_table()) {
    if (IsSideTypeKey(parts)) table->clear();
    value.visit([&](auto& v) { table->insert_or_assign(leaf, std::move(v)); });
  } else if (auto* array = node->as_array()) {
    if (!IsIndex(leaf) || std::stoul(leaf) >= array->size()) {
      throw InvalidParameter(o.key, o.value,
                             "an existing index below " + std::to_string(array->size()));
    }
    value.visit([&](auto& v) {
      array->replace(array->begin() + static_cast<long>(std::stoul(leaf)), std::move(v));
    });
  } else {
    throw InvalidParameter(walked, NodeText(*node), "a table or an array to set " + o.key + " in");
  }
}

// The node a part of a key names under `node` (a table by name, an array by index), or null.
const toml::node* Child(const toml::node* node, const std::string& part) {
  if (node == nullptr) return nullptr;
  if (const auto* table = node->as_table()) return table->get(part);
  if (const auto* array = node->as_array()) {
    if (IsIndex(part) && std::stoul(part) < array->size()) return array->get(std::stoul(part));
  }
  return nullptr;
}

// The concrete keys an override's key stands for: each `*` in place of an index becomes every
// index of the array found there (`particles.*.density` -> particles.0.density, ...).
std::vector<std::string> ExpandWildcards(const toml::table& root, const SceneOverride& o) {
  const std::vector<std::string> parts = SplitKey(o.key);
  std::vector<std::pair<const toml::node*, std::string>> frontier = {{&root, ""}};
  for (const std::string& part : parts) {
    std::vector<std::pair<const toml::node*, std::string>> next;
    for (const auto& [node, walked] : frontier) {
      const std::string prefix = walked.empty() ? "" : walked + ".";
      if (part != "*") {
        next.emplace_back(Child(node, part), prefix + part);
        continue;
      }
      const toml::array* array = node ? node->as_array() : nullptr;
      if (array == nullptr || array->empty()) {
        throw InvalidParameter(o.key, o.value,
                               "'*' in place of an index of a non-empty array (" +
                                   (walked.empty() ? std::string("the scene") : walked) +
                                   " is not one)");
      }
      for (std::size_t i = 0; i < array->size(); ++i) {
        next.emplace_back(array->get(i), prefix + std::to_string(i));
      }
    }
    frontier = std::move(next);
  }
  std::vector<std::string> keys;
  for (const auto& entry : frontier) keys.push_back(entry.second);
  return keys;
}

}  // namespace

void ApplyOverrides(toml::table& root, const std::vector<SceneOverride>& overrides) {
  for (const auto& o : overrides) {
    if (o.key.find('*') == std::string::npos) {
      ApplyOne(root, o);
      continue;
    }
    for (const std::string& key : ExpandWildcards(root, o)) ApplyOne(root, {key, o.value});
  }
}

}  // namespace scene
}  // namespace dlmfd
