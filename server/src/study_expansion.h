// Study expansion: the points of a SubmitStudy request (jobs.proto), one job each.
//
// Axes: each gives TOML value texts, or a range of `count` values from start to stop (both
// included; linear: start + (stop - start) k / (count - 1); logarithmic: start (stop / start)^(k /
// (count - 1)), start and stop of one sign), written with 12 significant digits, always as a TOML
// float. Axes with an empty `zip` are dimensions of their own; axes
// sharing a `zip` name are one dimension whose k-th point takes the k-th value of each (equal
// lengths). The points are the Cartesian product of the dimensions, enumerated with the last
// dimension fastest. Each point's overrides are the request's base overrides followed by one
// key=value per axis (in the request's order); its label "key=value,key=value" names the job
// ("<name>[label]") and an invalid point in errors; its parameters are the same values typed
// (scene_values.h). The axes are checked as a whole before anything is queued (jobs.proto's error
// contract); the scenes of the points are not: each is admitted as a job.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "dlmfd/v1/jobs.pb.h"
#include "job_store.h"

namespace dlmfd::server {

struct StudyPoint {
  std::vector<std::string> overrides;
  std::string label;
  std::vector<ParameterValue> parameters;
};

struct StudyPlan {
  std::vector<StoredAxis> axes;  // ranges expanded
  std::vector<StudyPoint> points;
};

inline constexpr int kMaxRangeCount = 10000;

// Throws ServiceError INVALID_ARGUMENT (no axes, an axis without key or values, a key with '=' or a
// line break, a repeated key, values and a range both, a bad range, zipped axes of unequal
// lengths, a value with a tab or line break) or RESOURCE_EXHAUSTED (more than max_points points).
StudyPlan ExpandStudy(const v1::SubmitStudyRequest& request, int64_t max_points);

}  // namespace dlmfd::server
