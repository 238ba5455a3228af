// splitting.constraint = "auto": the rules, one function each, tried in order
// (scene/auto_coupling.h). A rule returns the coupling it picks, or nothing when it does not
// apply; the evidence for each is beside it. To add a rule: write its function, put it in
// kRules at its place in the order, pin it with a test in tests/unit/auto_coupling_test.cc and
// list it in the header and in docs/scenes.md.
#include "dlmfd/scene/auto_coupling.h"

#include <algorithm>
#include <optional>

#include "dlmfd/core/number_text.h"
#include "dlmfd/core/param_words.h"
#include "dlmfd/scene/accuracy_envelope.h"

namespace dlmfd {
namespace {

struct Pick {
  ConstraintCoupling coupling;
  const char* rule;  // why, in words; the numbers follow it in the record
};

using Rule = std::optional<Pick> (*)(const CouplingNumbers&);

// 1. Nothing to couple. The couplings differ only in their default weights then; incremental's
// (alpha = 1, beta = 0) are the engine's default for a liquid alone.
std::optional<Pick> NoParticles(const CouplingNumbers& n) {
  if (n.particles) return std::nullopt;
  return Pick{ConstraintCoupling::kIncremental, "no particles"};
}

// 2. Particles that cross a good part of a cell a step where the paper's leak is small. The lagged
// multiplier acts where the particle was a step ago, and diverged on the paper's case 5.1 written
// without numerics keys from U_p dt / h = 0.60 on (docs/evidence/constraint_coupling.md, "The
// automatic coupling"). Such particles move by inertia: nu dt / h^2 is small there, and so is the
// paper's leak; the rule asks for nu dt / h^2 inside the paper coupling's envelope
// (accuracy_envelope.h), since U_p is an upper estimate and a light disk in a viscous liquid, which
// it overstates, needs the lag (tests/convergence/lagged_reaction_test.cc).
std::optional<Pick> FastParticles(const CouplingNumbers& n) {
  if (!(n.particle_courant > kMaxLaggedParticleCourant)) return std::nullopt;
  if (n.viscous_number > kMaxViscousNumberWithParticles) return std::nullopt;
  return Pick{ConstraintCoupling::kPaper,
              "particles cross more than 0.3 of a cell a step (U_p dt / h > 0.3), where the "
              "lagged multiplier diverged, and nu dt / h^2 <= 0.195 keeps the paper's leak small"};
}

// 3. Creeping flow: the lagged multiplier settles over about nu dt / h^2 steps (its error decays
// as (I - P^-1 S)^n; docs/evidence/constraint_coupling.md, "The lagged multiplier"), which in a
// liquid of small density at a time step set by the motion is longer than the flow itself, while
// the viscous coupling gives the steady answer from the first steps; the threshold is where the
// lag still settled as fast as the liquid (docs/evidence/validation_particles.md, "Creeping flow at
// a time step set by the motion"). A neutrally buoyant free particle cannot take it
// (ValidateScene), so such a scene keeps the lagged multiplier.
std::optional<Pick> CreepingFlow(const CouplingNumbers& n) {
  if (!(n.viscous_number > kMaxViscousNumberLaggedSettles)) return std::nullopt;
  if (n.neutral_free_particle) return std::nullopt;
  return Pick{ConstraintCoupling::kViscous,
              "nu dt / h^2 > 18.5: the lagged multiplier would settle over more steps than the "
              "flow takes (creeping flow)"};
}

// 4. The rest: the lagged multiplier removes the paper's leak at the paper's cost
// (docs/evidence/constraint_coupling.md, "Coupling the constraint with viscosity"). Particles that
// turn too: with interior points that cannot pair up in a cell the lagged multiplier completes
// every run that blew up with the turned lattice and is nearer its dt limit than the paper's
// coupling (docs/evidence/validation_particles.md, "The lagged multiplier on a turning shape").
std::optional<Pick> Incremental(const CouplingNumbers& n) {
  return Pick{ConstraintCoupling::kIncremental,
              n.particle_courant > kMaxLaggedParticleCourant
                  ? "nu dt / h^2 > 0.195: the paper's leak would be large"
                  : "particles slower than 0.3 of a cell a step"};
}

constexpr Rule kRules[] = {NoParticles, FastParticles, CreepingFlow, Incremental};

}  // namespace

const char* ConstraintCouplingName(ConstraintCoupling coupling) { return WordOf(coupling); }

std::string ResolvedChoiceText(const ResolvedChoice& c) {
  std::string numbers;
  for (const auto& [name, value] : c.numbers) {
    numbers += (numbers.empty() ? "; " : ", ") + name + " = " + ShortText(value);
  }
  return c.key + " = \"" + c.value + "\" (auto: " + c.rule + numbers + ")";
}

CouplingNumbers ComputeCouplingNumbers(const Params& p) {
  CouplingNumbers n;
  const double h = p.domain.h;
  const double dt = p.time.dt;
  const double rho = p.fluid.density;
  const double eta = p.fluid.viscosity;
  n.particles = !p.particles.empty();
  n.polymer = !p.fluid.IsNewtonian();
  n.viscous_number = eta / rho * dt / (h * h);
  n.particle_speed = ParticleVelocityScale(p);
  n.particle_courant = n.particle_speed * dt / h;
  double diameter = 0.0;
  double densest = 0.0;
  for (const ParticleParams& q : p.particles) {
    diameter = std::max(diameter, q.diameter);
    densest = std::max(densest, q.density);
    if (q.motion != Motion::kFree) continue;
    const double ratio = q.density / rho;
    n.neutral_free_particle = n.neutral_free_particle || q.density == rho;
    n.min_density_ratio = n.min_density_ratio == 0.0 ? ratio : std::min(n.min_density_ratio, ratio);
    n.max_density_ratio = std::max(n.max_density_ratio, ratio);
  }
  n.particle_reynolds = rho * n.particle_speed * diameter / eta;
  n.stokes_number = densest / rho * n.particle_reynolds / 9.0;
  return n;
}

ResolvedChoice ResolveConstraintCoupling(const Params& params) {
  const CouplingNumbers n = ComputeCouplingNumbers(params);
  ResolvedChoice choice;
  choice.key = "splitting.constraint";
  for (Rule rule : kRules) {
    const std::optional<Pick> pick = rule(n);
    if (!pick) continue;
    choice.value = ConstraintCouplingName(pick->coupling);
    choice.rule = pick->rule;
    break;
  }
  choice.numbers = {{"nu dt / h^2", n.viscous_number}, {"U_p dt / h", n.particle_courant}};
  if (n.particles) {
    choice.numbers.push_back({"Re_p", n.particle_reynolds});
    choice.numbers.push_back({"St", n.stokes_number});
    if (n.max_density_ratio > 0.0) {
      choice.numbers.push_back({"rho_p / rho (min)", n.min_density_ratio});
      choice.numbers.push_back({"rho_p / rho (max)", n.max_density_ratio});
    }
  }
  return choice;
}

}  // namespace dlmfd
