// job.json of a fetched results directory: the job as JSON, written by fetch, read by the captions.
#include "fetched_job.h"

#include <google/protobuf/util/json_util.h>

#include <system_error>

#include "dlmfd/core/errors.h"
#include "dlmfd/io/atomic_file.h"
#include "job_text.h"

namespace dlmfd::cli {

void WriteFetchedJob(const std::filesystem::path& dir, const v1::Job& job) {
  WriteTextAtomically((dir / kFetchedJobFile).string(), ToJsonLine(job) + "\n");
}

std::optional<v1::Job> ReadFetchedJob(const std::string& dir) {
  const std::filesystem::path path = std::filesystem::path(dir) / kFetchedJobFile;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return std::nullopt;
  const std::string text = ReadTextFile(path.string());
  google::protobuf::util::JsonParseOptions options;
  options.ignore_unknown_fields = true;
  v1::Job job;
  const auto status = google::protobuf::util::JsonStringToMessage(text, &job, options);
  if (!status.ok()) {
    throw InvalidParameter(path.string(),
                           "unreadable as a job (" + std::string(status.message()) + ")",
                           "the job's JSON that dlmfd fetch writes (or no such file)");
  }
  return job;
}

}  // namespace dlmfd::cli
