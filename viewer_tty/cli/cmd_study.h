// SPDX-License-Identifier: MIT
// cmd_study.h — `pemref study`: the five environment-map parameterizations inferred and compared
// (viewer_tty/report/layout_study.h).
//   pemref study SCENE... --out DIR [--layouts cube,latlong,...] [--sizes 8,16,32,64]
//                [--views circle:N:STEP] [--size WxH] [--spp K] [--reference-spp K]
//                [--threads N] [--quiet]
// Outputs: DIR/study.md, study.svg, study.json; per scene DIR/<scene>/trace and one PEM
// directory per layout and size, DIR/<scene>/<layout>_<size>. DIR appears whole when the study is
// done (base/atomic_file.h WriteDirectoryAtomically): absent, empty or an earlier study.
#pragma once

#include <CLI/CLI.hpp>

namespace pem::cli {

void AddStudyCommand(CLI::App& app);
int RunStudyCommand();

}  // namespace pem::cli
