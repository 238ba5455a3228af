// The search directions of the viscous coupling's outer PCG kept from one time step to the next,
// and the Galerkin start they give (particles/viscous_constraint.h; issue 32).
//
// When every particle is fixed, the Schur complement S of the coupled Stokes step (33) is the same
// operator at every step of one dt (the points keep their place against the grid, the Stokes
// solver does not change; a step of another dt clears the store), and only the right side g (the
// mismatch left by the warm start: the polymer stress and the advected velocity change) moves. The
// directions w_i that the PCG of earlier steps built, with their responses S w_i and the fluid and
// particle responses that go with them, then span the slow part of the next step's error as well.
// Before the PCG of a step the correction in their span is the Galerkin one:
//   (W^T S W) a = -W^T g,   nu += W a,   u, p, xi += (responses of W) a,
// which costs m^2 + m dot products of multiplier size and m updates of fluid size (m stored
// directions), and no Stokes solve. This is the initial guess of the augmented (recycled) CG for a
// sequence of systems with one matrix (Erhel & Guyomarc'h, SIAM J. Matrix Anal. Appl. 21 (2000)
// 1279-1299; Parks, de Sturler, Mackey, Johnson, Maiti, SIAM J. Sci. Comput. 28 (2006)
// 1651-1674). W^T S W is symmetrised (the coupled Stokes solves are inexact) and solved by a
// complete orthogonal decomposition (the stored directions can be nearly dependent); a start that
// does not lower the largest mismatch is undone.
// It halves the outer iterations of a polymer flow past a fixed disk in the Stokes limit
// (docs/evidence/constraint_coupling.md, "Recycled directions around fixed particles", with what
// else was tried).
// Memory: kCapacity directions, each two fluid-sized arrays, the coarse pressure and two arrays of
// multiplier size: 16 x 2.25 doubles a velocity node (scene/scene_footprint.h counts them).
// Not used with a moving particle (S changes with its position); not checkpointed (a resumed run
// starts with none, as at t = 0).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "dlmfd/core/params.h"

namespace dlmfd {

class RecycledDirections {
 public:
  static constexpr int kCapacity = 16;
  using Coefficient = Eigen::Matrix<double, kCapacity, 1>;

  // One PCG direction and its responses: d (multiplier size), S d (the mismatch it causes), the
  // fluid response (du, dv, dp) and the particles' (dvelocity, domega).
  struct Direction {
    std::vector<double> d, sd, du, dv, dp;
    std::vector<Vec2> dvelocity;
    std::vector<double> domega;
    Vec2 dgradient = Vec2::Zero();  // the response's mean pressure gradient (domain.flow_rate)
  };

  // Whether a scene's viscous coupling keeps directions: splitting.constraint = "viscous" and
  // every particle fixed (S the same operator at every step).
  static bool Used(const Params& params);
  // The doubles a velocity node of the store takes: du, dv and a quarter node of dp per direction.
  static constexpr double kDoublesPerNode = kCapacity * 2.25;

  int Count() const { return static_cast<int>(stored_.size()); }
  // Forgets every direction: S changed (a step of another dt), so their responses no longer hold.
  void Clear() {
    stored_.clear();
    next_ = 0;
  }
  const Direction& At(int i) const { return stored_[static_cast<std::size_t>(i)]; }

  // The coefficients a of the Galerkin start for the mismatch g (multiplier size): (W^T S W) a =
  // -W^T g over the stored directions (entries Count() and beyond are zero).
  Coefficient Coefficients(const std::vector<double>& g) const;

  // Stores a direction of the current step's PCG in place of the oldest once kCapacity are held
  // (the coefficients are taken at a step's start only, so the store may change during its PCG).
  // Copies into the slot's arrays: no allocation once the store is full.
  void Add(const std::vector<double>& d, const std::vector<double>& sd,
           const std::vector<double>& du, const std::vector<double>& dv,
           const std::vector<double>& dp, const std::vector<Vec2>& dvelocity,
           const std::vector<double>& domega, const Vec2& dgradient = Vec2::Zero());

 private:
  std::vector<Direction> stored_;
  int next_ = 0;  // the slot the next direction takes
};

}  // namespace dlmfd
