// Server-sent events (text/event-stream) that keep the dashboard's pages live without reloading,
// fed by the daemon's own Watch streams (job_watch_set.h):
//   /events/overview      the studies page: its studies' counts (event `overview`, the same JSON
//                         as /api/overview), sent again within 0.3 s of any event of an unfinished
//                         job, and every 3 s (new studies, new jobs);
//   /events/studies/ID     a study page: `job` (a state change: the whole job), `progress`,
//                         `snapshot` (a new field picture exists), `study` (the study's counts);
//   /events/jobs/ID       a job page: `job`, `progress`, `particles`, `snapshot`, `log`.
// Every stream may also say `daemon` ({connected: false, message} when the daemon is lost,
// {connected: true} when found again), `gone` (the job or study no longer exists for this user)
// and `resync` (events were dropped or missed: the page reloads what it shows). A page's stream
// starts after the study or job was found for the user (else an HTTP error), and is polled every
// 2-3 s besides (a retried job is followed again). A comment every 5 s finds a closed page; its
// streams are then cancelled. At most max_live_pages streams at once (503 beyond).
#pragma once

#include <httplib.h>

#include <string>

#include "web_context.h"

namespace dlmfd::web {

void ServeOverviewEvents(WebContext& context, const Caller& caller, httplib::Response& res);
void ServeStudyEvents(WebContext& context, const Caller& caller, const std::string& study_id,
                      httplib::Response& res);
void ServeJobEvents(WebContext& context, const Caller& caller, const std::string& job_id,
                    httplib::Response& res);

// The studies page's JSON: {"studies": [Study...], "jobs": [recent jobs outside studies]}, and the
// unfinished jobs of both (to follow) through *unfinished when not null.
grpc::Status OverviewJson(WebContext& context, const std::string& token, std::string* json,
                          std::vector<v1::Job>* unfinished);

}  // namespace dlmfd::web
