// SPDX-License-Identifier: MIT
// pem_manifest.h — manifest.json, the record of a PEM directory: what a renderer needs to draw
// from its maps (the scene, the viewpoint samples' cameras, the lens groups' EM geometry, the
// maps' layout, size and profile). Its one writer and its one reader, side by side.
//
//   PemManifest m = ReadPemManifest("out/pem");
//
// Format `pemref_pem`, version 2 (version 1 kept only eye and target of each camera: refused
// with a message to infer again). Paths (the scene, the trace directory) are stored relative to
// the PEM directory, with the paths as given beside them, so a baked directory can be moved.
// Errors: base::InputError naming manifest.json and the cause.
// Not here: the maps (pem_set.h), the figures of the solves (infer_report.h).
#pragma once

#include <string>
#include <vector>

#include "pipeline/trace_manifest.h"
#include "runtime/map_set.h"

namespace pem::pipeline {

struct PemManifest {
    std::string dir;  // the PEM directory (not stored)
    std::string scene, sceneGiven;
    std::string traceDir, traceDirGiven;
    int width = 0, height = 0, spp = 1, res = 0;
    int maxRes = 0;  // the largest face size of a map (infer --max-res; res when not given)
    runtime::MapHardware hardware;
    runtime::Parameterization parameterization = runtime::Parameterization::Cube;  // the maps'
    int fullTreeDepth = 6;  // the tracer's options of the trace (trace_manifest.h)
    double minWeight = 1e-3;
    std::string fresnel = "exact";
    bool hdr = false;
    double tessT = runtime::kDefaultTessT;          // the hybrid tessellation t of the inference
    double topologyT = runtime::kDefaultTopologyT;  // its topology threshold (0: t alone)
    std::vector<double> alsoTessT;                  // further t the layer maps fit (infer --also-t)
    std::vector<raster::Camera> views;              // every viewpoint sample of the trace
    std::vector<int> inferred;                      // the samples with maps
    std::vector<runtime::LensGroupEm> groups;
};

// The manifest of maps inferred at `inferred` (empty: every sample) from `trace` into pemDir.
PemManifest PemManifestFor(
    const TraceManifest& trace, const std::string& pemDir, int res, bool hdr,
    const std::vector<int>& inferred, const runtime::MapHardware& hardware = {}, int maxRes = 0,
    runtime::Parameterization parameterization = runtime::Parameterization::Cube);

void WritePemManifest(const PemManifest& manifest);  // dir/manifest.json
PemManifest ReadPemManifest(const std::string& dir);

// base::InputError(path, ...) unless `size` is a face size the manifest allows for a map (a
// power of two in [res, max_res]).
void CheckMapSize(const PemManifest& manifest, int size, const std::string& path);

// The sampler state the manifest's maps are drawn with: the hardware's filters
// (MapHardware::Sampler) with the layout's wrap modes (lat-long repeats along s).
raster::SamplerState MapSampler(const PemManifest& manifest);

// base::InputError(path, ...) unless a map of `kind`, `charts` textures (a cube: 1) of level-0
// width x height is one of the manifest's layout (runtime/parameterization.h) at a size
// CheckMapSize allows; returns that size (LayoutOf's; a cube's face size).
int CheckMapShape(const PemManifest& manifest, raster::TextureKind kind, int width, int height,
                  int charts, const std::string& path);

// The text of manifest.json and back, for a manifest kept elsewhere (a packed PEM, pem_pack.h):
// `dir` is where its relative paths start, `source` the file errors name.
std::string PemManifestText(const PemManifest& manifest);
PemManifest PemManifestFromText(const std::string& text, const std::string& dir,
                                const std::string& source);

// The manifest of the same maps kept in `dir`: the scene and trace paths stored relative to it.
PemManifest RelocatedPemManifest(const PemManifest& manifest, const std::string& dir);

}  // namespace pem::pipeline
