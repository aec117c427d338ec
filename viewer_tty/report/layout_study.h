// SPDX-License-Identifier: MIT
// layout_study.h — `pemref study`: the notes' five environment-map parameterizations (cube,
// lat-long, sphere map, dual paraboloid, tennis ball; runtime/parameterization.h) measured
// against each other. The PEM paper says the parameterization "is less crucial than the choice
// of geometry in determining final accuracy, but does impact how much resolution the maps will
// require"; this measures it.
//
//   LayoutStudyOptions o;  o.scenes = {"data/scenes/mirror_sphere.gltf"};  o.outDir = "out/study";
//   const LayoutStudy s = RunLayoutStudy(o);   // then WriteLayoutStudy (layout_study_writer.h)
//
// Per scene: one trace (outDir/<scene>/trace); per layout and size, the maps of every sample
// inferred from it (outDir/<scene>/<layout>_<size>/, a PEM directory `pemref render` reads);
// then, at the report's three positions (positions.h: on a sample, between two, 10° above), the
// hybrid, layered-PEM and static-EM frames against a K×K ray-traced reference (8-bit PSNR over the
// lens pixels, as the report scores), and the run time of inference and of the hybrid frame. Every
// solve uses the same trace, regularizer and hardware; only the layout and its size change. Not
// here: the documents (layout_study_writer.h), the command line (cli/cmd_study.cpp).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "runtime/parameterization.h"

namespace pem::report {

struct LayoutStudyOptions {
    std::vector<std::string> scenes;  // glTF files
    std::string outDir;
    std::vector<runtime::Parameterization> layouts{runtime::kParameterizations.begin(),
                                                   runtime::kParameterizations.end()};
    std::vector<int> sizes = {8, 16, 32, 64};  // LayoutOf's size (powers of two >= 2)
    std::string views = "circle:3:10";         // the viewpoint samples (pipeline/viewpoints.h)
    int width = 320, height = 240;
    int spp = 2;           // the trace's K×K samples (and the frames' subpixels)
    int referenceSpp = 4;  // the reference's K×K samples
    int threads = 1;
    // The stage's name and the fraction of the whole study done.
    std::function<void(const std::string& stage, double fraction)> progress;
};

// The methods each position is scored with: the maps inferred in the layout drawn by the hybrid
// renderer and in layered-PEM mode, and the static EM traced in the same layout and size (the
// layout's sampling without inference).
inline constexpr const char* kStudyMethods[] = {"hybrid", "layered PEM", "static EM"};

// One frame's score at one position.
struct LayoutScore {
    std::string position, method;  // "on circle" ...; one of kStudyMethods
    double psnr = 0.0;             // 8-bit, lens pixels, against the reference (dB)
    double seconds = 0.0;          // the whole frame
};

// One layout at one size on one scene.
struct LayoutPoint {
    std::string scene;  // the scene's file name without extension
    runtime::Parameterization layout = runtime::Parameterization::Cube;
    int size = 0;
    int64_t texels = 0;         // level 0, every face (MapLayout::Texels)
    int maps = 0;               // maps inferred over every sample
    double inferSeconds = 0.0;  // per viewpoint sample (trace excluded)
    double rmse8 = 0.0;         // mean of the maps' solve residuals (8-bit steps, rmse_8bit)
    std::string pemDir;         // relative to the study directory
    std::string picture;        // a map of the first sample (its PNG), relative likewise
    std::vector<LayoutScore> scores;

    double Psnr(const std::string& position, const std::string& method) const;  // NaN: absent
};

struct LayoutStudy {
    LayoutStudyOptions options;
    std::vector<std::string> scenes;     // names, in order
    std::vector<std::string> positions;  // names, in order
    std::vector<LayoutPoint> points;     // scene-major, then layout, then size
};

// Traces, infers and measures; throws base::InputError for bad options or scenes.
LayoutStudy RunLayoutStudy(const LayoutStudyOptions& options);

}  // namespace pem::report
