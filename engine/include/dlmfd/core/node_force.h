// A force on the momentum equation of step (33) as dual node vectors, f_i = (F, phi_i), on the
// velocity nodes; null components mean none. The polymer's (conformation/oldroyd_b_polymer.h) also
// names the stress it integrates, tau_p = modulus (S - I) with S P1 at the velocity nodes, which
// the cut-cell step integrates over the fluid part only (particles/cut_cell_polymer_force.h).
#pragma once

namespace dlmfd {

struct NodeForce {
  const double* x = nullptr;
  const double* y = nullptr;
  const double *s11 = nullptr, *s12 = nullptr, *s22 = nullptr;
  double modulus = 0.0;
  bool present() const { return x != nullptr; }
};

}  // namespace dlmfd
