// SPDX-License-Identifier: MIT
// infer_json.cpp — JSON forms of inference reports (infer_json.h).
#include "viewer_tty/infer_json.h"

#include <cstdio>
#include <fstream>

#include "viewer_tty/input_error.h"

namespace pem::cli {

using nlohmann::json;

json MapJson(const infer::MapReport& m) {
    char file[96];
    std::snprintf(file, sizeof file, "view_%03d/group_%d/%s.exr", m.view, m.group, m.name.c_str());
    json jm = {{"view", m.view},
               {"group", m.group},
               {"term", m.term},
               {"layer", m.layer},
               {"file", file},
               {"rows", m.rows},
               {"cols", m.cols},
               {"nnz", m.nnz},
               {"observed_texels", m.observedTexels},
               {"filled_texels", m.filledTexels},
               {"build_seconds", m.buildSeconds},
               {"solve_seconds", m.solveSeconds},
               {"iterations", m.iterations},
               {"stop", m.stop},
               {"rmse", m.rmse},
               {"rmse_8bit", m.rmse8},
               {"objective", m.objective},
               {"texel_min", m.texelMin},
               {"texel_max", m.texelMax},
               {"timing",
                {{"matrix_seconds", m.matrixSeconds},
                 {"render_seconds", m.renderSeconds},
                 {"fill_seconds", m.fillSeconds},
                 {"write_seconds", m.writeSeconds}}}};
    if (m.directRmse8 >= 0.0) {
        jm["rmse_8bit_direct"] = m.directRmse8;
        jm["direct_seconds"] = m.directSeconds;
    }
    return jm;
}

json SampleJson(const infer::SampleReport& s) {
    return {{"view", s.view},
            {"seconds", s.seconds},
            {"path_seconds", s.pathSeconds},
            {"vertex_rays", s.vertexRays},
            {"triangles", s.triangles}};
}

json LeftOutJson(const std::vector<infer::LeftOut>& leftOut) {
    json out = json::array();
    for (const infer::LeftOut& l : leftOut)
        out.push_back({{"view", l.view}, {"group", l.group}, {"what", l.what}, {"why", l.why}});
    return out;
}

json ManifestJson(const infer::TraceManifest& trace, const std::string& traceDir, int res, bool hdr,
                  const std::vector<int>& inferredViews) {
    json views = json::array();
    for (const raster::Camera& c : trace.views)
        views.push_back({{"eye", {c.eye.x, c.eye.y, c.eye.z}},
                         {"target", {c.target.x, c.target.y, c.target.z}}});
    json m = {{"format", "pemref_pem/1"},
              {"scene", trace.scenePath},
              {"trace_dir", traceDir},
              {"size", {trace.width, trace.height}},
              {"spp", trace.spp},
              {"res", res},
              {"profile", "llvmpipe"},
              {"hdr", hdr},
              {"views", views},
              {"inferred_views", inferredViews.empty() ? json(nullptr) : json(inferredViews)}};
    std::ifstream traceJson(traceDir + "/trace.json");
    if (!traceJson) throw InputError(traceDir + "/trace.json", "cannot open");
    m["lens_groups"] = json::parse(traceJson).at("lens_groups");
    return m;
}

}  // namespace pem::cli
