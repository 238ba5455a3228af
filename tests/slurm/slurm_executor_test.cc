// The daemon's slurm executor against a real Slurm (scripts/slurm-dev.sh start): one job end to
// end with its events streamed through the shared job directory (progress, particle states and
// trA snapshots, as for a local job), `dlmfd show`'s Slurm id, cancel as scancel, and a daemon
// killed with SIGKILL that adopts its Slurm job on restart. Skipped,
// naming scripts/slurm-dev.sh, when no Slurm answers sinfo.
#include <gtest/gtest.h>
#include <signal.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "../server/support/daemon_process.h"

namespace dlmfd::testing {
namespace {
namespace fs = std::filesystem;

constexpr char kDevSlurmDir[] = "/tmp/dlmfd-slurm";  // scripts/slurm-dev.sh's default

// The dev Slurm's configuration, unless SLURM_CONF already names one.
void UseDevSlurm() {
  const std::string dir =
      std::getenv("DLMFD_SLURM_DIR") ? std::getenv("DLMFD_SLURM_DIR") : kDevSlurmDir;
  if (!std::getenv("SLURM_CONF") && fs::exists(dir + "/slurm.conf")) {
    setenv("SLURM_CONF", (dir + "/slurm.conf").c_str(), 1);
  }
}

// Asked once: sinfo takes about 9 s to give up when no slurmctld answers.
bool SlurmRunning() {
  static const bool running = [] {
    UseDevSlurm();
    return std::system("sinfo -h > /dev/null 2>&1") == 0;
  }();
  return running;
}

std::string JobCompFile() {
  const std::string dir =
      std::getenv("DLMFD_SLURM_DIR") ? std::getenv("DLMFD_SLURM_DIR") : kDevSlurmDir;
  return dir + "/log/jobcomp.txt";
}

#define REQUIRE_SLURM()                                                                    \
  if (!SolverAvailable()) GTEST_SKIP() << "dlmfd-solve is not built: " << kSolverPath;     \
  if (!SlurmRunning())                                                                     \
  GTEST_SKIP() << "no Slurm answers sinfo: start one with scripts/slurm-dev.sh start (as " \
                  "root), or set SLURM_CONF"

// A fixed disk in an Oldroyd-B lid-driven cavity: particle states and trA snapshots to stream.
std::string DiskInCavity(double end_time) {
  std::ostringstream scene;
  scene << "title = \"disk in an Oldroyd-B cavity\"\n"
           "[domain]\nsize = [1.0, 1.0]\nh = 0.0625\n"
           "[domain.boundary]\n"
           "left = { type = \"wall\" }\nright = { type = \"wall\" }\nbottom = { type = \"wall\" }\n"
           "top = { type = \"velocity\", profile = \"uniform\", value = [1.0, 0.0] }\n"
           "[fluid]\nviscosity = 0.1\nrelaxation_time = 0.1\nsolvent_ratio = 0.5\n"
           "[time]\ndt = 0.01\nend = "
        << end_time
        << "\n"
           "[[particles]]\ncenter = [0.5, 0.5]\ndiameter = 0.25\ndensity = 1.0\n"
           "motion = \"fixed\"\n"
           "[output]\nfields_every = 0.05\nparticles_every = 0.02\n";
  return scene.str();
}

std::vector<std::string> SlurmFlags(const std::string& dir) {
  return {"--executor",           "slurm", "--slurm-shared-dir",   dir + "/shared",
          "--slurm-poll-seconds", "1",     "--slurm-jobcomp-file", JobCompFile()};
}

v1::Job Submit(v1::Jobs::Stub& stub, const std::string& scene) {
  v1::SubmitRequest request;
  request.set_scene(scene);
  request.set_name("slurm-test");
  v1::Job job;
  auto status = stub.Submit(Context().get(), request, &job);
  EXPECT_TRUE(status.ok()) << status.error_message();
  return job;
}

v1::Job Get(v1::Jobs::Stub& stub, const std::string& id) {
  v1::GetRequest request;
  request.set_job_id(id);
  v1::Job job;
  EXPECT_TRUE(stub.Get(Context().get(), request, &job).ok());
  return job;
}

TEST(SlurmExecutor, OneJobEndToEndStreamsLikeALocalJob) {
  REQUIRE_SLURM();
  TempDir dir;
  DaemonProcess daemon(dir.path() + "/data", SlurmFlags(dir.path()));
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  const v1::Job job = Submit(*stub, DiskInCavity(0.2));
  auto context = Context();
  v1::WatchRequest watch;
  watch.set_job_id(job.id());
  watch.set_include_snapshots(true);
  auto reader = stub->Watch(context.get(), watch);
  std::vector<v1::WatchEvent> events;
  for (v1::WatchEvent event; reader->Read(&event);) events.push_back(event);
  ASSERT_TRUE(reader->Finish().ok());
  ASSERT_FALSE(events.empty());
  ASSERT_TRUE(events.back().has_state()) << daemon.Log();
  EXPECT_EQ(events.back().state().state(), v1::COMPLETED) << events.back().state().reason() << "\n"
                                                          << daemon.Log();
  int progress = 0, particles = 0, snapshots = 0;
  v1::Snapshot last_snapshot;
  for (const auto& event : events) {
    if (event.has_progress()) ++progress;
    if (event.has_particles()) {
      ++particles;
      EXPECT_EQ(event.particles().particles_size(), 1);
    }
    if (event.has_snapshot()) {
      ++snapshots;
      last_snapshot = event.snapshot();
      EXPECT_EQ(event.snapshot().values_size(),
                (event.snapshot().nx() + 1) * (event.snapshot().ny() + 1));
    }
  }
  EXPECT_GT(progress, 0);
  // particles_every = 0.02 over t = 0.2: 10 outputs (the initial state may add one). Snapshots
  // are kept as for a local job: the hub holds the newest, a watcher's queue replaces a queued one
  // by a newer one, so a watcher sees at least the last (t = 0.2), of trA.
  EXPECT_GE(particles, 10);
  EXPECT_GE(snapshots, 1);
  EXPECT_EQ(last_snapshot.quantity(), "trA") << last_snapshot.DebugString().substr(0, 300);
  EXPECT_NEAR(last_snapshot.time(), 0.2, 1e-9);
  const v1::Job done = Get(*stub, job.id());
  EXPECT_FALSE(done.slurm_job_id().empty());
  EXPECT_EQ(done.step(), 20);
  EXPECT_TRUE(fs::exists(done.results_dir() + "/summary.json"));
  // The job really went through Slurm: the jobcomp file has its end.
  std::ifstream jobcomp(JobCompFile());
  std::string text((std::istreambuf_iterator<char>(jobcomp)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("JobId=" + done.slurm_job_id() + " "), std::string::npos);
  // dlmfd show names the Slurm id.
  const std::string out = dir.path() + "/show.txt";
  const std::string command = std::string(DLMFD_BINARY_DIR) + "/client/dlmfd --server " +
                              daemon.address() + " show " + job.id() + " > " + out;
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::ifstream show(out);
  std::string shown((std::istreambuf_iterator<char>(show)), std::istreambuf_iterator<char>());
  EXPECT_NE(shown.find("slurm job:   " + done.slurm_job_id()), std::string::npos) << shown;
}

TEST(SlurmExecutor, CancelIsScancelAndTheSolverCheckpoints) {
  REQUIRE_SLURM();
  TempDir dir;
  DaemonProcess daemon(dir.path() + "/data", SlurmFlags(dir.path()));
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  const v1::Job job = Submit(*stub, CavityScene(1.0e4));
  {
    auto context = Context();
    v1::WatchRequest watch;
    watch.set_job_id(job.id());
    auto reader = stub->Watch(context.get(), watch);
    v1::WatchEvent event;
    while (reader->Read(&event) && !(event.has_progress() && event.progress().step() > 0)) {}
    context->TryCancel();
    reader->Finish();
  }
  v1::CancelRequest cancel;
  cancel.set_job_id(job.id());
  v1::Job cancelled;
  ASSERT_TRUE(stub->Cancel(Context().get(), cancel, &cancelled).ok());
  const v1::Job done = WaitFinished(*stub, job.id());
  EXPECT_EQ(done.state(), v1::CANCELLED) << done.reason() << "\n" << daemon.Log();
  EXPECT_GT(done.step(), 0);
  EXPECT_TRUE(fs::exists(done.results_dir() + "/checkpoint.h5"));
  ASSERT_FALSE(done.slurm_job_id().empty());
  // Slurm no longer runs it.
  const std::string state = dir.path() + "/state.txt";
  const std::string command = "squeue -h -j " + done.slurm_job_id() + " -t R,PD -o %T > " + state;
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::ifstream in(state);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "");
}

TEST(SlurmExecutor, ADaemonKilledWithSigkillAdoptsItsSlurmJobOnRestart) {
  REQUIRE_SLURM();
  TempDir dir;
  std::string id, slurm_id;
  {
    DaemonProcess daemon(dir.path() + "/data", SlurmFlags(dir.path()));
    ASSERT_TRUE(daemon.Start()) << daemon.Log();
    auto stub = daemon.Stub();
    id = Submit(*stub, CavityScene(20.0)).id();
    auto context = Context();
    v1::WatchRequest watch;
    watch.set_job_id(id);
    auto reader = stub->Watch(context.get(), watch);
    v1::WatchEvent event;
    while (reader->Read(&event) && !(event.has_progress() && event.progress().step() > 0)) {}
    context->TryCancel();
    reader->Finish();
    slurm_id = Get(*stub, id).slurm_job_id();
    daemon.Kill(SIGKILL);
    daemon.Wait();
  }
  ASSERT_FALSE(slurm_id.empty());
  DaemonProcess daemon(dir.path() + "/data", SlurmFlags(dir.path()));
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  const v1::Job done = WaitFinished(*stub, id);
  EXPECT_EQ(done.state(), v1::COMPLETED) << done.reason() << "\n" << daemon.Log();
  EXPECT_EQ(done.slurm_job_id(), slurm_id);  // the same Slurm job: not submitted again
  EXPECT_EQ(done.step(), 2000);
  EXPECT_NE(daemon.Log().find("Slurm job " + slurm_id + " adopted"), std::string::npos)
      << daemon.Log();
  // Slurm ran one job of that name.
  std::ifstream jobcomp(JobCompFile());
  int runs = 0;
  for (std::string line; std::getline(jobcomp, line);) {
    if (line.find(" Name=dlmfd-" + id + " ") != std::string::npos) ++runs;
  }
  EXPECT_EQ(runs, 1);
}

}  // namespace
}  // namespace dlmfd::testing
