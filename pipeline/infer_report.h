// SPDX-License-Identifier: MIT
// infer_report.h — what inference reports, and its two files: infer.json (every map's figures
// over a PEM directory) and sample.json (one finished viewpoint sample of a bake, the mark that
// lets a killed bake resume). Each writer beside its reader.
//
//   WriteInferJson(record);   InferRecord r = ReadInferJson("out/pem");
//
// Formats `pemref_infer` and `pemref_sample`, version 1. Errors: base::InputError naming the
// file and the cause.
// Not here: the maps (pem_file.h), manifest.json (pem_manifest.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "infer/problem.h"

namespace pem::pipeline {

// One inferred map (one solve).
struct MapReport {
    int view = 0, group = 0, layer = 0;
    std::string term;                    // "R", "R+T", or "pem" (local/distant split)
    std::string name;                    // file stem under view_v/group_g/
    int res = 0;                         // the map's face size
    std::vector<double> levelsAccessed;  // with --max-res: share of subpixels per finest level
    int64_t rows = 0, cols = 0, nnz = 0;
    int64_t observedTexels = 0, filledTexels = 0;
    double buildSeconds = 0.0, solveSeconds = 0.0;
    int iterations = 0;
    std::string stop;
    // In the maps' units (RGB: radiance / the radiance scale; alpha), over the sample's rows.
    double rmse = 0.0, rmse8 = 0.0, objective = 0.0;
    double texelMin = 0.0, texelMax = 0.0;
    double directRmse8 = -1.0, directSeconds = 0.0;  // < 0: not run
    // Where the time goes (seconds): raster's rendering matrix (part of buildSeconds), one
    // forward render of the same pass (the rmse_8bit render), FillUnobserved and the files.
    double matrixSeconds = 0.0, renderSeconds = 0.0, fillSeconds = 0.0, writeSeconds = 0.0;
};

// One viewpoint sample.
struct SampleReport {
    int view = 0;
    double seconds = 0.0;      // the whole sample: paths, every map
    double pathSeconds = 0.0;  // vertex rays and tessellation
    uint64_t vertexRays = 0;
    size_t triangles = 0;
};

// Work the job decided not to do ("leave out what the scene does not need").
struct LeftOut {
    int view = 0, group = 0;
    std::string what, why;
};

// sample.json: one finished sample.
struct SampleRecord {
    SampleReport sample;
    std::vector<MapReport> maps;
    std::vector<LeftOut> leftOut;
};

// infer.json: every sample of a PEM directory.
struct InferRecord {
    std::string dir;       // the PEM directory (not stored)
    std::string traceDir;  // as given
    int res = 0, threads = 1, jobs = 1, neighbours = 0;
    bool hdr = false;
    infer::RegularizerWeights lambda;
    double seconds = 0.0;
    std::vector<SampleReport> samples;
    std::vector<MapReport> maps;
    std::vector<LeftOut> leftOut;
};

void WriteSampleJson(const std::string& pemDir, const SampleRecord& record);
SampleRecord ReadSampleJson(const std::string& pemDir, int view);

void WriteInferJson(const InferRecord& record);
InferRecord ReadInferJson(const std::string& pemDir);

}  // namespace pem::pipeline
