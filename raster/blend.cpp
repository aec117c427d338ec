// SPDX-License-Identifier: MIT
#include "raster/blend.h"

#include <algorithm>

#include "raster/numeric.h"

namespace pem::raster {
namespace {

// Factor for channel c (0..2 colour, 3 alpha), `one` being 255 (8-bit) or 1.0f (float).
// ONE_MINUS_X is one - x (for 8 bits a bitwise NOT); SRC_ALPHA_SATURATE is min(As, one - Ad)
// for colour and ONE for alpha.
template <typename T>
T Factor(BlendFactor f, int c, const std::array<T, 4>& s, const std::array<T, 4>& d, T one) {
    auto inv = [one](T x) { return static_cast<T>(one - x); };
    switch (f) {
        case BlendFactor::Zero:
            return T(0);
        case BlendFactor::One:
            return one;
        case BlendFactor::SrcColor:
            return s[c];
        case BlendFactor::OneMinusSrcColor:
            return inv(s[c]);
        case BlendFactor::DstColor:
            return d[c];
        case BlendFactor::OneMinusDstColor:
            return inv(d[c]);
        case BlendFactor::SrcAlpha:
            return s[3];
        case BlendFactor::OneMinusSrcAlpha:
            return inv(s[3]);
        case BlendFactor::DstAlpha:
            return d[3];
        case BlendFactor::OneMinusDstAlpha:
            return inv(d[3]);
        case BlendFactor::SrcAlphaSaturate:
            return c == 3 ? one : std::min(s[3], inv(d[3]));
    }
    return T(0);
}

}  // namespace

Rgba8 Blend8(const BlendState& st, const Rgba8& s, const Rgba8& d) {
    if (!st.enabled) return s;
    Rgba8 out;
    for (int c = 0; c < 4; ++c) {
        const bool alpha = c == 3;
        const BlendEquation eq = alpha ? st.eqAlpha : st.eqRgb;
        // Min and max ignore the factors (the GL state tracker sets them to ONE).
        if (eq == BlendEquation::Min) {
            out[c] = std::min(s[c], d[c]);
            continue;
        }
        if (eq == BlendEquation::Max) {
            out[c] = std::max(s[c], d[c]);
            continue;
        }
        const uint8_t ts =
            Mul8(s[c], Factor<uint8_t>(alpha ? st.srcAlpha : st.srcRgb, c, s, d, 255));
        const uint8_t td =
            Mul8(d[c], Factor<uint8_t>(alpha ? st.dstAlpha : st.dstRgb, c, s, d, 255));
        switch (eq) {
            case BlendEquation::Add:
                out[c] = SatAdd8(ts, td);
                break;
            case BlendEquation::Subtract:
                out[c] = SatSub8(ts, td);
                break;
            case BlendEquation::ReverseSubtract:
                out[c] = SatSub8(td, ts);
                break;
            default:
                break;
        }
    }
    return out;
}

RgbaF BlendF(const BlendState& st, const RgbaF& s, const RgbaF& d) {
    if (!st.enabled) return s;
    RgbaF out;
    for (int c = 0; c < 4; ++c) {
        const bool alpha = c == 3;
        const BlendEquation eq = alpha ? st.eqAlpha : st.eqRgb;
        if (eq == BlendEquation::Min) {
            out[c] = std::min(s[c], d[c]);
            continue;
        }
        if (eq == BlendEquation::Max) {
            out[c] = std::max(s[c], d[c]);
            continue;
        }
        const float ts = s[c] * Factor<float>(alpha ? st.srcAlpha : st.srcRgb, c, s, d, 1.0f);
        const float td = d[c] * Factor<float>(alpha ? st.dstAlpha : st.dstRgb, c, s, d, 1.0f);
        switch (eq) {
            case BlendEquation::Add:
                out[c] = ts + td;
                break;
            case BlendEquation::Subtract:
                out[c] = ts - td;
                break;
            case BlendEquation::ReverseSubtract:
                out[c] = td - ts;
                break;
            default:
                break;
        }
    }
    return out;
}

// llvmpipe (lp_bld_blend_aos.c, lp_bld_blend.c, Mesa 22.3.6) on float colour buffers: factor
// vectors with the RGB factor in R, G, B and the alpha factor in A (ONE_MINUS_X as 1 - x). When
// the source and destination factors are equal for RGB and for alpha, ADD, SUBTRACT and
// REVERSE_SUBTRACT are factored: (s op d) * factor. Otherwise s * sf op d * df, unfused. A
// product with the constant ONE is its operand and with ZERO is +0 (folded when the code is
// built). MIN and MAX take the operands (the factors are ONE). The alpha channel uses the alpha
// equation; the RGB channels the RGB one.
RgbaF BlendFloatLlvmpipe(const BlendState& st, const RgbaF& s, const RgbaF& d) {
    if (!st.enabled) return s;
    const bool factored = st.srcRgb == st.dstRgb && st.srcAlpha == st.dstAlpha;
    const auto times = [](float x, BlendFactor f, float value) {
        if (f == BlendFactor::One) return x;
        if (f == BlendFactor::Zero) return 0.0f;
        return x * value;
    };
    RgbaF out;
    for (int c = 0; c < 4; ++c) {
        const bool alpha = c == 3;
        const BlendEquation eq = alpha ? st.eqAlpha : st.eqRgb;
        if (eq == BlendEquation::Min) {
            out[c] = s[c] < d[c] ? s[c] : d[c];
            continue;
        }
        if (eq == BlendEquation::Max) {
            out[c] = s[c] > d[c] ? s[c] : d[c];
            continue;
        }
        const BlendFactor fs = alpha ? st.srcAlpha : st.srcRgb;
        const BlendFactor fd = alpha ? st.dstAlpha : st.dstRgb;
        const float vs = Factor<float>(fs, c, s, d, 1.0f), vd = Factor<float>(fd, c, s, d, 1.0f);
        if (factored) {
            const float sum = eq == BlendEquation::Add        ? s[c] + d[c]
                              : eq == BlendEquation::Subtract ? s[c] - d[c]
                                                              : d[c] - s[c];
            out[c] = times(sum, fs, vs);
            continue;
        }
        const float ts = times(s[c], fs, vs), td = times(d[c], fd, vd);
        out[c] = eq == BlendEquation::Add        ? ts + td
                 : eq == BlendEquation::Subtract ? ts - td
                                                 : td - ts;
    }
    return out;
}

}  // namespace pem::raster
