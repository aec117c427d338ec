// SPDX-License-Identifier: MIT
// infer_report.cpp — infer.json and sample.json (infer_report.h).
#include "pipeline/infer_report.h"

#include "base/atomic_file.h"
#include "base/input_error.h"
#include "pipeline/json_values.h"
#include "pipeline/layout.h"

namespace pem::pipeline {
namespace {

json MapJson(const MapReport& m) {
    json jm = {{"view", m.view},
               {"group", m.group},
               {"term", m.term},
               {"layer", m.layer},
               {"name", m.name},
               {"file", MapFile(m.view, m.group, m.name)},
               {"res", m.res},
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
    if (!m.levelsAccessed.empty()) jm["levels_accessed"] = m.levelsAccessed;
    if (m.directRmse8 >= 0.0) {
        jm["rmse_8bit_direct"] = m.directRmse8;
        jm["direct_seconds"] = m.directSeconds;
    }
    return jm;
}

MapReport MapFromJson(const json& j) {
    MapReport m;
    m.view = IntAt<int>(j, "view");
    m.group = IntAt<int>(j, "group");
    m.term = j.at("term").get<std::string>();
    m.layer = IntAt<int>(j, "layer");
    m.name = j.at("name").get<std::string>();
    m.res = IntAtOr<int>(j, "res", 0);  // absent in older directories
    m.levelsAccessed = j.value("levels_accessed", std::vector<double>{});
    m.rows = IntAt<int64_t>(j, "rows");
    m.cols = IntAt<int64_t>(j, "cols");
    m.nnz = IntAt<int64_t>(j, "nnz");
    m.observedTexels = IntAt<int64_t>(j, "observed_texels");
    m.filledTexels = IntAt<int64_t>(j, "filled_texels");
    m.buildSeconds = j.at("build_seconds").get<double>();
    m.solveSeconds = j.at("solve_seconds").get<double>();
    m.iterations = IntAt<int>(j, "iterations");
    m.stop = j.at("stop").get<std::string>();
    m.rmse = j.at("rmse").get<double>();
    m.rmse8 = j.at("rmse_8bit").get<double>();
    m.objective = j.at("objective").get<double>();
    m.texelMin = j.at("texel_min").get<double>();
    m.texelMax = j.at("texel_max").get<double>();
    const json& t = j.at("timing");
    m.matrixSeconds = t.at("matrix_seconds").get<double>();
    m.renderSeconds = t.at("render_seconds").get<double>();
    m.fillSeconds = t.at("fill_seconds").get<double>();
    m.writeSeconds = t.at("write_seconds").get<double>();
    m.directRmse8 = j.value("rmse_8bit_direct", -1.0);
    m.directSeconds = j.value("direct_seconds", 0.0);
    return m;
}

json SampleJson(const SampleReport& s) {
    return {{"view", s.view},
            {"seconds", s.seconds},
            {"path_seconds", s.pathSeconds},
            {"vertex_rays", s.vertexRays},
            {"triangles", s.triangles}};
}

SampleReport SampleFromJson(const json& j) {
    return {IntAt<int>(j, "view"), j.at("seconds").get<double>(),
            j.at("path_seconds").get<double>(), IntAt<uint64_t>(j, "vertex_rays"),
            IntAt<size_t>(j, "triangles")};
}

json LeftOutJson(const std::vector<LeftOut>& leftOut) {
    json out = json::array();
    for (const LeftOut& l : leftOut)
        out.push_back({{"view", l.view}, {"group", l.group}, {"what", l.what}, {"why", l.why}});
    return out;
}

std::vector<LeftOut> LeftOutFromJson(const json& j) {
    std::vector<LeftOut> out;
    for (const json& l : j)
        out.push_back({IntAt<int>(l, "view"), IntAt<int>(l, "group"),
                       l.at("what").get<std::string>(), l.at("why").get<std::string>()});
    return out;
}

json MapsJson(const std::vector<MapReport>& maps) {
    json out = json::array();
    for (const MapReport& m : maps) out.push_back(MapJson(m));
    return out;
}

std::vector<MapReport> MapsFromJson(const json& j) {
    std::vector<MapReport> out;
    for (const json& m : j) out.push_back(MapFromJson(m));
    return out;
}

void CheckFormat(const json& j, const char* format) {
    if (j.value("format", "") != format || j.value("version", json()) != 1)
        throw std::runtime_error(std::string("not a ") + format + " file (version 1)");
}

}  // namespace

void WriteSampleJson(const std::string& pemDir, const SampleRecord& r) {
    const json j = {{"format", "pemref_sample"},
                    {"version", 1},
                    {"sample", SampleJson(r.sample)},
                    {"maps", MapsJson(r.maps)},
                    {"left_out", LeftOutJson(r.leftOut)}};
    base::WriteTextAtomic(SampleJsonPath(pemDir, r.sample.view), j.dump(2) + "\n");
}

SampleRecord ReadSampleJson(const std::string& pemDir, int view) {
    return ReadJsonFile(SampleJsonPath(pemDir, view), "the sample is not done", [](const json& j) {
        CheckFormat(j, "pemref_sample");
        return SampleRecord{SampleFromJson(j.at("sample")), MapsFromJson(j.at("maps")),
                            LeftOutFromJson(j.at("left_out"))};
    });
}

void WriteInferJson(const InferRecord& r) {
    json samples = json::array();
    for (const SampleReport& s : r.samples) samples.push_back(SampleJson(s));
    const json j = {
        {"format", "pemref_infer"},
        {"version", 1},
        {"trace_dir", r.traceDir},
        {"res", r.res},
        {"threads", r.threads},
        {"jobs", r.jobs},
        {"neighbours", r.neighbours},
        {"hdr", r.hdr},
        {"lambda",
         {{"smooth", r.lambda.smooth}, {"pyramid", r.lambda.pyramid}, {"prior", r.lambda.prior}}},
        {"seconds", r.seconds},
        {"samples", samples},
        {"maps", MapsJson(r.maps)},
        {"left_out", LeftOutJson(r.leftOut)}};
    base::WriteTextAtomic(r.dir + "/" + kInferJson, j.dump(2) + "\n");
}

InferRecord ReadInferJson(const std::string& pemDir) {
    InferRecord rec =
        ReadJsonFile(pemDir + "/" + kInferJson, "run pemref infer first", [](const json& j) {
            CheckFormat(j, "pemref_infer");
            InferRecord r;
            r.traceDir = j.at("trace_dir").get<std::string>();
            r.res = IntAt<int>(j, "res");
            r.threads = IntAt<int>(j, "threads");
            r.jobs = IntAt<int>(j, "jobs");
            r.neighbours = IntAt<int>(j, "neighbours");
            r.hdr = j.at("hdr").get<bool>();
            r.lambda.smooth = j.at("lambda").at("smooth").get<double>();
            r.lambda.pyramid = j.at("lambda").at("pyramid").get<double>();
            r.lambda.prior = j.at("lambda").at("prior").get<double>();
            r.seconds = j.at("seconds").get<double>();
            for (const json& s : j.at("samples")) r.samples.push_back(SampleFromJson(s));
            r.maps = MapsFromJson(j.at("maps"));
            r.leftOut = LeftOutFromJson(j.at("left_out"));
            return r;
        });
    rec.dir = pemDir;
    return rec;
}

}  // namespace pem::pipeline
