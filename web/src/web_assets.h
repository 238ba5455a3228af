// The dashboard's pages, scripts and style (web/static), compiled into the binary by
// web/embed_assets.cmake so that dlmfd-web needs no files beside it.
#pragma once

#include <string_view>
#include <vector>

namespace dlmfd::web {

struct Asset {
  std::string_view name;          // file name in web/static ("job.js")
  std::string_view content_type;  // "text/javascript; charset=utf-8"
  std::string_view body;
};

const std::vector<Asset>& Assets();

}  // namespace dlmfd::web
