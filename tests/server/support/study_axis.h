// A study's axis of listed values, as a SubmitStudy request carries it (jobs.proto StudyAxis): the
// scene key, its values, and the zip group whose axes advance together ("" for a crossed axis).
#pragma once

#include <string>
#include <vector>

#include "dlmfd/v1/jobs.pb.h"

namespace dlmfd::testing {

inline v1::StudyAxis ListAxis(const std::string& key, const std::vector<std::string>& values,
                              const std::string& zip = "") {
  v1::StudyAxis axis;
  axis.set_key(key);
  for (const auto& v : values) axis.add_values(v);
  axis.set_zip(zip);
  return axis;
}

}  // namespace dlmfd::testing
