#include "job_table.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>

#include "dlmfd/solver/run_summary.h"

namespace dlmfd::server {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// TOML's integer: [+-]digits with single '_' between digits; false when it is not one or overflows.
bool ParseTomlInteger(const std::string& text, int64_t* out) {
  std::string digits;
  size_t i = 0;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) digits += text[i++];
  if (i == text.size()) return false;
  bool previous_digit = false;
  for (; i < text.size(); ++i) {
    const char c = text[i];
    if (c >= '0' && c <= '9') {
      digits += c;
      previous_digit = true;
    } else if (c == '_' && previous_digit && i + 1 < text.size()) {
      previous_digit = false;
    } else {
      return false;
    }
  }
  if (!previous_digit) return false;
  errno = 0;
  char* end = nullptr;
  const long long value = std::strtoll(digits.c_str(), &end, 10);
  if (errno == ERANGE || *end != '\0') return false;
  *out = value;
  return true;
}

// TOML's float: a number with a fraction or an exponent, or [+-]inf / [+-]nan.
bool ParseTomlFloat(const std::string& text, double* out) {
  std::string body = text;
  std::string sign;
  if (!body.empty() && (body[0] == '+' || body[0] == '-')) {
    sign = body.substr(0, 1);
    body = body.substr(1);
  }
  if (body == "inf" || body == "nan") {
    *out = body == "inf" ? std::numeric_limits<double>::infinity() : kNaN;
    if (sign == "-") *out = -*out;
    return true;
  }
  if (body.find_first_of(".eE") == std::string::npos) return false;
  std::string plain;
  for (char c : text) {
    if (c != '_') plain += c;
  }
  if (plain.empty() || plain.find_first_not_of("+-.0123456789eE") != std::string::npos)
    return false;
  char* end = nullptr;
  const double value = std::strtod(plain.c_str(), &end);
  if (end == plain.c_str() || *end != '\0') return false;
  *out = value;
  return true;
}

}  // namespace

v1::Parameter TypedParameter(const std::string& override_text) {
  v1::Parameter p;
  const size_t eq = override_text.find('=');
  const std::string key = override_text.substr(0, eq);
  const std::string value = eq == std::string::npos ? "" : override_text.substr(eq + 1);
  p.set_key(key);
  int64_t integer = 0;
  double real = 0.0;
  if (ParseTomlInteger(value, &integer)) {
    p.set_int_value(integer);
  } else if (ParseTomlFloat(value, &real)) {
    p.set_double_value(real);
  } else if (value == "true" || value == "false") {
    p.set_bool_value(value == "true");
  } else if (value.size() >= 2 && value.front() == '"' && value.back() == '"') {
    p.set_text_value(value.substr(1, value.size() - 2));
  } else {
    p.set_text_value(value);
  }
  return p;
}

v1::TableRow TableRowOf(const JobRecord& job) {
  v1::TableRow row;
  row.set_job_id(job.id);
  row.set_name(job.name);
  row.set_state(static_cast<v1::JobState>(job.state));
  for (const std::string& o : job.overrides) *row.add_parameters() = TypedParameter(o);
  for (auto set :
       {&v1::TableRow::set_time, &v1::TableRow::set_wall_seconds, &v1::TableRow::set_fall_speed,
        &v1::TableRow::set_min_gap, &v1::TableRow::set_min_wall_gap, &v1::TableRow::set_max_tra,
        &v1::TableRow::set_min_eig_a, &v1::TableRow::set_reynolds, &v1::TableRow::set_deborah,
        &v1::TableRow::set_elasticity, &v1::TableRow::set_mach}) {
    (row.*set)(kNaN);
  }
  const std::filesystem::path file =
      std::filesystem::path(job.results_dir) / solver::kRunSummaryFile;
  solver::RunSummary s;
  try {
    // A summary is written by rename, so it is whole or absent; a link is not the solver's.
    if (std::filesystem::is_symlink(file) || !std::filesystem::is_regular_file(file)) return row;
    s = solver::ReadRunSummary(file.string());
  } catch (const std::exception&) {
    return row;
  }
  row.set_has_summary(true);
  row.set_status(s.status);
  row.set_reason(s.reason);
  row.set_steps(s.steps);
  row.set_time(s.time);
  row.set_wall_seconds(s.wall_seconds);
  row.set_fall_speed(s.fall_speed);
  row.set_min_gap(s.min_gap);
  row.set_min_wall_gap(s.min_wall_gap);
  row.set_max_tra(s.max_trA);
  row.set_min_eig_a(s.min_eig_A);
  row.set_reynolds(s.reynolds);
  row.set_deborah(s.deborah);
  row.set_elasticity(s.elasticity);
  row.set_mach(s.mach);
  for (const solver::RunSummary::Particle& q : s.particles) {
    v1::ParticleRow* p = row.add_particles();
    p->set_id(q.id);
    p->set_radius(q.radius);
    p->set_x(q.position[0]);
    p->set_y(q.position[1]);
    p->set_u(q.velocity[0]);
    p->set_v(q.velocity[1]);
    p->set_angular_velocity(q.angular_velocity);
    p->set_force_x(q.force[0]);
    p->set_force_y(q.force[1]);
    p->set_torque(q.torque);
    p->set_fall_speed(q.fall_speed);
    p->set_angle(q.angle);
  }
  return row;
}

}  // namespace dlmfd::server
