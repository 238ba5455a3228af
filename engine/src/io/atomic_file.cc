#include "dlmfd/io/atomic_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "dlmfd/core/errors.h"

namespace dlmfd {

std::string TemporaryPath(const std::string& path) {
  const std::filesystem::path p(path);
  return (p.parent_path() / ("." + p.filename().string() + ".tmp")).string();
}

void CommitTemporary(const std::string& temporary, const std::string& path) {
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    throw Error("cannot rename " + temporary + " to " + path + ": " + std::strerror(errno));
  }
}

void WriteTextAtomically(const std::string& path, const std::string& text) {
  const std::string temporary = TemporaryPath(path);
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out << text;
    out.flush();
    if (!out) throw Error("cannot write " + temporary);
  }
  CommitTemporary(temporary, path);
}

std::string ReadTextFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot read " + path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace dlmfd
