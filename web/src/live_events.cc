#include "live_events.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <functional>
#include <map>
#include <memory>

#include "http_reply.h"
#include "job_text.h"
#include "job_watch_set.h"

namespace dlmfd::web {
namespace {

using Clock = std::chrono::steady_clock;
using nlohmann::json;

std::string Sse(const std::string& event, const std::string& data) {
  return "event: " + event + "\ndata: " + data + "\n\n";
}

// One open page's stream: its watches, what it last sent, and its own periodic work.
struct LivePage {
  LivePage(WebContext& c, const Caller& caller, bool snapshots)
      : context(c),
        token(caller.token),
        watches(c.link, caller.token, snapshots) {
    ++context.live_pages;
  }
  ~LivePage() { --context.live_pages; }
  WebContext& context;
  std::string token;
  JobWatchSet watches;
  std::map<std::string, v1::JobState> states;  // last state seen of each job
  Clock::time_point last_write = Clock::now();
  Clock::time_point last_poll;  // epoch: poll at once
  Clock::time_point last_summary_at;
  bool dirty = false;  // an event came since the counts were last sent
  bool started = false;
  bool daemon_down = false;  // the daemon was last seen unreachable
  bool call_failed = false;  // a daemon call of this poll failed
  std::string last_summary;  // the last `overview` or `study` JSON sent
  // Called at start and every poll_every; returns events to send.
  std::function<std::string(LivePage&)> poll;
  std::function<std::string(LivePage&)> summary;  // the study's or studies' counts, when dirty
  std::chrono::milliseconds poll_every{2000};
};

std::string TranslateEvent(LivePage& page, const std::string& job_id, const v1::WatchEvent& e) {
  if (e.has_state()) {
    page.states[job_id] = e.state().state();
    page.dirty = true;
    v1::Job job = e.state().job();
    if (job.id().empty()) job.set_id(job_id);
    job.set_state(e.state().state());
    return Sse("job", MessageJson(job));
  }
  if (e.has_progress()) {
    const v1::JobProgress& p = e.progress();
    page.dirty = true;
    return Sse("progress", JsonText({{"job_id", job_id},
                                     {"wall_time", JsonNumber(e.wall_time())},
                                     {"step", p.step()},
                                     {"time", JsonNumber(p.time())},
                                     {"end_time", JsonNumber(p.end_time())},
                                     {"steps_per_second", JsonNumber(p.steps_per_second())},
                                     {"eta_seconds", JsonNumber(p.eta_seconds())},
                                     {"max_trA", JsonNumber(p.max_tra())},
                                     {"min_eig_A", JsonNumber(p.min_eig_a())}}));
  }
  if (e.has_particles()) {
    json particles = json::array();
    for (const v1::Particle& q : e.particles().particles()) {
      particles.push_back({{"id", q.id()},
                           {"x", JsonNumber(q.x())},
                           {"y", JsonNumber(q.y())},
                           {"u", JsonNumber(q.u())},
                           {"v", JsonNumber(q.v())},
                           {"omega", JsonNumber(q.omega())}});
    }
    return Sse("particles", JsonText({{"job_id", job_id},
                                      {"step", e.particles().step()},
                                      {"time", JsonNumber(e.particles().time())},
                                      {"particles", particles}}));
  }
  if (e.has_snapshot()) {
    return Sse("snapshot", JsonText({{"job_id", job_id},
                                     {"step", e.snapshot().step()},
                                     {"time", JsonNumber(e.snapshot().time())}}));
  }
  if (e.has_log()) {
    return Sse(
        "log",
        JsonText({{"job_id", job_id}, {"level", e.log().level()}, {"text", e.log().text()}}));
  }
  if (e.has_gap()) {
    return Sse("resync",
               JsonText({{"job_id", job_id},
                         {"reason", "missed events " + std::to_string(e.gap().from_seq()) + " to " +
                                        std::to_string(e.gap().to_seq()) + " (" + e.gap().reason() +
                                        ")"}}));
  }
  return {};
}

bool Pump(LivePage& page, httplib::DataSink& sink) {
  if (page.context.stopping) {
    sink.done();
    return true;
  }
  std::string out;
  if (!page.started) {
    page.started = true;
    out += "retry: 1000\n\n";
  }
  const auto now = Clock::now();
  if (now - page.last_poll >= page.poll_every) {
    page.last_poll = now;
    page.call_failed = false;
    const std::string polled = page.poll(page);
    if (!page.call_failed && page.daemon_down) {
      out += Sse("daemon", JsonText({{"connected", true}}));
      out += Sse("resync", JsonText({{"reason", "the daemon is back"}}));
    }
    page.daemon_down = page.call_failed;
    out += polled;
  }
  const WatchBatch batch = page.watches.Next(std::chrono::milliseconds(250));
  for (const WatchItem& item : batch.items) {
    switch (item.kind) {
      case WatchItem::Kind::kEvent:
        out += TranslateEvent(page, item.job_id, item.event);
        break;
      case WatchItem::Kind::kEnded:
        if (item.status.error_code() == grpc::StatusCode::NOT_FOUND) {
          out += Sse("gone",
                     JsonText({{"job_id", item.job_id}, {"message", item.status.error_message()}}));
        } else if (!item.status.ok()) {
          out += Sse("daemon", JsonText({{"connected", false},
                                         {"message", "daemon: " + item.status.error_message()}}));
        }
        break;
      case WatchItem::Kind::kLost:
        page.daemon_down = true;
        out += Sse("daemon",
                   JsonText({{"connected", false},
                             {"message", "the daemon at " + page.context.link.address() +
                                             " cannot be reached (" + item.status.error_message() +
                                             "); reconnecting"}}));
        break;
      case WatchItem::Kind::kRestored:
        page.daemon_down = false;
        out += Sse("daemon", JsonText({{"connected", true}}));
        out += Sse("resync", JsonText({{"reason", "the daemon is back"}}));
        page.dirty = true;
        break;
    }
  }
  if (batch.dropped > 0) {
    out += Sse("resync", JsonText({{"reason", std::to_string(batch.dropped) +
                                                  " events dropped (the page read too slowly)"}}));
  }
  // The counts at most every 0.3 s while events come.
  if (page.dirty && page.summary &&
      Clock::now() - page.last_summary_at >= std::chrono::milliseconds(300)) {
    page.dirty = false;
    page.last_summary_at = Clock::now();
    out += page.summary(page);
  }
  if (out.empty() && Clock::now() - page.last_write >= std::chrono::seconds(5)) out = ": ping\n\n";
  if (out.empty()) return true;
  page.last_write = Clock::now();
  return sink.write(out.data(), out.size());
}

void StartStream(httplib::Response& res, std::shared_ptr<LivePage> page) {
  res.set_header("Cache-Control", "no-store");
  res.set_header("X-Accel-Buffering", "no");
  res.set_chunked_content_provider(
      "text/event-stream", [page](size_t, httplib::DataSink& sink) { return Pump(*page, sink); },
      [page](bool) mutable { page.reset(); });
}

bool RoomForPage(WebContext& context, httplib::Response& res) {
  if (context.live_pages.load() < context.options.max_live_pages) return true;
  ReplyError(res, 503,
             "too many live pages are open (max_live_pages = " +
                 std::to_string(context.options.max_live_pages) + "); close some and reload");
  return false;
}

bool Final(v1::JobState state) {
  return state == v1::COMPLETED || state == v1::FAILED || state == v1::CANCELLED;
}

// Follows the job when it is unfinished and not yet followed (within the page's bound).
void FollowUnfinished(LivePage& page, const v1::Job& job) {
  if (Final(job.state()) || page.watches.Follows(job.id())) return;
  if (page.watches.Active() >= static_cast<size_t>(page.context.options.max_watched_jobs)) return;
  page.watches.Follow(job.id(), job.last_seq());
}

grpc::Status ListAll(WebContext& context, const std::string& token, v1::ListRequest request,
                     std::vector<v1::Job>* jobs, size_t max_jobs) {
  request.set_page_size(1000);
  while (true) {
    v1::ListResponse response;
    const grpc::Status status =
        context.link.jobs().List(context.link.Unary(token).get(), request, &response);
    if (!status.ok()) return status;
    for (const v1::Job& job : response.jobs()) {
      if (jobs->size() >= max_jobs) return grpc::Status::OK;
      jobs->push_back(job);
    }
    if (response.next_page_token().empty()) return grpc::Status::OK;
    request.set_page_token(response.next_page_token());
  }
}

// A daemon call of the page's poll failed: the page says so, and is told when a later poll works.
std::string DaemonDown(LivePage& page, const grpc::Status& status) {
  page.call_failed = true;
  return Sse("daemon",
             JsonText({{"connected", false}, {"message", "daemon: " + status.error_message()}}));
}

}  // namespace

grpc::Status OverviewJson(WebContext& context, const std::string& token, std::string* out,
                          std::vector<v1::Job>* unfinished) {
  json studies = json::array();
  v1::ListStudiesRequest studies_request;
  studies_request.set_page_size(1000);
  v1::ListStudiesResponse studies_response;
  grpc::Status status = context.link.jobs().ListStudies(context.link.Unary(token).get(),
                                                        studies_request, &studies_response);
  if (!status.ok()) return status;
  for (const v1::Study& study : studies_response.studies()) {
    studies.push_back(json::parse(MessageJson(study), nullptr, false));
  }
  // Recent jobs outside studies (the newest 30) and every unfinished job, to follow.
  v1::ListRequest request;
  request.set_page_size(200);
  v1::ListResponse recent;
  status = context.link.jobs().List(context.link.Unary(token).get(), request, &recent);
  if (!status.ok()) return status;
  json jobs = json::array();
  for (const v1::Job& job : recent.jobs()) {
    if (job.study_id().empty() && jobs.size() < 30) {
      jobs.push_back(json::parse(MessageJson(job), nullptr, false));
    }
  }
  if (unfinished != nullptr) {
    v1::ListRequest open;
    open.add_states(v1::QUEUED);
    open.add_states(v1::RUNNING);
    std::vector<v1::Job> open_jobs;
    status = ListAll(context, token, open, &open_jobs,
                     static_cast<size_t>(context.options.max_watched_jobs));
    if (!status.ok()) return status;
    for (const v1::Job& job : open_jobs) unfinished->push_back(job);
  }
  *out = JsonText({{"studies", studies}, {"jobs", jobs}});
  return grpc::Status::OK;
}

void ServeOverviewEvents(WebContext& context, const Caller& caller, httplib::Response& res) {
  if (!RoomForPage(context, res)) return;
  auto page = std::make_shared<LivePage>(context, caller, false);
  page->poll_every = std::chrono::milliseconds(3000);
  page->summary = [](LivePage& p) -> std::string {
    std::string overview;
    const grpc::Status status = OverviewJson(p.context, p.token, &overview, nullptr);
    if (!status.ok()) return DaemonDown(p, status);
    if (overview == p.last_summary) return {};
    p.last_summary = overview;
    return Sse("overview", overview);
  };
  page->poll = [](LivePage& p) -> std::string {
    std::string overview;
    std::vector<v1::Job> unfinished;
    const grpc::Status status = OverviewJson(p.context, p.token, &overview, &unfinished);
    if (!status.ok()) return DaemonDown(p, status);
    for (const v1::Job& job : unfinished) FollowUnfinished(p, job);
    if (overview == p.last_summary) return {};
    p.last_summary = overview;
    return Sse("overview", overview);
  };
  StartStream(res, page);
}

void ServeStudyEvents(WebContext& context, const Caller& caller, const std::string& study_id,
                      httplib::Response& res) {
  v1::GetStudyRequest request;
  request.set_study_id(study_id);
  v1::Study study;
  const grpc::Status status =
      context.link.jobs().GetStudy(context.link.Unary(caller.token).get(), request, &study);
  if (!status.ok()) return ReplyRpcError(res, status);
  if (!RoomForPage(context, res)) return;
  auto page = std::make_shared<LivePage>(context, caller, true);
  page->summary = [study_id](LivePage& p) -> std::string {
    v1::GetStudyRequest get;
    get.set_study_id(study_id);
    v1::Study now;
    const grpc::Status s =
        p.context.link.jobs().GetStudy(p.context.link.Unary(p.token).get(), get, &now);
    if (s.error_code() == grpc::StatusCode::NOT_FOUND) {
      return Sse("gone", JsonText({{"study_id", study_id}, {"message", s.error_message()}}));
    }
    if (!s.ok()) return DaemonDown(p, s);
    const std::string text = MessageJson(now);
    if (text == p.last_summary) return {};
    p.last_summary = text;
    return Sse("study", text);
  };
  page->poll = [study_id](LivePage& p) -> std::string {
    v1::ListRequest list;
    list.set_study_id(study_id);
    std::vector<v1::Job> jobs;
    const grpc::Status s = ListAll(p.context, p.token, list, &jobs, 100000);
    if (s.error_code() == grpc::StatusCode::NOT_FOUND) {
      return Sse("gone", JsonText({{"study_id", study_id}, {"message", s.error_message()}}));
    }
    if (!s.ok()) return DaemonDown(p, s);
    std::string out;
    for (const v1::Job& job : jobs) {
      auto known = p.states.find(job.id());
      if (known == p.states.end() || known->second != job.state()) {
        // A change no Watch reported (a retry requeued a finished job): the page learns it here.
        if (known != p.states.end()) out += Sse("job", MessageJson(job));
        p.states[job.id()] = job.state();
        p.dirty = true;
      }
      FollowUnfinished(p, job);
    }
    return out;
  };
  StartStream(res, page);
}

void ServeJobEvents(WebContext& context, const Caller& caller, const std::string& job_id,
                    httplib::Response& res) {
  v1::GetRequest request;
  request.set_job_id(job_id);
  v1::Job job;
  const grpc::Status status =
      context.link.jobs().Get(context.link.Unary(caller.token).get(), request, &job);
  if (!status.ok()) return ReplyRpcError(res, status);
  if (!RoomForPage(context, res)) return;
  auto page = std::make_shared<LivePage>(context, caller, true);
  page->poll = [job_id](LivePage& p) -> std::string {
    v1::GetRequest get;
    get.set_job_id(job_id);
    v1::Job now;
    const grpc::Status s =
        p.context.link.jobs().Get(p.context.link.Unary(p.token).get(), get, &now);
    if (s.error_code() == grpc::StatusCode::NOT_FOUND) {
      return Sse("gone", JsonText({{"job_id", job_id}, {"message", s.error_message()}}));
    }
    if (!s.ok()) return DaemonDown(p, s);
    std::string out;
    auto known = p.states.find(job_id);
    if (known != p.states.end() && known->second != now.state()) out = Sse("job", MessageJson(now));
    p.states[job_id] = now.state();
    FollowUnfinished(p, now);
    return out;
  };
  StartStream(res, page);
}

}  // namespace dlmfd::web
