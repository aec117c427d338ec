// SPDX-License-Identifier: MIT
// trace_manifest.h — trace.json, the record of a trace directory: how it was traced, every
// viewpoint sample's camera (whole), each lens group's EM geometry and the trace's figures.
// Its one writer and its one reader, side by side.
//
//   TraceManifest t = ReadTraceManifest("out/trace");
//   raster::Camera c = t.views[2].camera;        // the camera sample 2 was traced with
//
// Format `pemref_trace`, version 2 (version 1 had no format field and kept only eye and target
// of each camera: it is refused with a message to trace again). The scene is stored relative to
// the directory when it can be (`scene`), with the path as given beside it (`scene_given`);
// ScenePath resolves it. Errors: base::InputError naming trace.json and the cause.
// Not here: the images (layout.h), tracing (trace_job.h).
#pragma once

#include <string>
#include <vector>

#include "raster/camera.h"
#include "runtime/lens_group_em.h"
#include "trace/image.h"
#include "trace/render.h"
#include "trace/tracer.h"

namespace pem::pipeline {

struct TracedView {
    raster::Camera camera;
    double referenceSeconds = 0.0, greedySeconds = 0.0;
    trace::RayCounts reference, greedy, segmentation, layers;
    trace::ImageError frame, lens, frameHdr, lensHdr;  // greedy vs reference, [0, 1] and HDR
};

struct TraceManifest {
    std::string dir;         // the trace directory (not stored: where it was read or written)
    std::string scene;       // the scene file, relative to dir when possible
    std::string sceneGiven;  // the scene file as given on the command line, made absolute
    int width = 0, height = 0;
    int spp = 1;  // K×K samples per pixel
    int threads = 1, fullTreeDepth = 6;
    double minWeight = 1e-3;
    std::string fresnel = "exact";
    std::string embreeConfig;
    double seconds = 0.0, bvhSeconds = 0.0;
    size_t triangles = 0;
    trace::RayCounts rays;
    std::vector<TracedView> views;
    std::vector<runtime::LensGroupEm> groups;
    std::vector<std::string> leftOut;

    std::vector<raster::Camera> Cameras() const;
    trace::TraceOptions Tracing() const;  // the tracer's options of the trace
};

void WriteTraceManifest(const TraceManifest& manifest);  // dir/trace.json

// A trace image (layout.h) checked against the manifest: inside the directory, the trace's size
// and `channels` channels; base::InputError naming the file otherwise.
trace::FloatImage ReadFrameImage(const TraceManifest& m, int view, const std::string& name);
trace::FloatImage ReadGroupImage(const TraceManifest& m, int view, int group,
                                 const std::string& name, int channels = 4);
// The K×K samples of a group image (RGBA, K W × K H; layout.h GroupSampleImagePath): what
// inference fits. K = 1: the image itself.
trace::FloatImage ReadGroupSamples(const TraceManifest& m, int view, int group,
                                   const std::string& name);
TraceManifest ReadTraceManifest(const std::string& dir);

// The scene file of a trace or PEM directory: `stored` relative to `dir` (or absolute); when it
// does not exist there, `given` (the path as given when the directory was made).
std::string ResolveScene(const std::string& dir, const std::string& stored,
                         const std::string& given);
// The path to store for `scenePath` in a directory `dir`: relative to dir when both are on
// the same file system tree, else absolute.
std::string SceneForStorage(const std::string& dir, const std::string& scenePath);

// `path` made absolute against the working directory (lexically normal).
std::string AbsolutePath(const std::string& path);

}  // namespace pem::pipeline
