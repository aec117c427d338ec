// SPDX-License-Identifier: MIT
// cube_lookup_impl.h — implementation of cube_lookup.h, compiled into each fragment-stage
// variant (fragment_base.cpp, fragment_fma.cpp; see fragment.h).
#pragma once
#include <cmath>

#include "raster/cube_lookup.h"
#include "raster/numeric.h"

namespace pem::raster::isa {
namespace {

float FlipSign(float v, uint32_t signBit) {
    return BitsFloat(FloatBits(v) ^ signBit);
}
float Neg(float v) {
    return FlipSign(v, 0x80000000u);
}

// x86 maxps: the second operand when either is NaN.
float MaxSse(float a, float b) {
    return a > b ? a : b;
}

enum Axis { kX, kY, kZ };

// Both tests are LLVM's unordered compares (lp_build_cmp): true when either side is NaN.
Axis MajorAxis(const Vec3f& d) {
    const float as = std::fabs(d[0]), at = std::fabs(d[1]), ar = std::fabs(d[2]);
    if (!(ar < MaxSse(as, at))) return kZ;  // select3: z wins over the x/y choice
    return !(as <= at) ? kX : kY;
}

// Mirrored minor coordinates (sc, tc) of a vector on the face of `axis` with major sign bit
// `sign` (0 or 0x80000000): X: (-r, -t) flipped by sign in s; Y: (s, r) flipped by sign in t;
// Z: (s, -t) flipped by sign in s.
void MinorCoords(Axis axis, uint32_t sign, const Vec3f& v, float* sc, float* tc) {
    switch (axis) {
        case kX:
            *sc = FlipSign(Neg(v[2]), sign);
            *tc = Neg(v[1]);
            break;
        case kY:
            *sc = v[0];
            *tc = FlipSign(v[2], sign);
            break;
        case kZ:
            *sc = FlipSign(v[0], sign);
            *tc = Neg(v[1]);
            break;
    }
}

int CubeFace(const Vec3f& dir) {
    const Axis axis = MajorAxis(dir);
    return 2 * static_cast<int>(axis) + static_cast<int>(FloatBits(dir[axis]) >> 31);
}

CubeCoord CubeLookup(const Vec3f& dir, const Vec3f& ddx, const Vec3f& ddy, bool withDerivatives) {
    const Axis axis = MajorAxis(dir);
    const float ma = dir[axis];
    const uint32_t sign = FloatBits(ma) & 0x80000000u;
    CubeCoord out;
    out.face = 2 * static_cast<int>(axis) + static_cast<int>(sign >> 31);
    float sc, tc;
    MinorCoords(axis, sign, dir, &sc, &tc);

    float imaHalfPos;
    if (withDerivatives) {
        // Quotient rule with the signed major component.
        const float ima = 1.0f / ma;
        const float imaHalf = 0.5f * ima;
        imaHalfPos = std::fabs(imaHalf);
        float scdx, tcdx, scdy, tcdy;
        MinorCoords(axis, sign, ddx, &scdx, &tcdx);
        MinorCoords(axis, sign, ddy, &scdy, &tcdy);
        const float madxDivMa = ddx[axis] * ima;
        out.dsdx = (scdx - madxDivMa * sc) * imaHalf;
        out.dtdx = (tcdx - madxDivMa * tc) * imaHalf;
        const float madyDivMa = ddy[axis] * ima;
        out.dsdy = (scdy - madyDivMa * sc) * imaHalf;
        out.dtdy = (tcdy - madyDivMa * tc) * imaHalf;
    } else {
        // lp_build_cube_imapos: 0.5/|ma| unless |ma| > 0 fails (unordered: NaN gives NaN).
        const float am = std::fabs(ma);
        imaHalfPos = !(am <= 0.0f) ? 0.5f / am : 0.0f;
    }
    out.s = sc * imaHalfPos + 0.5f;
    out.t = tc * imaHalfPos + 0.5f;
    return out;
}

}  // namespace
}  // namespace pem::raster::isa
