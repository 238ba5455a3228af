// Simulation's output port (core/observer.h): one step notifies in two rounds (every observer's
// OnStep, OnParticles and OnSnapshot, then every observer's OnStepEnd), and Run, the one time loop,
// notifies OnStopped once when its stop flag ends the run early and never when it reaches the end.
// A checkpoint written in OnStepEnd therefore follows every record of its step, whoever writes it.
#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <vector>

#include "../support/studied_numerics.h"
#include "dlmfd/core/simulation.h"

namespace dlmfd {
namespace {

// Records "name:event:step" for every notification, into a log shared by several observers.
class Recorder : public Observer {
 public:
  Recorder(std::string name, std::vector<std::string>* log, std::atomic<bool>* stop = nullptr,
           long stop_after = -1)
      : name_(std::move(name)),
        log_(log),
        stop_(stop),
        stop_after_(stop_after) {}
  void OnStep(const FlowState& s, const StepReport&) override { Add("step", s); }
  void OnParticles(const FlowState& s) override { Add("particles", s); }
  void OnSnapshot(const FlowState& s) override { Add("snapshot", s); }
  void OnStepEnd(const FlowState& s) override {
    Add("end", s);
    if (stop_ && s.step == stop_after_) stop_->store(true);
  }
  void OnStopped(const FlowState& s) override { Add("stopped", s); }

 private:
  void Add(const char* event, const FlowState& s) {
    log_->push_back(name_ + ":" + event + ":" + std::to_string(s.step));
  }
  std::string name_;
  std::vector<std::string>* log_;
  std::atomic<bool>* stop_;
  long stop_after_;
};

// A lid-driven box of 8 x 8 cells, 3 steps, particles recorded every step, no snapshots.
Params SmallCavity() {
  Params p;
  testing::UseStudiedNumerics(p);
  p.domain.size = Vec2(1.0, 1.0);
  p.domain.h = 1.0 / 8;
  for (auto& side : p.domain.sides) side.type = SideType::kWall;
  p.domain.sides[static_cast<int>(Side::kTop)] = {SideType::kVelocity, Profile::kUniform,
                                                  Vec2(1.0, 0.0), Vec2::Zero()};
  p.fluid.density = 1.0;
  p.fluid.viscosity = 1.0;
  p.time.dt = 0.01;
  p.time.end = 0.03;
  p.output.fields_every = 0.0;
  p.output.particles_every = 0.0;
  p.output.checkpoint_every = 0.0;
  p.particle_mesh.h = 1.0 / 8;
  p.threads = 1;
  return p;
}

TEST(SimulationObservers, EveryObserverSeesTheStepBeforeAnyStepEnd) {
  Simulation sim(SmallCavity());
  std::vector<std::string> log;
  Recorder a("a", &log), b("b", &log);
  sim.AddObserver(&a);
  sim.AddObserver(&b);
  sim.Step();
  EXPECT_EQ(log, (std::vector<std::string>{"a:step:1", "a:particles:1", "b:step:1", "b:particles:1",
                                           "a:end:1", "b:end:1"}));
}

TEST(SimulationObservers, RunToTheEndNeverNotifiesStopped) {
  Simulation sim(SmallCavity());
  std::vector<std::string> log;
  Recorder a("a", &log);
  sim.AddObserver(&a);
  std::atomic<bool> stop{false};
  sim.Run(&stop);
  EXPECT_TRUE(sim.Done());
  EXPECT_EQ(log.back(), "a:end:3");
  for (const auto& line : log) EXPECT_EQ(line.find("stopped"), std::string::npos) << line;
}

TEST(SimulationObservers, RunStoppedEarlyNotifiesStoppedOnceAfterTheLastStep) {
  Simulation sim(SmallCavity());
  std::vector<std::string> log;
  std::atomic<bool> stop{false};
  Recorder a("a", &log, &stop, 2), b("b", &log);
  sim.AddObserver(&a);
  sim.AddObserver(&b);
  sim.Run(&stop);
  EXPECT_FALSE(sim.Done());
  EXPECT_EQ(sim.state().step, 2);
  const std::vector<std::string> tail(log.end() - 4, log.end());
  EXPECT_EQ(tail, (std::vector<std::string>{"a:end:2", "b:end:2", "a:stopped:2", "b:stopped:2"}));
}

}  // namespace
}  // namespace dlmfd
