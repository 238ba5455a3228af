// The programs of this build that the tests run: the CLI, the daemon and the solver.
#pragma once

#include <string>

namespace dlmfd::testing {

inline const std::string kClient = DLMFD_BINARY_DIR "/client/dlmfd";
inline const std::string kDaemon = DLMFD_BINARY_DIR "/server/dlmfdd";
inline const std::string kSolver = DLMFD_BINARY_DIR "/solver/dlmfd-solve";

}  // namespace dlmfd::testing
