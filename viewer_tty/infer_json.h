// SPDX-License-Identifier: MIT
// infer_json.h — infer.json and manifest.json of a PEM directory, from infer_run.h's reports
// (shared by `pemref infer` and `pemref bake`).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "infer/infer_run.h"

namespace pem::cli {

nlohmann::json MapJson(const infer::MapReport& m);
nlohmann::json SampleJson(const infer::SampleReport& s);
nlohmann::json LeftOutJson(const std::vector<infer::LeftOut>& leftOut);
// manifest.json: format, scene, trace_dir, size, spp, res, profile, hdr, views, inferred_views,
// lens_groups (copied from trace.json).
nlohmann::json ManifestJson(const infer::TraceManifest& trace, const std::string& traceDir, int res,
                            bool hdr, const std::vector<int>& inferredViews);

}  // namespace pem::cli
