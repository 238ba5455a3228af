// The exit status of dlmfd-solve (design.md 3.1): the contract between the solver and whoever runs
// it (the daemon's executors, scripts). A run killed by a signal other than SIGINT/SIGTERM has no
// exit status of ours; its reader sees the signal.
#pragma once

namespace dlmfd::solver {

// The run reached the end time; summary.json says completed.
inline constexpr int kExitCompleted = 0;
// The run failed while stepping (or its results could not be written); the reason is in
// summary.json and in the `finished` event, the results up to then are kept and closed.
inline constexpr int kExitFailed = 1;
// Invalid scene or arguments: nothing ran; the message (key, value, what is allowed) is on stderr
// and in the `finished` event.
inline constexpr int kExitInvalid = 2;
// Stopped by SIGINT or SIGTERM after writing a checkpoint and closing every file (128 + SIGINT, the
// shell's convention); --resume goes on from there.
inline constexpr int kExitCancelled = 130;

}  // namespace dlmfd::solver
