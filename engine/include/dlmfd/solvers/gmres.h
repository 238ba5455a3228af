// Restarted GMRES with right preconditioning (Saad & Schultz 1986; Saad, Iterative methods for
// sparse linear systems, 2nd ed. (2003), algorithm 9.5): solves A x = b for operators given as
// functions, so the fast solvers can serve as the preconditioner M^-1 of a system that differs from
// theirs near a boundary (particles/cut_cell_stokes.h). Givens rotations on the Hessenberg matrix;
// the residual it tracks is the true residual of the right-preconditioned iteration.
//
// Stopping rule: ||b - A x||_2 <= tolerance ||b||_2 (checked on the recurrence, then on the true
// residual at each restart), or max_iterations inner steps in all.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <vector>

namespace dlmfd {

struct GmresResult {
  int iterations = 0;
  double relative_residual = 0.0;
  bool converged = false;
};

using LinearMap = std::function<void(const Eigen::VectorXd& in, Eigen::VectorXd& out)>;

// x: the initial guess on entry, the solution on return.
inline GmresResult SolveGmres(const LinearMap& apply, const LinearMap& precondition,
                              const Eigen::VectorXd& b, Eigen::VectorXd& x, double tolerance,
                              int max_iterations, int restart = 80) {
  GmresResult result;
  const double b_norm = b.norm();
  if (b_norm == 0.0) {
    x.setZero();
    result.converged = true;
    return result;
  }
  const Eigen::Index n = b.size();
  Eigen::VectorXd r(n), w(n), z(n);
  std::vector<Eigen::VectorXd> v(restart + 1);  // the Krylov basis, allocated as it grows
  Eigen::MatrixXd hess = Eigen::MatrixXd::Zero(restart + 1, restart);
  Eigen::VectorXd cs(restart), sn(restart), g(restart + 1);
  while (true) {
    apply(x, w);
    r = b - w;
    double beta = r.norm();
    result.relative_residual = beta / b_norm;
    if (result.relative_residual <= tolerance) {
      result.converged = true;
      return result;
    }
    if (result.iterations >= max_iterations) return result;
    v[0] = r / beta;
    g.setZero();
    g[0] = beta;
    int k = 0;
    for (; k < restart && result.iterations < max_iterations; ++k, ++result.iterations) {
      precondition(v[k], z);
      apply(z, w);
      for (int i = 0; i <= k; ++i) {  // modified Gram-Schmidt
        hess(i, k) = w.dot(v[i]);
        w -= hess(i, k) * v[i];
      }
      hess(k + 1, k) = w.norm();
      if (hess(k + 1, k) > 0.0) v[k + 1] = w / hess(k + 1, k);
      for (int i = 0; i < k; ++i) {  // the earlier rotations
        const double t = cs[i] * hess(i, k) + sn[i] * hess(i + 1, k);
        hess(i + 1, k) = -sn[i] * hess(i, k) + cs[i] * hess(i + 1, k);
        hess(i, k) = t;
      }
      const double d = std::hypot(hess(k, k), hess(k + 1, k));
      cs[k] = hess(k, k) / d;
      sn[k] = hess(k + 1, k) / d;
      hess(k, k) = d;
      hess(k + 1, k) = 0.0;
      g[k + 1] = -sn[k] * g[k];
      g[k] = cs[k] * g[k];
      if (std::abs(g[k + 1]) <= tolerance * b_norm) {
        ++k;
        ++result.iterations;
        break;
      }
    }
    // x += M^-1 V y, y from the triangular system of the rotated Hessenberg matrix.
    Eigen::VectorXd y = hess.topLeftCorner(k, k).triangularView<Eigen::Upper>().solve(g.head(k));
    w.setZero();
    for (int i = 0; i < k; ++i) w += y[i] * v[i];
    precondition(w, z);
    x += z;
  }
}

}  // namespace dlmfd
