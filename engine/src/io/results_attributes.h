// The self-description of the results' HDF5 files (results_format.h), written through hdf5_file.h:
// the root attributes format, format_version and units, the scene text as the dataset /scene, and
// each dataset's units, description and dimensions (the names of its axes, slowest first, e.g.
// "y x": the coordinate datasets that index it).
#pragma once

#include <cstdint>
#include <string>

#include "dlmfd/io/results_format.h"
#include "hdf5_file.h"

namespace dlmfd {
namespace h5 {

void WriteFormat(hid_t file, const char* format, const std::string& scene_text);
// The file's format_version: 1 when it has none (written before issue 35); checked against this
// build's (CheckFormatVersion).
std::int64_t ReadFormatVersion(hid_t file, const std::string& path);
// units and description of MeaningOfDataset(kind, meaning), and dimensions when not empty.
void Describe(hid_t loc, const std::string& name, ResultsFile kind, const std::string& meaning,
              const std::string& dimensions);

}  // namespace h5
}  // namespace dlmfd
