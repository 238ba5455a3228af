// Jacobi-preconditioned conjugate gradients on an assembled symmetric positive (semi-)definite
// sparse matrix: an independent reference for the fast solvers in tests and small problems.
//
// Stopping rule: ||b - A x||_2 <= tolerance ||b||_2, or max_iterations. A consistent singular
// system (b orthogonal to the kernel) converges as well; the kernel component of x is then that of
// the initial guess. Not for large problems (no matrix-free interface, no restart).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cmath>

namespace dlmfd {

struct PcgResult {
  int iterations = 0;
  double relative_residual = 0.0;
  bool converged = false;
};

// Solves A x = b starting from the x given; zero diagonal entries are left unpreconditioned.
inline PcgResult SolveSparsePcg(const Eigen::SparseMatrix<double>& a, const Eigen::VectorXd& b,
                                Eigen::VectorXd& x, double tolerance, int max_iterations) {
  PcgResult result;
  Eigen::VectorXd inv_diag = a.diagonal();
  for (Eigen::Index i = 0; i < inv_diag.size(); ++i)
    inv_diag[i] = inv_diag[i] != 0.0 ? 1.0 / inv_diag[i] : 1.0;
  const double b_norm = b.norm();
  if (b_norm == 0.0) {
    x.setZero();
    result.converged = true;
    return result;
  }
  Eigen::VectorXd r = b - a * x;
  Eigen::VectorXd z = inv_diag.cwiseProduct(r);
  Eigen::VectorXd p = z;
  double rz = r.dot(z);
  for (result.iterations = 0; result.iterations < max_iterations; ++result.iterations) {
    result.relative_residual = r.norm() / b_norm;
    if (result.relative_residual <= tolerance) {
      result.converged = true;
      return result;
    }
    const Eigen::VectorXd ap = a * p;
    const double step = rz / p.dot(ap);
    x += step * p;
    r -= step * ap;
    z = inv_diag.cwiseProduct(r);
    const double rz_next = r.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  result.relative_residual = (b - a * x).norm() / b_norm;
  result.converged = result.relative_residual <= tolerance;
  return result;
}

}  // namespace dlmfd
