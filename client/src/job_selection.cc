#include "job_selection.h"

namespace dlmfd::cli {

void AddSelectionFlags(CLI::App& app, JobSelection& selection, CLI::Option* ids) {
  auto* study = app.add_option("--study", selection.study, "every job of this study");
  auto* tags = app.add_option("--tag", selection.tags,
                              "every job carrying this tag (repeatable: all of them)");
  if (ids != nullptr) {
    ids->excludes(study);
    ids->excludes(tags);
  }
}

grpc::Status SelectJobs(Connection& connection, const JobSelection& selection,
                        std::vector<v1::Job>& jobs) {
  v1::ListRequest request;
  request.set_study_id(selection.study);
  for (const std::string& tag : selection.tags) request.add_tags(tag);
  request.set_page_size(1000);
  for (;;) {
    auto context = connection.UnaryContext();
    v1::ListResponse response;
    const grpc::Status status = connection.jobs().List(context.get(), request, &response);
    if (!status.ok()) return status;
    jobs.insert(jobs.end(), response.jobs().begin(), response.jobs().end());
    if (response.next_page_token().empty()) return grpc::Status::OK;
    request.set_page_token(response.next_page_token());
  }
}

std::string SelectionName(const JobSelection& selection) {
  if (!selection.study.empty()) return "study " + selection.study;
  std::string tags;
  for (const std::string& tag : selection.tags) tags += (tags.empty() ? "" : ",") + tag;
  return "tag " + tags;
}

}  // namespace dlmfd::cli
