// What the tables of scene/scene_keys.h say about a value: its TOML text, its range check, and the
// scene's values by full dotted key.
#include <cmath>

#include "dlmfd/core/errors.h"
#include "dlmfd/core/number_text.h"
#include "dlmfd/scene/scene_keys.h"
#include "toml_reader.h"

namespace dlmfd {
namespace scene {
namespace {

// The range as a message's "expected" text.
std::string RangeText(const KeyRange& r, bool integer) {
  switch (r.kind) {
    case KeyRange::kFinite:
      return "a finite number";
    case KeyRange::kPositive:
      return "a number > 0";
    case KeyRange::kNonNegative:
      return "a number >= 0";
    case KeyRange::kOpenUnit:
      return "a number in (0, 1)";
    case KeyRange::kHalfOpenUnit:
      return "a number in (0, 1]";
    case KeyRange::kAtLeastOne:
      return integer ? "an integer >= 1" : "a number >= 1";
    case KeyRange::kClosed:
      return "a number in [" + ShortText(r.low) + ", " + ShortText(r.high) + "]";
    case KeyRange::kAbove:
      return "a finite number > " + ShortText(r.low);
    case KeyRange::kAtLeast:
      return "a finite number >= " + ShortText(r.low);
    case KeyRange::kAny:
      break;
  }
  return "any value";
}

bool InRange(double x, const KeyRange& r) {
  switch (r.kind) {
    case KeyRange::kFinite:
      return std::isfinite(x);
    case KeyRange::kPositive:
      return x > 0.0;
    case KeyRange::kNonNegative:
      return x >= 0.0;
    case KeyRange::kOpenUnit:
      return x > 0.0 && x < 1.0;
    case KeyRange::kHalfOpenUnit:
      return x > 0.0 && x <= 1.0;
    case KeyRange::kAtLeastOne:
      return x >= 1.0;
    case KeyRange::kClosed:
      return x >= r.low && x <= r.high;
    case KeyRange::kAbove:
      return x > r.low && std::isfinite(x);
    case KeyRange::kAtLeast:
      return x >= r.low && std::isfinite(x);
    case KeyRange::kAny:
      break;
  }
  return true;
}

template <typename Record>
void AppendRecord(const std::vector<SceneKey<Record>>& keys, const Record& record,
                  const std::string& prefix, std::vector<std::pair<std::string, KeyValue>>& out) {
  for (const SceneKey<Record>& k : keys) {
    const bool applies = !k.applies || k.applies(record);
    if (k.written ? !k.written(record) : !applies) continue;
    out.emplace_back(prefix + k.name, k.get(record));
  }
}

}  // namespace

std::string ValueText(const KeyValue& value) {
  if (const auto* x = std::get_if<double>(&value)) return ExactText(*x);
  if (const auto* n = std::get_if<int>(&value)) return std::to_string(*n);
  if (const auto* b = std::get_if<bool>(&value)) return *b ? "true" : "false";
  if (const auto* v = std::get_if<Vec2>(&value)) return VecText(*v);
  return QuotedText(std::get<std::string>(value));
}

void RequireInRange(const std::string& key, const KeyValue& value, const KeyRange& range,
                    const std::string& what) {
  if (range.kind == KeyRange::kAny) return;
  const auto* n = std::get_if<int>(&value);
  const auto* x = std::get_if<double>(&value);
  if (n == nullptr && x == nullptr) return;  // vectors: finite on reading
  const double number = n != nullptr ? *n : *x;
  if (InRange(number, range)) return;
  std::string allowed = RangeText(range, n != nullptr);
  if (!what.empty()) allowed += " (" + what + ")";
  throw InvalidParameter(key, ValueText(value), allowed);
}

void RequireSectionKeys(const Params& params, const std::string& section) {
  for (const SceneKey<Params>& k : SceneKeys()) {
    if (SectionOf(k.name) != section) continue;
    const bool given = !k.optional || k.written(params);
    if (k.applies && !k.applies(params)) {
      if (!given || !k.optional) continue;
      throw InvalidParameter(k.name, ValueText(k.get(params)),
                             "absent unless " + k.applies_when + " (" + k.description +
                                 ", a parameter of that case only)");
    }
    if (!given) {
      if (k.default_kind != DefaultKind::kRequired) continue;
      throw InvalidParameter(
          k.name, "(absent)",
          RangeText(k.range, false) + " (" + k.range_why + "), required with " + k.applies_when);
    }
    const bool closed = k.range.kind == KeyRange::kClosed;
    const std::string why = !k.range_why.empty() ? k.range_why : closed ? k.description : "";
    RequireInRange(k.name, k.get(params), k.range, why);
  }
}

void RequireParticleRanges(const ParticleParams& particle, const std::string& prefix) {
  for (const SceneKey<ParticleParams>& k : ParticleKeys()) {
    if (k.applies && !k.applies(particle)) continue;
    RequireInRange(prefix + "." + k.name, k.get(particle), k.range);
  }
}

std::vector<std::pair<std::string, KeyValue>> SceneValues(const Params& params) {
  std::vector<std::pair<std::string, KeyValue>> out;
  const char* const sides[4] = {"left", "right", "bottom", "top"};
  bool sides_done = false;
  for (const SceneKey<Params>& k : SceneKeys()) {
    // The sides after the domain's own keys, as the writer writes them.
    if (!sides_done && SectionOf(k.name) == "fluid") {
      for (int s = 0; s < 4; ++s) {
        AppendRecord(SideKeys(), params.domain.sides[s],
                     std::string("domain.boundary.") + sides[s] + ".", out);
      }
      sides_done = true;
    }
    if (k.written ? !k.written(params) : false) continue;
    out.emplace_back(k.name, k.get(params));
  }
  for (std::size_t i = 0; i < params.particles.size(); ++i) {
    AppendRecord(ParticleKeys(), params.particles[i], "particles." + std::to_string(i) + ".", out);
  }
  return out;
}

}  // namespace scene
}  // namespace dlmfd
