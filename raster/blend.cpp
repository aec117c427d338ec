// SPDX-License-Identifier: MIT
#include "raster/blend.h"

#include <algorithm>

#include "raster/numeric.h"

namespace pem::raster {
namespace {

// Factor for channel c (0..2 colour, 3 alpha) in 8 bits. ONE_MINUS_X is 255 - x (a bitwise NOT);
// SRC_ALPHA_SATURATE is min(As, 255 - Ad) for colour and ONE for alpha.
uint8_t Factor8(BlendFactor f, int c, const Rgba8& s, const Rgba8& d) {
    switch (f) {
        case BlendFactor::Zero:
            return 0;
        case BlendFactor::One:
            return 255;
        case BlendFactor::SrcColor:
            return s[c];
        case BlendFactor::OneMinusSrcColor:
            return static_cast<uint8_t>(255 - s[c]);
        case BlendFactor::DstColor:
            return d[c];
        case BlendFactor::OneMinusDstColor:
            return static_cast<uint8_t>(255 - d[c]);
        case BlendFactor::SrcAlpha:
            return s[3];
        case BlendFactor::OneMinusSrcAlpha:
            return static_cast<uint8_t>(255 - s[3]);
        case BlendFactor::DstAlpha:
            return d[3];
        case BlendFactor::OneMinusDstAlpha:
            return static_cast<uint8_t>(255 - d[3]);
        case BlendFactor::SrcAlphaSaturate:
            return c == 3 ? 255 : std::min<uint8_t>(s[3], static_cast<uint8_t>(255 - d[3]));
    }
    return 0;
}

float FactorF(BlendFactor f, int c, const RgbaF& s, const RgbaF& d) {
    switch (f) {
        case BlendFactor::Zero:
            return 0.0f;
        case BlendFactor::One:
            return 1.0f;
        case BlendFactor::SrcColor:
            return s[c];
        case BlendFactor::OneMinusSrcColor:
            return 1.0f - s[c];
        case BlendFactor::DstColor:
            return d[c];
        case BlendFactor::OneMinusDstColor:
            return 1.0f - d[c];
        case BlendFactor::SrcAlpha:
            return s[3];
        case BlendFactor::OneMinusSrcAlpha:
            return 1.0f - s[3];
        case BlendFactor::DstAlpha:
            return d[3];
        case BlendFactor::OneMinusDstAlpha:
            return 1.0f - d[3];
        case BlendFactor::SrcAlphaSaturate:
            return c == 3 ? 1.0f : std::min(s[3], 1.0f - d[3]);
    }
    return 0.0f;
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
        const uint8_t ts = Mul8(s[c], Factor8(alpha ? st.srcAlpha : st.srcRgb, c, s, d));
        const uint8_t td = Mul8(d[c], Factor8(alpha ? st.dstAlpha : st.dstRgb, c, s, d));
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
        const float ts = s[c] * FactorF(alpha ? st.srcAlpha : st.srcRgb, c, s, d);
        const float td = d[c] * FactorF(alpha ? st.dstAlpha : st.dstRgb, c, s, d);
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

}  // namespace pem::raster
