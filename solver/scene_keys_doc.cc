// dlmfd-scene-keys: prints docs/scenes.md's key table from the tables of scene keys
// (scene/scene_keys.h), or with `--update FILE` rewrites the table between FILE's markers.
// `cmake --build build --target scene-keys-doc` runs the latter on docs/scenes.md;
// tests/unit/scene_keys_test.cc fails while the committed table is stale.
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include "dlmfd/scene/scene_keys.h"

int main(int argc, char** argv) {
  const std::string usage = "usage: dlmfd-scene-keys [--update docs/scenes.md]";
  if (argc == 1) {
    std::cout << dlmfd::scene::SceneKeysMarkdown();
    return 0;
  }
  if (argc != 3 || std::string(argv[1]) != "--update") {
    std::cerr << usage << "\n";
    return 2;
  }
  std::ifstream in(argv[2]);
  if (!in) {
    std::cerr << "dlmfd-scene-keys: cannot read " << argv[2] << "\n";
    return 1;
  }
  std::ostringstream text;
  text << in.rdbuf();
  in.close();
  try {
    const std::string updated = dlmfd::scene::WithSceneKeysTable(text.str());
    std::ofstream out(argv[2], std::ios::trunc);
    out << updated;
    return out ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "dlmfd-scene-keys: " << argv[2] << ": " << e.what() << "\n";
    return 1;
  }
}
