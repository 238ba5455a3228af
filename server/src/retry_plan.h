// Retry plan: what a Retry (jobs.proto) changes in one finished job.
//
// The overrides of the next attempt are the job's, each replaced by a change of the same key
// (the text before '='), with new keys appended in the order given. The point's parameters follow
// a change of an axis key, so a study's table shows what ran, and so does the name of a study's
// point ("NAME[key=value,...]", as SubmitStudy names it). The next attempt resumes from the
// last checkpoint only when it runs the same scene (same overrides) and the job did not complete;
// otherwise it starts afresh (a completed job resumed would only replay its end).
#pragma once

#include <string>
#include <vector>

#include "job_store.h"

namespace dlmfd::server {

std::vector<std::string> MergeOverrides(const std::vector<std::string>& current,
                                        const std::vector<std::string>& changes);
std::vector<ParameterValue> UpdatedParameters(const std::vector<ParameterValue>& parameters,
                                              const std::vector<std::string>& changes);
// The name after the parameters changed: a name that ends with the point's "[key=value,...]" of
// `before` gets that of `after`; any other name (one the user gave a single job) is kept.
std::string RenamedPoint(const std::string& name, const std::vector<ParameterValue>& before,
                         const std::vector<ParameterValue>& after);
bool ResumesFromCheckpoint(const JobRecord& job, const std::vector<std::string>& next_overrides);

}  // namespace dlmfd::server
