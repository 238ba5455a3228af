// Scene parsing (design.md 3.1): TOML -> Params, every key with the default of core/params.h except
// a particle's center (required), particle_mesh.h (kPaperParticleMeshRatio domain.h) and the
// numerics keys, whose defaults follow numerics.preset (scene/numerics_preset.h); "auto" is
// resolved here (scene/auto_coupling.h). Types, choices and unknown keys are checked here, values
// by ValidateScene (scene/scene_validation.h). Every error names the key, the value and what is
// allowed.
#include "dlmfd/scene/scene_file.h"

#include <fstream>
#include <sstream>

#include <toml++/toml.h>

#include "dlmfd/core/errors.h"
#include "dlmfd/core/number_text.h"
#include "dlmfd/scene/auto_coupling.h"
#include "dlmfd/scene/numerics_preset.h"
#include "dlmfd/scene/scene_validation.h"
#include "dlmfd/scene/toml_bounds.h"
#include "scene_overrides.h"
#include "toml_reader.h"

namespace dlmfd {
namespace {

// TOML text is UTF-8 (toml++ refuses a file that is not); an override's text must be too, or the
// scene written back from it (scene.toml in the results) could not be read again.
bool IsUtf8(const std::string& text) {
  // The least code point of each length: shorter (overlong) forms are not UTF-8.
  const unsigned least[] = {0, 0x80, 0x800, 0x10000};
  std::size_t i = 0;
  while (i < text.size()) {
    const auto c = static_cast<unsigned char>(text[i]);
    int extra = -1;
    if (c < 0x80) {
      extra = 0;
    } else if ((c >> 5) == 0x6) {
      extra = 1;
    } else if ((c >> 4) == 0xE) {
      extra = 2;
    } else if ((c >> 3) == 0x1E) {
      extra = 3;
    }
    // Not a lead byte, or the sequence runs past the end.
    if (extra < 0 || i + static_cast<std::size_t>(extra) >= text.size()) return false;
    unsigned code = extra == 0 ? c : (c & (0x3Fu >> extra));
    for (int k = 1; k <= extra; ++k) {
      const auto d = static_cast<unsigned char>(text[i + k]);
      if ((d & 0xC0) != 0x80) return false;
      code = (code << 6) | (d & 0x3Fu);
    }
    // UTF-16 surrogates and code points past U+10FFFF are not UTF-8 either.
    if (code < least[extra] || (code >= 0xD800 && code <= 0xDFFF) || code > 0x10FFFF) return false;
    i += static_cast<std::size_t>(extra) + 1;
  }
  return true;
}

using scene::TableReader;

template <typename Enum>
Enum Choose(const std::string& key, const std::string& word,
            std::initializer_list<std::pair<const char*, Enum>> choices) {
  std::string allowed = "one of";
  for (const auto& c : choices) {
    if (word == c.first) return c.second;
    allowed += std::string(allowed.size() > 6 ? ", " : " ") + "\"" + c.first + "\"";
  }
  throw InvalidParameter(key, "\"" + word + "\"", allowed);
}

void ReadDomain(TableReader& top, const NumericsDefaults& defaults, Params& p) {
  TableReader domain(top.Table("domain"), "domain");
  DomainParams& d = p.domain;
  d.size = domain.Vector("size", d.size);
  d.h = domain.Real("h", d.h);

  TableReader boundary(domain.Table("boundary"), "domain.boundary");
  const char* names[4] = {"left", "right", "bottom", "top"};
  for (int s = 0; s < 4; ++s) {
    BoundarySide& side = d.sides[s];
    side = BoundarySide{};
    const toml::table* table = boundary.Table(names[s]);
    if (table == nullptr) continue;
    TableReader r(table, boundary.Key(names[s]));
    side.type = Choose<SideType>(r.Key("type"), r.String("type", std::nullopt),
                                 {{"wall", SideType::kWall},
                                  {"velocity", SideType::kVelocity},
                                  {"outflow", SideType::kOutflow},
                                  {"periodic", SideType::kPeriodic}});
    if (side.type == SideType::kVelocity) {
      side.profile = Choose<Profile>(r.Key("profile"), r.String("profile", "uniform"),
                                     {{"uniform", Profile::kUniform},
                                      {"poiseuille", Profile::kPoiseuille},
                                      {"quartic", Profile::kQuartic}});
      side.ramp_time = r.Real("ramp_time", 0.0);
      if (side.profile == Profile::kUniform) {
        side.value = r.Vector("value", std::nullopt);
        r.RejectUnknown("type, profile, value, ramp_time for a uniform velocity side");
      } else {
        side.max = r.Vector("max", std::nullopt);
        r.RejectUnknown("type, profile, max, ramp_time for a poiseuille or quartic velocity side");
      }
    } else {
      r.RejectUnknown(std::string("type only, for a ") + names[s] + " side of this type");
    }
  }
  boundary.RejectUnknown("left, right, bottom, top");
  d.diagonals =
      Choose<MeshDiagonals>("domain.diagonals", domain.String("diagonals", defaults.diagonals),
                            {{"sw_ne", MeshDiagonals::kSwNe}, {"both", MeshDiagonals::kBoth}});
  if (domain.Has("flow_rate")) d.flow_rate = domain.Real("flow_rate", std::nullopt);
  domain.RejectUnknown("size, h, boundary, diagonals, flow_rate");
}

void ReadFluid(TableReader& top, const NumericsDefaults& defaults, Params& p) {
  TableReader fluid(top.Table("fluid"), "fluid");
  FluidParams& f = p.fluid;
  f.density = fluid.Real("density", f.density);
  f.viscosity = fluid.Real("viscosity", f.viscosity);
  f.relaxation_time = fluid.Real("relaxation_time", f.relaxation_time);
  f.solvent_ratio = fluid.Real("solvent_ratio", f.solvent_ratio);
  f.body_force = fluid.Vector("body_force", f.body_force);
  f.model = Choose<ConstitutiveModel>("fluid.model", fluid.String("model", "oldroyd_b"),
                                      {{"oldroyd_b", ConstitutiveModel::kOldroydB},
                                       {"giesekus", ConstitutiveModel::kGiesekus},
                                       {"fene_p", ConstitutiveModel::kFeneP},
                                       {"ptt_linear", ConstitutiveModel::kPttLinear},
                                       {"ptt_exponential", ConstitutiveModel::kPttExponential}});
  f.conformation = Choose<ConformationRepresentation>(
      "fluid.conformation", fluid.String("conformation", "standard"),
      {{"standard", ConformationRepresentation::kStandard},
       {"log", ConformationRepresentation::kLog},
       {"sqrt", ConformationRepresentation::kSqrt}});
  f.stress_splitting = Choose<StressSplitting>(
      "fluid.stress_splitting", fluid.String("stress_splitting", defaults.stress_splitting),
      {{"explicit", StressSplitting::kExplicit}, {"devss", StressSplitting::kDevss}});
  // Model parameters: present only when given (ValidateScene checks them against fluid.model).
  auto optional_real = [&fluid](const char* name) -> std::optional<double> {
    if (!fluid.Has(name)) return std::nullopt;
    return fluid.Real(name, std::nullopt);
  };
  f.mobility = optional_real("mobility");
  f.extensibility = optional_real("extensibility");
  f.ptt_epsilon = optional_real("ptt_epsilon");
  fluid.Vector("gravity", Vec2::Zero());  // read by ReadGravity
  fluid.RejectUnknown(
      "density, viscosity, relaxation_time, solvent_ratio, body_force, model, conformation, "
      "stress_splitting, mobility, extensibility, ptt_epsilon, gravity");
}

// gravity is a top-level key; `fluid.gravity` is accepted too, because a `gravity = ...` line
// written after the [fluid] header (as in design.md 3.1) belongs to that table in TOML.
void ReadGravity(TableReader& top, Params& p) {
  const toml::table* fluid = top.Has("fluid") ? top.Table("fluid") : nullptr;
  TableReader in_fluid(fluid, "fluid");
  const bool at_top = top.Has("gravity");
  const bool under_fluid = in_fluid.Has("gravity");
  if (at_top && under_fluid) {
    throw InvalidParameter("fluid.gravity", scene::NodeText(*fluid->get("gravity")),
                           "no second gravity (gravity is also given at the top level)");
  }
  p.gravity = at_top ? top.Vector("gravity", p.gravity) : in_fluid.Vector("gravity", p.gravity);
}

void ReadTime(TableReader& top, Params& p) {
  TableReader time(top.Table("time"), "time");
  p.time.dt = time.Real("dt", p.time.dt);
  p.time.end = time.Real("end", p.time.end);
  time.RejectUnknown("dt, end");
}

// Read last: "auto" is resolved from the rest of the scene (scene/auto_coupling.h).
void ReadSplitting(TableReader& top, const NumericsDefaults& defaults, Params& p) {
  TableReader splitting(top.Table("splitting"), "splitting");
  const std::string word = splitting.String("constraint", defaults.constraint);
  std::string chosen = word;
  if (word == "auto") {
    p.numerics.resolved.push_back(ResolveConstraintCoupling(p));
    chosen = p.numerics.resolved.back().value;
  }
  // The constraint first: the defaults of alpha and beta follow it.
  SplittingParams& s = p.splitting;
  s = SplittingParams::DefaultWeights(Choose<ConstraintCoupling>(
      "splitting.constraint", chosen,
      {{"auto", ConstraintCoupling::kIncremental},  // never taken (resolved above); listed for
                                                    // the error's allowed values
       {"incremental", ConstraintCoupling::kIncremental},
       {"paper", ConstraintCoupling::kPaper},
       {"viscous", ConstraintCoupling::kViscous}}));
  s.alpha = splitting.Real("alpha", s.alpha);
  s.beta = splitting.Real("beta", s.beta);
  s.advection = Choose<AdvectionScheme>(
      "splitting.advection", splitting.String("advection", defaults.advection),
      {{"least_squares", AdvectionScheme::kLeastSquares}, {"wave", AdvectionScheme::kWave}});
  // (ReadFluid first.) The correction's default depends on the liquid.
  s.steady_correction = Choose<SteadyCorrection>(
      "splitting.steady_correction",
      splitting.String("steady_correction", p.fluid.IsNewtonian()
                                                ? defaults.steady_correction
                                                : defaults.steady_correction_polymer),
      {{"none", SteadyCorrection::kNone},
       {"taylor", SteadyCorrection::kTaylor},
       {"tendency", SteadyCorrection::kTendency}});
  splitting.RejectUnknown("alpha, beta, advection, constraint, steady_correction");
}

// numerics.preset, read first: the numerics keys' defaults follow it.
NumericsDefaults ReadNumerics(TableReader& top, Params& p) {
  TableReader numerics(top.Table("numerics"), "numerics");
  p.numerics.preset = Choose<NumericsPreset>(
      "numerics.preset", numerics.String("preset", "default"),
      {{"default", NumericsPreset::kDefault}, {"paper", NumericsPreset::kPaper}});
  numerics.RejectUnknown("preset");
  return DefaultsOf(p.numerics.preset);
}

void ReadSolvers(TableReader& top, Params& p) {
  TableReader r(top.Table("solvers"), "solvers");
  SolverParams& s = p.solvers;
  s.stokes_tolerance = r.Real("stokes_tolerance", s.stokes_tolerance);
  s.stokes_max_iterations = r.Integer("stokes_max_iterations", s.stokes_max_iterations);
  s.advection_tolerance = r.Real("advection_tolerance", s.advection_tolerance);
  s.advection_max_iterations = r.Integer("advection_max_iterations", s.advection_max_iterations);
  s.wave_max_courant = r.Real("wave_max_courant", s.wave_max_courant);
  s.multiplier_tolerance = r.Real("multiplier_tolerance", s.multiplier_tolerance);
  s.multiplier_max_iterations = r.Integer("multiplier_max_iterations", s.multiplier_max_iterations);
  r.RejectUnknown(
      "stokes_tolerance, stokes_max_iterations, advection_tolerance, advection_max_iterations, "
      "wave_max_courant, "
      "multiplier_tolerance, multiplier_max_iterations");
}

void ReadMeshCollisionsConformationOutput(TableReader& top, const NumericsDefaults& defaults,
                                          Params& p) {
  TableReader mesh(top.Table("particle_mesh"), "particle_mesh");
  ParticleMeshParams& pm = p.particle_mesh;
  pm.kind = Choose<ParticleMeshKind>("particle_mesh.kind",
                                     mesh.String("kind", defaults.particle_mesh_kind),
                                     {{"ring", ParticleMeshKind::kRing},
                                      {"collocation", ParticleMeshKind::kCollocation},
                                      {"cut_cell", ParticleMeshKind::kCutCell}});
  pm.h = mesh.Real("h", kPaperParticleMeshRatio * p.domain.h);  // follows the fluid mesh
  pm.spacing = mesh.Real("spacing", pm.spacing);
  pm.interpolation = Choose<BoundaryInterpolation>(
      "particle_mesh.interpolation", mesh.String("interpolation", "quadratic"),
      {{"quadratic", BoundaryInterpolation::kQuadratic},
       {"linear", BoundaryInterpolation::kLinear},
       {"biquadratic", BoundaryInterpolation::kBiquadratic}});
  mesh.RejectUnknown("kind, h, spacing, interpolation");

  TableReader col(top.Table("collisions"), "collisions");
  CollisionParams& c = p.collisions;
  c.range = col.Real("range", c.range);
  c.wall_stiffness = col.Real("wall_stiffness", c.wall_stiffness);
  c.particle_stiffness = col.Real("particle_stiffness", c.particle_stiffness);
  c.substeps = col.Integer("substeps", c.substeps);
  col.RejectUnknown("range, wall_stiffness, particle_stiffness, substeps");

  TableReader conf(top.Table("conformation"), "conformation");
  p.conformation.form = Choose<ConformationForm>("conformation.form", conf.String("form", "A"),
                                                 {{"A", ConformationForm::kA}});
  p.conformation.max_courant = conf.Real("max_courant", p.conformation.max_courant);
  p.conformation.blend_kappa = conf.Real("blend_kappa", p.conformation.blend_kappa);
  conf.RejectUnknown("form, max_courant, blend_kappa");

  TableReader out(top.Table("output"), "output");
  OutputParams& o = p.output;
  o.fields_every = out.Real("fields_every", o.fields_every);
  o.particles_every = out.Real("particles_every", o.particles_every);
  o.checkpoint_every = out.Real("checkpoint_every", o.checkpoint_every);
  out.RejectUnknown("fields_every, particles_every, checkpoint_every");

  TableReader accuracy(top.Table("accuracy"), "accuracy");
  p.accuracy.strict = accuracy.Boolean("strict", p.accuracy.strict);
  accuracy.RejectUnknown("strict");
}

// A particle's shape: shape = "disk" (the default) with its diameter, or "ellipse" with
// semi_axes = [a, b] (along the body's x and y axes); angle (radians) turns the body's x axis from
// the domain's at t = 0. Each shape refuses the other's size key.
void ReadShape(TableReader& r, ParticleParams& q) {
  q.shape = Choose<ShapeKind>(r.Key("shape"), r.String("shape", "disk"),
                              {{"disk", ShapeKind::kDisk}, {"ellipse", ShapeKind::kEllipse}});
  if (q.shape == ShapeKind::kDisk) {
    if (r.Has("semi_axes")) {
      throw InvalidParameter(r.Key("semi_axes"), VecText(r.Vector("semi_axes", std::nullopt)),
                             "absent for a disk (give diameter), or shape = \"ellipse\"");
    }
    q.diameter = r.Real("diameter", q.diameter);
  } else {
    if (r.Has("diameter")) {
      throw InvalidParameter(r.Key("diameter"), ExactText(r.Real("diameter", std::nullopt)),
                             "absent for an ellipse (give semi_axes = [a, b]), or shape = "
                             "\"disk\"");
    }
    const Vec2 axes = r.Vector("semi_axes", std::nullopt);
    q.SetEllipse(axes.x(), axes.y());
  }
  q.angle = r.Real("angle", q.angle);
}

void ReadParticles(TableReader& top, Params& p) {
  const toml::array* array = top.Array("particles");
  p.particles.clear();
  if (array == nullptr) return;
  for (std::size_t i = 0; i < array->size(); ++i) {
    const std::string prefix = "particles." + std::to_string(i);
    const toml::table* table = array->get(i)->as_table();
    if (table == nullptr)
      throw InvalidParameter(prefix, scene::NodeText(*array->get(i)), "a table ([[particles]])");
    TableReader r(table, prefix);
    ParticleParams q;
    q.center = r.Vector("center", std::nullopt);
    ReadShape(r, q);
    q.density = r.Real("density", q.density);
    q.velocity = r.Vector("velocity", q.velocity);
    q.angular_velocity = r.Real("angular_velocity", q.angular_velocity);
    q.motion = Choose<Motion>(
        r.Key("motion"), r.String("motion", "free"),
        {{"free", Motion::kFree}, {"fixed", Motion::kFixed}, {"prescribed", Motion::kPrescribed}});
    r.RejectUnknown(
        "center, shape, diameter, semi_axes, angle, density, velocity, angular_velocity, motion");
    p.particles.push_back(q);
  }
}

}  // namespace

SceneOverride ParseOverride(const std::string& key_equals_value) {
  const auto eq = key_equals_value.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw InvalidParameter("--set", key_equals_value,
                           "key=value with a dotted scene key (e.g. fluid.viscosity=0.1)");
  }
  auto trim = [](std::string s) {
    const auto b = s.find_first_not_of(" \t");
    const auto e = s.find_last_not_of(" \t");
    return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
  };
  if (!IsUtf8(key_equals_value)) {
    throw InvalidParameter("--set", "(a key=value with bytes that are not UTF-8)",
                           "UTF-8 text, as in a scene file");
  }
  SceneOverride o{trim(key_equals_value.substr(0, eq)), trim(key_equals_value.substr(eq + 1))};
  if (o.key.empty()) {
    throw InvalidParameter("--set", key_equals_value,
                           "key=value with a dotted scene key (e.g. fluid.viscosity=0.1)");
  }
  return o;
}

Params ParseScene(const std::string& toml_text, const std::vector<SceneOverride>& overrides,
                  const std::string& origin) {
  scene::RequireBoundedToml(toml_text, origin);
  toml::table root;
  try {
    root = toml::parse(toml_text, origin);
  } catch (const toml::parse_error& e) {
    std::ostringstream where;
    where << "line " << e.source().begin.line << " column " << e.source().begin.column;
    throw InvalidParameter(origin, where.str(),
                           "valid TOML (" + std::string(e.description()) + ")");
  }
  scene::ApplyOverrides(root, overrides);

  Params p;
  TableReader top(&root, "");
  p.title = top.String("title", "");
  const NumericsDefaults defaults = ReadNumerics(top, p);
  ReadDomain(top, defaults, p);
  ReadFluid(top, defaults, p);
  ReadGravity(top, p);
  ReadTime(top, p);
  ReadSolvers(top, p);
  ReadMeshCollisionsConformationOutput(top, defaults, p);
  ReadParticles(top, p);
  ReadSplitting(top, defaults, p);
  top.RejectUnknown(
      "title, numerics, domain, fluid, gravity, time, splitting, solvers, particles, "
      "particle_mesh, collisions, conformation, output, accuracy");
  ValidateScene(p);
  return p;
}

Params LoadSceneFile(const std::string& path, const std::vector<SceneOverride>& overrides) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidParameter("scene", path, "a readable scene file");
  std::ostringstream text;
  text << in.rdbuf();
  return ParseScene(text.str(), overrides, path);
}

}  // namespace dlmfd
