// SPDX-License-Identifier: MIT
// cube_lookup.h — cube face selection, face coordinates and their screen derivatives, as
// llvmpipe's lp_build_cube_lookup computes them per pixel.
//
//  - Major axis: z if |z| >= max(|x|, |y|), else x if |x| > |y|, else y (ties: z, then y).
//  - The face sign is the sign bit of the major component (-0.0 selects the negative face).
//  - sc, tc follow GL table 8.19 by flipping sign bits; s = sc * |0.5 / ma| + 0.5.
//  - With derivatives: ds/dx = (dsc/dx - (dma/dx * (1/ma)) * sc) * (0.5 * (1/ma)), ma signed,
//    from fine quad differences of the direction (the quotient rule on the pixel's own face).
// Not here: LOD (lod.h), filtering (sample_*_impl.h). Implemented in cube_lookup_impl.h.
#pragma once

#include <array>

namespace pem::raster {

using Vec3f = std::array<float, 3>;

struct CubeCoord {
    int face = 0;        // 0 +X, 1 -X, 2 +Y, 3 -Y, 4 +Z, 5 -Z
    float s = 0, t = 0;  // face coordinates in [0, 1] for finite directions
    float dsdx = 0, dtdx = 0, dsdy = 0, dtdy = 0;  // with derivatives only
};

// Face selection and projection. `ddx`/`ddy` (direction derivatives) are used when
// `withDerivatives`; llvmpipe then computes the projection through 1/ma as well.
CubeCoord CubeLookup(const Vec3f& dir, const Vec3f& ddx, const Vec3f& ddy, bool withDerivatives);

// The major-axis test alone (for tests and the exact-LOD variant).
int CubeFace(const Vec3f& dir);

// GL table 8.19 inverted: a direction on face `face` whose face coordinates are sc = 2s - 1 and
// tc = 2t - 1 (not normalised).
inline Vec3f FaceDirection(int face, float sc, float tc) {
    switch (face) {
        case 0:
            return {1.0f, -tc, -sc};
        case 1:
            return {-1.0f, -tc, sc};
        case 2:
            return {sc, 1.0f, tc};
        case 3:
            return {sc, -1.0f, -tc};
        case 4:
            return {sc, -tc, 1.0f};
        default:
            return {-sc, -tc, -1.0f};
    }
}

}  // namespace pem::raster
