// WriteScene: Params back to TOML, every key written (defaults filled in), reals in the shortest
// text that reads back exactly, so that ParseScene(WriteScene(p)) gives p again.
#include <sstream>
#include <vector>

#include "dlmfd/conformation/relaxation_model.h"
#include "dlmfd/core/number_text.h"
#include "dlmfd/scene/auto_coupling.h"
#include "dlmfd/scene/numerics_preset.h"
#include "dlmfd/scene/scene_file.h"
#include "toml_reader.h"

namespace dlmfd {
namespace {

std::string Vec(const Vec2& v) { return "[" + ExactText(v.x()) + ", " + ExactText(v.y()) + "]"; }

std::string Quoted(const std::string& s) { return scene::QuotedText(s); }

const char* SideTypeName(SideType t) {
  switch (t) {
    case SideType::kWall:
      return "wall";
    case SideType::kVelocity:
      return "velocity";
    case SideType::kOutflow:
      return "outflow";
    case SideType::kPeriodic:
      return "periodic";
  }
  return "wall";
}

std::string SideText(const BoundarySide& s) {
  std::string out = std::string("{ type = \"") + SideTypeName(s.type) + "\"";
  if (s.type == SideType::kVelocity) {
    switch (s.profile) {
      case Profile::kUniform:
        out += ", profile = \"uniform\", value = " + Vec(s.value);
        break;
      case Profile::kPoiseuille:
        out += ", profile = \"poiseuille\", max = " + Vec(s.max);
        break;
      case Profile::kQuartic:
        out += ", profile = \"quartic\", max = " + Vec(s.max);
        break;
    }
    out += ", ramp_time = " + ExactText(s.ramp_time);
  }
  return out + " }";
}

const char* MotionName(Motion m) {
  switch (m) {
    case Motion::kFree:
      return "free";
    case Motion::kFixed:
      return "fixed";
    case Motion::kPrescribed:
      return "prescribed";
  }
  return "free";
}

// [fluid]: the liquid and its polymer model.
void WriteFluid(std::ostringstream& o, const FluidParams& f) {
  o << "\n[fluid]\n";
  o << "density = " << ExactText(f.density) << "\n";
  o << "viscosity = " << ExactText(f.viscosity) << "\n";
  o << "relaxation_time = " << ExactText(f.relaxation_time) << "\n";
  o << "solvent_ratio = " << ExactText(f.solvent_ratio) << "\n";
  o << "body_force = " << Vec(f.body_force) << "\n";
  o << "model = \"" << ModelName(f.model) << "\"\n";
  o << "conformation = \"" << RepresentationName(f.conformation) << "\"\n";
  o << "stress_splitting = \""
    << (f.stress_splitting == StressSplitting::kDevss ? "devss" : "explicit") << "\"\n";
  if (f.mobility) o << "mobility = " << ExactText(*f.mobility) << "\n";
  if (f.extensibility) o << "extensibility = " << ExactText(*f.extensibility) << "\n";
  if (f.ptt_epsilon) o << "ptt_epsilon = " << ExactText(*f.ptt_epsilon) << "\n";
}

// [[particles]], one table each.
void WriteParticles(std::ostringstream& o, const std::vector<ParticleParams>& particles) {
  for (const ParticleParams& q : particles) {
    o << "\n[[particles]]\n";
    o << "center = " << Vec(q.center) << "\n";
    // Only for an ellipse or a turned particle: a disk's scene text stays the one written before
    // the keys existed (a checkpoint's --resume compares it).
    if (q.shape == ShapeKind::kEllipse) {
      o << "shape = \"ellipse\"\n";
      o << "semi_axes = " << Vec(q.semi_axes) << "\n";
    } else {
      o << "diameter = " << ExactText(q.diameter) << "\n";
    }
    if (q.angle != 0.0) o << "angle = " << ExactText(q.angle) << "\n";
    o << "density = " << ExactText(q.density) << "\n";
    o << "velocity = " << Vec(q.velocity) << "\n";
    o << "angular_velocity = " << ExactText(q.angular_velocity) << "\n";
    o << "motion = \"" << MotionName(q.motion) << "\"\n";
  }
}

}  // namespace

std::string WriteScene(const Params& p) {
  std::ostringstream o;
  o << "# Written by dlmfd-solve: the scene as run, every default filled in (docs/scenes.md).\n";
  o << "title = " << Quoted(p.title) << "\n";
  o << "gravity = " << Vec(p.gravity) << "\n";
  // Only when not the default: every numerics key is written out below, so the preset
  // changes nothing on reading; it says where the values came from.
  if (p.numerics.preset != NumericsPreset::kDefault) {
    o << "\n[numerics]\npreset = \"" << NumericsPresetName(p.numerics.preset) << "\"\n";
  }

  o << "\n[domain]\n";
  o << "size = " << Vec(p.domain.size) << "\n";
  o << "h = " << ExactText(p.domain.h) << "\n";
  o << "diagonals = \"" << (p.domain.diagonals == MeshDiagonals::kBoth ? "both" : "sw_ne")
    << "\"\n";
  if (p.domain.flow_rate) o << "flow_rate = " << ExactText(*p.domain.flow_rate) << "\n";
  o << "\n[domain.boundary]\n";
  o << "left = " << SideText(p.domain.side(Side::kLeft)) << "\n";
  o << "right = " << SideText(p.domain.side(Side::kRight)) << "\n";
  o << "bottom = " << SideText(p.domain.side(Side::kBottom)) << "\n";
  o << "top = " << SideText(p.domain.side(Side::kTop)) << "\n";

  WriteFluid(o, p.fluid);

  o << "\n[time]\n";
  o << "dt = " << ExactText(p.time.dt) << "\n";
  o << "end = " << ExactText(p.time.end) << "\n";

  o << "\n[splitting]\n";
  o << "alpha = " << ExactText(p.splitting.alpha) << "\n";
  o << "beta = " << ExactText(p.splitting.beta) << "\n";
  o << "advection = \""
    << (p.splitting.advection == AdvectionScheme::kWave ? "wave" : "least_squares") << "\"\n";
  o << "constraint = \"" << ConstraintCouplingName(p.splitting.constraint) << "\"\n";
  o << "steady_correction = \""
    << (p.splitting.steady_correction == SteadyCorrection::kTaylor     ? "taylor"
        : p.splitting.steady_correction == SteadyCorrection::kTendency ? "tendency"
                                                                       : "none")
    << "\"\n";

  const SolverParams& s = p.solvers;
  o << "\n[solvers]\n";
  o << "stokes_tolerance = " << ExactText(s.stokes_tolerance) << "\n";
  o << "stokes_max_iterations = " << s.stokes_max_iterations << "\n";
  o << "advection_tolerance = " << ExactText(s.advection_tolerance) << "\n";
  o << "advection_max_iterations = " << s.advection_max_iterations << "\n";
  o << "wave_max_courant = " << ExactText(s.wave_max_courant) << "\n";
  o << "multiplier_tolerance = " << ExactText(s.multiplier_tolerance) << "\n";
  o << "multiplier_max_iterations = " << s.multiplier_max_iterations << "\n";

  o << "\n[particle_mesh]\n";
  o << "kind = \""
    << (p.particle_mesh.kind == ParticleMeshKind::kCollocation ? "collocation"
        : p.particle_mesh.kind == ParticleMeshKind::kCutCell   ? "cut_cell"
                                                               : "ring")
    << "\"\n";
  o << "h = " << ExactText(p.particle_mesh.h) << "\n";
  o << "spacing = " << ExactText(p.particle_mesh.spacing) << "\n";
  o << "interpolation = \""
    << (p.particle_mesh.interpolation == BoundaryInterpolation::kLinear        ? "linear"
        : p.particle_mesh.interpolation == BoundaryInterpolation::kBiquadratic ? "biquadratic"
                                                                               : "quadratic")
    << "\"\n";

  o << "\n[collisions]\n";
  o << "range = " << ExactText(p.collisions.range) << "\n";
  o << "wall_stiffness = " << ExactText(p.collisions.wall_stiffness) << "\n";
  o << "particle_stiffness = " << ExactText(p.collisions.particle_stiffness) << "\n";
  o << "substeps = " << p.collisions.substeps << "\n";

  o << "\n[conformation]\n";
  o << "form = \"A\"\n";
  o << "max_courant = " << ExactText(p.conformation.max_courant) << "\n";
  o << "blend_kappa = " << ExactText(p.conformation.blend_kappa) << "\n";

  o << "\n[output]\n";
  o << "fields_every = " << ExactText(p.output.fields_every) << "\n";
  o << "particles_every = " << ExactText(p.output.particles_every) << "\n";
  o << "checkpoint_every = " << ExactText(p.output.checkpoint_every) << "\n";

  // Only when set: the scene text of a run (and of its checkpoint, which --resume compares) stays
  // the one written before the key existed.
  if (p.accuracy.strict) o << "\n[accuracy]\nstrict = true\n";

  WriteParticles(o, p.particles);
  return o.str();
}

}  // namespace dlmfd
