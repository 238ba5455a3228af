// The picture of `dlmfd chart --study`: a column of a study's table (study_table.h) against one
// of its parameters, one point per job that has both, joined in increasing x; with a group key,
// one line per value of that parameter, named by the value under a legend titled by the key, in
// increasing value (numbers first, then texts and "not set"). Drawn by viz's LineChart, so the
// CLI and the web dashboard (web/) give the same picture.
#pragma once

#include <string>
#include <vector>

#include "dlmfd/viz/line_chart.h"
#include "study_table.h"

namespace dlmfd::cli {

struct StudyChartSpec {
  std::string study_id;  // for the default title
  std::string x;         // a column (a parameter)
  std::string y;         // a column (a result)
  std::string group;     // a column, or empty: one line
  bool log_x = false;
  bool log_y = false;
  LineChartOptions options;  // size and title; the axes' titles and scales are set here
};

struct StudyChart {
  ChartPicture picture;
  std::vector<std::string> legend;  // the lines' names, in order (empty without a group)
};

// Throws UsageError naming the flag (--x, --y, --group) for an unknown column, or when no job has
// both columns; InvalidParameter from the chart (a log axis without a positive value).
StudyChart DrawStudyChart(const StudyTable& table, const StudyChartSpec& spec);

}  // namespace dlmfd::cli
