// The table of scene keys (scene/scene_keys.h): docs/scenes.md's key table is the one the table
// generates; Params{} and an empty scene agree on every key; every key is declared once;
// every scene of cases/ reads back from what the writer writes.
#include "dlmfd/scene/scene_keys.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include "dlmfd/core/errors.h"
#include "dlmfd/core/simulation.h"
#include "dlmfd/scene/scene_file.h"

namespace dlmfd {
namespace {

using scene::DefaultKind;
using scene::SceneKey;

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(SceneKeys, TheDocsTableIsTheGeneratedOne) {
  const std::string path = std::string(DLMFD_SOURCE_DIR) + "/docs/scenes.md";
  const std::string committed = ReadText(path);
  ASSERT_FALSE(committed.empty()) << path;
  EXPECT_EQ(committed, scene::WithSceneKeysTable(committed))
      << "docs/scenes.md's key table is stale: regenerate it with `cmake --build build --target "
         "scene-keys-doc` and commit it";
}

TEST(SceneKeys, EachKeyIsDeclaredOnce) {
  std::set<std::string> names;
  for (const SceneKey<Params>& k : scene::SceneKeys()) {
    EXPECT_TRUE(names.insert(k.name).second) << k.name;
    EXPECT_FALSE(k.description.empty()) << k.name;
    EXPECT_EQ(k.derive != nullptr, k.default_kind == DefaultKind::kDerived) << k.name;
  }
  std::set<std::string> particle_names;
  for (const SceneKey<ParticleParams>& k : scene::ParticleKeys()) {
    EXPECT_TRUE(particle_names.insert(k.name).second) << k.name;
  }
}

// Params{} runs as an empty scene does: on every key of the table, with no exception, before
// and after scene::ResolveDefaults (which the Simulation applies), and so do a polymer and a finer
// mesh given in code and in a scene (the preset's word follows the liquid, h_p follows h).
TEST(SceneKeys, ParamsAndAnEmptySceneAgreeOnEveryKey) {
  const Params empty = ParseScene("");
  const Params built;
  Params resolved = built;
  ResolveDefaults(resolved);
  for (const SceneKey<Params>& k : scene::SceneKeys()) {
    EXPECT_EQ(k.get(empty), k.get(built))
        << k.name << ": an empty scene gives " << scene::ValueText(k.get(empty)) << ", Params{} "
        << scene::ValueText(k.get(built));
    EXPECT_EQ(k.get(empty), k.get(resolved)) << k.name;
  }
  EXPECT_EQ(WriteScene(resolved), WriteScene(empty));
  EXPECT_EQ(scene::SceneValues(built), scene::SceneValues(empty));
  EXPECT_EQ(resolved.splitting.steady_correction, empty.splitting.steady_correction);
  EXPECT_EQ(resolved.particle_mesh.h, empty.particle_mesh.h);
  EXPECT_EQ(empty.particle_mesh.h, kPaperParticleMeshRatio * empty.domain.h);
  // ResolveDefaults keeps what is set: the scene as read resolves to itself.
  Params again = empty;
  ResolveDefaults(again);
  EXPECT_EQ(WriteScene(again), WriteScene(empty));

  const Params polymer_scene =
      ParseScene("[domain]\nh = 0.015625\n[fluid]\nrelaxation_time = 0.1\nsolvent_ratio = 0.5\n");
  Params polymer;
  polymer.domain.h = 0.015625;
  polymer.fluid.relaxation_time = 0.1;
  polymer.fluid.solvent_ratio = 0.5;
  EXPECT_EQ(scene::SceneValues(polymer), scene::SceneValues(polymer_scene));
  ResolveDefaults(polymer);
  EXPECT_EQ(WriteScene(polymer), WriteScene(polymer_scene));
  EXPECT_EQ(polymer.splitting.steady_correction, SteadyCorrection::kNone);
  EXPECT_EQ(polymer.particle_mesh.h, kPaperParticleMeshRatio * 0.015625);
  EXPECT_EQ(empty.particles.size(), built.particles.size());
  // A particle and a side given with their required keys only get the structs' defaults.
  const Params one = ParseScene(
      "[domain.boundary]\nleft = { type = \"wall\" }\n[[particles]]\ncenter = [0.5, 0.5]\n");
  ParticleParams q;
  q.center = Vec2(0.5, 0.5);
  for (const SceneKey<ParticleParams>& k : scene::ParticleKeys()) {
    EXPECT_EQ(k.get(one.particles[0]), k.get(q)) << k.name;
  }
  for (const SceneKey<BoundarySide>& k : scene::SideKeys()) {
    EXPECT_EQ(k.get(one.domain.sides[0]), k.get(BoundarySide{})) << k.name;
  }
}

// The writer writes every key the reader reads back to the same values, for every case file.
TEST(SceneKeys, EveryCaseReadsBackFromTheSceneAsWritten) {
  int cases = 0;
  for (const auto& entry :
       std::filesystem::recursive_directory_iterator(std::string(DLMFD_SOURCE_DIR) + "/cases")) {
    if (entry.path().extension() != ".toml") continue;
    const Params p = LoadSceneFile(entry.path().string());
    const std::string written = WriteScene(p);
    const Params again = ParseScene(written);
    EXPECT_EQ(WriteScene(again), written) << entry.path();
    EXPECT_EQ(scene::SceneValues(again), scene::SceneValues(p)) << entry.path();
    ++cases;
  }
  EXPECT_GT(cases, 20);
}

// Every cross-key rule of the table's list (kCrossKeyRules) attaches to a key of the tables: a
// misspelt key would leave its rule out of docs/scenes.md.
TEST(SceneKeys, EachCrossKeyRuleNamesAKey) {
  std::set<std::string> ruled;
  for (const SceneKey<Params>& k : scene::SceneKeys()) {
    if (!k.rule.empty()) ruled.insert(k.name);
  }
  for (const SceneKey<BoundarySide>& k : scene::SideKeys()) {
    if (!k.rule.empty()) ruled.insert("domain.boundary.SIDE." + k.name);
  }
  for (const SceneKey<ParticleParams>& k : scene::ParticleKeys()) {
    if (!k.rule.empty()) ruled.insert("particles.N." + k.name);
  }
  EXPECT_EQ(ruled.size(), 19u);  // the entries of kCrossKeyRules
  for (const char* key : {"domain.size", "time.dt", "output.fields_every", "fluid.model",
                          "domain.boundary.SIDE.ramp_time", "particles.N.center"}) {
    EXPECT_EQ(ruled.count(key), 1u) << key;
  }
}

// A choice key refuses a word it does not know, naming the key and every allowed word.
TEST(SceneKeys, AChoiceNamesItsAllowedWords) {
  for (const SceneKey<Params>& k : scene::SceneKeys()) {
    if (k.type != scene::KeyType::kChoice) continue;
    const std::string section = scene::SectionOf(k.name);
    const std::string text = (section.empty() ? "" : "[" + section + "]\n") +
                             scene::LeafOf(k.name) + " = \"no_such_word\"\n";
    try {
      ParseScene(text);
      ADD_FAILURE() << k.name;
    } catch (const InvalidParameter& e) {
      EXPECT_EQ(e.key(), k.name);
      for (const std::string& w : k.words) EXPECT_THAT(e.allowed(), ::testing::HasSubstr(w));
    }
  }
}

// A value just outside a key's range, as TOML text ("" where the reader refuses it first).
std::string JustOutside(const scene::KeyRange& r, bool integer) {
  const auto number = [integer](double x) {
    std::ostringstream text;
    if (integer) {
      text << static_cast<long>(x);
    } else {
      text << std::showpoint << x;
    }
    return text.str();
  };
  switch (r.kind) {
    case scene::KeyRange::kFinite:
      return integer ? "" : "nan";
    case scene::KeyRange::kPositive:
    case scene::KeyRange::kHalfOpenUnit:
      return number(0.0);
    case scene::KeyRange::kNonNegative:
      return number(-1.0);
    case scene::KeyRange::kOpenUnit:
      return number(1.0);
    case scene::KeyRange::kAtLeastOne:
      return number(0.0);
    case scene::KeyRange::kClosed:
      return number(r.high + 1.0);
    case scene::KeyRange::kAbove:
      return number(r.low);
    case scene::KeyRange::kAtLeast:
      return number(r.low - 1.0);
    case scene::KeyRange::kAny:
      break;
  }
  return "";
}

// Every range of the scene's keys is the table's: a scene file with a value just outside it is
// refused naming that key (ValidateScene's RequireSectionKeys), where the key applies.
TEST(SceneKeys, EachRangeRefusesAValueJustOutsideIt) {
  const std::string polymer = "relaxation_time = 1.0\nsolvent_ratio = 0.5\n";
  const std::map<std::string, std::string> where = {
      {"fluid.mobility", polymer + "model = \"giesekus\"\n"},
      {"fluid.extensibility", polymer + "model = \"fene_p\"\n"},
      {"fluid.ptt_epsilon", polymer + "model = \"ptt_linear\"\n"}};
  int checked = 0;
  for (const SceneKey<Params>& k : scene::SceneKeys()) {
    if (k.type == scene::KeyType::kVector) continue;  // finite on reading
    const std::string value = JustOutside(k.range, k.type == scene::KeyType::kInteger);
    if (value.empty()) continue;
    const std::string section = scene::SectionOf(k.name);
    ASSERT_FALSE(section.empty()) << k.name;
    const auto extra = where.find(k.name);
    const std::string text = "[" + section + "]\n" + scene::LeafOf(k.name) + " = " + value + "\n" +
                             (extra == where.end() ? "" : extra->second);
    try {
      ParseScene(text);
      ADD_FAILURE() << k.name << " = " << value << " accepted";
    } catch (const InvalidParameter& e) {
      EXPECT_EQ(e.key(), k.name) << text << e.what();
    }
    ++checked;
  }
  EXPECT_GE(checked, 30);
}

// A model parameter is the table's to require with its model and to refuse without it.
TEST(SceneKeys, AModelParameterIsRequiredWithItsModelOnly) {
  const std::string polymer = "[fluid]\nrelaxation_time = 1.0\nsolvent_ratio = 0.5\n";
  try {
    ParseScene(polymer + "model = \"fene_p\"\n");
    ADD_FAILURE() << "fene_p without extensibility accepted";
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.key(), "fluid.extensibility");
    EXPECT_EQ(e.value(), "(absent)");
    EXPECT_THAT(e.allowed(), ::testing::HasSubstr("> 2"));
    EXPECT_THAT(e.allowed(), ::testing::HasSubstr("fluid.model = \"fene_p\""));
  }
  try {
    ParseScene(polymer + "ptt_epsilon = 0.1\n");
    ADD_FAILURE() << "ptt_epsilon with oldroyd_b accepted";
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.key(), "fluid.ptt_epsilon");
    EXPECT_THAT(e.allowed(), ::testing::HasSubstr("absent unless fluid.model"));
  }
}

// The engine's own guard (Simulation's constructor) checks the same table for Params built in
// code: time.end = 0 is refused naming time.end, as the scene validation refuses it.
TEST(SceneKeys, SimulationChecksTheTimeKeysOfTheTable) {
  for (const auto& [key, set] : std::vector<std::pair<std::string, void (*)(Params&)>>{
           {"time.end", [](Params& p) { p.time.end = 0.0; }},
           {"time.dt", [](Params& p) { p.time.dt = -1.0; }},
           {"output.fields_every", [](Params& p) { p.output.fields_every = -0.5; }},
           {"splitting.beta", [](Params& p) { p.splitting.beta = 1.5; }}}) {
    Params p;
    set(p);
    try {
      Simulation simulation(p);
      ADD_FAILURE() << key << " accepted";
    } catch (const InvalidParameter& e) {
      EXPECT_EQ(e.key(), key);
    }
  }
}

}  // namespace
}  // namespace dlmfd
