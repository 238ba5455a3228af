// The exit status of every dlmfd subcommand (docs/cli.md lists them for users and scripts).
#pragma once

namespace dlmfd::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitJobNotCompleted = 1;  // --wait / watch: the job ended FAILED or CANCELLED
inline constexpr int kExitUsage = 2;     // bad flags or input files; INVALID_ARGUMENT, OUT_OF_RANGE
inline constexpr int kExitNotFound = 3;  // NOT_FOUND: no such job (or not yours), study or file
inline constexpr int kExitDenied = 4;    // UNAUTHENTICATED, PERMISSION_DENIED
inline constexpr int kExitUnavailable = 5;    // UNAVAILABLE, DEADLINE_EXCEEDED: no daemon answering
inline constexpr int kExitConflict = 6;       // FAILED_PRECONDITION, ALREADY_EXISTS, ABORTED
inline constexpr int kExitResources = 7;      // RESOURCE_EXHAUSTED: a size or queue limit
inline constexpr int kExitServerError = 8;    // INTERNAL, UNKNOWN, UNIMPLEMENTED, DATA_LOSS, ...
inline constexpr int kExitLocalIo = 9;        // cannot write fetched files or a picture here
inline constexpr int kExitInterrupted = 130;  // SIGINT/SIGTERM while watching

}  // namespace dlmfd::cli
