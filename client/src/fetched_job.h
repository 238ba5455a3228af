// The job a fetched results directory came from: `dlmfd fetch` writes DIR/job.json (the job as
// `dlmfd show JOB --json` prints it, one line: id, name, overrides, parameters, study, tags, state
// at the fetch, ...) next to the solver's files, because the solver's own files know the scene as
// run (scene.toml, overrides applied) but not the job's name or which keys were overridden.
// `dlmfd plot DIR` and `dlmfd movie DIR` read it back to caption a fetched run as they caption
// the job itself (plot_options.h: JobCaption). docs/results.md lists the file.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "dlmfd/v1/jobs.pb.h"

namespace dlmfd::cli {

inline constexpr char kFetchedJobFile[] = "job.json";

// Writes DIR/job.json through a temporary name (dlmfd/io/atomic_file.h).
void WriteFetchedJob(const std::filesystem::path& dir, const v1::Job& job);
// The job of DIR/job.json; nullopt when DIR has none. Throws InvalidParameter when it is not a
// job's JSON (plot and movie: exit 2), Error when it cannot be read; unknown fields (a newer
// client's) are ignored.
std::optional<v1::Job> ReadFetchedJob(const std::string& dir);

}  // namespace dlmfd::cli
