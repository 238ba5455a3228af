// The rows of the Table rpc (jobs.proto): a job's parameters, typed, and the quantities of its
// results/summary.json (solver/include/dlmfd/solver/run_summary.h, docs/results.md).
//
// Parameters are the job's overrides "key=value" (for a study: the base overrides and the point's),
// each value typed as TOML reads a scalar: an integer (decimal, with optional sign and '_'
// separators), a float (with a '.', an exponent, inf or nan), true/false, a basic string in double
// quotes (its escapes left as written), else the text as given (an array, a table).
#pragma once

#include <string>

#include "dlmfd/v1/jobs.pb.h"
#include "job_store.h"

namespace dlmfd::server {

// key and value of one "key=value" override, the value typed.
v1::Parameter TypedParameter(const std::string& override_text);

// The row of one job: its record, and its summary.json when the results directory has a readable
// one (has_summary); every summary number absent is NaN.
v1::TableRow TableRowOf(const JobRecord& job);

}  // namespace dlmfd::server
