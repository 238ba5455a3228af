// The width of the terminal a live line is drawn on, and fitting a line into it.
//
// Width: $COLUMNS when it is a positive number (what the shell says, and what a test sets), else
// the TIOCGWINSZ size of stdout, else 80. A live line is held to width - 1 columns: writing the
// last column leaves some terminals in a pending wrap, and the next "\r" then rewrites the line
// below instead (one line per update, the bug of issue 14). Fields are dropped by priority, the
// least important first, and only what is left of the most important is cut.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace dlmfd::cli {

inline constexpr int kDefaultColumns = 80;
inline constexpr int kMinColumns = 20;

// The terminal's columns (at least kMinColumns).
int TerminalColumns();

struct LineField {
  std::string text;
  int priority;  // higher stays longer
};

// The fields joined by two spaces, in their order, in at most `columns` characters.
std::string FitToWidth(const std::vector<LineField>& fields, std::size_t columns);

}  // namespace dlmfd::cli
