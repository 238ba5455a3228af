// Conversions between the store's JobRecord and the API's dlmfd.v1.Job. A job that Slurm holds
// waiting (slurm executor) is QUEUED there, its reason Slurm's (job_store.h ShownState).
#pragma once

#include "dlmfd/v1/jobs.pb.h"
#include "job_store.h"

namespace dlmfd::server {

// now: the time a running job's elapsed_seconds counts to (a Clock's, clock.h).
v1::Job ToProto(const JobRecord& job, double now);
// A study and where its jobs stand.
v1::Study ToProto(const StudyRecord& study, const StudyStats& stats);

}  // namespace dlmfd::server
