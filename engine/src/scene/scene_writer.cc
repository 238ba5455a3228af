// WriteScene: Params back to TOML from the tables of scene/scene_keys.h, every key the tables write
// (defaults filled in), reals in the shortest text that reads back exactly, so that
// ParseScene(WriteScene(p)) gives p again. A section's header comes before its first key written;
// the sides of domain.boundary follow the domain's keys as inline tables.
#include <sstream>
#include <vector>

#include "dlmfd/scene/scene_file.h"
#include "dlmfd/scene/scene_keys.h"

namespace dlmfd {
namespace {

using scene::SceneKey;

template <typename Record>
bool IsWritten(const SceneKey<Record>& k, const Record& r) {
  if (k.written) return k.written(r);
  return !k.applies || k.applies(r);
}

std::string SideText(const BoundarySide& side) {
  std::string out = "{";
  bool first = true;
  for (const SceneKey<BoundarySide>& k : scene::SideKeys()) {
    if (!IsWritten(k, side)) continue;
    out += std::string(first ? " " : ", ") + k.name + " = " + scene::ValueText(k.get(side));
    first = false;
  }
  return out + " }";
}

void WriteSides(std::ostringstream& o, const DomainParams& d) {
  const char* const names[4] = {"left", "right", "bottom", "top"};
  o << "\n[domain.boundary]\n";
  for (int s = 0; s < 4; ++s) o << names[s] << " = " << SideText(d.sides[s]) << "\n";
}

// [[particles]], one table each.
void WriteParticles(std::ostringstream& o, const std::vector<ParticleParams>& particles) {
  for (const ParticleParams& q : particles) {
    o << "\n[[particles]]\n";
    for (const SceneKey<ParticleParams>& k : scene::ParticleKeys()) {
      if (IsWritten(k, q)) o << k.name << " = " << scene::ValueText(k.get(q)) << "\n";
    }
  }
}

}  // namespace

std::string WriteScene(const Params& p) {
  std::ostringstream o;
  o << "# Written by dlmfd-solve: the scene as run, every default filled in (docs/scenes.md).\n";
  std::string section;
  for (const SceneKey<Params>& k : scene::SceneKeys()) {
    const std::string key_section = scene::SectionOf(k.name);
    if (section == "domain" && key_section != "domain") {
      WriteSides(o, p.domain);
      section = "domain.boundary";
    }
    if (!IsWritten(k, p)) continue;
    if (key_section != section) {
      o << "\n[" << key_section << "]\n";
      section = key_section;
    }
    o << scene::LeafOf(k.name) << " = " << scene::ValueText(k.get(p)) << "\n";
  }
  WriteParticles(o, p.particles);
  return o.str();
}

}  // namespace dlmfd
