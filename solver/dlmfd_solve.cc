// dlmfd-solve: one scene in, one results directory out (design.md 3.1-3.2).
//
//   dlmfd-solve SCENE --out DIR [--set key=value]... [--resume] [--threads N] [--events FD]
//   [--quiet]
//   dlmfd-solve SCENE --check [--set key=value]...
//
// --check validates the scene as a run would and prints its grid, steps, footprint estimate and
// accuracy settings and warnings on stdout; it runs nothing and writes no file (exit 0 or 2).
// Exit status (dlmfd/solver/exit_codes.h): 0 completed; 1 failed while running (reason in
// summary.json, results so far kept and closed); 2 invalid scene or arguments (message on stderr
// naming key, value and what is allowed; nothing run); 130 cancelled by SIGINT/SIGTERM (checkpoint
// written, every file closed, summary.json status cancelled). The handler only sets an atomic flag,
// which Simulation::Run checks between steps.
//
// The time loop is Simulation::Run; everything the run writes is an observer of it: the results
// directory (ResultsWriter, which also checkpoints), the event stream and the progress line.
// --resume goes on from DIR/checkpoint.h5 when the scene (after defaults and --set) is the one in
// DIR/scene.toml; the resumed run's results equal an uninterrupted run's bit for bit.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <system_error>
#include <vector>

#include "dlmfd/core/errors.h"
#include "dlmfd/core/number_text.h"
#include "dlmfd/core/simulation.h"
#include "dlmfd/core/time_stepping.h"
#include "dlmfd/io/atomic_file.h"
#include "dlmfd/io/checkpoint.h"
#include "dlmfd/io/results_writer.h"
#include "dlmfd/io/run_statistics.h"
#include "dlmfd/scene/accuracy_envelope.h"
#include "dlmfd/scene/auto_coupling.h"
#include "dlmfd/scene/scene_file.h"
#include "dlmfd/scene/scene_footprint.h"
#include "dlmfd/solver/exit_codes.h"
#include "dlmfd/solver/run_summary.h"
#include "event_stream.h"

namespace {

using dlmfd::solver::kExitCancelled;
using dlmfd::solver::kExitCompleted;
using dlmfd::solver::kExitFailed;
using dlmfd::solver::kExitInvalid;

std::atomic<bool> g_stop{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");

extern "C" void OnStopSignal(int) { g_stop.store(true); }

void InstallSignalHandlers() {
  struct sigaction action {};
  action.sa_handler = OnStopSignal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  std::signal(SIGPIPE, SIG_IGN);  // a reader of --events that goes away must not kill the run
}

struct Options {
  std::string scene;
  std::string out;
  std::vector<std::string> sets;
  bool resume = false;
  int threads = 0;
  int events_fd = -1;
  bool quiet = false;
  bool check = false;
};

// One progress line on stderr about every second: step, t / end, steps/s, ETA.
class ProgressLine : public dlmfd::Observer {
 public:
  ProgressLine(bool quiet, long first_step, long total_steps, double end_time)
      : quiet_(quiet),
        first_step_(first_step),
        total_steps_(total_steps),
        end_time_(end_time),
        start_(std::chrono::steady_clock::now()),
        last_(start_) {}

  void OnStepEnd(const dlmfd::FlowState& state) override { Update(state.step, state.time, false); }

  // The last line, whatever the end of the run.
  void Finish(const dlmfd::FlowState& state) { Update(state.step, state.time, true); }

 private:
  void Update(long step, double time, bool force) {
    const auto now = std::chrono::steady_clock::now();
    if (quiet_ || (!force && now - last_ < std::chrono::seconds(1))) return;
    last_ = now;
    const double wall = std::chrono::duration<double>(now - start_).count();
    const double rate = wall > 0.0 ? static_cast<double>(step - first_step_) / wall : 0.0;
    const double eta = rate > 0.0 ? static_cast<double>(total_steps_ - step) / rate : 0.0;
    std::fprintf(stderr, "step %ld/%ld  t = %.6g / %.6g  %.1f steps/s  ETA %.0f s\n", step,
                 total_steps_, time, end_time_, rate, eta);
    std::fflush(stderr);
  }

  bool quiet_;
  long first_step_, total_steps_;
  double end_time_;
  std::chrono::steady_clock::time_point start_, last_;
};

int Invalid(dlmfd::solver::EventStream& events, const std::string& message) {
  spdlog::error("invalid scene or arguments: {}", message);
  events.Log("error", message);
  events.Finished("failed", message, 0, 0.0, kExitInvalid);
  return kExitInvalid;
}

// The settings that govern the run's error, and each one outside the accuracy envelope as a
// warning in the log and the event stream (summary.json carries them too).
void LogAccuracy(const dlmfd::Params& params, dlmfd::solver::EventStream& events) {
  std::string settings;
  for (const dlmfd::AccuracySetting& s : dlmfd::AccuracySettings(params)) {
    settings += (settings.empty() ? "" : ", ") + s.name + " = " + dlmfd::ShortText(s.value);
  }
  spdlog::info("accuracy settings: {}", settings);
  for (const dlmfd::ResolvedChoice& c : params.numerics.resolved) {
    spdlog::info("numerics: {}", dlmfd::ResolvedChoiceText(c));
    events.Log("info", "numerics: " + dlmfd::ResolvedChoiceText(c));
  }
  for (const dlmfd::AccuracyWarning& w : dlmfd::AccuracyWarnings(params)) {
    spdlog::warn("accuracy: {}", w.Message());
    events.Log("warning", "accuracy: " + w.Message());
  }
}

// The summary.json of the run as it ended.
dlmfd::solver::RunSummary Summary(const dlmfd::Params& params, const dlmfd::FlowState& state,
                                  const dlmfd::StepReport& last_report) {
  dlmfd::solver::RunSummary summary;
  summary.steps = state.step;
  summary.time = state.time;
  summary.end_time = params.time.end;
  summary.title = params.title;
  summary.version = DLMFD_VERSION;
  for (const dlmfd::ParticleState& q : state.particles) {
    dlmfd::solver::RunSummary::Particle p;
    p.id = q.id;
    p.radius = q.radius;
    p.position = {q.position.x(), q.position.y()};
    p.angle = q.angle;
    p.velocity = {q.velocity.x(), q.velocity.y()};
    p.angular_velocity = q.angular_velocity;
    p.force = {q.force.x(), q.force.y()};
    p.torque = q.torque;
    summary.particles.push_back(p);
  }
  summary.diagnostics = last_report.columns;
  for (const dlmfd::AccuracyWarning& w : dlmfd::AccuracyWarnings(params)) {
    summary.warnings.push_back(
        {w.setting, w.value, w.allowed, w.key, w.current, w.suggested, w.source});
  }
  for (const dlmfd::ResolvedChoice& c : params.numerics.resolved) {
    summary.numerics.push_back({c.key, c.value, c.rule, c.numbers});
  }
  return summary;
}

// The statistics of the whole run, read back from the closed results files.
void AddStatistics(const dlmfd::RunStatistics& r, dlmfd::solver::RunSummary& summary) {
  summary.fall_window = {r.fall_window_start, r.fall_window_end};
  summary.fall_speed = r.mean_fall_speed;
  summary.diameter = r.diameter;
  summary.min_gap = r.min_gap;
  summary.min_wall_gap = r.min_wall_gap;
  summary.max_trA = r.max_trA;
  summary.min_eig_A = r.min_eig_A;
  summary.reynolds = r.reynolds;
  summary.deborah = r.deborah;
  summary.mach = r.mach;
  summary.elasticity = r.elasticity;
  for (std::size_t p = 0; p < summary.particles.size(); ++p) {
    if (p < r.fall_speed.size()) summary.particles[p].fall_speed = r.fall_speed[p];
  }
}

// --check: the scene as a run would validate it, described on stdout; nothing runs.
int Check(const Options& opt) {
  using namespace dlmfd;
  Params params;
  try {
    std::vector<SceneOverride> overrides;
    for (const std::string& s : opt.sets) overrides.push_back(ParseOverride(s));
    params = LoadSceneFile(opt.scene, overrides);
  } catch (const InvalidParameter& e) {
    spdlog::error("invalid scene or arguments: {}", e.what());
    return kExitInvalid;
  }
  const Grid grid = params.domain.VelocityGrid();
  const SceneFootprint footprint = EstimateFootprint(params);
  std::printf("scene: %s\nmesh: %d x %d cells, h = %s\nsteps: %ld to t = %s (dt = %s)\n",
              opt.scene.c_str(), grid.nx, grid.ny, ShortText(grid.h).c_str(),
              StepCount(params.time), ShortText(params.time.end).c_str(),
              ShortText(params.time.dt).c_str());
  std::printf("particles: %zu\nmemory: about %s MiB (%s velocity nodes, %s multiplier nodes)\n",
              params.particles.size(), ShortText(footprint.bytes / (1024.0 * 1024.0)).c_str(),
              ShortText(footprint.velocity_nodes).c_str(),
              ShortText(footprint.multiplier_nodes).c_str());
  for (const AccuracySetting& s : AccuracySettings(params)) {
    std::printf("setting: %s = %s\n", s.name.c_str(), ShortText(s.value).c_str());
  }
  for (const ResolvedChoice& c : params.numerics.resolved) {
    std::printf("numerics: %s\n", ResolvedChoiceText(c).c_str());
  }
  for (const AccuracyWarning& w : AccuracyWarnings(params)) {
    std::printf("warning: %s\n", w.Message().c_str());
  }
  return kExitCompleted;
}

// NOLINTNEXTLINE(readability-function-size): predates the limit; split it when you change it
int Run(const Options& opt, dlmfd::solver::EventStream& events) {
  using namespace dlmfd;
  using namespace dlmfd::solver;
  // Everything that can be wrong with the scene or the arguments is found before anything runs.
  Params params;
  std::unique_ptr<Simulation> sim;
  Checkpoint checkpoint;
  try {
    std::vector<SceneOverride> overrides;
    for (const std::string& s : opt.sets) overrides.push_back(ParseOverride(s));
    params = LoadSceneFile(opt.scene, overrides);
    if (opt.threads < 0)
      throw InvalidParameter("--threads", std::to_string(opt.threads), "an integer >= 0");
    params.threads = opt.threads;
    sim = std::make_unique<Simulation>(params);
    if (opt.resume) {
      const std::string ckpt_path = opt.out + "/" + ResultsWriter::kCheckpoint;
      try {
        checkpoint = ReadCheckpoint(ckpt_path);
      } catch (const Error& e) {
        throw InvalidParameter("--resume", ckpt_path,
                               std::string("a readable checkpoint (") + e.what() + ")");
      }
      const std::string scene_text = WriteScene(params);
      std::string stored;
      try {
        stored = ReadTextFile(opt.out + "/" + ResultsWriter::kScene);
      } catch (const Error&) {}
      if (stored != scene_text || checkpoint.scene_text != scene_text) {
        throw InvalidParameter("--resume", opt.scene,
                               "the scene of " + opt.out +
                                   "/scene.toml and of its checkpoint (after defaults "
                                   "and --set); run without --resume to start over");
      }
      sim->Restore(checkpoint.state);
    }
  } catch (const InvalidParameter& e) {
    return Invalid(events, e.what());
  }

  // An earlier run's summary would tell a reader that this one has ended.
  std::error_code no_summary;
  std::filesystem::remove(opt.out + "/" + kRunSummaryFile, no_summary);
  std::unique_ptr<ResultsWriter> results;
  try {
    results = opt.resume
                  ? ResultsWriter::Resume(opt.out, params, sim->grid(), checkpoint.state.step)
                  : ResultsWriter::Start(opt.out, params, sim->grid(), sim->state());
  } catch (const Error& e) {
    spdlog::error("cannot prepare the results directory: {}", e.what());
    events.Log("error", e.what());
    events.Finished("failed", e.what(), sim->state().step, sim->state().time, kExitFailed);
    return kExitFailed;
  }
  results->SetCheckpointCallback([&events](long step, double time, const std::string& file) {
    v1::SolverEvent e;
    e.mutable_checkpointed()->set_step(step);
    e.mutable_checkpointed()->set_time(time);
    e.mutable_checkpointed()->set_file(file);
    events.Send(e);
  });
  // A checkpoint written before it stored the angles: the results' angles (the records'
  // angular velocities integrated) are the state's.
  if (opt.resume && checkpoint.particle_angles.empty()) {
    std::vector<ParticleState>& particles = sim->mutable_state().particles;
    const std::vector<double>& angles = results->particle_angles();
    for (std::size_t p = 0; p < particles.size() && p < angles.size(); ++p) {
      particles[p].angle = angles[p];
    }
  }
  const long first_step = sim->state().step;
  EventObserver event_observer(&events, params, sim->grid());
  ProgressLine progress(opt.quiet, first_step, sim->TotalSteps(), params.time.end);
  // The results first: a step's checkpoint event follows that step's other events.
  sim->AddObserver(results.get());
  sim->AddObserver(&event_observer);
  sim->AddObserver(&progress);

  {
    v1::SolverEvent e;
    v1::Started* s = e.mutable_started();
    s->set_step(first_step);
    s->set_time(sim->state().time);
    s->set_end_time(params.time.end);
    s->set_dt(params.time.dt);
    s->set_particle_count(static_cast<int>(params.particles.size()));
    s->set_nx(sim->grid().nx);
    s->set_ny(sim->grid().ny);
    s->set_h(sim->grid().h);
    s->set_resumed(opt.resume);
    events.Send(e);
  }
  if (opt.resume) {
    spdlog::info("resuming {} from step {} (t = {})", opt.scene, first_step, sim->state().time);
  } else {
    spdlog::info("running {} into {}: {} steps on a {} x {} mesh", opt.scene, opt.out,
                 sim->TotalSteps(), sim->grid().nx, sim->grid().ny);
  }
  LogAccuracy(params, events);

  event_observer.Begin(first_step);
  const auto start = std::chrono::steady_clock::now();
  std::string status, reason;
  int code = kExitCompleted;
  try {
    if (!opt.resume) sim->EmitInitial();
    sim->Run(&g_stop);  // a stopped run has its checkpoint written by ResultsWriter::OnStopped
    if (!sim->Done()) {
      status = "cancelled";
      reason = "stopped by a signal; resume with --resume";
      code = kExitCancelled;
    } else {
      status = "completed";
    }
  } catch (const Error& e) {  // RunFailure and I/O errors: the run ends FAILED, results so far kept
    status = "failed";
    reason = e.what();
    code = kExitFailed;
    spdlog::error("run failed at step {}: {}", sim->state().step, e.what());
    events.Log("error", e.what());
  }
  progress.Finish(sim->state());
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const long steps_here = sim->state().step - first_step;
  RunSummary summary = Summary(params, sim->state(), results->last_report());
  summary.status = status;
  summary.reason = reason;
  summary.exit_code = code;
  summary.resumed_from_step = opt.resume ? first_step : -1;
  summary.wall_seconds = wall;
  summary.ms_per_step = steps_here > 0 ? 1e3 * wall / static_cast<double>(steps_here) : 0.0;
  try {
    results->Finish();
    AddStatistics(ReadRunStatistics(params, results->dir()), summary);
    WriteRunSummary(results->dir() + "/" + kRunSummaryFile, summary);
  } catch (const Error& e) {
    spdlog::error("cannot write the summary: {}", e.what());
    if (code == kExitCompleted) code = kExitFailed;
  }
  results.reset();
  spdlog::info("{} after {} steps (t = {}); results in {}", summary.status, summary.steps,
               summary.time, opt.out);
  events.Finished(summary.status, summary.reason, summary.steps, summary.time, code);
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  spdlog::set_default_logger(spdlog::stderr_color_st("dlmfd-solve"));
  Options opt;
  CLI::App app{
      "dlmfd-solve: DLM/FD particulate flow in an Oldroyd-B or Newtonian liquid; one scene in, one "
      "results directory out"};
  app.add_option("scene", opt.scene, "scene file (TOML, docs/scenes.md)")->required();
  auto* out = app.add_option("--out", opt.out, "results directory (docs/results.md)");
  app.add_option("--set", opt.sets,
                 "override a scene key: key=value (dotted, e.g. fluid.relaxation_time=2)");
  app.add_flag("--resume", opt.resume, "go on from DIR/checkpoint.h5");
  app.add_option("--threads", opt.threads, "OpenMP threads (0: the default)");
  app.add_option("--events", opt.events_fd, "write the SolverEvent stream to this file descriptor");
  app.add_flag("--quiet", opt.quiet, "no progress lines on stderr");
  auto* check = app.add_flag("--check", opt.check,
                             "validate the scene and describe it on stdout; run nothing");
  check->excludes(out);
  try {
    app.parse(argc, argv);
    if (!opt.check && opt.out.empty()) throw CLI::RequiredError("--out");
  } catch (const CLI::ParseError& e) {
    const int cli_code = app.exit(e);
    return cli_code == 0 ? 0 : kExitInvalid;
  }
  if (opt.quiet) spdlog::set_level(spdlog::level::warn);
  if (opt.check) return Check(opt);
  InstallSignalHandlers();
  dlmfd::solver::EventStream events(opt.events_fd);
  return Run(opt, events);
}
