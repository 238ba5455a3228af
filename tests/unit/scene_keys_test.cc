// The table of scene keys (scene/scene_keys.h): docs/scenes.md's key table is the one the table
// generates; Params{} and an empty scene agree on every key whose default is the struct's, and
// differ only on keys the table declares as the preset's or derived; every key is declared once;
// every scene of cases/ reads back from what the writer writes.
#include "dlmfd/scene/scene_keys.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "dlmfd/core/errors.h"
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

// An empty scene gets the struct defaults of core/params.h, except where the table says the
// default is the preset's or follows other keys; there a test states each difference.
TEST(SceneKeys, ParamsAndAnEmptySceneAgreeWhereTheTableSaysSo) {
  const Params empty = ParseScene("");
  const Params built;
  std::set<std::string> differ;
  for (const SceneKey<Params>& k : scene::SceneKeys()) {
    if (k.get(empty) == k.get(built)) continue;
    differ.insert(k.name);
    EXPECT_TRUE(k.default_kind == DefaultKind::kPreset || k.default_kind == DefaultKind::kDerived)
        << k.name << ": an empty scene gives " << scene::ValueText(k.get(empty)) << ", Params{} "
        << scene::ValueText(k.get(built));
    if (k.default_kind == DefaultKind::kPreset) {
      EXPECT_EQ(scene::ValueText(k.get(empty)),
                scene::ValueText(scene::PresetWord(NumericsPreset::kDefault, k.name, empty)))
          << k.name;
    }
  }
  // The struct keeps the paper's choices where the engine's tests studied them
  // (scene/numerics_preset.h), and the paper's h_p = 1/70 (core/params.h).
  const std::set<std::string> expected = {"domain.diagonals", "splitting.advection",
                                          "splitting.steady_correction", "particle_mesh.h"};
  EXPECT_EQ(differ, expected);
  EXPECT_EQ(empty.particle_mesh.h, kPaperParticleMeshRatio * empty.domain.h);
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

}  // namespace
}  // namespace dlmfd
