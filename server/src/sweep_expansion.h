// Sweep expansion: the points of a SubmitSweep request (jobs.proto), one job each.
//
// The grid is the Cartesian product of the axes' values, enumerated with the last axis fastest.
// Each point's overrides are the request's base overrides followed by one key=value per axis; its
// label "key=value,key=value" names the job ("<name>[label]") and an invalid point in errors. The
// axes are checked as a whole before anything is queued (jobs.proto's error contract); the scenes
// of the points are not: each is admitted as a job.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "dlmfd/v1/jobs.pb.h"

namespace dlmfd::server {

struct SweepPoint {
  std::vector<std::string> overrides;
  std::string label;
};

// Throws ServiceError INVALID_ARGUMENT (no axes, an axis without key or values, a key with '=' or a
// line break, a repeated key) or RESOURCE_EXHAUSTED (more than max_points points).
std::vector<SweepPoint> ExpandSweep(const v1::SubmitSweepRequest& request, int64_t max_points);

}  // namespace dlmfd::server
