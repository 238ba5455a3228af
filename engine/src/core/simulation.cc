// Simulation: the Marchuk-Yanenko loop (paper section 4). This file owns the state and the substep
// objects (built once, sized once); Step() runs the paper's list of substeps, one member each:
//   SolveStokes (33)        StokesSolver, with the polymer's force on the momentum equation (and
//                           with splitting.constraint = "viscous" the particles in it, through
//                           ParticleStep::CoupleStokes; with "incremental" the last step's
//                           multiplier, through ParticleStep::LagMultiplier);
//   AdvectVelocity (34)     the VelocityAdvection scheme of splitting.advection;
//   UpdateConformation (35) OldroydBPolymer (conformation module: modulus, A^0, inflow A_L, force),
//                           with the velocity of conformation.velocity: u^{n+2/4} (the paper's)
//                           or the Stokes step's u^{n+1/4}, lent by the same swap as below;
//   MoveParticles (36)-(38) ParticleStep (predictor, DLM multiplier, corrector), in place on u.
// With particle_mesh.kind = "cut_cell" the (fixed, prescribed or free) particles are cut out of
// the mesh instead: step (33) is CutCellStep's (particles/cut_cell_step.h), which also gives their
// force, and there is no step (36)-(38); a polymer's force then acts on the fluid part only, and
// after step (35) the nodes inside a body next to the fluid take the fluid's A
// (CutCellStep::ExtendIntoBodies); a prescribed or free body moves to X^{n+1} before step (33)
// (CutCellStep::MoveBeforeStep), so that A is extended into its new band before the polymer's
// force of step (33) is made.
// A step models no more than the scene needs: a Newtonian liquid (relaxation_time = 0 or
// solvent_ratio = 1) builds no polymer, so no conformation arrays, no force and no step (35); a
// scene without particles has no step (36)-(38).
// The velocity the observers' snapshots see: with splitting.steady_correction = "tendency" the
// velocity of step (33), u^{n+1/4}, the field whose steady state is the discrete steady solution
// whatever dt (fluid/advection_wave.h; the end-of-step velocity u^{n+1} lies O(dt) from it); it is
// kept only on the steps whose fields are written and lent to OnSnapshot by a swap, so the state
// (u^{n+1}, what the next step and a checkpoint start from) is untouched. Otherwise u^{n+1}.
// Initial state: u = 0 with the boundary data, the polymer's A^0, the particles of the scene at
// rest or at their given velocities (ParticleStep::InitialStates).
#include "dlmfd/core/simulation.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <utility>

#include "../mesh/grid_kernels.h"
#include "dlmfd/conformation/oldroyd_b_polymer.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/core/parallel_copy.h"
#include "dlmfd/core/time_stepping.h"
#include "dlmfd/fluid/boundary_data.h"
#include "dlmfd/fluid/stokes_solver.h"
#include "dlmfd/fluid/velocity_advection.h"
#include "dlmfd/particles/cut_cell_step.h"
#include "dlmfd/particles/particle_step.h"
#include "dlmfd/scene/scene_file.h"
#include "dlmfd/scene/scene_validation.h"

namespace dlmfd {
namespace {

using Clock = std::chrono::steady_clock;

double Milliseconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// The settings of step (33)'s solver: with the constraint inside it (splitting.constraint =
// "viscous") the coupled solve's (ViscousConstraint::StokesSettings).
SolverParams StokesSettings(const Params& p) {
  const bool coupled =
      !p.particles.empty() && p.splitting.constraint.value() == ConstraintCoupling::kViscous;
  return coupled ? ViscousConstraint::StokesSettings(p) : p.solvers;
}

// The columns of domain.flow_rate (fluid/flux_control.h): in a channel `mean_pressure_gradient` and
// `flow_rate` along its periodic axis; in a box periodic in both directions, one of each per axis
// (`mean_pressure_gradient_x`, `_y`, `flow_rate_x`, `_y`).
constexpr std::string_view kGradientColumns[2][2] = {
    {"mean_pressure_gradient", "mean_pressure_gradient"},
    {"mean_pressure_gradient_x", "mean_pressure_gradient_y"}};
constexpr std::string_view kRateColumns[2][2] = {{"flow_rate", "flow_rate"},
                                                 {"flow_rate_x", "flow_rate_y"}};

void ReportGradient(const FluxControl* flux, const Vec2& gradient, StepReport& report) {
  if (!flux) return;
  const std::size_t box = flux->axes().size() > 1 ? 1 : 0;
  for (int a : flux->axes()) report.Set(kGradientColumns[box][a], gradient[a]);
}

void ReportFlowRates(const FluxControl* flux, const FlowState& state, StepReport& report) {
  if (!flux) return;
  const std::size_t box = flux->axes().size() > 1 ? 1 : 0;
  for (int a : flux->axes()) {
    report.Set(kRateColumns[box][a], flux->FlowRate(a, state.u.data(), state.v.data()));
  }
}

}  // namespace

struct Simulation::Impl {
  explicit Impl(const Params& p)
      : params(p),
        grid(p.domain.VelocityGrid()),
        pgrid(grid.Coarse()),
        boundary_data(grid, p.domain),
        stokes(grid, p.domain, p.fluid, p.splitting.alpha, StokesSettings(p), boundary_data),
        advection(MakeVelocityAdvection(grid, p, boundary_data)),
        viscoelastic(!p.fluid.IsNewtonian()) {
    state.u.assign(grid.NodeCount(), 0.0);
    state.v.assign(grid.NodeCount(), 0.0);
    state.p.assign(pgrid.NodeCount(), 0.0);
    boundary_data.Apply(state.u.data(), state.v.data());
    if (!p.particles.empty()) {
      state.particles = ParticleStep::InitialStates(p);
      if (p.particle_mesh.kind == ParticleMeshKind::kCutCell) {
        cut_cells = std::make_unique<CutCellStep>(p, grid);
      } else {
        particle_step = std::make_unique<ParticleStep>(p, grid);
      }
    }
    if (viscoelastic) {
      polymer = std::make_unique<OldroydBPolymer>(p, grid);
      polymer->SetInitialState(state);
    }
  }

  // The four sub-steps are kept out of line so that a profile attributes each its cost
  // (bench/serial_fraction.sh: callgrind collects inside one at a time).
  // Step (33): u^n -> u^{n+1/4}, p^{n+1/4}, with the polymer stress of A^n on the right side;
  // with splitting.constraint = "viscous" the particles at X^n are in it (their constraint and
  // velocities: particles/viscous_constraint.h).
  [[gnu::noinline]] void SolveStokes(StepReport& report) {
    const auto t0 = Clock::now();
    if (cut_cells && cut_cells->MoveBeforeStep(params.time.dt, state.u.data(), state.v.data()) &&
        polymer) {
      // A moving body's band at X^{n+1} holds nodes that were deeper inside at X^n (A = I there),
      // which the polymer's force of the step reads: the bodies move first and A is extended.
      cut_cells->ExtendIntoBodies(state.a11.data(), state.a12.data(), state.a22.data());
      if (!state.d11.empty()) {
        cut_cells->ExtendIntoBodies(state.d11.data(), state.d12.data(), state.d22.data());
      }
    }
    const NodeForce force = polymer ? polymer->MomentumForce(state) : NodeForce{};
    if (particle_step && particle_step->LagsMultiplier()) {
      particle_step->LagMultiplier(state.time, params.time.dt, state.particles, state.u.data(),
                                   state.v.data());
    }
    if (cut_cells) {
      cut_cells->Solve(params.time.dt, boundary_data, state.particles, state.u.data(),
                       state.v.data(), state.p.data(), report, force);
    } else if (particle_step && particle_step->CouplesStokes()) {
      const ViscousConstraint::Outcome r = particle_step->CoupleStokes(
          state.time + params.time.dt, params.time.dt, stokes, force.x, force.y, state.particles,
          state.u.data(), state.v.data(), state.p.data());
      report.Set("stokes_iterations", r.stokes_iterations);
      report.Set("stokes_residual", r.stokes_residual);
      report.Set("divergence", r.divergence);
      report.Set("coupling_iterations", r.iterations);
      report.Set("coupling_residual", r.residual);
      report.Set("coupling_stokes_tolerance", r.stokes_tolerance);
      ReportGradient(stokes.flux_control(), r.mean_pressure_gradient, report);
    } else {
      const StokesReport r = stokes.Solve(params.time.dt, force.x, force.y, state.u.data(),
                                          state.v.data(), state.p.data(), &state.stokes_defect);
      report.Set("stokes_iterations", r.iterations);
      report.Set("stokes_residual", r.residual);
      report.Set("divergence", r.divergence);
      ReportGradient(stokes.flux_control(), r.mean_pressure_gradient, report);
    }
    if (particle_step && particle_step->LagsMultiplier()) {
      particle_step->SampleStokesVelocity(state.u.data(), state.v.data());
    }
    report.Set("ms_stokes", Milliseconds(t0, Clock::now()));
  }

  // With the tendency correction, snapshots show u^{n+1/4}: the observers' OnSnapshot sees it in
  // place of u^{n+1} (swapped in and back, no copy). With conformation.velocity = "stokes" step
  // (35) sees it in place of u^{n+2/4} the same way.
  struct StokesVelocityLent {
    StokesVelocityLent(Impl& impl, bool lend)
        : s(impl),
          lent(lend) {
      Swap();
    }
    ~StokesVelocityLent() { Swap(); }
    void Swap() {
      if (!lent) return;
      s.state.u.swap(s.stokes_u);
      s.state.v.swap(s.stokes_v);
    }
    Impl& s;
    bool lent;
  };

  // A checkpoint (io/results_writer.cc writes one in OnStepEnd where output.checkpoint_every is
  // due, and in OnStopped) holds what the cut-cell step keeps of earlier steps: lent to the state
  // for the observers' call, as it is large (core/state.h).
  struct CutCellStartLent {
    CutCellStartLent(Impl& impl, bool lend)
        : s(impl) {
      if (lend && s.cut_cells) s.state.cut_cell_start = s.cut_cells->SavedStart();
    }
    ~CutCellStartLent() { s.state.cut_cell_start = {}; }
    Impl& s;
  };

  // Step (34): u^{n+1/4} -> u^{n+2/4}.
  [[gnu::noinline]] void AdvectVelocity(StepReport& report) {
    const auto t0 = Clock::now();
    advection->Record(advection->Solve(params.time.dt, state.u.data(), state.v.data()), report);
    report.Set("ms_advection", Milliseconds(t0, Clock::now()));
  }

  // Step (35): A^n -> A^{n+1} with u^{n+2/4}; A = I inside the particles at X^n.
  [[gnu::noinline]] void UpdateConformation(StepReport& report) {
    const auto t0 = Clock::now();
    polymer->Update(params.time.dt, state, report,
                    cut_cells ? cut_cells->InsideNodes().data() : nullptr);
    if (cut_cells) {
      // With devss D_h too: the stress there is then G (A - I) - w eta_p 2 D_h of fluid values,
      // the share the implicit viscosity carries taken out as in the fluid.
      cut_cells->ExtendIntoBodies(state.a11.data(), state.a12.data(), state.a22.data());
      if (!state.d11.empty()) {
        cut_cells->ExtendIntoBodies(state.d11.data(), state.d12.data(), state.d22.data());
      }
    }
    report.Set("ms_conformation", Milliseconds(t0, Clock::now()));
  }

  // Steps (36)-(38): particles X^n -> X^{n+1}, velocity u^{n+2/4} -> u^{n+1} in place.
  [[gnu::noinline]] void MoveParticles(StepReport& report) {
    const auto t0 = Clock::now();
    particle_step->Advance(state.time, params.time.dt, state.particles, state.u.data(),
                           state.v.data(), report);
    report.Set("ms_particles", Milliseconds(t0, Clock::now()));
  }

  // NaN/Inf anywhere ends the run with the quantity, the time and a node position.
  void CheckFinite() const {
    auto check = [&](const std::vector<double>& f, const Grid& g, const char* name) {
      const long n = static_cast<long>(f.size());
      long first_bad = n;  // the first node, whatever the team
#pragma omp parallel for schedule(static) reduction(min : first_bad)
      for (long k = 0; k < n; ++k) {
        if (!std::isfinite(f[k])) first_bad = std::min(first_bad, k);
      }
      if (first_bad < n) {
        const auto k = static_cast<std::size_t>(first_bad);
        const auto [i, j] = kernels::NodeAt(g, k);
        std::ostringstream msg;
        msg << "numerical blow-up: " << name << " = " << f[k] << " at t = " << state.time
            << " (step " << state.step << "), node (" << i << ", " << j << ") at x = " << g.X(i)
            << ", y = " << g.Y(j) << "; reduce time.dt or refine domain.h";
        throw NumericalBlowUp(msg.str());
      }
    };
    check(state.u, grid, "velocity u");
    check(state.v, grid, "velocity v");
    check(state.p, pgrid, "pressure p");
  }

  double MaxSpeed() const {
    const long n = static_cast<long>(state.u.size());
    const double *u = state.u.data(), *v = state.v.data();
    double m = 0.0;  // a maximum: the same on any team
#pragma omp parallel for schedule(static) reduction(max : m)
    for (long k = 0; k < n; ++k) m = std::max(m, u[k] * u[k] + v[k] * v[k]);
    return std::sqrt(m);
  }

  Params params;
  Grid grid, pgrid;
  BoundaryData boundary_data;
  StokesSolver stokes;
  std::unique_ptr<VelocityAdvection> advection;
  bool viscoelastic;
  std::unique_ptr<OldroydBPolymer> polymer;     // viscoelastic only
  std::unique_ptr<ParticleStep> particle_step;  // with particles only, but cut cells
  std::unique_ptr<CutCellStep> cut_cells;       // particle_mesh.kind = "cut_cell" only
  StepReport report;  // reused: its columns are created by the first step, overwritten after
  FlowState state;
  // u^{n+1/4}: of the last step whose fields were written (steady_correction = "tendency"), and of
  // every step where step (35) freezes it (conformation.velocity = "stokes").
  std::vector<double> stokes_u, stokes_v;
  std::vector<Observer*> observers;
};

Simulation::Simulation(const Params& params) {
  Params resolved = params;  // Params built in code runs as the same scene read from a file
  ResolveDefaults(resolved);
  ValidateTimeStepping(resolved);  // the time loop's own guard, as the scene validation applies it
  if (resolved.threads > 0) omp_set_num_threads(resolved.threads);
  impl_ = std::make_unique<Impl>(resolved);
}

Simulation::~Simulation() = default;

void Simulation::AddObserver(Observer* observer) { impl_->observers.push_back(observer); }

void Simulation::EmitInitial() {
  for (Observer* o : impl_->observers) {
    o->OnParticles(impl_->state);
    o->OnSnapshot(impl_->state);
  }
}

void Simulation::Step() {
  Impl& s = *impl_;
  const auto t0 = Clock::now();
  StepReport& report = s.report;
  const OutputParams& out = s.params.output;
  const long n = s.state.step + 1;
  const double dt = s.params.time.dt;
  // particles_every = 0: every step.
  const bool particles_due = out.particles_every <= 0.0 || OutputDue(n, dt, out.particles_every);
  const bool fields_due = OutputDue(n, dt, out.fields_every);
  const bool show_stokes =
      fields_due && s.params.splitting.steady_correction == SteadyCorrection::kTendency;
  s.boundary_data.SetTime(s.state.time + s.params.time.dt);  // the data of t_{n+1}
  s.advection->BeginStep(s.state.u.data(), s.state.v.data());
  const bool conformation_sees_stokes =
      s.polymer && s.params.conformation.velocity == ConformationVelocity::kStokes;
  s.SolveStokes(report);
  if (show_stokes || conformation_sees_stokes) {
    const long nodes = static_cast<long>(s.state.u.size());
    s.stokes_u.resize(s.state.u.size());
    s.stokes_v.resize(s.state.v.size());
    ParallelCopy(s.state.u.data(), nodes, s.stokes_u.data());
    ParallelCopy(s.state.v.data(), nodes, s.stokes_v.data());
  }
  s.AdvectVelocity(report);
  if (s.polymer) {
    const Impl::StokesVelocityLent lent(s, conformation_sees_stokes);
    s.UpdateConformation(report);
  }
  if (s.particle_step) s.MoveParticles(report);
  s.state.step += 1;
  s.state.time = static_cast<double>(s.state.step) * s.params.time.dt;
  s.CheckFinite();
  report.Set("cfl", s.MaxSpeed() * s.params.time.dt / s.grid.h);
  // domain.flow_rate: the rates of u^{n+1}, O(dt) off the target that (33) holds to round-off.
  ReportFlowRates(s.stokes.flux_control(), s.state, report);
  report.step = s.state.step;
  report.time = s.state.time;
  report.wall_seconds = std::chrono::duration<double>(Clock::now() - t0).count();

  for (Observer* o : s.observers) {
    o->OnStep(s.state, report);
    if (particles_due) o->OnParticles(s.state);
    if (fields_due) {
      const Impl::StokesVelocityLent lent(s, show_stokes);
      o->OnSnapshot(s.state);
    }
  }
  const Impl::CutCellStartLent lent(s, OutputDue(s.state.step, dt, out.checkpoint_every));
  for (Observer* o : s.observers) o->OnStepEnd(s.state);
}

void Simulation::Run(const std::atomic<bool>* stop) {
  while (!Done() && !(stop && stop->load())) Step();
  if (!Done()) {
    const Impl::CutCellStartLent lent(*impl_, true);
    for (Observer* o : impl_->observers) o->OnStopped(impl_->state);
  }
}

bool Simulation::Done() const { return impl_->state.step >= TotalSteps(); }

long Simulation::TotalSteps() const { return StepCount(impl_->params.time); }

void Simulation::Restore(const FlowState& state) {
  const Impl& s = *impl_;
  if (state.u.size() != s.grid.NodeCount() || state.v.size() != s.grid.NodeCount() ||
      state.p.size() != s.pgrid.NodeCount()) {
    throw InvalidParameter("checkpoint", "fields of " + std::to_string(state.u.size()) + " nodes",
                           std::to_string(s.grid.NodeCount()) + " velocity and " +
                               std::to_string(s.pgrid.NodeCount()) +
                               " pressure nodes (the same scene)");
  }
  const std::size_t a_nodes = s.viscoelastic ? s.grid.NodeCount() : 0;
  if (state.a11.size() != a_nodes || state.a12.size() != a_nodes || state.a22.size() != a_nodes) {
    throw InvalidParameter(
        "checkpoint", "a configuration tensor of " + std::to_string(state.a11.size()) + " nodes",
        std::to_string(a_nodes) + " nodes (" + (s.viscoelastic ? "a viscoelastic" : "a Newtonian") +
            " scene)");
  }
  const std::size_t d_nodes = s.params.fluid.Devss() ? s.grid.NodeCount() : 0;
  if (state.d11.size() != d_nodes || state.d12.size() != d_nodes || state.d22.size() != d_nodes) {
    throw InvalidParameter("checkpoint",
                           "a strain rate D_h of " + std::to_string(state.d11.size()) + " nodes",
                           std::to_string(d_nodes) + " nodes (fluid.stress_splitting = \"" +
                               (d_nodes > 0 ? "devss" : "explicit") + "\" in this scene)");
  }
  if (state.particles.size() != s.state.particles.size()) {
    throw InvalidParameter(
        "checkpoint", std::to_string(state.particles.size()) + " particles",
        std::to_string(s.state.particles.size()) + " particles (the same scene)");
  }
  for (std::size_t p = 0; p < state.particles.size(); ++p) {
    if (state.particles[p].multiplier.size() != s.state.particles[p].multiplier.size()) {
      throw InvalidParameter(
          "checkpoint",
          "particle " + std::to_string(p) + " with " +
              std::to_string(state.particles[p].multiplier.size()) + " multiplier values",
          std::to_string(s.state.particles[p].multiplier.size()) + " (the same scene)");
    }
  }
  const std::size_t previous_pressure = state.cut_cell_start.previous_pressure.size();
  if (previous_pressure != 0 && previous_pressure != s.pgrid.NodeCount()) {
    throw InvalidParameter("checkpoint:/cut_cell_start/previous_pressure",
                           std::to_string(previous_pressure) + " values",
                           std::to_string(s.pgrid.NodeCount()) + " (the same scene)");
  }
  // The shapes come from the scene (a checkpoint stores the bounding radius only).
  std::vector<ParticleState> initial = impl_->state.particles;
  impl_->state = state;
  for (std::size_t p = 0; p < initial.size(); ++p) {
    impl_->state.particles[p].shape = initial[p].shape;
    impl_->state.particles[p].semi_axes = initial[p].semi_axes;
  }
  if (impl_->cut_cells) {
    impl_->cut_cells->Restore(impl_->state.particles, std::move(impl_->state.cut_cell_start));
  }
  impl_->state.cut_cell_start = {};
}

const Params& Simulation::params() const { return impl_->params; }
const Grid& Simulation::grid() const { return impl_->grid; }
const Grid& Simulation::pressure_grid() const { return impl_->pgrid; }
const FlowState& Simulation::state() const { return impl_->state; }
FlowState& Simulation::mutable_state() { return impl_->state; }

}  // namespace dlmfd
