// The table of scene keys (issue 39, the step-60 habit: a parameter is declared once). Each key is
// one SceneKey: its dotted name, the member of core/params.h it sets, its type, its default, its
// allowed values or range, and a one-line description. The reader (scene_file.cc), the unknown-key
// check, the writer (scene_writer.cc), the range checks of ValidateScene, the daemon's flattened
// scene values and docs/scenes.md's key table (SceneKeysMarkdown) all walk these tables.
//
// Three tables, one per record kind: SceneKeys() for the keys of the scene itself
// ("fluid.viscosity", section.leaf), SideKeys() for a side of domain.boundary.SIDE, ParticleKeys()
// for one
// [[particles]] table. A key's default is one of:
//   kStruct   the value of the record's struct built by default (core/params.h);
//   kPreset   the word numerics.preset gives it (PresetWord below; a preset is a table of
//             key = word pairs applied before the scene's own keys, the scene's keys win);
//   kDerived  a function of the other keys, applied after them (particle_mesh.h follows domain.h);
//   kRequired none: the key must be given (where it applies);
//   kAbsent   an optional member left empty.
// The struct holds numerics.preset's default words itself; a preset word or a derived value that
// follows other keys (splitting.steady_correction, particle_mesh.h) is an absent std::optional
// in the struct, which ResolveDefaults (scene/scene_file.h) fills for a scene file and for code
// that builds Params alike, so Params{} runs as an empty scene does
// (tests/unit/scene_keys_test.cc). A choice key may accept "auto": a named rule (`resolve`) picks
// its word at the start of a run from the rest of the scene, and the choice is recorded in
// Params::numerics.resolved.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "dlmfd/core/param_words.h"
#include "dlmfd/core/params.h"

namespace dlmfd {
namespace scene {

class TableReader;

// A key's value as a record holds it (a choice as its scene word).
using KeyValue = std::variant<double, int, bool, Vec2, std::string>;

enum class KeyType { kReal, kInteger, kBoolean, kVector, kString, kChoice };

// The range a number must lie in (ValidateScene): the message names it, the docs show it.
struct KeyRange {
  enum Kind {
    kAny,
    kFinite,
    kPositive,
    kNonNegative,
    kOpenUnit,
    kHalfOpenUnit,
    kAtLeastOne,
    kClosed,
    kAbove,   // a finite number > low
    kAtLeast  // a finite number >= low
  };
  Kind kind = kAny;
  double low = 0.0;  // kClosed: [low, high]; kAbove, kAtLeast: the bound
  double high = 0.0;
};

enum class DefaultKind { kStruct, kPreset, kDerived, kRequired, kAbsent };

template <typename Record>
struct SceneKey {
  std::string name;  // dotted, from the record ("fluid.viscosity"; a particle's "density")
  KeyType type = KeyType::kReal;
  KeyRange range;
  DefaultKind default_kind = DefaultKind::kStruct;
  std::string default_text;        // docs, for kDerived: how the default follows the other keys
  std::string allowed_note;        // docs: what is allowed beyond the range and the words
  std::string description;         // one line
  std::string range_why;           // why the range, after it in the message ("" when evident)
  std::vector<std::string> words;  // kChoice: the allowed words, "auto" first where it is one
  // A std::optional member the scene may leave out (OptionalRealKey): `written` says whether it
  // holds a value, and its range applies only when it does.
  bool optional = false;
  // Sets the member from the key's TOML value (the key is present); `key` is its full dotted name.
  std::function<void(TableReader&, const std::string& leaf, Record&)> read;
  // kChoice: sets the member from a word; throws naming `key` and the allowed words.
  std::function<void(Record&, const std::string& key, const std::string& word)> set_word;
  std::function<KeyValue(const Record&)> get;
  // Whether the key belongs to the record as read so far (null: always). A key given where it
  // does not apply is unknown there, or refused with `refused` when that is set. A key of the
  // scene itself (SceneKeys) that has `applies` states its condition in `applies_when`
  // ("fluid.model = \"giesekus\""): RequireSectionKeys refuses it elsewhere and, when it is
  // required, asks for it there; docs/scenes.md shows the condition.
  std::function<bool(const Record&)> applies;
  std::string applies_when;
  std::string refused;
  // Another dotted name of the same top-level key, in a section: "fluid.gravity" (TOML puts a
  // `gravity = ...` line written after [fluid] into that table). A scene gives at most one.
  std::string alias;
  // The named rule that checks the key together with other keys, beyond its range and words
  // ("ValidateTimeSteps (core/time_stepping.h)"); "" when none. All of them are listed in one
  // table, kCrossKeyRules of scene_keys.cc; ValidateScene calls them.
  std::string rule;
  // Whether the writer writes it (null: where it applies).
  std::function<bool(const Record&)> written;
  // A member the struct may leave absent (std::optional): true while it is. Its default (kPreset or
  // kDerived) is then given by ResolveDefaults (scene/scene_file.h), and `get` gives that default.
  std::function<bool(const Record&)> unset;
  std::function<void(Params&)> derive;                 // kDerived
  ResolvedChoice (*resolve)(const Params&) = nullptr;  // a choice that may be "auto"
};

const std::vector<SceneKey<Params>>& SceneKeys();
const std::vector<SceneKey<BoundarySide>>& SideKeys();
const std::vector<SceneKey<ParticleParams>>& ParticleKeys();

// The part of a dotted name before its last dot ("" at the top level), and the part after it.
std::string SectionOf(const std::string& name);
std::string LeafOf(const std::string& name);

// The word a preset gives a kPreset key of this scene (its liquid as read), or "" when none.
std::string PresetWord(NumericsPreset preset, const std::string& key, const Params& params);

// The value as TOML text: reals exactly (number_text.h), strings quoted.
std::string ValueText(const KeyValue& value);

// Throws InvalidParameter naming `key` when `value` is outside `range` (`what` follows the range
// in the message, e.g. the key's description).
void RequireInRange(const std::string& key, const KeyValue& value, const KeyRange& range,
                    const std::string& what = "");

// Every key of `section` (a section of SceneKeys) as its table entry declares it: where it does
// not apply, absent (else `refused`); where it applies, given if it is required, and in its range
// (with `range_why` in the message).
void RequireSectionKeys(const Params& params, const std::string& section);
// Every range of a particle's keys that apply to it (prefix "particles.N").
void RequireParticleRanges(const ParticleParams& particle, const std::string& prefix);

// Every key the writer writes, by its full dotted name ("domain.boundary.left.type",
// "particles.0.center"), with its value, in the writer's order.
std::vector<std::pair<std::string, KeyValue>> SceneValues(const Params& params);

// docs/scenes.md's key table, as Markdown.
std::string SceneKeysMarkdown();
// `markdown` (docs/scenes.md's text) with the lines between its two markers replaced by
// SceneKeysMarkdown(); throws std::runtime_error when a marker is missing. Regenerate the docs
// with `cmake --build build --target scene-keys-doc` (solver/scene_keys_doc.cc).
std::string WithSceneKeysTable(const std::string& markdown);
inline constexpr const char* kSceneKeysBegin =
    "<!-- scene keys: generated from engine/src/scene/scene_keys.cc by `cmake --build build "
    "--target scene-keys-doc`; do not edit by hand -->";
inline constexpr const char* kSceneKeysEnd = "<!-- end of the generated scene keys -->";

}  // namespace scene
}  // namespace dlmfd
