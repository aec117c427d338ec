// SPDX-License-Identifier: MIT
// map_set.h — what a renderer draws from: the viewpoint samples' cameras, the lens groups' EM
// geometry and the maps inferred at each sample. A PEM directory fills it
// (pipeline/pem_set.h); tests fill it by hand.
//
//   MapSet m;  m.samples = {camera0, camera1};  m.inferred = {0, 1};  m.groups = {group};
//   m.map = [&](int view, int group, const std::string& name) { return &textures.at(name); };
//
// Map names: layer_<l> (hybrid layers, l = 0 innermost, both terms), single (the single-layer
// PEM) and pem_local / pem_distant (mirror-only groups, PEM mode). `map` returns nullptr for a
// map that does not exist; the texture is the hardware's copy (MapHardware::format) with its
// sampler. A map of a two-image layout (paraboloid, tennis) is two textures: `map` returns the
// first of two consecutive ones (chart 0, chart 1; LayoutOf(parameterization, res).textures).
// Not here: reading files (pipeline/), drawing (renderer.h).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "raster/camera.h"
#include "raster/frame.h"
#include "runtime/lens_group_em.h"
#include "runtime/lens_paths.h"
#include "runtime/parameterization.h"
#include "trace/tracer.h"

namespace pem::runtime {

// The hardware that draws the maps: a profile (raster/profile.h), the maps' sampler state and
// their radiance scale, the same for inference and rendering.
struct MapHardware {
    std::string profile = "llvmpipe";
    float maxAnisotropy = 1.0f;  // GL_TEXTURE_MAX_ANISOTROPY of the lens maps (1: off)
    // The maps and the lens frames hold radiance / radianceScale (a power of two, so the
    // scaling is exact): 8-bit maps reach incident radiance up to the scale, at steps of
    // scale / 255; the renderers multiply the lens frames by it (a frame of 8-bit maps
    // saturates at the scale, one of float maps does not).
    float radianceScale = 1.0f;
    // GL_TEXTURE_LOD_BIAS of the lens maps: below 0 the hardware reads finer levels than the
    // footprint asks for, which the fit (every subpixel a row) can use where a sharp
    // reflection would otherwise be blurred by the MIP filter.
    float lodBias = 0.0f;
    // The maps' texels: RGBA8 (8-bit copies of the inferred maps, each value clamped into
    // [0, 1]) or RGBA32F (the inferred floats as they are, negative or above 1 too; the lens
    // frames are then drawn into an RGBA32F colour buffer, unclamped, and the inference solves
    // without bounds).
    raster::TexelFormat format = raster::TexelFormat::Rgba8;

    // Trilinear, seamless, with the anisotropy and the LOD bias.
    raster::SamplerState Sampler() const {
        raster::SamplerState s;
        s.maxAnisotropy = maxAnisotropy;
        s.lodBias = lodBias;
        return s;
    }
};

// The LOD biases MapHardware accepts: [-kMaxLodBias, kMaxLodBias].
constexpr float kMaxLodBias = 4.0f;

// A radiance scale MapHardware accepts: a power of two in [1, 64].
inline bool IsRadianceScale(float s) {
    for (float p = 1.0f; p <= 64.0f; p *= 2.0f)
        if (s == p) return true;
    return false;
}

struct MapSet {
    std::string name;                     // for messages: the PEM directory
    std::vector<raster::Camera> samples;  // every viewpoint sample's camera, whole
    std::vector<int> inferred;            // the samples that have maps (not empty)
    std::vector<LensGroupEm> groups;      // one per scene lens group
    int spp = 1;                          // the traced images' K×K sampling (t's unit)
    int res = 0;                          // face size of the maps (the layout's size)
    Parameterization parameterization = Parameterization::Cube;  // the maps' layout
    trace::TraceOptions tracing;           // the ray tracer's options the maps were traced with
    MapHardware hardware;                  // what they were inferred for and are drawn by
    double tessT = kDefaultTessT;          // the hybrid tessellation t they were inferred on
    double topologyT = kDefaultTopologyT;  // and its topology threshold (0: t alone)
    std::function<const raster::Texture*(int view, int group, const std::string& name)> map;
};

}  // namespace pem::runtime
