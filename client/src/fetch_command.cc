// dlmfd fetch JOB [--out DIR] [--path FILE]...
// dlmfd fetch --study S | --tag T... [--out DIR] [--path FILE]...
// A study arrives as one folder per point, named by its parameter values
// (DIR/fluid.relaxation_time=0.5,particles.*.density=1.02/), a job without parameters under its
// name; characters outside [A-Za-z0-9._=,+*-] become '_', and a name taken twice gets the job id.
// Writes each file to DIR/<its path in the results directory> through a temporary name
// (dlmfd/io/atomic_file.h), renamed when its last chunk has arrived, so an interrupted fetch never
// leaves a truncated file under the final name. Paths from the server are checked: absolute ones or
// ones with ".." are refused. Each job's folder also gets job.json (fetched_job.h): the job as
// `dlmfd show --json` prints it, which names its overrides for the captions of plot and movie.
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>

#include "command.h"
#include "connection.h"
#include "dlmfd/io/atomic_file.h"
#include "exit_codes.h"
#include "fetched_job.h"
#include "job_selection.h"
#include "job_text.h"
#include "rpc_status.h"

namespace dlmfd::cli {
namespace {

namespace fs = std::filesystem;

// A relative path of a file: no "..", and no trailing '/' (which names a directory and would make
// the file's target a directory here).
bool SafeRelative(const std::string& path) {
  const fs::path p(path);
  if (path.empty() || p.is_absolute() || path.back() == '/') return false;
  for (const auto& part : p) {
    if (part == "..") return false;
  }
  return true;
}

// Receives one Fetch stream into `out_dir`; counts files and bytes.
int Receive(Connection& connection, const std::string& job_id, const std::string& path,
            const fs::path& out_dir, int& files, long long& bytes) {
  v1::FetchRequest request;
  request.set_job_id(job_id);
  request.set_path(path);
  auto context = connection.StreamContext();
  auto reader = connection.jobs().Fetch(context.get(), request);
  v1::FileChunk chunk;
  std::ofstream file;
  std::string current;
  fs::path temporary;
  long long written = 0;
  while (reader->Read(&chunk)) {
    if (chunk.path() != current) {
      if (file.is_open()) {
        file.close();
        fs::remove(temporary);
        return ReportError("fetch", "the transfer of " + current + " ended early",
                           kExitServerError);
      }
      if (!SafeRelative(chunk.path())) {
        context->TryCancel();
        reader->Finish();
        return ReportError("fetch",
                           "refusing the unsafe path '" + chunk.path() + "' sent by the server",
                           kExitServerError);
      }
      current = chunk.path();
      const fs::path target = out_dir / current;
      fs::create_directories(target.parent_path());
      temporary = TemporaryPath(target.string());
      file.open(temporary, std::ios::binary | std::ios::trunc);
      if (!file) return ReportError("fetch", "cannot write " + temporary.string(), kExitLocalIo);
      written = 0;
    }
    if (chunk.offset() != written) {
      return ReportError("fetch",
                         current + ": chunk at offset " + std::to_string(chunk.offset()) +
                             ", expected " + std::to_string(written),
                         kExitServerError);
    }
    file.write(chunk.data().data(), std::streamsize(chunk.data().size()));
    written += static_cast<long long>(chunk.data().size());
    if (!file) return ReportError("fetch", "cannot write " + temporary.string(), kExitLocalIo);
    if (chunk.last()) {
      file.close();
      if (!file) return ReportError("fetch", "cannot write " + temporary.string(), kExitLocalIo);
      CommitTemporary(temporary.string(), (out_dir / current).string());
      ++files;
      bytes += written;
      current.clear();
    }
  }
  const grpc::Status status = reader->Finish();
  if (file.is_open()) {
    file.close();
    fs::remove(temporary);
    if (status.ok())
      return ReportError("fetch", "the transfer of " + current + " ended early", kExitServerError);
  }
  if (!status.ok()) return ReportRpcError("fetch", status);
  return kExitOk;
}

// The folder of one job of a study: its point's "key=value,..." (or its name), made safe.
std::string PointFolder(const v1::Job& job) {
  std::string name;
  for (const v1::ParameterValue& p : job.parameters()) {
    name += (name.empty() ? "" : ",") + p.key() + "=" + p.text();
  }
  if (name.empty()) name = job.name().empty() ? job.id() : job.name();
  for (char& c : name) {
    const bool safe =
        std::isalnum(static_cast<unsigned char>(c)) || std::strchr("._=,+*-", c) != nullptr;
    if (!safe) c = '_';
  }
  if (name == "." || name == "..") name = job.id();
  return name.substr(0, 200);
}

// Every file of every job of the selection into DIR/<point folder>/.
int FetchSelection(Connection& connection, const JobSelection& selection, const fs::path& dir,
                   const std::vector<std::string>& paths, int& files, long long& bytes) {
  std::vector<v1::Job> jobs;
  const grpc::Status status = SelectJobs(connection, selection, jobs);
  if (!status.ok()) return ReportRpcError("fetch", status);
  if (jobs.empty()) {
    return ReportError("fetch", "no job carries " + SelectionName(selection), kExitNotFound);
  }
  std::set<std::string> taken;
  for (auto it = jobs.rbegin(); it != jobs.rend(); ++it) {  // oldest first: points in order
    std::string folder = PointFolder(*it);
    if (!taken.insert(folder).second) folder += "." + it->id();
    taken.insert(folder);
    std::cout << folder << "  " << it->id() << "  " << StateName(it->state()) << "\n";
    for (const std::string& p : paths) {
      const int code = Receive(connection, it->id(), p, dir / folder, files, bytes);
      if (code != kExitOk) return code;
    }
    fs::create_directories(dir / folder);
    WriteFetchedJob(dir / folder, *it);
  }
  return kExitOk;
}

// DIR/job.json of one job, as the daemon describes it now.
int WriteJobOf(Connection& connection, const std::string& job_id, const fs::path& dir) {
  v1::GetRequest request;
  request.set_job_id(job_id);
  v1::Job job;
  auto context = connection.UnaryContext();
  const grpc::Status status = connection.jobs().Get(context.get(), request, &job);
  if (!status.ok()) return ReportRpcError("fetch", status);
  WriteFetchedJob(dir, job);
  return kExitOk;
}

}  // namespace

int RunFetch(int argc, char** argv) {
  CLI::App app{"Download a job's result files."};
  ConnectionFlags connection_flags;
  AddConnectionFlags(app, connection_flags);
  std::string job_id;
  std::string out_dir;
  std::vector<std::string> paths;
  JobSelection selection;
  auto* job_option = app.add_option("job", job_id, "job id");
  AddSelectionFlags(app, selection, job_option);
  app.add_option("--out,-o", out_dir,
                 "directory to write into (default: ./<job id>, ./<study id> or ./<tag>)");
  app.add_option("--path", paths,
                 "one file, relative to the results directory (repeatable; default: all)");
  if (auto code = ParseArgs(app, argc, argv)) return *code;
  if (job_id.empty() && selection.empty())
    return ReportError("fetch", "name a job id, --study ID or --tag T", kExitUsage);

  return Guarded("fetch", [&] {
    const std::string fallback =
        !job_id.empty() ? job_id
                        : (!selection.study.empty() ? selection.study : selection.tags.front());
    const fs::path dir = out_dir.empty() ? fs::path(fallback) : fs::path(out_dir);
    for (const std::string& p : paths) {
      if (!SafeRelative(p))
        throw UsageError("--path " + p +
                         ": expected the path of a file relative to the results directory");
    }
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec)
      return ReportError("fetch", "cannot create " + dir.string() + ": " + ec.message(),
                         kExitLocalIo);
    Connection connection(connection_flags);
    int files = 0;
    long long bytes = 0;
    if (paths.empty()) paths.emplace_back();
    if (!selection.empty()) {
      const int code = FetchSelection(connection, selection, dir, paths, files, bytes);
      if (code != kExitOk) return code;
    }
    for (const std::string& p : paths) {
      if (job_id.empty()) break;
      const int code = Receive(connection, job_id, p, dir, files, bytes);
      if (code != kExitOk) return code;
    }
    if (!job_id.empty()) {
      const int code = WriteJobOf(connection, job_id, dir);
      if (code != kExitOk) return code;
    }
    std::cerr << "fetched " << files << (files == 1 ? " file" : " files") << ", " << bytes
              << " bytes, into " << dir.string() << "\n";
    return kExitOk;
  });
}

}  // namespace dlmfd::cli
