// CaptionLines: a picture's caption laid out in the width it has.
//
// The caption is paragraphs separated by '\n'; the first is the title (bold). Each paragraph is
// wrapped at spaces (not around a lone "=": "dt = 0.001" stays whole) into lines no wider than
// `room` pixels, at most `max_lines_per_paragraph` lines: a caption that names a job and its
// swept parameters reads whole on a narrow picture of a tall domain, instead of being cut. A word
// wider than the room alone, or the last allowed line of a paragraph that goes on, is drawn
// smaller (down to 3/4 of the font size) and then cut with "..." (at a UTF-8 character boundary).
#pragma once

#include <string>
#include <vector>

#include "dlmfd/viz/canvas.h"

namespace dlmfd {

struct CaptionLine {
  std::string text;
  double size = 0.0;  // font size in pixels
  bool bold = false;
};

inline constexpr int kCaptionLinesPerParagraph = 3;

std::vector<CaptionLine> CaptionLines(const Canvas& measure, const std::string& caption,
                                      double room, double font_size,
                                      int max_lines_per_paragraph = kCaptionLinesPerParagraph);

}  // namespace dlmfd
