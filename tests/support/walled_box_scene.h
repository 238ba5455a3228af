// The [domain] tables of a scene whose box is closed by walls on its four sides, as TOML text:
// `size` ("W, H") and `h` are written as given, so a scene keeps the digits its test chose.
#pragma once

#include <string>

namespace dlmfd::testing {

inline std::string WalledBoxDomain(const std::string& size, const std::string& h) {
  return "[domain]\nsize = [" + size + "]\nh = " + h +
         "\n[domain.boundary]\n"
         "left = { type = \"wall\" }\n"
         "right = { type = \"wall\" }\n"
         "bottom = { type = \"wall\" }\n"
         "top = { type = \"wall\" }\n";
}

}  // namespace dlmfd::testing
