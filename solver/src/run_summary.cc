#include "dlmfd/solver/run_summary.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "dlmfd/io/atomic_file.h"

namespace dlmfd::solver {
namespace {

// Keeps the keys in the order of the contract (the header), which a reader of the text expects.
using Json = nlohmann::ordered_json;

Json Pair(const std::array<double, 2>& v) { return Json::array({v[0], v[1]}); }

// JSON null stands for a non-finite number.
double Number(const Json& j, const char* key) {
  const Json& value = j.at(key);
  if (value.is_null()) return std::numeric_limits<double>::quiet_NaN();
  if (!value.is_number()) throw RunSummaryError(std::string(key) + ": not a number");
  return value.get<double>();
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
  j["time"] = s.time;
  j["end_time"] = s.end_time;
  j["wall_seconds"] = s.wall_seconds;
  j["ms_per_step"] = s.ms_per_step;
  j["resumed_from_step"] = s.resumed_from_step;
  j["title"] = s.title;
  j["version"] = s.version;
  Json particles = Json::array();
  for (const RunSummary::Particle& q : s.particles) {
    Json p;
    p["id"] = q.id;
    p["position"] = Pair(q.position);
    p["velocity"] = Pair(q.velocity);
    p["angular_velocity"] = q.angular_velocity;
    p["force"] = Pair(q.force);
    p["torque"] = q.torque;
    particles.push_back(std::move(p));
  }
  j["particles"] = std::move(particles);
  Json diagnostics = Json::object();
  for (const auto& [name, value] : s.diagnostics) diagnostics[name] = value;
  j["diagnostics"] = std::move(diagnostics);
  // nlohmann writes NaN and infinities as null; invalid UTF-8 in a reason becomes U+FFFD.
  return j.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

RunSummary ParseRunSummary(const std::string& text) {
  try {
    const Json j = Json::parse(text);
    RunSummary s;
    s.status = j.at("status").get<std::string>();
    s.reason = j.at("reason").get<std::string>();
    s.exit_code = j.at("exit_code").get<int>();
    s.steps = j.at("steps").get<long>();
    s.time = Number(j, "time");
    s.end_time = Number(j, "end_time");
    s.wall_seconds = Number(j, "wall_seconds");
    s.ms_per_step = Number(j, "ms_per_step");
    s.resumed_from_step = j.at("resumed_from_step").get<long>();
    s.title = j.at("title").get<std::string>();
    s.version = j.at("version").get<std::string>();
    for (const Json& p : j.at("particles")) {
      RunSummary::Particle q;
      q.id = p.at("id").get<long>();
      q.position = NumberPair(p, "position");
      q.velocity = NumberPair(p, "velocity");
      q.angular_velocity = Number(p, "angular_velocity");
      q.force = NumberPair(p, "force");
      q.torque = Number(p, "torque");
      s.particles.push_back(q);
    }
    for (const auto& [name, value] : j.at("diagnostics").items()) {
      s.diagnostics.emplace_back(
          name, value.is_null() ? std::numeric_limits<double>::quiet_NaN() : value.get<double>());
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
