// What the HDF5 files of a results directory say about themselves (docs/results.md, "Files that
// describe themselves"): a format name and version, the scene as run, and for every dataset its
// units and a description.
//
// Units are written as dimensions in the scene's own units, L (length), M (mass), T (time), each
// with an integer power ("L T-1" for a velocity, "1" for a dimensionless number, "rad" for an
// angle): a scene file has no unit system of its own (the paper's cases are CGS: L = cm, M = g,
// T = s, g = 981). The 2D domain is a slice of unit depth, so a density is M L-3, a particle's
// force per unit length M T-2 and its torque per unit length M L T-2 (the paper's section 2: disk
// mass rho_d pi R^2 per unit length). `dlmfd plot --units cgs|si` turns the dimensions into unit
// names.
//
// Versions: 1 (no version attribute: before issue 35) had no coordinates, attributes, scene text or
// particle state in the snapshots and no /angle in particles.h5; 2 adds them. Readers accept both
// and refuse a newer version with a message that names it.
#pragma once

#include <cstdint>
#include <string>

namespace dlmfd {

inline constexpr std::int64_t kResultsFormatVersion = 2;
// The root attribute `format` of each file kind.
inline constexpr const char* kSnapshotFormat = "dlmfd field snapshot";
inline constexpr const char* kParticlesFormat = "dlmfd particle history";
inline constexpr const char* kUnitsNote =
    "units are dimensions in the scene's own units of length L, mass M and time T (the paper's "
    "cases: cm, g, s); the domain is a slice of unit depth (forces and torques per unit length)";

struct DatasetMeaning {
  const char* units;        // "L T-1", "1", "rad", ...
  const char* description;  // one sentence
};

enum class ResultsFile { kSnapshot, kParticles };

// The meaning of a dataset of a snapshot (`u`, `p`, `x`, `particles/angle`, ...) or of particles.h5
// (`time`, `position`, ...); nullptr for a name the file does not have.
const DatasetMeaning* MeaningOfDataset(ResultsFile file, const std::string& name);

// Throws dlmfd::Error naming the file and both versions when `version` is newer than this build's.
void CheckFormatVersion(const std::string& path, std::int64_t version);

// "L T-1" in named units: system "cgs" (cm, g, s), "si" (m, kg, s); "" or "none": the dimensions
// as they are. "1" is "" (dimensionless) in every system. Throws InvalidParameter for another
// system, naming the allowed ones.
std::string UnitsIn(const std::string& dimensions, const std::string& system);

}  // namespace dlmfd
