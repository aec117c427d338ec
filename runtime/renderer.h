// SPDX-License-Identifier: MIT
// renderer.h — frames at any viewpoint from the inferred maps, drawn by raster/'s llvmpipe
// profile (PEM §5, hybrid §5), and the baselines they are compared with.
//
//   Renderer r(std::move(scene), std::move(maps), /*threads=*/2);   // map_set.h
//   RenderedFrame f = r.Render(r.Orbit(30, 20, 1), {Method::Hybrid});
//
// Methods (per lens group that has maps; other lens groups are ray traced with the full tree):
//  - Hybrid: vertex greedy paths on the adaptively tessellated mesh (lens_paths.h, t subpixels
//    of 1/spp pixel), per term one frame: the layers' passes outermost first (replace), inner
//    ones with premultiplied *over*, colour F·G per vertex; the terms' frames added.
//  - Pem: the same without adaptive tessellation (the model's own vertices); mirror-only groups
//    use the PEM split: the eye ray reflected off each vertex normal, `pem_distant` then
//    `pem_local` over it (only on polygons off the reflector's convex hull), times Schlick's F
//    per vertex. `layers` = 1 keeps the outermost layer
//    only (single-layer PEM).
//  - StaticEm: one cube map per group traced from its EM origin (static_em.h), looked up with
//    the exit directions of the hybrid paths (a shell at infinity), F·G.
//  - RayTraced: trace/render.h's reference (full tree) at spp × spp.
// The two viewpoint samples nearest to the eye are blended by distance (w_i ∝ the other's
// distance). The rest of the frame: one camera ray per pixel, shaded by the ray tracer (diffuse
// direct light with shadows, environment); pixels whose camera ray first hits a group with maps
// take that group's raster result. The groups are drawn with k×k subpixels per pixel (k = the
// `subpixels` setting; supersampling.h) and box-filtered over the subpixels they cover; the
// pixels on a group's border take k×k camera samples, each lens sample the group's subpixel
// (silhouettes.h). Timings per stage as the hybrid paper's table (the border's camera samples
// count as background).
// Not here: files (pipeline/pem_set.h opens a PEM directory), the command line, the viewer.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "raster/camera.h"
#include "runtime/map_set.h"
#include "trace/image.h"
#include "trace/scene.h"
#include "trace/tracer.h"

namespace pem::runtime {

enum class Method { Hybrid, Pem, StaticEm, RayTraced };
const char* ToString(Method m);

struct RenderSettings {
    Method method = Method::Hybrid;
    double t = 0.0;  // hybrid tessellation threshold (subpixels); 0: the maps' (MapSet::tessT)
    // Its topology threshold (subpixels, trace/tessellate.h; 0: t alone); nullopt: the maps'
    // (MapSet::topologyT).
    std::optional<double> topologyT;
    int subpixels = 0;  // k: subpixels per pixel side of the lens frames, and t's unit
                        // (1/k pixel); 0: the PEMs' supersampling (the traced images' K×K,
                        // the hybrid paper's 3×3), as inferred; the viewer, which draws one
                        // sample per pixel, uses 1
    int spp = 3;        // RayTraced: spp × spp samples per pixel
    int layers = 0;     // 0: all layers; 1: the outermost only
    int threads = 1;
    std::string profile;  // the hardware that draws (raster/profile.h); "": the maps' profile
    // StaticEm: the map's layout (parameterization.h; the sphere map traced in each frame's eye
    // space). The PEM methods draw the maps' own layout (MapSet::parameterization).
    Parameterization staticLayout = Parameterization::Cube;
};

struct FrameStats {
    uint64_t vertexRays = 0, backgroundRays = 0, tracerRays = 0;
    size_t trianglesIn = 0, trianglesOut = 0;
    size_t backFacingTriangles = 0;  // input triangles neither traced, refined nor drawn
    size_t untracedVertices = 0;     // vertices only back-facing triangles use: no rays
    size_t tracedVertices = 0;
    int groupsSkipped = 0;  // lens groups with maps that no pixel sees: no work at all
    double traceSeconds = 0.0, tessSeconds = 0.0, texgenSeconds = 0.0, rasterSeconds = 0.0;
    double backgroundSeconds = 0.0;
    double lensSeconds = 0.0;   // trace + tess + texgen + raster (the lens objects' frame)
    double totalSeconds = 0.0;  // the whole frame
    std::vector<int> samples;   // blended viewpoint samples
    std::vector<double> sampleWeights;
};

struct RenderedFrame {
    trace::FloatImage image;        // RGB, linear (values from 8-bit maps are in [0, 1])
    std::vector<uint8_t> lensMask;  // 1 where a group with maps is seen
    std::vector<int> groupOf;       // per pixel: the lens group its camera ray sees, -1 none
    FrameStats stats;
};

class Renderer {
  public:
    // embreeIsa: trace/embree_scene.h's EmbreeOptions::isa ("sse2" where frames feed a golden).
    Renderer(trace::Scene scene, MapSet maps, int threads, const std::string& embreeIsa = "auto");
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    RenderedFrame Render(const raster::Camera& camera, const RenderSettings& settings);

    // For the error budget: one lens group's maps of one sample through their texgen passes,
    // each layer alone (linear profile: exact texel weights, float framebuffer; no F·G, no
    // blending): [term][layer] RGBA premultiplied, RGB in radiance (times the radiance scale),
    // layers as drawn (innermost first).
    std::vector<std::vector<raster::ImageF>> LayerImages(const raster::Camera& camera,
                                                         const RenderSettings& settings, int group,
                                                         int sample);

    const MapSet& maps() const;
    const trace::Scene& scene() const;
    const trace::Tracer& tracer() const;
    // The camera of viewpoint sample v, as it was traced and inferred.
    raster::Camera SampleCamera(int v) const;
    // The first sample's camera orbited about the lens centre: azimuth and elevation (degrees)
    // added to the sample's, distance scaled by `distanceScale`.
    raster::Camera Orbit(double azimuthDeg, double elevationDeg, double distanceScale) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace pem::runtime
