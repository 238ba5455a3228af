// ReadFlatScene, DifferingKeys: toml++ over the scenes as run.
#include "scene_differences.h"

#include <toml++/toml.h>

#include <cstdio>
#include <filesystem>
#include <sstream>
#include <utility>

#include "connection.h"

namespace dlmfd::cli {
namespace {

void Flatten(const toml::node& node, const std::string& prefix, FlatScene& out) {
  if (const toml::table* table = node.as_table()) {
    for (const auto& [key, value] : *table) {
      Flatten(value,
              prefix.empty() ? std::string(key.str()) : prefix + "." + std::string(key.str()), out);
    }
    return;
  }
  if (const toml::array* array = node.as_array(); array != nullptr && array->is_array_of_tables()) {
    for (std::size_t k = 0; k < array->size(); ++k)
      Flatten(*array->get(k), prefix + "." + std::to_string(k), out);
    return;
  }
  std::ostringstream text;
  if (const auto* real = node.as_floating_point()) {
    // 15 digits: 1.1 reads "1.1", not toml++'s round-trip "1.1000000000000001".
    char digits[32];
    std::snprintf(digits, sizeof(digits), "%.15g", real->get());
    text << digits;
  } else if (const auto* word = node.as_string()) {
    text << word->get();
  } else {
    node.visit([&](const auto& leaf) { text << leaf; });
  }
  out[prefix] = text.str();
}

}  // namespace

FlatScene ReadFlatScene(const std::string& results_dir) {
  const std::filesystem::path file = std::filesystem::path(results_dir) / "scene.toml";
  std::error_code ec;
  FlatScene flat;
  if (!std::filesystem::is_regular_file(file, ec)) return flat;
  try {
    const toml::table table = toml::parse_file(file.string());
    Flatten(table, "", flat);
  } catch (const toml::parse_error& e) {
    throw UsageError(file.string() + " is not TOML: " + std::string(e.description()));
  }
  flat.erase("title");
  return flat;
}

std::vector<std::string> DifferingKeys(const std::vector<FlatScene>& scenes) {
  std::map<std::string, bool> keys;
  for (const FlatScene& s : scenes) {
    for (const auto& [key, value] : s) keys.emplace(key, false);
  }
  std::vector<std::string> differing;
  for (const auto& entry : keys) {
    // A named reference, not a structured binding: lambdas capture bindings only from C++20.
    const std::string& key = entry.first;
    const auto value_in = [&](const FlatScene& s) {
      const auto it = s.find(key);
      return it == s.end() ? std::pair<bool, std::string>{false, ""}
                           : std::pair<bool, std::string>{true, it->second};
    };
    for (const FlatScene& s : scenes) {
      if (value_in(s) != value_in(scenes.front())) {
        differing.push_back(key);
        break;
      }
    }
  }
  return differing;
}

std::string ValuesOf(const FlatScene& scene, const std::vector<std::string>& keys) {
  std::string text;
  for (const std::string& key : keys) {
    const auto it = scene.find(key);
    text += (text.empty() ? "" : ", ") + (it == scene.end() ? std::string("-") : it->second);
  }
  return text;
}

}  // namespace dlmfd::cli
