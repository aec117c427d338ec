// SPDX-License-Identifier: MIT
// trace_run.h — the whole `pemref trace` job: viewpoints → reference and greedy frames,
// per-lens-group segmented images, layers over all viewpoints, layer images, all as float
// OpenEXR files under one output directory; returns what trace.json reports.
//
// Files (v = viewpoint index, 3 digits; g = lens group index; τ ∈ {R, T}, T only with glass):
//   view_v/reference.exr (RGB, full ray tree)      view_v/greedy.exr (RGB, two-term model)
//   view_v/group_g/b_τ.exr, FG_τ.exr (RGBA)        view_v/group_g/confidence_τ.exr (Y)
//   view_v/group_g/layer_l_τ.exr (RGBA)            mirror-only groups: local.exr, distant.exr,
//                                                  fresnel1.exr (RGBA)
// Order of work: for each viewpoint the frames and segmentation, then the layers (all
// viewpoints' records at once), then every viewpoint's layer images. The bytes of every file
// are independent of the thread count.
// Not here: argument parsing, PNG previews and trace.json (viewer_tty/cmd_trace.cpp).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "raster/camera.h"
#include "trace/embree_scene.h"
#include "trace/layers.h"
#include "trace/render.h"
#include "trace/tracer.h"

namespace pem::trace {

struct TraceRunOptions {
    std::vector<raster::Camera> views;
    int k = 3;  // k×k supersamples per pixel
    int threads = 1;
    int layers = 2;  // N for the LBG clustering
    TraceOptions trace;
    std::string outDir;
    bool segment = true;  // false: only the reference and greedy frames
    // Progress: the stage's name and the fraction of the whole job done.
    std::function<void(const std::string& stage, double fraction)> progress;
    // Called after each EXR file is written (e.g. for PNG previews).
    std::function<void(const std::string& path, const FloatImage& image)> written;
};

struct ViewReport {
    double referenceSeconds = 0.0, greedySeconds = 0.0;
    RayCounts reference, greedy, segmentation, layers;
    ImageError frame, lens;        // greedy vs reference, display range [0, 1]
    ImageError frameHdr, lensHdr;  // same on raw radiance
};

struct GroupReport {
    int group = -1;
    std::vector<std::string> objects;
    bool glass = false;
    GroupLayers layers;
    size_t records = 0;
};

struct TraceRunReport {
    std::vector<ViewReport> views;
    std::vector<GroupReport> groups;
    RayCounts total;
    double seconds = 0.0;
    double buildSeconds = 0.0;  // Embree BVH
    size_t triangles = 0;
    std::string embreeConfig;
};

TraceRunReport RunTrace(const Scene& scene, const TraceRunOptions& options);

// Centre of all lens objects' bounds (the scene bounds' centre without lenses).
glm::vec3 LensCentre(const Scene& scene);

// n viewpoints stepDeg apart: the camera's eye rotated about the vertical axis through `centre`
// (height and horizontal distance kept, positive angles from +Z toward +X), looking at `centre`.
std::vector<raster::Camera> CircleViews(const raster::Camera& camera, const glm::vec3& centre,
                                        int n, double stepDeg);

}  // namespace pem::trace
