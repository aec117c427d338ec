// SPDX-License-Identifier: MIT
// depth.h — the depth buffer and the depth test as Mesa 22.3.6 llvmpipe computes them for a GL
// 3.3 context (docs/raster-model.md §6 gives each rule with its Mesa source):
//
//   std::vector<uint32_t> zbuf(w * h, DepthClearValue(format, clear));     // glClear
//   const float z = FragmentDepth(setup.z, X, Y);          // the plane at the pixel, in [0, 1]
//   const uint32_t v = DepthFromFloat(format, z);          // the value the buffer would hold
//   if (DepthPasses(func, format, v, zbuf[i])) { if (write) zbuf[i] = v; /* shade */ }
//
// Stored values: Z16 and Z24 hold the unorm integer (0..65535, 0..16777215; llvmpipe keeps
// GL_DEPTH_COMPONENT24 as Z24X8_UNORM, whose X8 bits never take part), Z32F the float's bits.
// Every function gives the same bits with or without MXCSR DAZ/FTZ: FragmentDepth flushes
// subnormals itself, as llvmpipe's threads do in hardware.
// Not here: which lanes are tested and when (shade_impl.h), the value types (frame.h).
#pragma once

#include <cfloat>
#include <cmath>
#include <cstdint>

#include "raster/frame.h"
#include "raster/numeric.h"
#include "raster/triangle_setup.h"

namespace pem::raster {

// MXCSR DAZ/FTZ in software: a subnormal becomes a zero of the same sign.
inline float FlushSubnormal(float v) {
    return std::fabs(v) < FLT_MIN ? std::copysign(0.0f, v) : v;
}

// The depth of the fragment at pixel (X, Y) (the integer point after the setup's 0.5 offset):
// the z plane evaluated like every attribute, fma(dzdy, Y, fma(dzdx, X, a0)), plus the polygon
// offset llvmpipe keeps in a0.x (0 here: -0 becomes +0), then clamped to [0, 1] with x86
// min/max semantics (NaN -> 1). GL always clamps (depth range [0, 1]; with GL_DEPTH_CLAMP the
// viewport's [0, 1] clamp again), whatever the buffer's format.
inline float FragmentDepth(const Plane& z, float x, float y) {
    const float a0 = FlushSubnormal(z.a0), dzdx = FlushSubnormal(z.dadx);
    const float dzdy = FlushSubnormal(z.dady);
    float v = FlushSubnormal(std::fma(dzdx, x, a0));
    v = FlushSubnormal(std::fma(dzdy, y, v));
    v = v + 0.0f;                // polygon offset (none)
    v = v < 1.0f ? v : 1.0f;     // minps(v, 1)
    return v > 0.0f ? v : 0.0f;  // maxps(v, 0)
}

// The buffer value of fragment depth z in [0, 1] (lp_build_clamped_float_to_unsigned_norm):
//  - Z16: the "magic number" conversion, low 16 bits of fl(fl(z * 65535/65536) + 128)
//    (two float roundings; the sum's last 16 mantissa bits hold round(z * 65535)),
//  - Z24: cvtps2dq(fl(z * 16777215)), round half to even after a float multiply,
//  - Z32F: the float itself.
inline uint32_t DepthFromFloat(DepthFormat format, float z) {
    switch (format) {
        case DepthFormat::Z16:
            return FloatBits(z * 0.9999847412109375f + 128.0f) & 0xFFFFu;
        case DepthFormat::Z24:
            return static_cast<uint32_t>(RoundHalfEvenI32(z * 16777215.0f));
        case DepthFormat::Z32F:
            break;
    }
    return FloatBits(z);
}

// `a FUNC b` (for floats: on numbers; DepthPasses handles NaN).
template <class T>
bool CompareDepth(DepthFunc func, T a, T b) {
    switch (func) {
        case DepthFunc::Never:
            return false;
        case DepthFunc::Less:
            return a < b;
        case DepthFunc::Equal:
            return a == b;
        case DepthFunc::LEqual:
            return a <= b;
        case DepthFunc::Greater:
            return a > b;
        case DepthFunc::NotEqual:
            return a != b;
        case DepthFunc::GEqual:
            return a >= b;
        case DepthFunc::Always:
            break;
    }
    return true;
}

// Whether a fragment whose buffer value is `fragment` passes `func` against `stored`, compared
// in the format's type: Z16 unsigned, Z24 signed 32-bit (lp_depth_type: the 24 bits do not
// fill the word), Z32F float with LLVM's unordered predicates (a NaN passes every function but
// NEVER; only a NaN clear value could put one there) on operands flushed by DAZ (a subnormal
// clear value compares as zero).
inline bool DepthPasses(DepthFunc func, DepthFormat format, uint32_t fragment, uint32_t stored) {
    switch (format) {
        case DepthFormat::Z16:
            return CompareDepth(func, fragment, stored);
        case DepthFormat::Z24:
            return CompareDepth(func, static_cast<int32_t>(fragment), static_cast<int32_t>(stored));
        case DepthFormat::Z32F:
            break;
    }
    const float a = FlushSubnormal(BitsFloat(fragment)), b = FlushSubnormal(BitsFloat(stored));
    if (std::isnan(a) || std::isnan(b)) return func != DepthFunc::Never;
    return CompareDepth(func, a, b);
}

// The value glClear writes for glClearDepth(clear) (util_pack_z on the clamped double):
// Z32F the float; unorm formats 0 for clear <= 0, all ones for clear >= 1, else
// round-half-even(clear * (2^n - 1)) in double (exact: the product needs at most 48 bits).
uint32_t DepthClearValue(DepthFormat format, float clear);

}  // namespace pem::raster
