// `watch --study S | --tag T`: one aggregate line for a set of jobs, until every job has finished.
//
// The jobs are read with List every `interval` seconds (a study has no event stream of its own).
// live (a terminal): "s-... 12 jobs  2 queued  3 running  6 done  1 failed  58%  ETA 3m10s",
//   rewritten in place and held to the terminal's width, with each job's end on a line above it;
// plain: the line when a count changes, and each job's end;
// json: one JSON object per change of the counts ({"study": ..., "jobs": ..., "queued": ..., ...,
//   "progress": ..., "eta_seconds": ...}), numbers as numbers.
// Exit: 0 when every job completed, 1 when one failed or was cancelled, 130 on Ctrl-C (the jobs go
// on), or the code of an rpc error. The ETA is study_text.h's.
#pragma once

#include <ostream>

#include "connection.h"
#include "job_selection.h"
#include "progress_printer.h"

namespace dlmfd::cli {

int WatchStudy(Connection& connection, const JobSelection& selection, PrintMode mode,
               std::ostream& out, double interval_seconds);

}  // namespace dlmfd::cli
