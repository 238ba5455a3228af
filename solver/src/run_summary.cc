#include "dlmfd/io/run_summary.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "dlmfd/io/atomic_file.h"

namespace dlmfd {
namespace {

std::string Number(double x) {
  if (!std::isfinite(x)) return "null";
  char buffer[32];
  for (int digits = 1; digits <= 17; ++digits) {  // the shortest text that reads back as x
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, x);
    if (std::strtod(buffer, nullptr) == x) break;
  }
  return buffer;
}

std::string String(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (c == '\n') {
      out += "\\n";
    } else if (u < 0x20) {
      char buffer[8];
      std::snprintf(buffer, sizeof buffer, "\\u%04x", u);
      out += buffer;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string Pair(const Vec2& v) { return "[" + Number(v.x()) + ", " + Number(v.y()) + "]"; }

}  // namespace

std::string RunSummaryJson(const RunSummary& s) {
  std::ostringstream o;
  o << "{\n";
  o << "  \"status\": " << String(s.status) << ",\n";
  o << "  \"reason\": " << String(s.reason) << ",\n";
  o << "  \"exit_code\": " << s.exit_code << ",\n";
  o << "  \"steps\": " << s.steps << ",\n";
  o << "  \"time\": " << Number(s.time) << ",\n";
  o << "  \"end_time\": " << Number(s.end_time) << ",\n";
  o << "  \"wall_seconds\": " << Number(s.wall_seconds) << ",\n";
  o << "  \"ms_per_step\": " << Number(s.ms_per_step) << ",\n";
  o << "  \"resumed_from_step\": " << s.resumed_from_step << ",\n";
  o << "  \"title\": " << String(s.title) << ",\n";
  o << "  \"version\": " << String(DLMFD_VERSION) << ",\n";
  o << "  \"particles\": [";
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    const ParticleState& q = s.particles[i];
    o << (i ? ",\n" : "\n") << "    {\"id\": " << q.id << ", \"position\": " << Pair(q.position)
      << ", \"velocity\": " << Pair(q.velocity)
      << ", \"angular_velocity\": " << Number(q.angular_velocity)
      << ", \"force\": " << Pair(q.force) << ", \"torque\": " << Number(q.torque) << "}";
  }
  o << (s.particles.empty() ? "],\n" : "\n  ],\n");
  o << "  \"diagnostics\": {";
  for (std::size_t k = 0; k < s.diagnostics.size(); ++k) {
    o << (k ? ", " : "") << String(s.diagnostics[k].first) << ": "
      << Number(s.diagnostics[k].second);
  }
  o << "}\n";
  o << "}\n";
  return o.str();
}

void WriteRunSummary(const std::string& path, const RunSummary& summary) {
  WriteTextAtomically(path, RunSummaryJson(summary));
}

}  // namespace dlmfd
