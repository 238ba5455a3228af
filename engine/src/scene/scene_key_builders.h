// The builders of scene/scene_keys.h's tables: one function per type of member. `at` is a generic
// lambda naming the member, [](auto& r) -> auto& { return r.fluid.viscosity; }, so that one
// declaration serves reading (Record&) and writing (const Record&).
#pragma once

#include <optional>
#include <string>
#include <utility>

#include "dlmfd/core/errors.h"
#include "dlmfd/scene/scene_keys.h"
#include "toml_reader.h"

namespace dlmfd {
namespace scene {

template <typename Record, typename At>
SceneKey<Record> RealKey(std::string name, At at, KeyRange range, std::string description) {
  SceneKey<Record> k;
  k.name = std::move(name);
  k.type = KeyType::kReal;
  k.range = range;
  k.description = std::move(description);
  k.read = [at](TableReader& t, const std::string& leaf, Record& r) {
    at(r) = t.Real(leaf, std::nullopt);
  };
  k.get = [at](const Record& r) -> KeyValue { return at(r); };
  return k;
}

// A real that is absent unless given (std::optional<double>).
template <typename Record, typename At>
SceneKey<Record> OptionalRealKey(std::string name, At at, std::string description) {
  SceneKey<Record> k;
  k.name = std::move(name);
  k.type = KeyType::kReal;
  k.default_kind = DefaultKind::kAbsent;
  k.description = std::move(description);
  k.read = [at](TableReader& t, const std::string& leaf, Record& r) {
    at(r) = t.Real(leaf, std::nullopt);
  };
  k.get = [at](const Record& r) -> KeyValue { return at(r).value_or(0.0); };
  k.written = [at](const Record& r) { return at(r).has_value(); };
  return k;
}

template <typename Record, typename At>
SceneKey<Record> IntegerKey(std::string name, At at, KeyRange range, std::string description) {
  SceneKey<Record> k;
  k.name = std::move(name);
  k.type = KeyType::kInteger;
  k.range = range;
  k.description = std::move(description);
  k.read = [at](TableReader& t, const std::string& leaf, Record& r) {
    at(r) = t.Integer(leaf, std::nullopt);
  };
  k.get = [at](const Record& r) -> KeyValue { return at(r); };
  return k;
}

template <typename Record, typename At>
SceneKey<Record> BooleanKey(std::string name, At at, std::string description) {
  SceneKey<Record> k;
  k.name = std::move(name);
  k.type = KeyType::kBoolean;
  k.description = std::move(description);
  k.read = [at](TableReader& t, const std::string& leaf, Record& r) {
    at(r) = t.Boolean(leaf, std::nullopt);
  };
  k.get = [at](const Record& r) -> KeyValue { return at(r); };
  return k;
}

// Two finite numbers (the reader refuses others).
template <typename Record, typename At>
SceneKey<Record> VectorKey(std::string name, At at, std::string description) {
  SceneKey<Record> k;
  k.name = std::move(name);
  k.type = KeyType::kVector;
  k.range.kind = KeyRange::kFinite;
  k.description = std::move(description);
  k.read = [at](TableReader& t, const std::string& leaf, Record& r) {
    at(r) = t.Vector(leaf, std::nullopt);
  };
  k.get = [at](const Record& r) -> KeyValue { return at(r); };
  return k;
}

template <typename Record, typename At>
SceneKey<Record> StringKey(std::string name, At at, std::string description) {
  SceneKey<Record> k;
  k.name = std::move(name);
  k.type = KeyType::kString;
  k.description = std::move(description);
  k.read = [at](TableReader& t, const std::string& leaf, Record& r) {
    at(r) = t.String(leaf, std::nullopt);
  };
  k.get = [at](const Record& r) -> KeyValue { return at(r); };
  return k;
}

// "one of \"a\", \"b\"": the allowed words of a choice, as messages show them.
std::string AllowedWords(const std::vector<std::string>& words);

// One of the words of Enum (core/param_words.h), and "auto" first when `resolve` is set.
template <typename Enum, typename Record, typename At>
SceneKey<Record> ChoiceKey(std::string name, At at, std::string description,
                           ResolvedChoice (*resolve)(const Params&) = nullptr) {
  SceneKey<Record> k;
  k.name = std::move(name);
  k.type = KeyType::kChoice;
  k.description = std::move(description);
  k.resolve = resolve;
  if (resolve != nullptr) k.words.emplace_back("auto");
  for (const Word<Enum>& w : Words<Enum>::kAll) k.words.emplace_back(w.text);
  const std::vector<std::string> words = k.words;
  k.set_word = [at, words](Record& r, const std::string& key, const std::string& word) {
    const std::optional<Enum> value = ValueOfWord<Enum>(word);
    if (!value) throw InvalidParameter(key, QuotedText(word), AllowedWords(words));
    at(r) = *value;
  };
  k.read = [k_set = k.set_word](TableReader& t, const std::string& leaf, Record& r) {
    k_set(r, t.Key(leaf), t.String(leaf, std::nullopt));
  };
  k.get = [at](const Record& r) -> KeyValue { return std::string(WordOf(at(r))); };
  return k;
}

// Marks a key as one the scene must give where it applies.
template <typename Record>
SceneKey<Record> Required(SceneKey<Record> k) {
  k.default_kind = DefaultKind::kRequired;
  return k;
}

// A key that applies only where `applies` holds for the record as read so far.
template <typename Record, typename Applies>
SceneKey<Record> Where(SceneKey<Record> k, Applies applies) {
  k.applies = applies;
  return k;
}

// A key whose default the numerics preset gives (PresetWord).
template <typename Record>
SceneKey<Record> FromPreset(SceneKey<Record> k) {
  k.default_kind = DefaultKind::kPreset;
  return k;
}

// Docs' allowed column beyond the range and the words.
template <typename Record>
SceneKey<Record> Allowed(SceneKey<Record> k, std::string note) {
  k.allowed_note = std::move(note);
  return k;
}

}  // namespace scene
}  // namespace dlmfd
