// dlmfd figure --panel 'plot RUN ...' --panel 'chart RUN ... --y v' ... [--columns N]
//              [--size W,H] [--dpi D] [--font-size PT] [--labels abc|none] [--out FILE]
// dlmfd figure LAYOUT.toml [--out FILE]
// A multi-panel figure, as the paper's (a)-(d): each panel a `plot` or `chart` command line
// (figure_panel.h: their own flags, the same code), drawn into a cell of a grid of N columns with
// the figure's text size, labelled (a), (b), ... in bold at its top left, composed as vectors
// (Canvas::Place) and written as PNG, SVG or PDF at the figure's size and resolution.
// The layout file holds the same: columns, size = [W, H], dpi, font_size, labels, out, and
// [[panel]] tables with command = "plot ..." and an optional label = "(a) t = 0.5".
#include <cctype>
#include <cmath>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "command.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/viz/canvas.h"
#include "exit_codes.h"
#include "figure_panel.h"
#include "rpc_status.h"

namespace dlmfd::cli {
namespace {

struct Panel {
  std::string command;
  std::string label;  // "" : (a), (b), ... by position (unless labels = none)
};

struct Figure {
  std::vector<Panel> panels;
  int columns = 0;           // 0: all panels in one row
  std::vector<double> size;  // inches; default 3 x 4 a panel
  double dpi = 300.0;
  double font_points = 8.0;
  std::string labels = "abc";  // abc or none
  std::string out = "figure.pdf";
};

// Words of a command line: split at blanks outside quotes; '...' and "..." quote, \ escapes.
std::vector<std::string> SplitWords(const std::string& text) {
  std::vector<std::string> words;
  std::string word;
  bool in_word = false;
  char quote = 0;
  for (std::size_t k = 0; k < text.size(); ++k) {
    const char c = text[k];
    if (quote != 0) {
      if (c == quote) {
        quote = 0;
      } else if (c == '\\' && quote == '"' && k + 1 < text.size()) {
        word += text[++k];
      } else {
        word += c;
      }
    } else if (c == '\'' || c == '"') {
      quote = c;
      in_word = true;
    } else if (c == '\\' && k + 1 < text.size()) {
      word += text[++k];
      in_word = true;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      if (in_word) words.push_back(word);
      word.clear();
      in_word = false;
    } else {
      word += c;
      in_word = true;
    }
  }
  if (quote != 0) throw UsageError("--panel '" + text + "': an unclosed quote");
  if (in_word) words.push_back(word);
  return words;
}

void ReadLayout(const std::string& path, Figure& figure) {
  toml::table layout;
  try {
    layout = toml::parse(ReadInputFile(path), path);
  } catch (const toml::parse_error& e) {
    throw UsageError(path + " is not TOML: " + std::string(e.description()));
  }
  for (const auto& [key, value] : layout) {
    const std::string k(key.str());
    if (k == "columns" && value.is_integer()) {
      figure.columns = int(value.as_integer()->get());
    } else if (k == "dpi" && (value.is_number())) {
      figure.dpi = value.value<double>().value();
    } else if (k == "font_size" && value.is_number()) {
      figure.font_points = value.value<double>().value();
    } else if (k == "labels" && value.is_string()) {
      figure.labels = value.as_string()->get();
    } else if (k == "out" && value.is_string()) {
      if (figure.out == "figure.pdf") figure.out = value.as_string()->get();
    } else if (k == "size" && value.is_array() && value.as_array()->size() == 2) {
      figure.size = {value.as_array()->get(0)->value<double>().value_or(0.0),
                     value.as_array()->get(1)->value<double>().value_or(0.0)};
    } else if (k == "panel" && value.is_array_of_tables()) {
      for (const toml::node& node : *value.as_array()) {
        const toml::table& t = *node.as_table();
        Panel panel;
        for (const auto& [panel_key, panel_value] : t) {
          const std::string pk(panel_key.str());
          if (pk == "command" && panel_value.is_string()) {
            panel.command = panel_value.as_string()->get();
          } else if (pk == "label" && panel_value.is_string()) {
            panel.label = panel_value.as_string()->get();
          } else {
            throw UsageError(path + ": panel." + pk +
                             " is not a key of a panel (command = \"plot ...\", label = \"...\")");
          }
        }
        if (panel.command.empty()) throw UsageError(path + ": a [[panel]] without command");
        figure.panels.push_back(panel);
      }
    } else {
      throw UsageError(path + ": " + k +
                       " is not a key of a layout (columns, size = [W, H], dpi, font_size, labels, "
                       "out, [[panel]]) or has the wrong type");
    }
  }
}

// "(a)", "(b)", ... "(z)", "(aa)".
std::string LetterLabel(std::size_t k) {
  std::string letters;
  for (std::size_t n = k + 1; n > 0; n = (n - 1) / 26)
    letters.insert(letters.begin(), char('a' + (n - 1) % 26));
  return "(" + letters + ")";
}

}  // namespace

int RunFigure(int argc, char** argv) {
  CLI::App app{
      "Compose a multi-panel figure from plot and chart command lines, labelled (a), (b), ... "
      "(PNG, SVG or PDF at the figure's size and resolution)."};
  Figure figure;
  std::string layout;
  std::vector<std::string> panels;
  app.add_option("layout", layout, "a layout file (TOML: columns, size, dpi, [[panel]] command)");
  app.add_option("--panel", panels,
                 "one panel: a plot or chart command line without `dlmfd`, e.g. "
                 "'plot runs/a --quantity trA --isolines 12' (repeat, in order)")
      ->allow_extra_args(false);
  app.add_option("--columns", figure.columns, "panels a row (default: all in one row)")
      ->check(CLI::Range(1, 26));
  app.add_option("--size", figure.size, "figure size W,H in inches (default 3 x 4 a panel)")
      ->expected(2)
      ->delimiter(',');
  app.add_option("--dpi", figure.dpi, "resolution (default 300)")->check(CLI::Range(10.0, 4800.0));
  app.add_option("--font-size", figure.font_points, "text size in points (default 8)")
      ->check(CLI::Range(2.0, 200.0));
  app.add_option("--labels", figure.labels, "panel labels: abc ((a), (b), ...) or none")
      ->check(CLI::IsMember({"abc", "none"}));
  app.add_option("--out,-o", figure.out, "file to write: .png, .svg or .pdf (default figure.pdf)");
  if (auto code = ParseArgs(app, argc, argv)) return *code;

  return Guarded("figure", [&] {
    if (!layout.empty()) ReadLayout(layout, figure);
    for (const std::string& p : panels) figure.panels.push_back({p, ""});
    if (figure.panels.empty()) throw UsageError("no panel: give --panel '...' or a layout file");
    FormatOfPath(figure.out);
    const int n = int(figure.panels.size());
    const int columns = figure.columns > 0 ? std::min(figure.columns, n) : n;
    const int rows = (n + columns - 1) / columns;
    if (figure.size.empty()) figure.size = {3.0 * columns, 4.0 * rows};
    if (!(figure.size[0] > 0.0 && figure.size[1] > 0.0))
      throw UsageError("--size W,H needs W, H > 0 inches");
    const int width = int(std::lround(figure.size[0] * figure.dpi));
    const int height = int(std::lround(figure.size[1] * figure.dpi));
    const double fs = figure.font_points * figure.dpi / 72.0;
    const bool labelled = figure.labels != "none";
    const double label_height = labelled ? std::ceil(1.6 * fs) : 0.0;
    const int cell_width = width / columns;
    const int cell_height = height / rows;
    if (cell_width < 100 || cell_height - label_height < 100) {
      throw UsageError("a panel of " + std::to_string(cell_width) + "x" +
                       std::to_string(int(cell_height - label_height)) +
                       " pixels is too small: a larger --size or --dpi, or fewer panels a row");
    }
    Canvas canvas(width, height);
    canvas.SetResolution(figure.dpi);
    for (int k = 0; k < n; ++k) {
      const Panel& panel = figure.panels[std::size_t(k)];
      std::vector<std::string> words = SplitWords(panel.command);
      if (words.empty() || (words[0] != "plot" && words[0] != "chart")) {
        throw UsageError("panel " + std::to_string(k + 1) + " '" + panel.command +
                         "': a panel is a plot or chart command line");
      }
      std::vector<std::string> args = {"dlmfd figure panel " + std::to_string(k + 1) + ": " +
                                       words[0]};
      args.insert(args.end(), words.begin() + 1, words.end());
      std::vector<char*> argv_panel;
      for (std::string& a : args) argv_panel.push_back(a.data());
      argv_panel.push_back(nullptr);
      std::optional<Canvas> drawn;
      PanelRequest request{cell_width, int(cell_height - label_height), fs, &drawn};
      const int code = words[0] == "plot"
                           ? RunPlotPanel(int(args.size()), argv_panel.data(), request)
                           : RunChartPanel(int(args.size()), argv_panel.data(), request);
      if (code != kExitOk || !drawn) return code == kExitOk ? int(kExitUsage) : code;
      const double x = (k % columns) * cell_width;
      const double y = (k / columns) * cell_height;
      canvas.Place(*drawn, x, y + label_height);
      if (labelled) {
        const std::string label = panel.label.empty() ? LetterLabel(std::size_t(k)) : panel.label;
        canvas.Text(x + 0.4 * fs, y + 0.3 * fs, label, fs * 1.1, kAxisColour, Align::kStart,
                    Align::kStart, 0.0, true);
      }
    }
    try {
      canvas.Write(figure.out);
    } catch (const InvalidParameter&) {
      throw;
    } catch (const Error& e) {
      return ReportError("figure", e.what(), kExitLocalIo);
    }
    std::cout << figure.out << "\n";
    std::cerr << "figure: " << n << " panels in " << rows << " x " << columns << ", " << width
              << "x" << height << " pixels (" << figure.size[0] << " x " << figure.size[1]
              << " in at " << figure.dpi << " dpi)\n";
    return kExitOk;
  });
}

}  // namespace dlmfd::cli
