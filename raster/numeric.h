// SPDX-License-Identifier: MIT
// numeric.h — the only numeric primitives of raster/: the float and 8-bit operations whose exact
// bits the hardware model depends on. Every function is defined for all inputs (NaN and Inf
// included) and gives the same bits on any IEEE-754 machine, compiler and optimisation level
// (the project builds with -ffp-contract=off; fused operations are written as std::fma).
// Not here: anything approximate from libm (log2f, powf, ...): none is used in raster/.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace pem::raster {

// 64-bit integer add, subtract and multiply that wrap modulo 2^64, as the reference's compiled
// int64 edge arithmetic does (vertices that snap to INT32_MIN, from NaN or overflow, take edge
// values near 2^63).
inline int64_t WrapAdd64(int64_t a, int64_t b) {
    return static_cast<int64_t>(static_cast<uint64_t>(a) + static_cast<uint64_t>(b));
}
inline int64_t WrapSub64(int64_t a, int64_t b) {
    return static_cast<int64_t>(static_cast<uint64_t>(a) - static_cast<uint64_t>(b));
}
inline int64_t WrapMul64(int64_t a, int64_t b) {
    return static_cast<int64_t>(static_cast<uint64_t>(a) * static_cast<uint64_t>(b));
}

inline uint32_t FloatBits(float f) {
    return std::bit_cast<uint32_t>(f);
}
inline float BitsFloat(uint32_t u) {
    return std::bit_cast<float>(u);
}

// Float lerp as llvmpipe's float path computes it: fmuladd(w, b - a, a), fused on FMA hosts.
inline float LerpF(float w, float a, float b) {
    return std::fma(w, b - a, a);
}

// x86 cvtps2dq: round half to even; NaN and values outside int32 give INT32_MIN.
inline int32_t RoundHalfEvenI32(float x) {
    if (!(std::fabs(x) < 2147483648.0f)) return INT32_MIN;
    return static_cast<int32_t>(std::nearbyint(x));  // default rounding mode: to nearest even
}

// x86 cvttps2dq: truncate toward zero; NaN and out-of-range values give INT32_MIN.
inline int32_t TruncI32(float x) {
    if (!(std::fabs(x) < 2147483648.0f)) return INT32_MIN;
    return static_cast<int32_t>(x);
}

// floor to int as llvmpipe's lp_build_ifloor (cvttps2dq of a value already floored):
// NaN/out-of-range give INT32_MIN.
inline int32_t FloorI32(float x) {
    if (!(std::fabs(x) < 2147483648.0f)) return INT32_MIN;
    return static_cast<int32_t>(std::floor(x));
}

// gallivm's lp_build_fast_log2: (biased exponent - 128) + mantissa in [1, 2). Exact at powers of
// two, below log2 by at most 0.0861 in between. Works on the raw bits, so it is defined for
// zero, denormals, Inf and NaN exactly as the JIT code computes it.
inline float FastLog2(float x) {
    const uint32_t bits = FloatBits(x);
    const int32_t e = static_cast<int32_t>((bits >> 23) & 255u) - 128;
    const float m = BitsFloat((bits & 0x007fffffu) | 0x3f800000u);
    return static_cast<float>(e) + m;
}

// Round half to even of 0 <= x < 2^22 (nearbyint in the default rounding mode) without a libm
// call (baseline x86-64 has no roundss): adding 1.5 * 2^23 leaves no fraction bits, so the add
// rounds x to an integer, and taking 1.5 * 2^23 away again is exact.
inline float RoundEvenSmall(float x) {
    constexpr float kShift = 12582912.0f;  // 1.5 * 2^23 (no -ffast-math: the sum is not folded)
    return (x + kShift) - kShift;
}

// x > 0 ? (x < 1 ? x : 1) : +0 (NaN -> 0), as bit selects: without -ffinite-math-only the
// compilers turn the ternaries into two branches per channel, while the selects vectorise over
// a pixel's four channels (cmpps, and, blend).
inline float ClampUnit(float x) {
    const uint32_t positive = 0u - static_cast<uint32_t>(x > 0.0f);
    const float low = BitsFloat(FloatBits(x) & positive);
    const uint32_t below = 0u - static_cast<uint32_t>(low < 1.0f);
    return BitsFloat((FloatBits(low) & below) | (FloatBits(1.0f) & ~below));
}

// float -> unorm8 as llvmpipe stores a fragment colour: clamp to [0, 1] (NaN -> 0), multiply
// by 255 in float, round half to even.
inline uint8_t UnormFromFloatRne(float x) {
    return static_cast<uint8_t>(RoundEvenSmall(ClampUnit(x) * 255.0f));
}

// The D3D rule: clamp, then floor(x * 255 + 0.5) with the product rounded to float first.
inline uint8_t UnormFromFloatHalfUp(float x) {
    return static_cast<uint8_t>(std::floor(ClampUnit(x) * 255.0f + 0.5f));
}

// float -> unorm8 with the rounding rule selected (RNE: GL/llvmpipe; half up: D3D).
inline uint8_t UnormFromFloat(float x, bool halfEven) {
    return halfEven ? UnormFromFloatRne(x) : UnormFromFloatHalfUp(x);
}

// unorm8 -> float as llvmpipe converts texels and framebuffer values: c * fl(1/255).
inline float FloatFromUnorm8(uint8_t c) {
    return static_cast<float>(c) * static_cast<float>(1.0 / 255.0);
}

// 8-bit normalized product as llvmpipe blends: (t + (t >> 8) + 128) >> 8, t = a * b.
inline uint8_t Mul8(uint8_t a, uint8_t b) {
    const uint32_t t = static_cast<uint32_t>(a) * b;
    return static_cast<uint8_t>((t + (t >> 8) + 128u) >> 8);
}

// 8-bit lerp of llvmpipe's fixed-point sampler: a + ((w * (b - a) + 128) >> 8), w in 0..255
// meaning w/256, arithmetic shift (the pmulhrsw form on SSSE3/AVX2 hosts).
inline uint8_t Lerp8(int32_t w, uint8_t a, uint8_t b) {
    const int32_t d = static_cast<int32_t>(b) - static_cast<int32_t>(a);
    const int32_t p = w * d + 128;
    const int32_t q = p >= 0 ? p >> 8 : -((-p + 255) >> 8);  // floor division by 256
    return static_cast<uint8_t>(static_cast<int32_t>(a) + q);
}

inline uint8_t SatAdd8(uint8_t a, uint8_t b) {
    const int32_t s = static_cast<int32_t>(a) + b;
    return static_cast<uint8_t>(s > 255 ? 255 : s);
}
inline uint8_t SatSub8(uint8_t a, uint8_t b) {
    return static_cast<uint8_t>(a > b ? a - b : 0);
}

}  // namespace pem::raster
