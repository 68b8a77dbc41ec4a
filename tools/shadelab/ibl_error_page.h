// The files of an IBL error map (render/ibl_error.h), written by `shadelab ibl-error` and by `shadelab report
// --ibl-error`: ibl_error.json (every cell), split_sum_error.png (|error| per cell through the heat ramp, rows
// roughness from the top, columns N.V from the left), split_sum_error.svg (signed error against N.V, one line
// per roughness, and the SH9 line), index.html (the tables and the pictures) and corrected_error.png (the
// split sum read along the dominant direction, on the same scale), each atomically.
#pragma once

#include <cstdint>
#include <filesystem>
#include <utility>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "shadelab/brdf/params.h"
#include "shadelab/render/ibl_error.h"

namespace shadelab::cli {

// What the JSON records besides the map.
struct IblErrorHeader {
  std::string input;  // the environment: a file, or a scene's
  ParamAssignments params;
  int nv_bins = 0, size = 0, spp = 0, specular_size = 0;
  std::uint64_t seed = 0;
};

// The file names, in the order of the JSON's "outputs".
std::vector<std::string> ibl_error_file_names();

// Writes the files into dir (which must exist) as one output set (write_files_atomically) and returns the JSON
// written as ibl_error.json. Throws UsageError (cli_common.h) when a file cannot be written.
nlohmann::json write_ibl_error_files(const IblErrorMap& map, const IblErrorHeader& h, const std::filesystem::path& dir);
// The same files, encoded and appended to `out` for a caller that publishes them with others (report).
nlohmann::json ibl_error_files(const IblErrorMap& map, const IblErrorHeader& h, const std::filesystem::path& dir,
                               std::vector<std::pair<std::filesystem::path, std::vector<char>>>& out);

}  // namespace shadelab::cli
