#include "toml_reader.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "dlmfd/core/errors.h"
#include "dlmfd/core/number_text.h"

namespace dlmfd {
namespace scene {

std::string NodeText(const toml::node& node) {
  if (const auto* f = node.as_floating_point()) return ExactText(f->get());
  if (const auto* i = node.as_integer()) return std::to_string(i->get());
  if (const auto* s = node.as_string()) return QuotedText(s->get());
  if (const auto* b = node.as_boolean()) return b->get() ? "true" : "false";
  if (const auto* a = node.as_array()) {
    std::string out = "[";
    for (std::size_t k = 0; k < a->size(); ++k) out += (k ? ", " : "") + NodeText(*a->get(k));
    return out + "]";
  }
  if (const auto* t = node.as_table()) {
    std::string out = "{";
    bool first = true;
    for (const auto& [key, value] : *t) {
      out += std::string(first ? " " : ", ") + std::string(key.str()) + " = " + NodeText(value);
      first = false;
    }
    return out + (first ? "}" : " }");
  }
  std::ostringstream out;  // dates and times
  node.visit([&out](const auto& n) { out << n; });
  return out.str();
}

std::string QuotedText(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (u < 0x20 || u == 0x7f) {
      char buffer[8];
      std::snprintf(buffer, sizeof buffer, "\\u%04x", u);
      out += buffer;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

TableReader::TableReader(const toml::table* table, std::string prefix)
    : table_(table),
      prefix_(std::move(prefix)) {}

bool TableReader::Has(const std::string& name) const {
  return table_ != nullptr && table_->contains(name);
}

const toml::node* TableReader::Find(const std::string& name) {
  known_.insert(name);
  if (table_ == nullptr) return nullptr;
  return table_->get(name);
}

void TableReader::Missing(const std::string& name, const std::string& what) const {
  throw InvalidParameter(Key(name), "(missing)", what);
}

double TableReader::Real(const std::string& name, std::optional<double> fallback) {
  const toml::node* node = Find(name);
  if (node == nullptr) {
    if (!fallback) Missing(name, "a number");
    return *fallback;
  }
  if (const auto* f = node->as_floating_point()) {
    if (!std::isfinite(f->get()))
      throw InvalidParameter(Key(name), NodeText(*node), "a finite number");
    return f->get();
  }
  if (const auto* i = node->as_integer()) return static_cast<double>(i->get());
  throw InvalidParameter(Key(name), NodeText(*node), "a number");
}

int TableReader::Integer(const std::string& name, std::optional<int> fallback) {
  const toml::node* node = Find(name);
  if (node == nullptr) {
    if (!fallback) Missing(name, "an integer");
    return *fallback;
  }
  const auto* i = node->as_integer();
  if (i == nullptr) throw InvalidParameter(Key(name), NodeText(*node), "an integer");
  if (i->get() > 2147483647LL || i->get() < -2147483647LL) {
    throw InvalidParameter(Key(name), NodeText(*node), "an integer of magnitude < 2^31");
  }
  return static_cast<int>(i->get());
}

std::string TableReader::String(const std::string& name, std::optional<std::string> fallback) {
  const toml::node* node = Find(name);
  if (node == nullptr) {
    if (!fallback) Missing(name, "a string");
    return *fallback;
  }
  const auto* s = node->as_string();
  if (s == nullptr) throw InvalidParameter(Key(name), NodeText(*node), "a string");
  return s->get();
}

Vec2 TableReader::Vector(const std::string& name, std::optional<Vec2> fallback) {
  const toml::node* node = Find(name);
  if (node == nullptr) {
    if (!fallback) Missing(name, "an array of two numbers");
    return *fallback;
  }
  const auto* a = node->as_array();
  if (a == nullptr || a->size() != 2) {
    throw InvalidParameter(Key(name), NodeText(*node), "an array of two numbers");
  }
  Vec2 out;
  for (int k = 0; k < 2; ++k) {
    const toml::node& e = *a->get(static_cast<std::size_t>(k));
    if (const auto* f = e.as_floating_point()) {
      out[k] = f->get();
    } else if (const auto* i = e.as_integer()) {
      out[k] = static_cast<double>(i->get());
    } else {
      throw InvalidParameter(Key(name), NodeText(*node), "an array of two numbers");
    }
    if (!std::isfinite(out[k]))
      throw InvalidParameter(Key(name), NodeText(*node), "two finite numbers");
  }
  return out;
}

bool TableReader::Boolean(const std::string& name, std::optional<bool> fallback) {
  const toml::node* node = Find(name);
  if (node == nullptr) {
    if (!fallback) Missing(name, "true or false");
    return *fallback;
  }
  const auto* b = node->as_boolean();
  if (b == nullptr) throw InvalidParameter(Key(name), NodeText(*node), "true or false");
  return b->get();
}

const toml::table* TableReader::Table(const std::string& name) {
  const toml::node* node = Find(name);
  if (node == nullptr) return nullptr;
  const auto* t = node->as_table();
  if (t == nullptr) throw InvalidParameter(Key(name), NodeText(*node), "a table");
  return t;
}

const toml::array* TableReader::Array(const std::string& name) {
  const toml::node* node = Find(name);
  if (node == nullptr) return nullptr;
  const auto* a = node->as_array();
  if (a == nullptr) throw InvalidParameter(Key(name), NodeText(*node), "an array");
  return a;
}

void TableReader::RejectUnknown(const std::string& allowed_keys) const {
  if (table_ == nullptr) return;
  for (const auto& [key, node] : *table_) {
    const std::string name(key.str());
    if (known_.count(name) == 0) {
      throw InvalidParameter(Key(name), NodeText(node),
                             "no such key here (known keys: " + allowed_keys + ")");
    }
  }
}

}  // namespace scene
}  // namespace dlmfd
