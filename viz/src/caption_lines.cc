// CaptionLines: greedy wrapping at spaces (never around a lone "="), then the fit of each line
// (smaller font, then "...").
#include "dlmfd/viz/caption_lines.h"

#include <algorithm>

namespace dlmfd {
namespace {

std::vector<std::string> Split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = text.find(separator, start);
    parts.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) return parts;
    start = end + 1;
  }
}

// The units a line may break between: the words, with a lone "=" keeping its neighbours
// ("dt = 0.001" is never split).
std::vector<std::string> Words(const std::string& paragraph) {
  std::vector<std::string> words;
  bool glue_next = false;
  for (const std::string& word : Split(paragraph, ' ')) {
    if (word.empty()) continue;
    if (word == "=" && !words.empty()) {
      words.back() += " =";
      glue_next = true;
    } else if (glue_next) {
      words.back() += " " + word;
      glue_next = false;
    } else {
      words.push_back(word);
    }
  }
  return words;
}

// Removes the last UTF-8 character: its continuation bytes, then its first byte.
void PopCharacter(std::string& text) {
  unsigned char last = 0;
  do {
    last = static_cast<unsigned char>(text.back());
    text.pop_back();
  } while (!text.empty() && (last & 0xC0) == 0x80);
}

// One line fitted into the room: a smaller font first (down to 3/4), then cut with "...".
CaptionLine Fitted(const Canvas& measure, std::string text, double room, double fs, bool bold) {
  const double natural = measure.MeasureText(text, fs, bold).advance;
  const double size = natural > room ? std::max(0.75 * fs, 0.995 * fs * room / natural) : fs;
  if (measure.MeasureText(text, size, bold).advance > room) {
    while (text.size() > 1 && measure.MeasureText(text + "...", size, bold).advance > room) {
      PopCharacter(text);
    }
    text += "...";
  }
  return CaptionLine{text, size, bold};
}

}  // namespace

std::vector<CaptionLine> CaptionLines(const Canvas& measure, const std::string& caption,
                                      double room, double font_size, int max_lines_per_paragraph) {
  std::vector<CaptionLine> lines;
  if (caption.empty()) return lines;
  const std::vector<std::string> paragraphs = Split(caption, '\n');
  for (std::size_t p = 0; p < paragraphs.size(); ++p) {
    const bool bold = p == 0;
    std::vector<std::string> wrapped;
    std::string line;
    for (const std::string& word : Words(paragraphs[p])) {
      const std::string longer = line.empty() ? word : line + " " + word;
      if (line.empty() || measure.MeasureText(longer, font_size, bold).advance <= room) {
        line = longer;
      } else {
        wrapped.push_back(line);
        line = word;
      }
    }
    wrapped.push_back(line);  // an empty paragraph keeps its (blank) line
    const std::size_t kept =
        std::min(wrapped.size(), std::size_t(std::max(1, max_lines_per_paragraph)));
    for (std::size_t k = 0; k < kept; ++k) {
      std::string text = wrapped[k];
      const bool goes_on = k + 1 == kept && kept < wrapped.size();
      if (goes_on) {
        // The rest of the paragraph on its last line: fitted, that is smaller and then cut.
        for (std::size_t rest = kept; rest < wrapped.size(); ++rest) text += " " + wrapped[rest];
      }
      lines.push_back(Fitted(measure, text, room, font_size, bold));
    }
  }
  return lines;
}

}  // namespace dlmfd
