// libFuzzer target: the scene parser (engine/src/scene) on any bytes, as dlmfd-solve and the
// daemon read a scene and its overrides (issue 38 point 1).
//
// Input: the scene's TOML text, then, after each NUL byte, one override "key=value" (as
// `dlmfd-solve --set` and SubmitRequest.overrides carry them). The parser must either accept the
// scene or throw dlmfd::InvalidParameter (scene_file.h: every error names the key); any other
// exception, a crash, a sanitizer report or a stack overflow is a finding. An accepted scene must
// also round-trip: the TOML that WriteScene writes parses again and writes the same text.
// Run: scripts/fuzz.sh (bounded; CI), or build-fuzz/tests/fuzz/scene_text_fuzz CORPUS_DIR.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "dlmfd/core/errors.h"
#include "dlmfd/scene/scene_file.h"

namespace {

std::vector<std::string> SplitAtNul(const uint8_t* data, size_t size) {
  std::vector<std::string> parts(1);
  for (size_t i = 0; i < size; ++i) {
    if (data[i] == 0) {
      parts.emplace_back();
    } else {
      parts.back().push_back(static_cast<char>(data[i]));
    }
  }
  return parts;
}

[[noreturn]] void Finding(const std::string& what) {
  std::fprintf(stderr, "scene_text_fuzz: %s\n", what.c_str());
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::vector<std::string> parts = SplitAtNul(data, size);
  std::vector<dlmfd::SceneOverride> overrides;
  try {
    for (size_t i = 1; i < parts.size(); ++i) overrides.push_back(dlmfd::ParseOverride(parts[i]));
    const dlmfd::Params params = dlmfd::ParseScene(parts[0], overrides, "fuzz.toml");
    const std::string written = dlmfd::WriteScene(params);
    std::string again;
    try {
      again = dlmfd::WriteScene(dlmfd::ParseScene(written, {}, "written.toml"));
    } catch (const dlmfd::InvalidParameter& e) {
      Finding("an accepted scene's WriteScene text is refused: " + std::string(e.what()) +
              "\n--- written:\n" + written);
    }
    if (again != written) {
      Finding("WriteScene does not round-trip:\n--- first:\n" + written + "\n--- second:\n" +
              again);
    }
  } catch (const dlmfd::InvalidParameter&) {
    // The documented refusal, naming the key.
  }
  return 0;
}
