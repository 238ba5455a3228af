// Scene parsing (design.md 3.1): TOML -> Params, driven by the tables of scene/scene_keys.h. Pass 1
// reads every key the scene gives (types and words checked, unknown keys refused, section by
// section); pass 2 gives the others their defaults: numerics.preset's words, then "auto" resolved
// from the rest of the scene (scene/auto_coupling.h), then the keys derived from others
// (particle_mesh.h from domain.h, splitting.alpha and beta from the coupling). Values are checked
// by ValidateScene (scene/scene_validation.h). Every error names the key, the value and what is
// allowed.
#include "dlmfd/scene/scene_file.h"

#include <algorithm>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <type_traits>

#include <toml++/toml.h>

#include "dlmfd/core/errors.h"
#include "dlmfd/scene/scene_keys.h"
#include "dlmfd/scene/scene_validation.h"
#include "dlmfd/scene/toml_bounds.h"
#include "scene_overrides.h"
#include "toml_reader.h"

namespace dlmfd {
namespace {

// TOML text is UTF-8 (toml++ refuses a file that is not); an override's text must be too, or the
// scene written back from it (scene.toml in the results) could not be read again.
bool IsUtf8(const std::string& text) {
  // The least code point of each length: shorter (overlong) forms are not UTF-8.
  const unsigned least[] = {0, 0x80, 0x800, 0x10000};
  std::size_t i = 0;
  while (i < text.size()) {
    const auto c = static_cast<unsigned char>(text[i]);
    int extra = -1;
    if (c < 0x80) {
      extra = 0;
    } else if ((c >> 5) == 0x6) {
      extra = 1;
    } else if ((c >> 4) == 0xE) {
      extra = 2;
    } else if ((c >> 3) == 0x1E) {
      extra = 3;
    }
    // Not a lead byte, or the sequence runs past the end.
    if (extra < 0 || i + static_cast<std::size_t>(extra) >= text.size()) return false;
    unsigned code = extra == 0 ? c : (c & (0x3Fu >> extra));
    for (int k = 1; k <= extra; ++k) {
      const auto d = static_cast<unsigned char>(text[i + k]);
      if ((d & 0xC0) != 0x80) return false;
      code = (code << 6) | (d & 0x3Fu);
    }
    // UTF-16 surrogates and code points past U+10FFFF are not UTF-8 either.
    if (code < least[extra] || (code >= 0xD800 && code <= 0xDFFF) || code > 0x10FFFF) return false;
    i += static_cast<std::size_t>(extra) + 1;
  }
  return true;
}

using scene::DefaultKind;
using scene::KeyType;
using scene::SceneKey;
using scene::TableReader;

// The choice keys whose word is "auto", resolved once the rest of the scene is read.
using AutoKeys = std::vector<const SceneKey<Params>*>;

// Reads a key that is present (or required: then its absence is the error).
template <typename Record>
void ReadKey(TableReader& r, const SceneKey<Record>& k, const std::string& leaf, Record& record,
             AutoKeys* autos) {
  if (k.type != KeyType::kChoice) {
    k.read(r, leaf, record);
    return;
  }
  const std::string word = r.String(leaf, std::nullopt);
  if constexpr (std::is_same_v<Record, Params>) {
    if (word == "auto" && k.resolve != nullptr) {
      autos->push_back(&k);
      return;
    }
  }
  k.set_word(record, r.Key(leaf), word);
}

// A record of SideKeys or ParticleKeys: each key where it applies, in the table's order.
template <typename Record>
void ReadRecord(TableReader& r, const std::vector<SceneKey<Record>>& keys, Record& record) {
  std::string allowed;
  for (const SceneKey<Record>& k : keys) {
    const bool applies = !k.applies || k.applies(record);
    if (applies || !k.refused.empty()) allowed += (allowed.empty() ? "" : ", ") + k.name;
    if (!applies) {
      if (r.Has(k.name) && !k.refused.empty()) {
        Record refused = record;
        k.read(r, k.name, refused);
        throw InvalidParameter(r.Key(k.name), scene::ValueText(k.get(refused)), k.refused);
      }
      continue;
    }
    if (r.Has(k.name) || k.default_kind == DefaultKind::kRequired) {
      ReadKey<Record>(r, k, k.name, record, nullptr);
    }
  }
  r.RejectUnknown(allowed);
}

void ReadSides(TableReader& domain, Params& p) {
  TableReader boundary(domain.Table("boundary"), "domain.boundary");
  const char* names[4] = {"left", "right", "bottom", "top"};
  for (int s = 0; s < 4; ++s) {
    BoundarySide& side = p.domain.sides[s];
    side = BoundarySide{};
    const toml::table* table = boundary.Table(names[s]);
    if (table == nullptr) continue;
    TableReader r(table, boundary.Key(names[s]));
    ReadRecord(r, scene::SideKeys(), side);
  }
  boundary.RejectUnknown("left, right, bottom, top");
}

// A top-level key with an alias in a section (SceneKey::alias: gravity is accepted as
// `fluid.gravity` too, because a `gravity = ...` line written after the [fluid] header, as in
// design.md 3.1, belongs to that table in TOML): read from where it is given, not both.
void ReadAliased(TableReader& top, TableReader& in_section, const SceneKey<Params>& k, Params& p) {
  const std::string leaf = scene::LeafOf(k.alias);
  if (in_section.Has(leaf)) {
    Params aliased = p;
    k.read(in_section, leaf, aliased);  // its type checked first
    if (top.Has(k.name)) {
      throw InvalidParameter(
          k.alias, scene::ValueText(k.get(aliased)),
          "no second " + k.name + " (" + k.name + " is also given at the top level)");
    }
    k.read(in_section, leaf, p);
  } else if (top.Has(k.name)) {
    k.read(top, k.name, p);
  }
}

// The end of a section of SceneKeys: its records, then its unknown keys.
void FinishSection(TableReader& top, TableReader& r, const std::string& section, Params& p) {
  std::string allowed;
  for (const SceneKey<Params>& k : scene::SceneKeys()) {
    if (scene::SectionOf(k.name) != section) continue;
    allowed += (allowed.empty() ? "" : ", ") + scene::LeafOf(k.name);
  }
  if (section == "domain") {
    ReadSides(r, p);
    allowed += ", boundary";
  }
  for (const SceneKey<Params>& k : scene::SceneKeys()) {
    if (k.alias.empty() || scene::SectionOf(k.alias) != section) continue;
    ReadAliased(top, r, k, p);
    allowed += ", " + scene::LeafOf(k.alias);
  }
  r.RejectUnknown(allowed);
}

// Pass 1: every key of SceneKeys the scene gives, section by section.
std::set<std::string> ReadGivenKeys(TableReader& top, Params& p, AutoKeys& autos) {
  std::set<std::string> given;
  std::optional<TableReader> current;
  std::string section;
  for (const SceneKey<Params>& k : scene::SceneKeys()) {
    const std::string key_section = scene::SectionOf(k.name);
    if (key_section != section) {
      if (current) FinishSection(top, *current, section, p);
      section = key_section;
      current.emplace(top.Table(section), section);
    }
    TableReader& r = section.empty() ? top : *current;
    const std::string leaf = scene::LeafOf(k.name);
    if (!k.alias.empty() || !r.Has(leaf)) continue;  // an aliased key: ReadAliased
    ReadKey<Params>(r, k, leaf, p, &autos);
    given.insert(k.name);
  }
  if (current) FinishSection(top, *current, section, p);
  return given;
}

// The keys derived from others (kDerived) that the scene does not give, from the values so far.
void DeriveKeys(const std::set<std::string>& given, Params& p) {
  for (const SceneKey<Params>& k : scene::SceneKeys()) {
    if (given.count(k.name) == 0 && k.default_kind == DefaultKind::kDerived && !k.unset) {
      k.derive(p);
    }
  }
}

// Pass 2: the defaults of the keys not given: the preset's words, then "auto" resolved from the
// rest of the scene (scene/auto_coupling.h), then the keys derived from others, then the members
// the struct leaves absent (ResolveDefaults).
void ApplyDefaults(const std::set<std::string>& given, AutoKeys& autos, Params& p) {
  for (const SceneKey<Params>& k : scene::SceneKeys()) {
    // A member the struct leaves absent waits for ResolveDefaults, but "auto", which the keys
    // derived from it need now.
    if (given.count(k.name) != 0 || k.default_kind != DefaultKind::kPreset) continue;
    if (k.unset && k.resolve == nullptr) continue;
    const std::string word = scene::PresetWord(p.numerics.preset, k.name, p);
    if (word == "auto" && k.resolve != nullptr) {
      autos.push_back(&k);
    } else {
      k.set_word(p, k.name, word);
    }
  }
  // In the table's order, each rule reading the keys derived from what the ones before chose
  // (particle_mesh.kind reads splitting.beta, which follows the coupling).
  for (const SceneKey<Params>& k : scene::SceneKeys()) {
    if (std::find(autos.begin(), autos.end(), &k) == autos.end()) continue;
    DeriveKeys(given, p);
    p.numerics.resolved.push_back(k.resolve(p));
    k.set_word(p, k.name, p.numerics.resolved.back().value);
  }
  DeriveKeys(given, p);
  ResolveDefaults(p);
}

// "title, gravity, numerics, domain, ...": the top-level keys and sections, then the particles.
std::string TopLevelKeys() {
  std::string names;
  std::string last;
  for (const SceneKey<Params>& k : scene::SceneKeys()) {
    const std::string section = scene::SectionOf(k.name);
    const std::string name = section.empty() ? k.name : section;
    if (name == last) continue;
    names += (names.empty() ? "" : ", ") + name;
    last = name;
  }
  return names + ", particles";
}

void ReadParticles(TableReader& top, Params& p) {
  const toml::array* array = top.Array("particles");
  p.particles.clear();
  if (array == nullptr) return;
  for (std::size_t i = 0; i < array->size(); ++i) {
    const std::string prefix = "particles." + std::to_string(i);
    const toml::table* table = array->get(i)->as_table();
    if (table == nullptr)
      throw InvalidParameter(prefix, scene::NodeText(*array->get(i)), "a table ([[particles]])");
    TableReader r(table, prefix);
    ParticleParams q;
    ReadRecord(r, scene::ParticleKeys(), q);
    p.particles.push_back(q);
  }
}

}  // namespace

void ResolveDefaults(Params& params) {
  // A Params that leaves the constraint to "auto" with the struct's weights gets the weights of the
  // constraint "auto" picks, as a scene that names neither (SplittingParams).
  const bool weights_follow = !params.splitting.constraint &&
                              params.splitting.alpha == SplittingParams{}.alpha &&
                              params.splitting.beta == SplittingParams{}.beta;
  for (const SceneKey<Params>& k : scene::SceneKeys()) {
    if (!k.unset || !k.unset(params)) continue;
    if (k.default_kind == DefaultKind::kDerived) {
      k.derive(params);
      continue;
    }
    std::string word = scene::PresetWord(params.numerics.preset, k.name, params);
    if (word == "auto" && k.resolve != nullptr) {
      params.numerics.resolved.push_back(k.resolve(params));
      word = params.numerics.resolved.back().value;
    }
    k.set_word(params, k.name, word);
  }
  if (weights_follow) {
    const SplittingParams weights = SplittingParams::DefaultWeights(*params.splitting.constraint);
    params.splitting.alpha = weights.alpha;
    params.splitting.beta = weights.beta;
  }
}

SceneOverride ParseOverride(const std::string& key_equals_value) {
  const auto eq = key_equals_value.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw InvalidParameter("--set", key_equals_value,
                           "key=value with a dotted scene key (e.g. fluid.viscosity=0.1)");
  }
  auto trim = [](std::string s) {
    const auto b = s.find_first_not_of(" \t");
    const auto e = s.find_last_not_of(" \t");
    return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
  };
  if (!IsUtf8(key_equals_value)) {
    throw InvalidParameter("--set", "(a key=value with bytes that are not UTF-8)",
                           "UTF-8 text, as in a scene file");
  }
  SceneOverride o{trim(key_equals_value.substr(0, eq)), trim(key_equals_value.substr(eq + 1))};
  if (o.key.empty()) {
    throw InvalidParameter("--set", key_equals_value,
                           "key=value with a dotted scene key (e.g. fluid.viscosity=0.1)");
  }
  return o;
}

Params ParseScene(const std::string& toml_text, const std::vector<SceneOverride>& overrides,
                  const std::string& origin) {
  scene::RequireBoundedToml(toml_text, origin);
  toml::table root;
  try {
    root = toml::parse(toml_text, origin);
  } catch (const toml::parse_error& e) {
    std::ostringstream where;
    where << "line " << e.source().begin.line << " column " << e.source().begin.column;
    throw InvalidParameter(origin, where.str(),
                           "valid TOML (" + std::string(e.description()) + ")");
  }
  scene::ApplyOverrides(root, overrides);

  Params p;
  TableReader top(&root, "");
  AutoKeys autos;
  const std::set<std::string> given = ReadGivenKeys(top, p, autos);
  ReadParticles(top, p);
  top.RejectUnknown(TopLevelKeys());
  ApplyDefaults(given, autos, p);
  ValidateScene(p);
  return p;
}

Params LoadSceneFile(const std::string& path, const std::vector<SceneOverride>& overrides) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidParameter("scene", path, "a readable scene file");
  std::ostringstream text;
  text << in.rdbuf();
  return ParseScene(text.str(), overrides, path);
}

}  // namespace dlmfd
