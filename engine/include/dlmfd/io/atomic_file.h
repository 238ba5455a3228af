// Files that others may read while a run goes on are written under a temporary name in the same
// folder and renamed over the target (rename is atomic on POSIX): a reader sees the old file or the
// new one, never half of one (design.md 3.2).
#pragma once

#include <string>

namespace dlmfd {

// The temporary name used for `path` ("DIR/.NAME.tmp", hidden, same folder).
std::string TemporaryPath(const std::string& path);
// Renames the temporary file over `path`; throws dlmfd::Error on failure.
void CommitTemporary(const std::string& temporary, const std::string& path);
// Writes `text` to `path` through a temporary file.
void WriteTextAtomically(const std::string& path, const std::string& text);
// The whole content of a text file; throws dlmfd::Error when it cannot be read.
std::string ReadTextFile(const std::string& path);

}  // namespace dlmfd
