// docs/scenes.md's key table from the tables of scene/scene_keys.h (SceneKeysMarkdown): one row
// per key, its type, default, allowed values and one-line description.
#include <sstream>
#include <stdexcept>

#include "dlmfd/core/number_text.h"
#include "dlmfd/scene/scene_keys.h"

namespace dlmfd {
namespace scene {
namespace {

const char* TypeName(KeyType type) {
  switch (type) {
    case KeyType::kReal:
      return "real";
    case KeyType::kInteger:
      return "integer";
    case KeyType::kBoolean:
      return "boolean";
    case KeyType::kVector:
      return "[x, y]";
    case KeyType::kString:
    case KeyType::kChoice:
      break;
  }
  return "string";
}

std::string Code(const std::string& text) { return "`" + text + "`"; }

std::string QuotedWord(const std::string& word) { return "\"" + word + "\""; }

// The default under each preset, for a kPreset key: "`"wave"` (`"least_squares"` under
// `numerics.preset = "paper"`)"; a word that depends on the liquid names both.
std::string PresetDefault(const std::string& key) {
  Params newtonian;
  Params polymer;
  polymer.fluid.relaxation_time = 1.0;
  polymer.fluid.solvent_ratio = 0.5;
  std::string text;
  for (const NumericsPreset preset : {NumericsPreset::kDefault, NumericsPreset::kPaper}) {
    const std::string a = PresetWord(preset, key, newtonian);
    const std::string b = PresetWord(preset, key, polymer);
    std::string words = a == b ? Code(QuotedWord(a))
                               : Code(QuotedWord(a)) + " in a Newtonian liquid, " +
                                     Code(QuotedWord(b)) + " with a polymer";
    if (preset == NumericsPreset::kDefault) {
      text = words;
    } else {
      text += " (" + words + " under `numerics.preset = \"paper\"`)";
    }
  }
  return text;
}

template <typename Record>
std::string DefaultText(const SceneKey<Record>& k) {
  switch (k.default_kind) {
    case DefaultKind::kStruct:
      return Code(ValueText(k.get(Record{})));
    case DefaultKind::kPreset:
      return PresetDefault(k.name);
    case DefaultKind::kDerived:
      return k.default_text;
    case DefaultKind::kRequired:
      return k.applies_when.empty() ? "required" : "required where it applies";
    case DefaultKind::kAbsent:
      break;
  }
  return "absent";
}

std::string RangeDocs(const KeyRange& r) {
  switch (r.kind) {
    case KeyRange::kFinite:
      return "finite";
    case KeyRange::kPositive:
      return "> 0";
    case KeyRange::kNonNegative:
      return ">= 0";
    case KeyRange::kOpenUnit:
      return "(0, 1)";
    case KeyRange::kHalfOpenUnit:
      return "(0, 1]";
    case KeyRange::kAtLeastOne:
      return ">= 1";
    case KeyRange::kClosed:
      return "[" + ShortText(r.low) + ", " + ShortText(r.high) + "]";
    case KeyRange::kAbove:
      return "> " + ShortText(r.low);
    case KeyRange::kAtLeast:
      return ">= " + ShortText(r.low);
    case KeyRange::kAny:
      break;
  }
  return "";
}

template <typename Record>
std::string AllowedText(const SceneKey<Record>& k) {
  std::string text;
  for (const std::string& w : k.words) text += (text.empty() ? "" : ", ") + Code(w);
  if (k.type == KeyType::kBoolean) text = "`true`, `false`";
  const std::string range = RangeDocs(k.range);
  const std::string rule = k.rule.empty() ? "" : "rule: " + k.rule;
  const std::string alias =
      k.alias.empty() ? "" : "also accepted as " + Code(k.alias) + ", not both";
  const std::string when =
      k.applies_when.empty() ? "" : "only with " + Code(k.applies_when) + ", refused otherwise";
  for (const std::string& part : {range, when, alias, k.allowed_note, rule}) {
    if (!part.empty()) text += (text.empty() ? "" : "; ") + part;
  }
  return text.empty() ? "any" : text;
}

template <typename Record>
void Rows(std::ostringstream& o, const std::vector<SceneKey<Record>>& keys,
          const std::string& prefix) {
  for (const SceneKey<Record>& k : keys) {
    o << "| " << Code(prefix + k.name) << " | " << TypeName(k.type) << " | " << DefaultText(k)
      << " | " << AllowedText(k) << " | " << k.description << " |\n";
  }
}

}  // namespace

std::string SceneKeysMarkdown() {
  std::ostringstream o;
  o << "| key | type | default | allowed | meaning |\n|---|---|---|---|---|\n";
  std::vector<SceneKey<Params>> before;
  std::vector<SceneKey<Params>> after;
  for (const SceneKey<Params>& k : SceneKeys()) {
    const std::string section = SectionOf(k.name);
    (section.empty() || section == "numerics" || section == "domain" ? before : after).push_back(k);
  }
  Rows(o, before, "");
  o << "| `domain.boundary.SIDE` | table | `{ type = \"wall\" }` | SIDE in `left`, `right`, "
       "`bottom`, `top` | boundary condition of a side |\n";
  Rows(o, SideKeys(), "domain.boundary.SIDE.");
  Rows(o, after, "");
  o << "| `particles` | array of tables | none | | `[[particles]]`, one table per particle |\n";
  Rows(o, ParticleKeys(), "particles.N.");
  return o.str();
}

std::string WithSceneKeysTable(const std::string& markdown) {
  const std::string begin(kSceneKeysBegin);
  const std::string end(kSceneKeysEnd);
  const auto b = markdown.find(begin);
  const auto e = markdown.find(end);
  if (b == std::string::npos || e == std::string::npos || e < b) {
    throw std::runtime_error("the scene keys' markers are missing: " + begin + " ... " + end);
  }
  return markdown.substr(0, b) + begin + "\n\n" + SceneKeysMarkdown() + "\n" + markdown.substr(e);
}

}  // namespace scene
}  // namespace dlmfd
