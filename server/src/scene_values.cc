#include "scene_values.h"

#include <toml++/toml.h>

#include <charconv>
#include <cmath>
#include <sstream>
#include <system_error>
#include <variant>

#include "dlmfd/scene/scene_keys.h"
#include "dlmfd/scene/toml_bounds.h"
#include "service_error.h"

namespace dlmfd::server {
namespace {

// The value text read as TOML ("v = TEXT"); a text that is not one is a string.
toml::table ReadValue(const std::string& text) {
  // Text deeper than a scene may be (dlmfd/scene/toml_bounds.h) is a string, as unparsable text is.
  if (scene::IsBoundedToml(text)) {
    try {
      toml::table wrapper = toml::parse("v = " + text);
      if (wrapper.size() == 1 && wrapper.contains("v")) return wrapper;
    } catch (const toml::parse_error&) {}
  }
  toml::table wrapper;
  wrapper.insert_or_assign("v", text);
  return wrapper;
}

std::string ShortestText(double value) {
  char text[64];
  const auto result = std::to_chars(text, text + sizeof text, value);
  return result.ec == std::errc() ? std::string(text, result.ptr) : std::string("nan");
}

std::string Normalized(const toml::node& node) {
  if (node.is_integer()) return ShortestText(static_cast<double>(*node.value<int64_t>()));
  if (node.is_floating_point()) return ShortestText(*node.value<double>());
  if (node.is_boolean()) return *node.value<bool>() ? "true" : "false";
  if (node.is_string()) return *node.value<std::string>();
  if (const auto* array = node.as_array()) {
    std::string out = "[";
    for (size_t i = 0; i < array->size(); ++i) {
      out += (i ? ", " : "") + Normalized(*array->get(i));
    }
    return out + "]";
  }
  if (node.is_table()) return "{table}";
  std::ostringstream text;  // a date or a time
  node.visit([&text](const auto& v) { text << v; });
  return text.str();
}

void Flatten(const toml::node& node, const std::string& key,
             std::vector<std::pair<std::string, std::string>>& out) {
  const std::string prefix = key.empty() ? "" : key + ".";
  if (const auto* table = node.as_table()) {
    for (const auto& [name, child] : *table) Flatten(child, prefix + std::string(name.str()), out);
    return;
  }
  if (const auto* array = node.as_array()) {
    if (!array->is_array_of_tables() || array->empty()) out.emplace_back(key, Normalized(node));
    for (size_t i = 0; i < array->size(); ++i) {
      Flatten(*array->get(i), prefix + std::to_string(i), out);
    }
    return;
  }
  out.emplace_back(key, Normalized(node));
}

}  // namespace

std::vector<std::pair<std::string, std::string>> FlattenScene(const std::string& scene_as_run) {
  std::vector<std::pair<std::string, std::string>> out;
  try {
    Flatten(toml::parse(scene_as_run), "", out);
  } catch (const toml::parse_error& e) {
    throw StoreError(std::string("the scene as run cannot be read: ") +
                     std::string(e.description()));
  }
  return out;
}

std::vector<std::pair<std::string, std::string>> FlattenParams(const Params& params) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& [key, value] : scene::SceneValues(params)) {
    if (const auto* x = std::get_if<double>(&value)) {
      out.emplace_back(key, ShortestText(*x));
    } else if (const auto* n = std::get_if<int>(&value)) {
      out.emplace_back(key, ShortestText(static_cast<double>(*n)));
    } else if (const auto* b = std::get_if<bool>(&value)) {
      out.emplace_back(key, *b ? "true" : "false");
    } else if (const auto* v = std::get_if<Vec2>(&value)) {
      out.emplace_back(key, "[" + ShortestText(v->x()) + ", " + ShortestText(v->y()) + "]");
      out.emplace_back(key + ".0", ShortestText(v->x()));
      out.emplace_back(key + ".1", ShortestText(v->y()));
    } else {
      out.emplace_back(key, std::get<std::string>(value));
    }
  }
  return out;
}

std::string NormalizedValue(const std::string& value_text) {
  return Normalized(*ReadValue(value_text).get("v"));
}

ParameterValue TypedValue(const std::string& key, const std::string& value_text) {
  const toml::table wrapper = ReadValue(value_text);
  const toml::node& node = *wrapper.get("v");
  ParameterValue out;
  out.key = key;
  out.text = value_text;
  if (node.is_integer()) {
    out.type = "integer";
    out.number = static_cast<double>(*node.value<int64_t>());
  } else if (node.is_floating_point()) {
    out.type = "float";
    out.number = *node.value<double>();
  } else if (node.is_boolean()) {
    out.type = "boolean";
  } else if (node.is_array()) {
    out.type = "array";
  } else if (node.is_table()) {
    out.type = "table";
  } else {
    out.type = "string";
  }
  return out;
}

SceneValueFilter ParseWhere(const std::string& text) {
  RequireNoNul("where", text);
  const std::string expected =
      "expected KEY=VALUE, KEY!=VALUE, or KEY<NUMBER (also <=, >, >=), KEY a dotted key of the "
      "scene (* for any index)";
  const size_t at = text.find_first_of("=!<>");
  Require(at != std::string::npos && at > 0,
          "where: \"" + CutForMessage(text) + "\" is not allowed: " + expected);
  SceneValueFilter filter;
  filter.pattern = text.substr(0, at);
  const bool two = at + 1 < text.size() && text[at + 1] == '=' && text[at] != '=';
  filter.op = text.substr(at, two ? 2 : 1);
  Require(filter.op != "!", "where: \"" + CutForMessage(text) + "\" is not allowed: " + expected);
  const std::string operand = text.substr(at + filter.op.size());
  if (filter.op == "=" || filter.op == "!=") {
    filter.value = NormalizedValue(operand);
    return filter;
  }
  const toml::table wrapper = ReadValue(operand);
  const toml::node& node = *wrapper.get("v");
  const bool number = node.is_integer() || node.is_floating_point();
  filter.bound = node.is_integer() ? static_cast<double>(*node.value<int64_t>())
                                   : node.value<double>().value_or(NAN);
  Require(number && !std::isnan(filter.bound),
          "where: \"" + CutForMessage(text) + "\" is not allowed: " + filter.op +
              " compares numbers, and \"" + CutForMessage(operand) + "\" is not one");
  return filter;
}

}  // namespace dlmfd::server
