#include "time_limit_text.h"

#include <cctype>
#include <stdexcept>
#include <vector>

namespace dlmfd::cli {
namespace {

constexpr int64_t kMostSeconds = int64_t{1} << 40;  // far beyond any limit; keeps sums exact

[[noreturn]] void Bad(const std::string& text, const std::string& why) {
  throw std::invalid_argument(
      "--time " + text + ": " + why +
      " (expected a positive duration: 90m, 2h, 1h30m, 45s, 1d; or as sbatch --time: minutes, "
      "MM:SS, HH:MM:SS, D-HH, D-HH:MM, D-HH:MM:SS)");
}

// The digits of `part` as a number; Bad when it is not one.
int64_t Number(const std::string& text, const std::string& part) {
  if (part.empty() || part.size() > 9) Bad(text, "\"" + part + "\" is not a number");
  for (char c : part) {
    if (!std::isdigit(static_cast<unsigned char>(c))) Bad(text, "\"" + part + "\" is not a number");
  }
  return std::stoll(part);
}

std::vector<std::string> Split(const std::string& text, char sep) {
  std::vector<std::string> parts(1);
  for (char c : text) {
    if (c == sep) {
      parts.emplace_back();
    } else {
      parts.back() += c;
    }
  }
  return parts;
}

// "1h30m": numbers each followed by a unit (d, h, m, s), each unit at most once, in that order.
int64_t WithUnits(const std::string& text) {
  static const std::string kUnits = "dhms";
  static const int64_t kSeconds[] = {86400, 3600, 60, 1};
  int64_t total = 0;
  size_t next_unit = 0;
  std::string digits;
  for (char c : text) {
    if (std::isdigit(static_cast<unsigned char>(c))) {
      digits += c;
      continue;
    }
    const size_t unit = kUnits.find(c);
    if (unit == std::string::npos) Bad(text, std::string("unknown unit '") + c + "'");
    if (digits.empty()) Bad(text, std::string("no number before '") + c + "'");
    if (unit < next_unit) Bad(text, "units must come once each, largest first");
    total += Number(text, digits) * kSeconds[unit];
    next_unit = unit + 1;
    digits.clear();
  }
  if (!digits.empty()) Bad(text, "a number without a unit after another with one");
  return total;
}

// sbatch's forms: [D-]H..., minutes alone, MM:SS, HH:MM:SS.
int64_t SlurmForm(const std::string& text) {
  int64_t days = 0;
  std::string clock = text;
  const size_t dash = text.find('-');
  if (dash != std::string::npos) {
    days = Number(text, text.substr(0, dash));
    clock = text.substr(dash + 1);
  }
  std::vector<int64_t> fields;
  for (const std::string& part : Split(clock, ':')) fields.push_back(Number(text, part));
  if (fields.size() > 3) Bad(text, "more than three fields");
  if (dash != std::string::npos) {
    // days-hours[:minutes[:seconds]]
    const int64_t hours = fields[0];
    const int64_t minutes = fields.size() > 1 ? fields[1] : 0;
    const int64_t seconds = fields.size() > 2 ? fields[2] : 0;
    return ((days * 24 + hours) * 60 + minutes) * 60 + seconds;
  }
  if (fields.size() == 1) return fields[0] * 60;              // minutes
  if (fields.size() == 2) return fields[0] * 60 + fields[1];  // minutes:seconds
  return (fields[0] * 60 + fields[1]) * 60 + fields[2];       // hours:minutes:seconds
}

}  // namespace

int64_t ParseTimeLimit(const std::string& text) {
  if (text.empty()) Bad(text, "empty");
  const bool units = text.find_first_of("dhms") != std::string::npos;
  const int64_t seconds = units ? WithUnits(text) : SlurmForm(text);
  if (seconds <= 0) Bad(text, "not positive (give no --time for the daemon's limit)");
  if (seconds > kMostSeconds) Bad(text, "too long");
  return seconds;
}

}  // namespace dlmfd::cli
