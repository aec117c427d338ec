// SPDX-License-Identifier: MIT
// sampler_impl.h — texture lookups of eight lanes (sampler.h): derivatives, face selection, LOD,
// then llvmpipe's float ("SoA") or 8-bit ("AoS") filtering path, whichever it would take.
#pragma once
#include "raster/sampler.h"

#include <algorithm>
#include <cmath>

#include "raster/cube_lookup_impl.h"
#include "raster/lod_impl.h"
#include "raster/numeric.h"
#include "raster/sample_fixed8_impl.h"
#include "raster/sample_fast_impl.h"
#include "raster/sample_float_impl.h"
#include "raster/sampler_paths.h"

namespace pem::raster::isa {
namespace {

// True when llvmpipe samples this texture with its 8-bit AoS path.
bool UsesAosPath(const Texture& t) {
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

// Face selection, projection and squared scale factor of all eight lanes, written as
// branch-free loops over lanes (structure of arrays) so the compiler can vectorise them; the
// per-lane arithmetic is exactly cube_lookup_impl.h's CubeLookup followed by llvmpipe's rho^2.
void CubeLanes(const LaneCoords& c, bool withDerivs, float n, LaneSample* ls, float* rhoOut) {
    alignas(32) float d[3][kLanes], dx[3][kLanes], dy[3][kLanes];
    for (int k = 0; k < 3; ++k)
        for (int l = 0; l < kLanes; ++l) d[k][l] = c.c[l][k];
    // Fine quad differences: ddx = right - left in the lane's row, ddy = bottom - top.
    for (int k = 0; k < 3; ++k)
        for (int l = 0; l < kLanes; ++l) {
            const int q = l & ~3, p = l & 3;
            const int left = q + (p & 2), top = q + (p & 1);
            dx[k][l] = d[k][left + 1] - d[k][left];
            dy[k][l] = d[k][top + 2] - d[k][top];
        }
    for (int l = 0; l < kLanes; ++l) {
        const float x = d[0][l], y = d[1][l], z = d[2][l];
        const float as = std::fabs(x), at = std::fabs(y), ar = std::fabs(z);
        const bool xGt = as > at;
        const bool zGe = ar >= (as > at ? as : at);
        const int axis = zGe ? 2 : (xGt ? 0 : 1);
        const float ma = zGe ? z : (xGt ? x : y);
        const uint32_t sign = FloatBits(ma) & 0x80000000u;
        ls->face[l] = 2 * axis + static_cast<int>(sign >> 31);
        // (sc, tc): X: (-z ^ sign, -y); Y: (x, z ^ sign); Z: (x ^ sign, -y).
        auto minor = [&](const float (*v)[kLanes], float* sc, float* tc) {
            const float vx = v[0][l], vy = v[1][l], vz = v[2][l];
            *sc = axis == 0 ? BitsFloat(FloatBits(vz) ^ 0x80000000u ^ sign)
                            : (axis == 1 ? vx : BitsFloat(FloatBits(vx) ^ sign));
            *tc = axis == 1 ? BitsFloat(FloatBits(vz) ^ sign) : BitsFloat(FloatBits(vy) ^ 0x80000000u);
        };
        float sc, tc;
        minor(d, &sc, &tc);
        float imaHalfPos, rho = 0.0f;
        if (withDerivs) {
            const float ima = 1.0f / ma;
            const float imaHalf = 0.5f * ima;
            imaHalfPos = std::fabs(imaHalf);
            float scdx, tcdx, scdy, tcdy;
            minor(dx, &scdx, &tcdx);
            minor(dy, &scdy, &tcdy);
            const float madx = axis == 0 ? dx[0][l] : (axis == 1 ? dx[1][l] : dx[2][l]);
            const float mady = axis == 0 ? dy[0][l] : (axis == 1 ? dy[1][l] : dy[2][l]);
            const float qx = madx * ima, qy = mady * ima;
            const float xs = n * ((scdx - qx * sc) * imaHalf), xt = n * ((tcdx - qx * tc) * imaHalf);
            const float ys = n * ((scdy - qy * sc) * imaHalf), yt = n * ((tcdy - qy * tc) * imaHalf);
            const float rx = xs * xs + xt * xt, ry = ys * ys + yt * yt;
            rho = rx > ry ? rx : ry;  // maxps
            rho = std::isfinite(rho) ? rho : 0.0f;
        } else {
            const float am = std::fabs(ma);
            imaHalfPos = am > 0.0f ? 0.5f / am : 0.0f;
        }
        ls->s[l] = sc * imaHalfPos + 0.5f;
        ls->t[l] = tc * imaHalfPos + 0.5f;
        rhoOut[l] = rho;
    }
}

void SampleLanes(const PreparedFrame& frame, int textureIndex, const RenderOptions& options,
                 const LaneCoords& coords, std::array<RgbaF, kLanes>* colour,
                 std::array<PixelTaps, kLanes>* taps, unsigned live) {
    const PreparedTexture& pt = frame.texture(textureIndex);
    const Texture& tex = *pt.source;
    const SamplerState& s = tex.sampler;
    const PipeLodState& lodState = pt.lod;
    if (!taps && FastSeamlessApplies(tex, lodState, options)) {
        SampleFastSeamless(frame, textureIndex, coords, live, colour);
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
        alignas(32) float rho[kLanes];
        CubeLanes(coords, withDerivs, static_cast<float>(tex.width), &ls, rho);
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
        FilterFloat(frame, tex, pt, options.profile == Profile::Linear, ls, colour, taps);
    else
        FilterFixed8(frame, tex, pt, ls, colour, taps);
}

}  // namespace
}  // namespace pem::raster::isa
