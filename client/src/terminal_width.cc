#include "terminal_width.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>

namespace dlmfd::cli {

int TerminalColumns() {
  if (const char* env = std::getenv("COLUMNS")) {
    char* end = nullptr;
    const long value = std::strtol(env, &end, 10);
    if (end != env && *end == '\0' && value > 0 && value < 100000) {
      return std::max(kMinColumns, static_cast<int>(value));
    }
  }
  winsize size{};
  if (ioctl(STDOUT_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 0) {
    return std::max(kMinColumns, static_cast<int>(size.ws_col));
  }
  return kDefaultColumns;
}

std::string FitToWidth(const std::vector<LineField>& fields, std::size_t columns) {
  std::vector<LineField> kept;
  for (const LineField& f : fields) {
    if (!f.text.empty()) kept.push_back(f);
  }
  auto joined = [&kept] {
    std::string line;
    for (const LineField& f : kept) line += (line.empty() ? "" : "  ") + f.text;
    return line;
  };
  std::string line = joined();
  while (line.size() > columns && kept.size() > 1) {
    const auto lowest = std::min_element(
        kept.begin(), kept.end(),
        [](const LineField& a, const LineField& b) { return a.priority < b.priority; });
    kept.erase(lowest);
    line = joined();
  }
  if (line.size() > columns) line.resize(columns);
  return line;
}

}  // namespace dlmfd::cli
