// Scene parsing and validation (design.md 3.1). Every key has the default of core/params.h except a
// particle's center; every check names the key, the value and what is allowed.
#include "dlmfd/scene/scene_file.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include <toml++/toml.h>

#include "dlmfd/core/errors.h"
#include "scene_overrides.h"
#include "toml_reader.h"

namespace dlmfd {
namespace {

using scene::ExactText;
using scene::TableReader;

// Largest grid accepted: velocity nodes of the h-grid. About kBytesPerNode of memory each (fields,
// conformation, solver work arrays), so 2e7 nodes is some 6 GiB.
constexpr double kMaxNodes = 2e7;
constexpr double kBytesPerNode = 320.0;

std::string VecText(const Vec2& v) {
  return "[" + ExactText(v.x()) + ", " + ExactText(v.y()) + "]";
}

void RequirePositive(const std::string& key, double x) {
  if (!(x > 0.0)) throw InvalidParameter(key, ExactText(x), "a number > 0");
}
void RequireNonNegative(const std::string& key, double x) {
  if (!(x >= 0.0)) throw InvalidParameter(key, ExactText(x), "a number >= 0");
}
void RequireOpenUnit(const std::string& key, double x) {
  if (!(x > 0.0 && x < 1.0)) throw InvalidParameter(key, ExactText(x), "a number in (0, 1)");
}
void RequireHalfOpenUnit(const std::string& key, double x) {
  if (!(x > 0.0 && x <= 1.0)) throw InvalidParameter(key, ExactText(x), "a number in (0, 1]");
}
void RequireClosedUnit(const std::string& key, double x) {
  if (!(x >= 0.0 && x <= 1.0)) throw InvalidParameter(key, ExactText(x), "a number in [0, 1]");
}
void RequireAtLeastOne(const std::string& key, int n) {
  if (n < 1) throw InvalidParameter(key, std::to_string(n), "an integer >= 1");
}

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

// The number of cells that `length` holds; an even integer within 1e-9 relative, else an error.
int EvenCells(const std::string& key, const Vec2& size, double length, double h) {
  const double n = length / h;
  const double rounded = std::round(n);
  if (std::abs(n - rounded) > 1e-9 * std::max(1.0, n) || static_cast<long long>(rounded) % 2 != 0 ||
      rounded < 2) {
    std::ostringstream allowed;
    allowed << "a size that is an even number of cells of domain.h = " << ExactText(h)
            << " in both directions (here " << ExactText(length) << " / h = " << n
            << "; the pressure mesh is 2h)";
    throw InvalidParameter(key, VecText(size), allowed.str());
  }
  return static_cast<int>(rounded);
}

void ReadDomain(TableReader& top, Params& p) {
  TableReader domain(top.Table("domain"), "domain");
  DomainParams& d = p.domain;
  d.size = domain.Vector("size", d.size);
  if (!(d.size.x() > 0.0 && d.size.y() > 0.0)) {
    throw InvalidParameter("domain.size", VecText(d.size), "two numbers > 0 (width, height)");
  }
  d.h = domain.Real("h", d.h);
  RequirePositive("domain.h", d.h);
  const double nodes = (d.size.x() / d.h + 1.0) * (d.size.y() / d.h + 1.0);
  if (nodes > kMaxNodes) {
    std::ostringstream allowed;
    allowed << "a mesh of at most " << kMaxNodes << " velocity nodes (this one has " << nodes
            << ", about " << nodes * kBytesPerNode / (1024.0 * 1024.0 * 1024.0)
            << " GiB of memory)";
    throw InvalidParameter("domain.h", ExactText(d.h), allowed.str());
  }
  EvenCells("domain.size", d.size, d.size.x(), d.h);
  EvenCells("domain.size", d.size, d.size.y(), d.h);

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
      side.profile =
          Choose<Profile>(r.Key("profile"), r.String("profile", "uniform"),
                          {{"uniform", Profile::kUniform}, {"poiseuille", Profile::kPoiseuille}});
      if (side.profile == Profile::kUniform) {
        side.value = r.Vector("value", std::nullopt);
        r.RejectUnknown("type, profile, value for a uniform velocity side");
      } else {
        side.max = r.Vector("max", std::nullopt);
        r.RejectUnknown("type, profile, max for a poiseuille velocity side");
      }
    } else {
      r.RejectUnknown(std::string("type only, for a ") + names[s] + " side of this type");
    }
  }
  boundary.RejectUnknown("left, right, bottom, top");
  for (int s = 0; s < 4; s += 2) {
    const bool first = d.sides[s].type == SideType::kPeriodic;
    const bool second = d.sides[s + 1].type == SideType::kPeriodic;
    if (first != second) {
      const int odd = first ? s + 1 : s;
      const int even = first ? s : s + 1;
      throw InvalidParameter(
          std::string("domain.boundary.") + names[odd] + ".type", "(not periodic)",
          std::string("\"periodic\", because domain.boundary.") + names[even] +
              " is periodic (periodic sides come in pairs: left with right, bottom with top)");
    }
  }
  domain.RejectUnknown("size, h, boundary");
}

void ReadFluid(TableReader& top, Params& p) {
  TableReader fluid(top.Table("fluid"), "fluid");
  FluidParams& f = p.fluid;
  f.density = fluid.Real("density", f.density);
  RequirePositive("fluid.density", f.density);
  f.viscosity = fluid.Real("viscosity", f.viscosity);
  RequirePositive("fluid.viscosity", f.viscosity);
  f.relaxation_time = fluid.Real("relaxation_time", f.relaxation_time);
  RequireNonNegative("fluid.relaxation_time", f.relaxation_time);
  f.solvent_ratio = fluid.Real("solvent_ratio", f.solvent_ratio);
  RequireHalfOpenUnit("fluid.solvent_ratio", f.solvent_ratio);
  f.body_force = fluid.Vector("body_force", f.body_force);
  fluid.Vector("gravity", Vec2::Zero());  // read by ReadGravity
  fluid.RejectUnknown("density, viscosity, relaxation_time, solvent_ratio, body_force, gravity");
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

void ReadTimeAndSplitting(TableReader& top, Params& p) {
  TableReader time(top.Table("time"), "time");
  p.time.dt = time.Real("dt", p.time.dt);
  RequirePositive("time.dt", p.time.dt);
  p.time.end = time.Real("end", p.time.end);
  RequireNonNegative("time.end", p.time.end);
  if (p.time.end > 0.0 && p.time.dt > p.time.end) {
    throw InvalidParameter(
        "time.dt", ExactText(p.time.dt),
        "a step <= time.end = " + ExactText(p.time.end) + " (unless time.end = 0)");
  }
  time.RejectUnknown("dt, end");

  TableReader splitting(top.Table("splitting"), "splitting");
  SplittingParams& s = p.splitting;
  s.alpha = splitting.Real("alpha", s.alpha);
  RequireClosedUnit("splitting.alpha", s.alpha);
  s.beta = splitting.Real("beta", s.beta);
  RequireClosedUnit("splitting.beta", s.beta);
  if (std::abs(s.alpha + s.beta - 1.0) > 1e-12) {
    throw InvalidParameter(
        "splitting.beta", ExactText(s.beta),
        "1 - splitting.alpha = " + ExactText(1.0 - s.alpha) +
            " (gamma = 1 - alpha - beta must be 0: the only splitting the engine supports)");
  }
  s.advection = Choose<AdvectionScheme>(
      "splitting.advection", splitting.String("advection", "least_squares"),
      {{"least_squares", AdvectionScheme::kLeastSquares}, {"wave", AdvectionScheme::kWave}});
  splitting.RejectUnknown("alpha, beta, advection");
}

void ReadSolvers(TableReader& top, Params& p) {
  TableReader r(top.Table("solvers"), "solvers");
  SolverParams& s = p.solvers;
  s.stokes_tolerance = r.Real("stokes_tolerance", s.stokes_tolerance);
  RequireOpenUnit("solvers.stokes_tolerance", s.stokes_tolerance);
  s.stokes_max_iterations = r.Integer("stokes_max_iterations", s.stokes_max_iterations);
  RequireAtLeastOne("solvers.stokes_max_iterations", s.stokes_max_iterations);
  s.advection_tolerance = r.Real("advection_tolerance", s.advection_tolerance);
  RequireOpenUnit("solvers.advection_tolerance", s.advection_tolerance);
  s.advection_max_iterations = r.Integer("advection_max_iterations", s.advection_max_iterations);
  RequireAtLeastOne("solvers.advection_max_iterations", s.advection_max_iterations);
  s.wave_max_courant = r.Real("wave_max_courant", s.wave_max_courant);
  RequireHalfOpenUnit("solvers.wave_max_courant", s.wave_max_courant);
  s.multiplier_tolerance = r.Real("multiplier_tolerance", s.multiplier_tolerance);
  RequireOpenUnit("solvers.multiplier_tolerance", s.multiplier_tolerance);
  s.multiplier_max_iterations = r.Integer("multiplier_max_iterations", s.multiplier_max_iterations);
  RequireAtLeastOne("solvers.multiplier_max_iterations", s.multiplier_max_iterations);
  r.RejectUnknown(
      "stokes_tolerance, stokes_max_iterations, advection_tolerance, advection_max_iterations, "
      "wave_max_courant, "
      "multiplier_tolerance, multiplier_max_iterations");
}

void ReadMeshCollisionsConformationOutput(TableReader& top, Params& p) {
  TableReader mesh(top.Table("particle_mesh"), "particle_mesh");
  p.particle_mesh.h = mesh.Real("h", p.particle_mesh.h);
  RequirePositive("particle_mesh.h", p.particle_mesh.h);
  mesh.RejectUnknown("h");

  TableReader col(top.Table("collisions"), "collisions");
  CollisionParams& c = p.collisions;
  c.range = col.Real("range", c.range);
  RequirePositive("collisions.range", c.range);
  c.wall_stiffness = col.Real("wall_stiffness", c.wall_stiffness);
  RequirePositive("collisions.wall_stiffness", c.wall_stiffness);
  c.particle_stiffness = col.Real("particle_stiffness", c.particle_stiffness);
  RequirePositive("collisions.particle_stiffness", c.particle_stiffness);
  c.substeps = col.Integer("substeps", c.substeps);
  RequireAtLeastOne("collisions.substeps", c.substeps);
  col.RejectUnknown("range, wall_stiffness, particle_stiffness, substeps");

  TableReader conf(top.Table("conformation"), "conformation");
  p.conformation.form = Choose<ConformationForm>("conformation.form", conf.String("form", "A"),
                                                 {{"A", ConformationForm::kA}});
  p.conformation.max_courant = conf.Real("max_courant", p.conformation.max_courant);
  RequireHalfOpenUnit("conformation.max_courant", p.conformation.max_courant);
  p.conformation.blend_kappa = conf.Real("blend_kappa", p.conformation.blend_kappa);
  RequireHalfOpenUnit("conformation.blend_kappa", p.conformation.blend_kappa);
  conf.RejectUnknown("form, max_courant, blend_kappa");

  TableReader out(top.Table("output"), "output");
  OutputParams& o = p.output;
  o.fields_every = out.Real("fields_every", o.fields_every);
  RequireNonNegative("output.fields_every", o.fields_every);
  o.particles_every = out.Real("particles_every", o.particles_every);
  RequireNonNegative("output.particles_every", o.particles_every);
  o.checkpoint_every = out.Real("checkpoint_every", o.checkpoint_every);
  RequireNonNegative("output.checkpoint_every", o.checkpoint_every);
  out.RejectUnknown("fields_every, particles_every, checkpoint_every");
}

// Distance between two centres; the nearest periodic image along periodic directions.
double CenterDistance(const DomainParams& d, const Vec2& a, const Vec2& b) {
  Vec2 delta = a - b;
  if (d.PeriodicX()) delta.x() -= d.size.x() * std::round(delta.x() / d.size.x());
  if (d.PeriodicY()) delta.y() -= d.size.y() * std::round(delta.y() / d.size.y());
  return delta.norm();
}

void CheckInside(const DomainParams& d, const std::string& key, const ParticleParams& q) {
  const double r = q.Radius();
  const bool periodic[2] = {d.PeriodicX(), d.PeriodicY()};
  for (int k = 0; k < 2; ++k) {
    const double c = q.center[k];
    const double lo = periodic[k] ? 0.0 : r;
    const double hi = periodic[k] ? d.size[k] : d.size[k] - r;
    if (!(c >= lo && c <= hi)) {
      throw InvalidParameter(key, VecText(q.center),
                             std::string("a centre with ") + (k == 0 ? "x" : "y") + " in [" +
                                 ExactText(lo) + ", " + ExactText(hi) + "] (the disk of radius " +
                                 ExactText(r) + " inside the domain [0, " + ExactText(d.size.x()) +
                                 "] x [0, " + ExactText(d.size.y()) +
                                 "]; it may cross periodic sides only)");
    }
  }
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
    q.diameter = r.Real("diameter", q.diameter);
    RequirePositive(r.Key("diameter"), q.diameter);
    q.density = r.Real("density", q.density);
    RequirePositive(r.Key("density"), q.density);
    q.velocity = r.Vector("velocity", q.velocity);
    q.angular_velocity = r.Real("angular_velocity", q.angular_velocity);
    q.motion = Choose<Motion>(
        r.Key("motion"), r.String("motion", "free"),
        {{"free", Motion::kFree}, {"fixed", Motion::kFixed}, {"prescribed", Motion::kPrescribed}});
    r.RejectUnknown("center, diameter, density, velocity, angular_velocity, motion");
    if (q.motion == Motion::kFree && q.density < p.fluid.density) {
      throw InvalidParameter(
          r.Key("density"), ExactText(q.density),
          ">= fluid.density = " + ExactText(p.fluid.density) +
              " for a free particle (a light disk makes the excess mass (rho_d - rho_L) V "
              "of (36)-(38) negative and the multiplier problem (37) indefinite)");
    }
    CheckInside(p.domain, r.Key("center"), q);
    p.particles.push_back(q);
  }
  for (std::size_t j = 1; j < p.particles.size(); ++j) {
    for (std::size_t i = 0; i < j; ++i) {
      const ParticleParams& a = p.particles[i];
      const ParticleParams& b = p.particles[j];
      const double gap = CenterDistance(p.domain, a.center, b.center) - a.Radius() - b.Radius();
      if (gap < 0.0) {
        throw InvalidParameter("particles." + std::to_string(j) + ".center", VecText(b.center),
                               "a disk that does not overlap particle " + std::to_string(i) +
                                   " at t = 0 (gap " + scene::ShortText(gap) +
                                   " between particles " + std::to_string(i) + " and " +
                                   std::to_string(j) + ")");
      }
    }
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
  SceneOverride o{trim(key_equals_value.substr(0, eq)), trim(key_equals_value.substr(eq + 1))};
  if (o.key.empty()) {
    throw InvalidParameter("--set", key_equals_value,
                           "key=value with a dotted scene key (e.g. fluid.viscosity=0.1)");
  }
  return o;
}

Params ParseScene(const std::string& toml_text, const std::vector<SceneOverride>& overrides,
                  const std::string& origin) {
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
  ReadDomain(top, p);
  ReadFluid(top, p);
  ReadGravity(top, p);
  ReadTimeAndSplitting(top, p);
  ReadSolvers(top, p);
  ReadMeshCollisionsConformationOutput(top, p);
  ReadParticles(top, p);
  top.RejectUnknown(
      "title, domain, fluid, gravity, time, splitting, solvers, particles, particle_mesh, "
      "collisions, conformation, "
      "output");
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
