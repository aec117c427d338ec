// SPDX-License-Identifier: MIT
// pem_set.h — a PEM directory opened for drawing: manifest.json, the scene it was made from and
// its maps, loaded on first use and kept.
//
//   std::unique_ptr<runtime::Renderer> r = OpenPemDirectory("out/pem", /*threads=*/2);
//   runtime::RenderedFrame f = r->Render(r->SampleCamera(0), {});
//
// Maps: view_v/group_g/<name>.exr (layout.h), read as float and converted to the hardware's
// copy in the manifest's map_format (infer/env_map.h ToTextures: 8-bit, or the floats) with the
// manifest's sampler (trilinear, seamless) and,
// for a 2D layout (manifest "parameterization"), the layout's wrap modes; a map of another
// layout's shape is refused.
// The scene is found relative to the PEM directory first (pem_manifest.h), so a directory can
// be moved or copied. A packed PEM (pem_pack.h) opens the same way, its scene found relative
// to the pack's folder. Errors: base::InputError naming the file and the cause.
#pragma once

#include <memory>
#include <string>

#include "pipeline/pem_manifest.h"
#include "pipeline/pem_pack.h"
#include "runtime/map_set.h"
#include "runtime/renderer.h"

namespace pem::pipeline {

// The manifest's maps as a renderer sees them (runtime/map_set.h); the cameras as traced.
runtime::MapSet LoadMapSet(const PemManifest& manifest);

// The scene the directory was made from; a missing scene is reported against `source` (the
// pack file) or, when empty, the directory's manifest.json.
trace::Scene LoadPemScene(const PemManifest& manifest, const std::string& source = "");

// The maps of a packed PEM (pem_pack.h), already decoded; the rest as LoadMapSet.
runtime::MapSet PackMapSet(PemPack pack, const std::string& packFile);

// A PEM directory or a packed PEM (pem_pack.h IsPemPack) opened for drawing.
std::unique_ptr<runtime::Renderer> OpenPemDirectory(const std::string& pemDir, int threads,
                                                    const std::string& embreeIsa = "auto");

// A view spec as a camera of the given size: sample:I (the camera sample I was traced with),
// orbit:AZ:EL:DIST (degrees added to the first sample's azimuth and elevation about the lens
// centre, DIST scales its distance) or camera (the scene's camera). base::InputError naming
// `--view SPEC` otherwise.
raster::Camera ViewCamera(const runtime::Renderer& renderer, const std::string& spec, int width,
                          int height);

}  // namespace pem::pipeline
