// The dashboard's data, actions, pictures, downloads and live events: each a daemon call made
// with the caller's token (web_server.h lists the routes and their rules).
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

#include "dlmfd/core/errors.h"
#include "dlmfd/io/particle_history.h"
#include "field_pictures.h"
#include "http_reply.h"
#include "live_events.h"
#include "request_guard.h"
#include "result_files.h"
#include "routes.h"
#include "study_table.h"

namespace dlmfd::web {
namespace {

using nlohmann::json;

json Parsed(const google::protobuf::Message& message) {
  return json::parse(MessageJson(message), nullptr, false);
}

std::string Id(const httplib::Request& req) { return req.matches[1].str(); }

// An integer query parameter in [lo, hi], `fallback` when absent; false (and a 400) otherwise.
bool IntParam(const httplib::Request& req, httplib::Response& res, const char* name, long lo,
              long hi, long fallback, long* out) {
  *out = fallback;
  if (!req.has_param(name)) return true;
  const std::string text = req.get_param_value(name);
  char* end = nullptr;
  const long value = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || value < lo || value > hi) {
    ReplyError(res, 400,
               std::string(name) + " = " + text.substr(0, 40) +
                   " is not allowed: expected an "
                   "integer from " +
                   std::to_string(lo) + " to " + std::to_string(hi));
    return false;
  }
  *out = value;
  return true;
}

bool FlagParam(const httplib::Request& req, const char* name) {
  const std::string value = req.get_param_value(name);
  return value == "1" || value == "true";
}

// The JSON body of a POST ({} when empty); false (and a 400) when it is not a JSON object.
bool BodyObject(const httplib::Request& req, httplib::Response& res, json* body) {
  if (req.body.empty()) {
    *body = json::object();
    return true;
  }
  *body = json::parse(req.body, nullptr, false);
  if (body->is_object()) return true;
  ReplyError(res, 400, "the request body must be a JSON object");
  return false;
}

bool Confirmed(const json& body, const std::string& id, httplib::Response& res) {
  if (body.contains("confirm") && body["confirm"].is_string() && body["confirm"] == id) {
    return true;
  }
  ReplyError(res, 400, "confirm: a deletion needs {\"confirm\": \"" + id + "\"} in the body");
  return false;
}

template <typename Reply>
void JsonOrError(httplib::Response& res, const grpc::Status& status, const Reply& reply) {
  if (!status.ok()) return ReplyRpcError(res, status);
  ReplyJson(res, MessageJson(reply));
}

void SendPicture(httplib::Response& res, const Picture& picture) {
  if (picture.status != 200) return ReplyError(res, picture.status, picture.message);
  res.set_header("Cache-Control", "no-store");
  res.set_content(picture.data, "image/png");
}

// The file name of a download: the path's last part, made of safe bytes only.
std::string DownloadName(const std::string& path) {
  std::string name = path.substr(path.rfind('/') + 1);
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-' && c != '_') c = '_';
  }
  return name;
}

// Streams one result file through the daemon's Fetch. The first chunk is read before answering,
// so a missing file or job is a plain 404 rather than a broken download.
void ServeDownload(WebContext& context, const Caller& caller, const std::string& job_id,
                   const std::string& path, httplib::Response& res) {
  std::string why;
  if (!SafeResultPath(path, &why))
    return ReplyError(res, 400, "path " + path.substr(0, 200) + ": " + why);
  struct Transfer {
    std::unique_ptr<grpc::ClientContext> call;
    std::unique_ptr<grpc::ClientReader<v1::FileChunk>> reader;
    v1::FileChunk chunk;
    bool have_chunk = false;
  };
  auto transfer = std::make_shared<Transfer>();
  transfer->call = context.link.Stream(caller.token);
  v1::FetchRequest request;
  request.set_job_id(job_id);
  request.set_path(path);
  transfer->reader = context.link.jobs().Fetch(transfer->call.get(), request);
  transfer->have_chunk = transfer->reader->Read(&transfer->chunk);
  if (!transfer->have_chunk) {
    const grpc::Status status = transfer->reader->Finish();
    if (!status.ok()) return ReplyRpcError(res, status);
    res.set_header("Content-Disposition", "attachment; filename=\"" + DownloadName(path) + "\"");
    res.set_content("", "application/octet-stream");
    return;
  }
  res.set_header("Content-Disposition", "attachment; filename=\"" + DownloadName(path) + "\"");
  res.set_header("Cache-Control", "no-store");
  res.set_chunked_content_provider(
      "application/octet-stream",
      [transfer](size_t, httplib::DataSink& sink) {
        if (transfer->have_chunk) {
          const std::string& data = transfer->chunk.data();
          if (!sink.write(data.data(), data.size())) return false;
          transfer->have_chunk = transfer->reader->Read(&transfer->chunk);
          return true;
        }
        // A transfer broken by the daemon ends without the last chunk: the client sees it short.
        if (!transfer->reader->Finish().ok()) return false;
        sink.done();
        return true;
      },
      [transfer](bool success) {
        if (!success) transfer->call->TryCancel();
      });
}

// particles.h5 of a job as JSON, at most max_records records (evenly thinned).
void ServeParticles(WebContext& context, const Caller& caller, const std::string& job_id,
                    httplib::Response& res) {
  v1::ListFilesRequest list;
  list.set_job_id(job_id);
  v1::ListFilesResponse files;
  grpc::Status status =
      context.link.jobs().ListFiles(context.link.Unary(caller.token).get(), list, &files);
  if (!status.ok()) return ReplyRpcError(res, status);
  const bool has = std::any_of(files.files().begin(), files.files().end(),
                               [](const v1::FileInfo& f) { return f.path() == "particles.h5"; });
  json body = {{"time", json::array()}, {"particles", json::array()}};
  if (!has) return ReplyJson(res, JsonText(body));
  ScratchDirectory scratch;
  const auto path = scratch.path() / "particles.h5";
  status = FetchFileTo(context.link, caller.token, job_id, "particles.h5", path);
  if (!status.ok()) return ReplyRpcError(res, status);
  ParticleHistory history;
  try {
    history = ReadParticleHistory(path.string());
  } catch (const Error& e) {
    return ReplyError(res, 500, std::string("cannot read particles.h5: ") + e.what());
  }
  const size_t max_records = 1500;
  const size_t stride = std::max<size_t>(1, (history.records + max_records - 1) / max_records);
  std::vector<size_t> rows;
  for (size_t r = 0; r < history.records; r += stride) rows.push_back(r);
  if (history.records > 0 && rows.back() != history.records - 1)
    rows.push_back(history.records - 1);
  for (size_t r : rows) body["time"].push_back(JsonNumber(history.time[r]));
  for (size_t p = 0; p < history.particles; ++p) {
    json particle = {
        {"id", p < history.id.size() ? history.id[p] : static_cast<int64_t>(p)},
        {"radius", p < history.radius.size() ? JsonNumber(history.radius[p]) : json(nullptr)}};
    json x = json::array(), y = json::array(), u = json::array(), v = json::array(),
         omega = json::array();
    for (size_t r : rows) {
      const size_t k = r * history.particles + p;
      x.push_back(JsonNumber(history.position[2 * k]));
      y.push_back(JsonNumber(history.position[2 * k + 1]));
      u.push_back(JsonNumber(history.velocity[2 * k]));
      v.push_back(JsonNumber(history.velocity[2 * k + 1]));
      omega.push_back(JsonNumber(history.angular_velocity[k]));
    }
    particle["x"] = x;
    particle["y"] = y;
    particle["u"] = u;
    particle["v"] = v;
    particle["omega"] = omega;
    body["particles"].push_back(particle);
  }
  ReplyJson(res, JsonText(body));
}

void ServeStudy(WebContext& context, const Caller& caller, const std::string& study_id,
                httplib::Response& res) {
  v1::GetStudyRequest get;
  get.set_study_id(study_id);
  v1::Study study;
  grpc::Status status =
      context.link.jobs().GetStudy(context.link.Unary(caller.token).get(), get, &study);
  if (!status.ok()) return ReplyRpcError(res, status);
  v1::TableRequest table_request;
  table_request.set_study_id(study_id);
  v1::TableResponse rows;
  status = context.link.jobs().Table(context.link.Unary(caller.token).get(), table_request, &rows);
  if (!status.ok()) return ReplyRpcError(res, status);
  const cli::StudyTable table = cli::FlattenTable(rows);
  json jobs = json::array();
  v1::ListRequest list;
  list.set_study_id(study_id);
  list.set_page_size(1000);
  while (true) {
    v1::ListResponse page;
    status = context.link.jobs().List(context.link.Unary(caller.token).get(), list, &page);
    if (!status.ok()) return ReplyRpcError(res, status);
    for (const v1::Job& job : page.jobs()) jobs.push_back(Parsed(job));
    if (page.next_page_token().empty()) break;
    list.set_page_token(page.next_page_token());
  }
  json parameters = json::array();
  for (const v1::StudyAxis& axis : study.axes()) parameters.push_back(axis.key());
  json body = {{"study", Parsed(study)},
               {"columns", table.columns},
               {"parameters", parameters},
               {"rows", json::parse(cli::TableJson(table), nullptr, false)},
               {"jobs", jobs}};
  ReplyJson(res, JsonText(body));
}

void ServeLog(WebContext& context, const Caller& caller, const std::string& job_id,
              const httplib::Request& req, httplib::Response& res) {
  long offset = 0, max_bytes = 0;
  if (!IntParam(req, res, "offset", 0, (1L << 62), 0, &offset)) return;
  if (!IntParam(req, res, "max_bytes", 0, 1 << 20, 256 << 10, &max_bytes)) return;
  v1::ReadLogRequest request;
  request.set_job_id(job_id);
  request.set_offset(offset);
  request.set_max_bytes(static_cast<int32_t>(max_bytes));
  v1::LogChunk chunk;
  const grpc::Status status =
      context.link.jobs().ReadLog(context.link.Unary(caller.token).get(), request, &chunk);
  if (!status.ok()) return ReplyRpcError(res, status);
  ReplyJson(res,
            JsonText({{"offset", chunk.offset()},
                      {"size", chunk.size()},
                      {"finished", chunk.finished()},
                      {"next_offset", chunk.offset() + static_cast<int64_t>(chunk.data().size())},
                      {"text", chunk.data()}}));
}

}  // namespace

// NOLINTNEXTLINE(readability-function-size): predates the limit; split it when you change it
void InstallApiRoutes(httplib::Server& server, WebContext& context) {
  const std::string job = std::string("/api/jobs/") + kIdPattern;
  const std::string study = std::string("/api/studies/") + kIdPattern;
  DaemonLink& link = context.link;

  server.Get(
      "/api/overview",
      ForUser(context, Access::kRead,
              [&context](const httplib::Request&, httplib::Response& res, const Caller& caller) {
                std::string overview;
                const grpc::Status status = OverviewJson(context, caller.token, &overview, nullptr);
                if (!status.ok()) return ReplyRpcError(res, status);
                ReplyJson(res, overview);
              }));
  server.Get(study, ForUser(context, Access::kRead,
                            [&context](const httplib::Request& req, httplib::Response& res,
                                       const Caller& caller) {
                              ServeStudy(context, caller, Id(req), res);
                            }));
  server.Get(
      job,
      ForUser(context, Access::kRead,
              [&link](const httplib::Request& req, httplib::Response& res, const Caller& caller) {
                v1::GetRequest request;
                request.set_job_id(Id(req));
                v1::Job reply;
                JsonOrError(res, link.jobs().Get(link.Unary(caller.token).get(), request, &reply),
                            reply);
              }));
  server.Get(
      job + "/files",
      ForUser(context, Access::kRead,
              [&link](const httplib::Request& req, httplib::Response& res, const Caller& caller) {
                v1::ListFilesRequest request;
                request.set_job_id(Id(req));
                v1::ListFilesResponse reply;
                JsonOrError(res,
                            link.jobs().ListFiles(link.Unary(caller.token).get(), request, &reply),
                            reply);
              }));
  server.Get(job + "/log", ForUser(context, Access::kRead,
                                   [&context](const httplib::Request& req, httplib::Response& res,
                                              const Caller& caller) {
                                     ServeLog(context, caller, Id(req), req, res);
                                   }));
  server.Get(job + "/particles", ForUser(context, Access::kRead,
                                         [&context](const httplib::Request& req,
                                                    httplib::Response& res, const Caller& caller) {
                                           ServeParticles(context, caller, Id(req), res);
                                         }));

  // Actions, as the CLI's cancel, retry, hold, release and delete.
  server.Post(
      job + "/cancel",
      ForUser(context, Access::kChange,
              [&link](const httplib::Request& req, httplib::Response& res, const Caller& caller) {
                v1::CancelRequest request;
                request.set_job_id(Id(req));
                v1::Job reply;
                JsonOrError(res,
                            link.jobs().Cancel(link.Unary(caller.token).get(), request, &reply),
                            reply);
              }));
  server.Post(
      job + "/retry",
      ForUser(context, Access::kChange,
              [&link](const httplib::Request& req, httplib::Response& res, const Caller& caller) {
                v1::RetryRequest request;
                request.add_job_ids(Id(req));
                v1::RetryResponse reply;
                JsonOrError(res, link.jobs().Retry(link.Unary(caller.token).get(), request, &reply),
                            reply);
              }));
  server.Post(
      job + "/hold",
      ForUser(context, Access::kChange,
              [&link](const httplib::Request& req, httplib::Response& res, const Caller& caller) {
                v1::HoldRequest request;
                request.set_job_id(Id(req));
                v1::Job reply;
                JsonOrError(res, link.jobs().Hold(link.Unary(caller.token).get(), request, &reply),
                            reply);
              }));
  server.Post(
      job + "/release",
      ForUser(context, Access::kChange,
              [&link](const httplib::Request& req, httplib::Response& res, const Caller& caller) {
                v1::HoldRequest request;
                request.set_job_id(Id(req));
                v1::Job reply;
                JsonOrError(res,
                            link.jobs().Release(link.Unary(caller.token).get(), request, &reply),
                            reply);
              }));
  server.Post(
      job + "/delete",
      ForUser(context, Access::kChange,
              [&link](const httplib::Request& req, httplib::Response& res, const Caller& caller) {
                json body;
                if (!BodyObject(req, res, &body) || !Confirmed(body, Id(req), res)) return;
                v1::DeleteRequest request;
                request.add_job_ids(Id(req));
                request.set_force(body.value("force", false));
                v1::DeleteResponse reply;
                JsonOrError(res,
                            link.jobs().Delete(link.Unary(caller.token).get(), request, &reply),
                            reply);
              }));
  server.Post(
      study + "/cancel",
      ForUser(context, Access::kChange,
              [&link](const httplib::Request& req, httplib::Response& res, const Caller& caller) {
                v1::CancelStudyRequest request;
                request.set_study_id(Id(req));
                v1::CancelStudyResponse reply;
                JsonOrError(
                    res, link.jobs().CancelStudy(link.Unary(caller.token).get(), request, &reply),
                    reply);
              }));
  server.Post(
      study + "/retry",
      ForUser(context, Access::kChange,
              [&link](const httplib::Request& req, httplib::Response& res, const Caller& caller) {
                v1::RetryRequest request;
                request.set_study_id(Id(req));
                v1::RetryResponse reply;
                JsonOrError(res, link.jobs().Retry(link.Unary(caller.token).get(), request, &reply),
                            reply);
              }));
  server.Post(
      study + "/delete",
      ForUser(context, Access::kChange,
              [&link](const httplib::Request& req, httplib::Response& res, const Caller& caller) {
                json body;
                if (!BodyObject(req, res, &body) || !Confirmed(body, Id(req), res)) return;
                v1::DeleteRequest request;
                request.set_study_id(Id(req));
                request.set_force(body.value("force", false));
                v1::DeleteResponse reply;
                JsonOrError(res,
                            link.jobs().Delete(link.Unary(caller.token).get(), request, &reply),
                            reply);
              }));

  // Pictures drawn by viz/.
  server.Get(
      std::string("/pictures/jobs/") + kIdPattern + "/field.png",
      ForUser(
          context, Access::kRead,
          [&context](const httplib::Request& req, httplib::Response& res, const Caller& caller) {
            long width = 0, height = 0;
            if (!IntParam(req, res, "width", 100, 3000, 900, &width) ||
                !IntParam(req, res, "height", 100, 3000, 900, &height)) {
              return;
            }
            PictureSize size{int(width), int(height), req.get_param_value("caption") != "0"};
            SendPicture(res, LatestFieldPicture(context.link, caller.token, Id(req), size,
                                                context.pictures));
          }));
  server.Get(
      std::string("/pictures/studies/") + kIdPattern + "/chart.png",
      ForUser(
          context, Access::kRead,
          [&context](const httplib::Request& req, httplib::Response& res, const Caller& caller) {
            ChartRequest chart;
            chart.x = req.get_param_value("x");
            chart.y = req.get_param_value("y");
            chart.group = req.get_param_value("group");
            chart.log_x = FlagParam(req, "logx");
            chart.log_y = FlagParam(req, "logy");
            if (chart.x.empty() || chart.y.empty()) {
              return ReplyError(res, 400, "x and y: name a parameter and a result column");
            }
            long width = 0, height = 0;
            if (!IntParam(req, res, "width", 200, 3000, 900, &width) ||
                !IntParam(req, res, "height", 150, 3000, 600, &height)) {
              return;
            }
            chart.width = int(width);
            chart.height = int(height);
            SendPicture(res, StudyChartPicture(context.link, caller.token, Id(req), chart));
          }));

  server.Get(
      std::string("/movies/jobs/") + kIdPattern + "/movie.mp4",
      ForUser(
          context, Access::kRead,
          [&context](const httplib::Request& req, httplib::Response& res, const Caller& caller) {
            const Picture movie = context.movies.Movie(context.link, caller.token, Id(req));
            if (movie.status != 200) return ReplyError(res, movie.status, movie.message);
            res.set_header("Cache-Control", "no-store");
            res.set_content(movie.data, "video/mp4");
          }));

  // Downloads: any file of the job's results, by its path relative to them.
  server.Get(std::string("/files/jobs/") + kIdPattern + "/(.+)",
             ForUser(context, Access::kRead,
                     [&context](const httplib::Request& req, httplib::Response& res,
                                const Caller& caller) {
                       ServeDownload(context, caller, Id(req), req.matches[2].str(), res);
                     }));

  // Live events.
  server.Get("/events/overview", ForUser(context, Access::kRead,
                                         [&context](const httplib::Request&, httplib::Response& res,
                                                    const Caller& caller) {
                                           ServeOverviewEvents(context, caller, res);
                                         }));
  server.Get(std::string("/events/studies/") + kIdPattern,
             ForUser(context, Access::kRead,
                     [&context](const httplib::Request& req, httplib::Response& res,
                                const Caller& caller) {
                       ServeStudyEvents(context, caller, Id(req), res);
                     }));
  server.Get(
      std::string("/events/jobs/") + kIdPattern,
      ForUser(context, Access::kRead,
              [&context](const httplib::Request& req, httplib::Response& res,
                         const Caller& caller) { ServeJobEvents(context, caller, Id(req), res); }));
}

}  // namespace dlmfd::web
