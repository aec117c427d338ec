// SPDX-License-Identifier: MIT
// sampler_impl.h — texture lookups of eight lanes (sampler.h): derivatives, face selection, LOD,
// then llvmpipe's float ("SoA") or 8-bit ("AoS") filtering path, whichever it would take, or
// its anisotropic path (aniso_impl.h) when the sampler asks for one.
#pragma once
#include <algorithm>
#include <cmath>

#include "raster/aniso_impl.h"
#include "raster/cube_lookup_impl.h"
#include "raster/lod_impl.h"
#include "raster/numeric.h"
#include "raster/sample_fast_impl.h"
#include "raster/sample_fixed8_impl.h"
#include "raster/sample_float_impl.h"
#include "raster/sampler.h"
#include "raster/sampler_paths.h"

namespace pem::raster::isa {
namespace {

// True when llvmpipe samples this texture with its 8-bit AoS path.
bool UsesAosPath(const Texture& t) {
    if (t.format != TexelFormat::Rgba8) return false;  // float texels: the SoA path only
    const SamplerState& s = t.sampler;
    const bool cube = t.kind == TextureKind::Cube;
    // AoS needs one LOD per quad or equal min/mag filters; cubes with a MIP filter have
    // per-pixel LODs.
    const bool perPixelLod = cube && s.mipFilter != MipFilter::None;
    if (perPixelLod && s.minFilter != s.magFilter) return false;
    if (cube && s.seamless && (s.minFilter == Filter::Linear || s.magFilter == Filter::Linear))
        return false;
    // Only repeat and clamp-to-edge are "simple" wraps (cubes always clamp).
    const auto simple = [](Wrap w) { return w != Wrap::MirroredRepeat; };
    return cube || (simple(s.wrapS) && simple(s.wrapT));
}

// `cache` (optional, fast path only): the footprints of these coordinates on an earlier
// texture, reused when its shape serves this one (sample_fast_impl.h).
void SampleLanes(const PreparedFrame& frame, int textureIndex, const RenderOptions& options,
                 const LaneCoords& coords, std::array<RgbaF, kLanes>* colour,
                 std::array<PixelTaps, kLanes>* taps, unsigned live,
                 FastFootprints* cache = nullptr) {
    const PreparedTexture& pt = frame.texture(textureIndex);
    const Texture& tex = *pt.source;
    const SamplerState& s = tex.sampler;
    const PipeLodState& lodState = pt.lod;
    if (lodState.maxAnisotropy > 1) {
        SampleAniso(frame, textureIndex, options, coords, colour, taps, live);
        return;
    }
    if (!taps && FastSeamlessApplies(tex, lodState, options)) {
        SampleFastSeamless(frame, textureIndex, coords, live, colour, cache);
        return;
    }
    const bool needLod = s.mipFilter != MipFilter::None || s.minFilter != s.magFilter;
    const bool exact = options.cubeLod == CubeLod::Exact;

    // Coordinates on the texture and LOD per lane.
    LaneSample ls;
    ls.texture = textureIndex;
    ls.live = live;
    if (tex.kind == TextureKind::Cube) {
        const bool withDerivs = needLod && !lodState.minMaxEqual;
        alignas(32) float rho[kLanes], s0[kLanes], t0[kLanes];
        alignas(32) int32_t face[kLanes];
        CubeLanes(coords, withDerivs, static_cast<float>(tex.width), face, s0, t0, rho);
        for (int l = 0; l < kLanes; ++l) {
            ls.face[l] = face[l];
            ls.s[l] = s0[l];
            ls.t[l] = t0[l];
        }
        if (needLod) {
            for (int l = 0; l < kLanes; ++l)
                ls.lod[l] = isa::SelectLod(rho[l], lodState, s.mipFilter, tex.NumLevels(), exact);
            // Without a MIP filter (min != mag) the LOD is per quad: its top-left pixel's.
            if (s.mipFilter == MipFilter::None)
                for (int l = 0; l < kLanes; ++l) ls.lod[l] = ls.lod[l & ~3];
        }
    } else {
        // 2D: coarse derivatives per quad from its top-left pixel, one LOD per quad.
        const float w = static_cast<float>(tex.width), h = static_cast<float>(tex.height);
        for (int q = 0; q < kLanes; q += 4) {
            LodResult lod;
            if (needLod) {
                const auto& tl = coords.c[q];
                const auto& tr = coords.c[q + 1];
                const auto& bl = coords.c[q + 2];
                const float dsdx = (tr[0] - tl[0]) * w, dsdy = (bl[0] - tl[0]) * w;
                const float dtdx = (tr[1] - tl[1]) * h, dtdy = (bl[1] - tl[1]) * h;
                const float rx = dsdx * dsdx + dtdx * dtdx, ry = dsdy * dsdy + dtdy * dtdy;
                float rho = rx > ry ? rx : ry;
                lod = isa::SelectLod(rho, lodState, s.mipFilter, tex.NumLevels(), exact);
            }
            for (int p = 0; p < 4; ++p) {
                ls.s[q + p] = coords.c[q + p][0];
                ls.t[q + p] = coords.c[q + p][1];
                ls.face[q + p] = 0;
                ls.lod[q + p] = lod;
            }
        }
    }

    // Filtering.
    if (options.profile == Profile::Linear || !UsesAosPath(tex))
        FilterFloat(frame, tex, s, pt, options.profile == Profile::Linear, ls, colour, taps);
    else
        FilterFixed8(frame, tex, pt, ls, colour, taps);
}

}  // namespace
}  // namespace pem::raster::isa
