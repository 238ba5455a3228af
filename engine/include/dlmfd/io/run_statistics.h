// The quantities of a whole run that a study tabulates (summary.json, docs/results.md), read back
// from the results directory when the run ends: diagnostics.csv (every step) and particles.h5 (the
// particle records). Both are cut back to the checkpoint on resume, so the statistics of a resumed
// run are those of an uninterrupted one.
//
//   min_gap, min_wall_gap   the smallest particle_pair_gap and particle_wall_gap of every step
//   (true
//                           surface gaps, particles/collision_forces.h); NaN when never defined.
//   max_trA, min_eig_A      the largest max_trA and the smallest min_eig_A of every step; NaN for a
//                           Newtonian liquid.
//   fall_speed (particle p) the mean speed along gravity over the last half of the simulated time
//                           of the records, [t_a, t_b] with t_a the first record at or after
//                           t_b / 2 (t_b the last record): U_p = (X_p(t_b) - X_p(t_a)) . g / (|g|
//                           (t_b - t_a)), from the displacement summed record to record with the
//                           minimum image across periodic sides (exact whatever the cadence, as
//                           long as a particle moves less than half a period between records).
//                           NaN without gravity or with fewer than two records in the window.
//   fall_speed (run)        U, the mean of U_p over the free particles; D their mean diameter.
//   Re = rho_L U D / eta, De = U lambda_r / D, M = sqrt(Re De), E = De / Re: the Reynolds, Deborah,
//                           viscoelastic Mach and elasticity numbers of the paper's section 1 (eta
//                           the zero-shear viscosity; De = M = E = 0 for a Newtonian liquid).
// Reference: Singh, Joseph, Hesla, Glowinski, Pan, J. Non-Newtonian Fluid Mech. 91 (2000) 165-188,
// section 1 (the definitions) and section 5 (Re, De, M and E of each case).
#pragma once

#include <string>
#include <vector>

#include "dlmfd/core/params.h"
#include "dlmfd/io/diagnostics_csv.h"
#include "dlmfd/io/particle_history.h"

namespace dlmfd {

struct RunStatistics {
  double min_gap = 0.0, min_wall_gap = 0.0;
  double max_trA = 0.0, min_eig_A = 0.0;
  double fall_window_start = 0.0, fall_window_end = 0.0;
  std::vector<double> fall_speed;  // per particle, U_p
  double mean_fall_speed = 0.0;    // U
  double diameter = 0.0;           // D
  double reynolds = 0.0, deborah = 0.0, mach = 0.0, elasticity = 0.0;
};

// The statistics from the tables already read.
RunStatistics ComputeRunStatistics(const Params& params, const DiagnosticsTable& diagnostics,
                                   const ParticleHistory& particles);
// Reads DIR/diagnostics.csv and DIR/particles.h5 (a missing or unreadable one counts as empty).
RunStatistics ReadRunStatistics(const Params& params, const std::string& dir);

}  // namespace dlmfd
