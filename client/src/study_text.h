// How studies look: the `studies` table, the details of one study, and the aggregate of a set of
// jobs (a study or a tag) that `show` and `watch` print.
//
// Aggregate ETA: the work of a job is its simulated time over its end time (a finished job counts
// 1); the rate is the work done so far (every job started) over the wall time since the first
// start, and the ETA is the remaining work (queued and running jobs) over that rate. It assumes
// the points cost about the same and the concurrency stays as it was; "-" until work was done.
#pragma once

#include <string>
#include <vector>

#include "dlmfd/v1/jobs.pb.h"
#include "terminal_width.h"

namespace dlmfd::cli {

struct StudyCounts {
  int jobs = 0, queued = 0, running = 0, completed = 0, failed = 0, cancelled = 0;
  double work_done = 0;      // sum of the jobs' fractions done
  double first_started = 0;  // epoch seconds; 0: nothing started
  bool Finished() const { return jobs > 0 && queued == 0 && running == 0; }
};

StudyCounts CountJobs(const std::vector<v1::Job>& jobs);
// Seconds to the end of the queued and running jobs at `now`, or -1 when unknown.
double StudyEta(const StudyCounts& counts, double now);
// "12 jobs: 2 queued, 3 running, 6 completed, 1 failed, 0 cancelled" and progress, ETA, as fields.
std::vector<LineField> StudyFields(const std::string& label, const StudyCounts& counts,
                                   double eta_seconds);

// The `studies` table: ID, NAME, TAGS, JOBS, QUEUED, RUNNING, DONE, FAILED, CANCELLED, PROGRESS,
// AGE.
std::string StudyListText(const std::vector<v1::Study>& studies, double now);
// "key: value" lines describing one study (its axes, limit, counts).
std::string StudyDetails(const v1::Study& study);
// The text of an axis as `study` takes it back ("key=v1,v2", "key=lin:1:2:5").
std::string AxisText(const v1::StudyAxis& axis);

}  // namespace dlmfd::cli
