// SPDX-License-Identifier: MIT
// depth.cpp — the depth clear value (depth.h): glClearDepth clamps to [0, 1] in double
// (main/depth.c), llvmpipe packs it with util_pack_z (auxiliary/util/u_pack_color.h).
#include "raster/depth.h"

namespace pem::raster {

uint32_t DepthClearValue(DepthFormat format, float clear) {
    // Step 1: glClearDepth's CLAMP(depth, 0.0, 1.0) (keeps -0.0 and NaN as they are).
    double z = static_cast<double>(clear);
    z = z < 0.0 ? 0.0 : (z > 1.0 ? 1.0 : z);
    // Step 2: util_pack_z.
    if (format == DepthFormat::Z32F) return FloatBits(static_cast<float>(z));
    if (!(z > 0.0)) return 0;  // NaN too (lrint(NaN) is 0x8000...0, whose low 32 bits are 0)
    const double ones = format == DepthFormat::Z16 ? 65535.0 : 16777215.0;
    if (z >= 1.0) return static_cast<uint32_t>(ones);
    return static_cast<uint32_t>(std::nearbyint(z * ones));  // lrint: round half to even
}

}  // namespace pem::raster
