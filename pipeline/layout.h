// SPDX-License-Identifier: MIT
// layout.h — the directory layout of trace and PEM directories, the one place that spells file
// names. Every reader and writer of pipeline/ builds its paths here.
//
//   trace directory (pemref trace):             PEM directory (pemref infer / bake):
//     trace.json                                  manifest.json, infer.json
//     view_vvv/reference.exr, greedy.exr          view_vvv/sample.json (bake: a finished sample)
//     view_vvv/group_g/b_τ.exr, FG_τ.exr,         view_vvv/group_g/<map>.exr (+ .png, .csv)
//       confidence_τ.exr, layer_l_τ.exr,            maps: layer_l, single, pem_local,
//       local.exr, distant.exr, fresnel1.exr        pem_distant
//     view_vvv/group_g/samples/b_τ.exr,
//       layer_l_τ.exr, local.exr, distant.exr
//       (the K×K samples of those images, K > 1)
//   (+ .png previews of reference, greedy, b_τ, local, distant; v: 3 digits; τ ∈ {R, T})
//   bake directory: trace/ and pem/ side by side.
//
// Not here: what the files hold (trace_manifest.h, pem_manifest.h, infer_report.h).
#pragma once

#include <string>

namespace pem::pipeline {

inline constexpr const char* kTraceJson = "trace.json";
inline constexpr const char* kManifestJson = "manifest.json";
inline constexpr const char* kInferJson = "infer.json";
inline constexpr const char* kSampleJson = "sample.json";
inline constexpr const char* kBakeJson = "bake.json";

// "view_007".
std::string ViewDirName(int view);
// dir/view_007.
std::string ViewDir(const std::string& dir, int view);
// view_007/group_1 (relative to a trace or PEM directory).
std::string GroupSubdir(int view, int group);
// dir/view_007/group_1.
std::string GroupDir(const std::string& dir, int view, int group);

// Trace images: dir/view_v/<name>.exr (frame images) and dir/view_v/group_g/<name>.exr.
std::string FrameImagePath(const std::string& traceDir, int view, const std::string& name);
std::string GroupImagePath(const std::string& traceDir, int view, int group,
                           const std::string& name);
// The K× sample image of a group image (trace/image.h SampleCell): dir/view_v/group_g/samples/
// <name>.exr.
std::string GroupSampleImagePath(const std::string& traceDir, int view, int group,
                                 const std::string& name);
// The layer image of layer l and term τ: "layer_<l>_<τ>".
std::string LayerImageName(int layer, int term);

// A map's file relative to the PEM directory (infer.json's "file"): view_v/group_g/<name>.exr.
std::string MapFile(int view, int group, const std::string& name);
std::string MapPath(const std::string& pemDir, int view, int group, const std::string& name);
// A map's stem: PEM dir/view_v/group_g/<name> (+ ".exr", ".png", ".csv").
std::string MapStem(const std::string& pemDir, int view, int group, const std::string& name);
// The layer map of layer l: "layer_<l>".
std::string LayerMapName(int layer);

std::string SampleJsonPath(const std::string& pemDir, int view);

// A bake directory's parts: trace/, pem/ and bake.json (the settings it was started with).
std::string BakeTraceDir(const std::string& bakeDir);
std::string BakePemDir(const std::string& bakeDir);
std::string BakeJsonPath(const std::string& bakeDir);

// Throws base::InputError(path, ...) unless `path`, symbolic links resolved, lies inside `dir`
// (nothing is read or written outside the directories the user named).
void CheckInside(const std::string& dir, const std::string& path);

// `path` with a ".exr" ending replaced by ".png" (the preview next to an image).
std::string PreviewPath(const std::string& exrPath);

}  // namespace pem::pipeline
