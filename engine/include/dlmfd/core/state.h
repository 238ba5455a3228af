// The state of a run at the end of a time step: everything a checkpoint must hold to resume
// bit-for-bit, and everything an observer may read.
#pragma once

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "dlmfd/core/params.h"

namespace dlmfd {

struct ParticleState {
  int id = 0;
  Vec2 position = Vec2::Zero();
  Vec2 velocity = Vec2::Zero();
  double angular_velocity = 0.0;
  Vec2 force = Vec2::Zero();  // hydrodynamic force on the particle over the last step
  double torque = 0.0;        // hydrodynamic torque on the particle over the last step
  double radius = 0.0;        // the bounding radius: R of a disk, max(a, b) of an ellipse
  double density = 0.0;
  double angle = 0.0;  // theta: the body's x axis from the domain's x axis, d theta / dt = omega
  ShapeKind shape = ShapeKind::kDisk;
  Vec2 semi_axes = Vec2::Zero();  // (a, b); (R, R) for a disk
  Motion motion = Motion::kFree;
  std::vector<double> multiplier;  // DLM nodal forces of the last step (warm start); may be empty
};

// The cut-cell step's pressure corrections of earlier steps
// (particles/pressure_correction_basis.h): q_i on the pressure unknowns with S q_i and A^-1 B^T q_i
// on the velocity unknowns, oldest first.
struct PressureCorrections {
  std::vector<Eigen::VectorXd> q, sq, wq;
};

// What the cut-cell step (33) keeps of earlier steps to start its pressure iteration, beyond p
// (particles/cut_cell_step.h), so that a run resumed from a checkpoint takes the same steps as the
// run that wrote it.
struct CutCellStart {
  std::vector<double> previous_pressure;  // p^{n-1} on the 2h-grid: a moving body's extrapolation
  // Around fixed bodies only (a moving body's S changes every step): the corrections and the dt of
  // the S they belong to (0: none).
  double corrections_dt = 0.0;
  PressureCorrections corrections;
};

struct FlowState {
  long step = 0;
  double time = 0.0;
  std::vector<double> u, v;           // velocity on the h-grid nodes
  std::vector<double> p;              // pressure on the 2h-grid nodes
  std::vector<double> a11, a12, a22;  // configuration tensor on the h-grid; empty when Newtonian
  // fluid.stress_splitting = "devss" only (else empty): the nodal strain rate D_h of the velocity
  // that step (35) used for A (0 inside particles, 0 before the first step).
  std::vector<double> d11, d12, d22;
  // Step (33)'s predicted warm start (fluid/stokes_solver.h, "Warm start"): the defect e = r - d of
  // its last solve, on the 2h-grid nodes; empty before the first step (and where (33) is the
  // viscous coupling's or the cut cells'), which then starts from p alone.
  std::vector<double> stokes_defect;
  std::vector<ParticleState> particles;
  // particle_mesh.kind = "cut_cell" only, and only while a checkpoint is written (Simulation lends
  // it to the observers' OnStepEnd and OnStopped) or read: else empty, as it is large (16
  // corrections of the unknowns).
  CutCellStart cut_cell_start;
};

// Per-step diagnostics: named columns, the same names in the same order at every step of a run
// (iterations and residual of each solver, divergence, CFL, min eigenvalue of A, max trA, substep
// milliseconds). diagnostics.csv prints them as they come.
struct StepReport {
  long step = 0;
  double time = 0.0;
  double wall_seconds = 0.0;  // of this step
  std::vector<std::pair<std::string, double>> columns;

  // After the first step every column exists, and Set allocates nothing (a string_view, not a
  // std::string built from the literal, is compared).
  void Set(std::string_view name, double value) {
    for (auto& c : columns) {
      if (c.first == name) {
        c.second = value;
        return;
      }
    }
    columns.emplace_back(std::string(name), value);
  }
  // The value of a column, or `fallback` when the run has no such column.
  double Get(std::string_view name, double fallback = 0.0) const {
    for (const auto& c : columns) {
      if (c.first == name) return c.second;
    }
    return fallback;
  }
};

}  // namespace dlmfd
