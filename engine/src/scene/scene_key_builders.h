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

// A member's value as its key's `get` gives it; an absent std::optional as T{} (its key's `get` is
// then replaced by one that gives its default, SceneKey::unset).
template <typename T>
KeyValue ValueOfMember(const T& value) {
  return value;
}
template <typename T>
KeyValue ValueOfMember(const std::optional<T>& value) {
  return value.value_or(T{});
}

// A key read by one of TableReader's typed readers (Real, Integer, Boolean, Vector, String) into
// the member `at` names.
template <typename Record, typename T, typename At>
SceneKey<Record> TypedKey(std::string name, KeyType type,
                          T (TableReader::*reader)(const std::string&, std::optional<T>), At at,
                          std::string description) {
  SceneKey<Record> k;
  k.name = std::move(name);
  k.type = type;
  k.description = std::move(description);
  k.read = [at, reader](TableReader& t, const std::string& leaf, Record& r) {
    at(r) = (t.*reader)(leaf, std::nullopt);
  };
  k.get = [at](const Record& r) -> KeyValue { return ValueOfMember(at(r)); };
  return k;
}

template <typename Record, typename At>
SceneKey<Record> RealKey(std::string name, At at, KeyRange range, std::string description) {
  SceneKey<Record> k = TypedKey<Record>(std::move(name), KeyType::kReal, &TableReader::Real, at,
                                        std::move(description));
  k.range = range;
  return k;
}

// A real that is absent unless given (std::optional<double>); `range` applies when it is given.
template <typename Record, typename At>
SceneKey<Record> OptionalRealKey(std::string name, At at, KeyRange range, std::string description) {
  SceneKey<Record> k;
  k.name = std::move(name);
  k.type = KeyType::kReal;
  k.range = range;
  k.optional = true;
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
  SceneKey<Record> k = TypedKey<Record>(std::move(name), KeyType::kInteger, &TableReader::Integer,
                                        at, std::move(description));
  k.range = range;
  return k;
}

template <typename Record, typename At>
SceneKey<Record> BooleanKey(std::string name, At at, std::string description) {
  return TypedKey<Record>(std::move(name), KeyType::kBoolean, &TableReader::Boolean, at,
                          std::move(description));
}

// Two finite numbers (the reader refuses others).
template <typename Record, typename At>
SceneKey<Record> VectorKey(std::string name, At at, std::string description) {
  SceneKey<Record> k = TypedKey<Record>(std::move(name), KeyType::kVector, &TableReader::Vector, at,
                                        std::move(description));
  k.range.kind = KeyRange::kFinite;
  return k;
}

template <typename Record, typename At>
SceneKey<Record> StringKey(std::string name, At at, std::string description) {
  return TypedKey<Record>(std::move(name), KeyType::kString, &TableReader::String, at,
                          std::move(description));
}

// "one of \"a\", \"b\"": the allowed words of a choice, as messages show them.
std::string AllowedWords(const std::vector<std::string>& words);

// The word of a choice member; "" for an absent std::optional one (its key's `get` then gives its
// default, SceneKey::unset).
template <typename Enum>
std::string WordOfMember(const Enum& value) {
  return WordOf(value);
}
template <typename Enum>
std::string WordOfMember(const std::optional<Enum>& value) {
  return value ? WordOf(*value) : "";
}

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
  k.get = [at](const Record& r) -> KeyValue { return WordOfMember(at(r)); };
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

// Why the key's range is what it is: the message of a value outside it ends with this.
template <typename Record>
SceneKey<Record> Because(SceneKey<Record> k, std::string why) {
  k.range_why = std::move(why);
  return k;
}

// A key of the scene (SceneKeys) that applies only where `applies` holds; `when` is that condition
// as a message and the docs state it ("fluid.model = \"giesekus\"").
template <typename Record, typename Applies>
SceneKey<Record> OnlyWhere(SceneKey<Record> k, Applies applies, std::string when) {
  k.applies = applies;
  k.applies_when = std::move(when);
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
