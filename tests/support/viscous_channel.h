// Scenes of the viscosity-rule tests (issue 13 point 1), shared by
// tests/unit/viscosity_rule_test.cc and tests/convergence/viscosity_limit_test.cc so that both
// measure the same liquid and disk. ViscousBase: a walled box, rho = eta = 1, t_end = 0.5, tight
// solver tolerances (Stokes and multiplier 1e-9, advection 1e-6: the differences the tests measure
// stand far above the solver noise), no output, the ring mesh with the paper's ratio h_p / h =
// 96 / 70, one thread.
// ChannelWithFixedDisk: the channel [0, 2] x [0, 1] fed by a poiseuille profile (max 1) on the
// left, outflow on the right, with a fixed disk of diameter 0.4 at (0.6, 0.5).
#pragma once

#include "dlmfd/core/params.h"
#include "studied_numerics.h"

namespace dlmfd::testing {

inline Params ViscousBase(double width, double height, int cells_per_unit, double dt) {
  Params p;
  testing::UseStudiedNumerics(p);
  p.domain.size = Vec2(width, height);
  p.domain.h = 1.0 / cells_per_unit;
  for (auto& side : p.domain.sides)
    side = {SideType::kWall, Profile::kUniform, Vec2::Zero(), Vec2::Zero()};
  p.fluid.density = 1.0;
  p.fluid.viscosity = 1.0;
  p.time.dt = dt;
  p.time.end = 0.5;
  p.solvers.stokes_tolerance = 1e-9;
  p.solvers.advection_tolerance = 1e-6;
  p.solvers.multiplier_tolerance = 1e-9;
  p.output.fields_every = 0.0;
  p.output.particles_every = 0.0;
  p.output.checkpoint_every = 0.0;
  p.particle_mesh.kind = ParticleMeshKind::kRing;  // the mesh these tests' numbers were measured on
  p.particle_mesh.h = p.domain.h * 96.0 / 70.0;
  p.threads = 1;
  return p;
}

inline Params ChannelWithFixedDisk(int cells_per_unit, double dt, double lambda, double beta) {
  Params p = ViscousBase(2.0, 1.0, cells_per_unit, dt);
  p.domain.sides[static_cast<int>(Side::kLeft)] = {SideType::kVelocity, Profile::kPoiseuille,
                                                   Vec2::Zero(), Vec2(1.0, 0.0)};
  p.domain.sides[static_cast<int>(Side::kRight)] = {SideType::kOutflow, Profile::kUniform,
                                                    Vec2::Zero(), Vec2::Zero()};
  p.fluid.relaxation_time = lambda;
  p.fluid.solvent_ratio = beta;
  ParticleParams disk;
  disk.center = Vec2(0.6, 0.5);
  disk.diameter = 0.4;
  disk.density = 2.0;
  disk.motion = Motion::kFixed;
  p.particles.push_back(disk);
  return p;
}

}  // namespace dlmfd::testing
