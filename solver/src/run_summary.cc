#include "dlmfd/solver/run_summary.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <string>

#include "dlmfd/io/atomic_file.h"

namespace dlmfd::solver {
namespace {

// Keeps the keys in the order of the contract (the header), which a reader of the text expects.
using Json = nlohmann::ordered_json;

// A double as JSON: an integral value that a double holds exactly is written as an integer ("1",
// not "1.0": counts among the diagnostics, t = 1), anything else as the shortest text that reads
// back as the same double; non-finite as null (nlohmann's rule: JSON has no NaN).
Json Number(double x) {
  constexpr double kExactIntegers = 9007199254740992.0;  // 2^53
  if (std::isfinite(x) && x == std::trunc(x) && std::abs(x) < kExactIntegers &&
      !(x == 0.0 && std::signbit(x))) {
    return static_cast<int64_t>(x);
  }
  return x;
}

Json Pair(const std::array<double, 2>& v) { return Json::array({Number(v[0]), Number(v[1])}); }

// One value on one line, with ", " and ": " between items (nlohmann's compact form has none).
std::string Inline(const Json& j) {
  // Invalid UTF-8 in a text (a reason quoting a file name) becomes U+FFFD instead of throwing.
  if (!j.is_structured()) return j.dump(-1, ' ', false, Json::error_handler_t::replace);
  std::string out = j.is_array() ? "[" : "{";
  bool first = true;
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (!first) out += ", ";
    first = false;
    if (j.is_object()) out += Inline(Json(it.key())) + ": ";
    out += Inline(*it);
  }
  return out + (j.is_array() ? "]" : "}");
}

// JSON null stands for a non-finite number.
double ReadNumber(const Json& j, const char* key) {
  const Json& value = j.at(key);
  if (value.is_null()) return std::numeric_limits<double>::quiet_NaN();
  if (!value.is_number()) throw RunSummaryError(std::string(key) + ": not a number");
  return value.get<double>();
}

// A key an older solver did not write reads as NaN.
double OptionalNumber(const Json& j, const char* key) {
  return j.contains(key) ? ReadNumber(j, key) : std::numeric_limits<double>::quiet_NaN();
}

std::array<double, 2> NumberPair(const Json& j, const char* key) {
  const Json& value = j.at(key);
  if (!value.is_array() || value.size() != 2) {
    throw RunSummaryError(std::string(key) + ": not a pair of numbers");
  }
  std::array<double, 2> out{};
  for (std::size_t k = 0; k < 2; ++k) {
    out[k] = value[k].is_null() ? std::numeric_limits<double>::quiet_NaN() : value[k].get<double>();
  }
  return out;
}

}  // namespace

std::string RunSummaryJson(const RunSummary& s) {
  Json j;
  j["status"] = s.status;
  j["reason"] = s.reason;
  j["exit_code"] = s.exit_code;
  j["steps"] = s.steps;
  j["time"] = Number(s.time);
  j["end_time"] = Number(s.end_time);
  j["wall_seconds"] = Number(s.wall_seconds);
  j["ms_per_step"] = Number(s.ms_per_step);
  j["resumed_from_step"] = s.resumed_from_step;
  j["title"] = s.title;
  j["version"] = s.version;
  j["fall_window"] = Pair(s.fall_window);
  j["fall_speed"] = Number(s.fall_speed);
  j["diameter"] = Number(s.diameter);
  j["min_gap"] = Number(s.min_gap);
  j["min_wall_gap"] = Number(s.min_wall_gap);
  j["max_trA"] = Number(s.max_trA);
  j["min_eig_A"] = Number(s.min_eig_A);
  j["reynolds"] = Number(s.reynolds);
  j["deborah"] = Number(s.deborah);
  j["mach"] = Number(s.mach);
  j["elasticity"] = Number(s.elasticity);
  Json particles = Json::array();
  for (const RunSummary::Particle& q : s.particles) {
    Json p;
    p["id"] = q.id;
    p["radius"] = Number(q.radius);
    p["position"] = Pair(q.position);
    p["angle"] = Number(q.angle);
    p["velocity"] = Pair(q.velocity);
    p["angular_velocity"] = Number(q.angular_velocity);
    p["force"] = Pair(q.force);
    p["torque"] = Number(q.torque);
    p["fall_speed"] = Number(q.fall_speed);
    particles.push_back(std::move(p));
  }
  j["particles"] = std::move(particles);
  Json diagnostics = Json::object();
  for (const auto& [name, value] : s.diagnostics) diagnostics[name] = Number(value);
  j["diagnostics"] = std::move(diagnostics);
  Json warnings = Json::array();
  for (const RunSummary::Warning& w : s.warnings) {
    Json o;
    o["setting"] = w.setting;
    o["value"] = Number(w.value);
    o["allowed"] = w.allowed;
    o["key"] = w.key;
    o["current"] = w.current;
    o["suggested"] = w.suggested;
    o["source"] = w.source;
    warnings.push_back(std::move(o));
  }
  j["warnings"] = std::move(warnings);
  Json numerics = Json::array();
  for (const RunSummary::Choice& c : s.numerics) {
    Json o;
    o["key"] = c.key;
    o["value"] = c.value;
    o["rule"] = c.rule;
    Json numbers = Json::object();
    for (const auto& [name, value] : c.numbers) numbers[name] = Number(value);
    o["numbers"] = std::move(numbers);
    numerics.push_back(std::move(o));
  }
  // Only when a scheme was chosen: a scene that names every scheme keeps the layout of before.
  if (!numerics.empty()) j["numerics"] = std::move(numerics);
  // One key per line; one line per particle (a run of many particles stays readable).
  std::string out = "{\n";
  for (auto it = j.begin(); it != j.end(); ++it) {
    out += "  " + Inline(Json(it.key())) + ": ";
    if ((it.key() == "particles" || it.key() == "warnings" || it.key() == "numerics") &&
        !it->empty()) {
      out += "[";
      for (std::size_t k = 0; k < it->size(); ++k) {
        out += (k ? ",\n    " : "\n    ") + Inline((*it)[k]);
      }
      out += "\n  ]";
    } else {
      out += Inline(*it);
    }
    out += std::next(it) == j.end() ? "\n" : ",\n";
  }
  return out + "}\n";
}

RunSummary ParseRunSummary(const std::string& text) {
  try {
    const Json j = Json::parse(text);
    RunSummary s;
    s.status = j.at("status").get<std::string>();
    s.reason = j.at("reason").get<std::string>();
    s.exit_code = j.at("exit_code").get<int>();
    s.steps = j.at("steps").get<long>();
    s.time = ReadNumber(j, "time");
    s.end_time = ReadNumber(j, "end_time");
    s.wall_seconds = ReadNumber(j, "wall_seconds");
    s.ms_per_step = ReadNumber(j, "ms_per_step");
    s.resumed_from_step = j.at("resumed_from_step").get<long>();
    s.title = j.at("title").get<std::string>();
    s.version = j.at("version").get<std::string>();
    if (j.contains("fall_window")) s.fall_window = NumberPair(j, "fall_window");
    s.fall_speed = OptionalNumber(j, "fall_speed");
    s.diameter = OptionalNumber(j, "diameter");
    s.min_gap = OptionalNumber(j, "min_gap");
    s.min_wall_gap = OptionalNumber(j, "min_wall_gap");
    s.max_trA = OptionalNumber(j, "max_trA");
    s.min_eig_A = OptionalNumber(j, "min_eig_A");
    s.reynolds = OptionalNumber(j, "reynolds");
    s.deborah = OptionalNumber(j, "deborah");
    s.mach = OptionalNumber(j, "mach");
    s.elasticity = OptionalNumber(j, "elasticity");
    for (const Json& p : j.at("particles")) {
      RunSummary::Particle q;
      q.id = p.at("id").get<long>();
      q.radius = OptionalNumber(p, "radius");
      q.fall_speed = OptionalNumber(p, "fall_speed");
      q.position = NumberPair(p, "position");
      q.angle = OptionalNumber(p, "angle");
      q.velocity = NumberPair(p, "velocity");
      q.angular_velocity = ReadNumber(p, "angular_velocity");
      q.force = NumberPair(p, "force");
      q.torque = ReadNumber(p, "torque");
      s.particles.push_back(q);
    }
    for (const auto& [name, value] : j.at("diagnostics").items()) {
      s.diagnostics.emplace_back(
          name, value.is_null() ? std::numeric_limits<double>::quiet_NaN() : value.get<double>());
    }
    if (j.contains("warnings")) {
      for (const Json& w : j.at("warnings")) {
        RunSummary::Warning v;
        v.setting = w.at("setting").get<std::string>();
        v.value = ReadNumber(w, "value");
        v.allowed = w.at("allowed").get<std::string>();
        v.key = w.at("key").get<std::string>();
        v.current = w.at("current").get<std::string>();
        v.suggested = w.at("suggested").get<std::string>();
        v.source = w.at("source").get<std::string>();
        s.warnings.push_back(std::move(v));
      }
    }
    if (j.contains("numerics")) {
      for (const Json& c : j.at("numerics")) {
        RunSummary::Choice v;
        v.key = c.at("key").get<std::string>();
        v.value = c.at("value").get<std::string>();
        v.rule = c.at("rule").get<std::string>();
        for (const auto& [name, value] : c.at("numbers").items()) {
          v.numbers.emplace_back(name, value.is_null() ? std::numeric_limits<double>::quiet_NaN()
                                                       : value.get<double>());
        }
        s.numerics.push_back(std::move(v));
      }
    }
    return s;
  } catch (const Json::exception& e) {
    throw RunSummaryError(std::string("not a run summary: ") + e.what());
  }
}

void WriteRunSummary(const std::string& path, const RunSummary& summary) {
  WriteTextAtomically(path, RunSummaryJson(summary));
}

RunSummary ReadRunSummary(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw RunSummaryError("cannot read " + path);
  std::ostringstream text;
  text << in.rdbuf();
  try {
    return ParseRunSummary(text.str());
  } catch (const RunSummaryError& e) {
    throw RunSummaryError(path + ": " + e.what());
  }
}

}  // namespace dlmfd::solver
