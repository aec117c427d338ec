// SPDX-License-Identifier: MIT
// fragment_base.cpp — the baseline build of the fragment stage (fragment.h), the dispatcher, and
// the public entry points of cube_lookup.h, lod.h, aniso.h and sampler.h (which forward to it).
#include <cstdlib>
#include <cstring>

#include "raster/fragment.h"
#include "raster/shade_impl.h"

namespace pem::raster {

DrawBandsFn DrawBandsBase() {
    return &isa::DrawBands;
}

DrawBandsFn SelectDrawBands(const char** name) {
    const char* force = std::getenv("PEM_ISA");
    const bool forceBase = force && std::strcmp(force, "base") == 0;
    DrawBandsFn fma = DrawBandsFma();
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
    const bool cpuOk = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
    const bool cpuOk = false;
#endif
    if (fma && cpuOk && !forceBase) {
        if (name) *name = "avx2-fma";
        return fma;
    }
    if (name) *name = "base";
    return DrawBandsBase();
}

CubeCoord CubeLookup(const Vec3f& dir, const Vec3f& ddx, const Vec3f& ddy, bool withDerivatives) {
    return isa::CubeLookup(dir, ddx, ddy, withDerivatives);
}
int CubeFace(const Vec3f& dir) {
    return isa::CubeFace(dir);
}

PipeLodState DerivePipeLodState(const SamplerState& s, int numLevels) {
    return isa::DerivePipeLodState(s, numLevels);
}
float LambdaFromRhoSquared(float rhoSquared, const PipeLodState& st, bool exactLog2) {
    return isa::LambdaFromRhoSquared(rhoSquared, st, exactLog2);
}
LodResult LevelsFor(float lambda, MipFilter mip, int numLevels) {
    return isa::LevelsFor(lambda, mip, numLevels);
}
LodResult SelectLod(float rhoSquared, const PipeLodState& st, MipFilter mip, int numLevels,
                    bool exactLog2) {
    return isa::SelectLod(rhoSquared, st, mip, numLevels, exactLog2);
}
float AnisoRhoSquared(const std::array<float, 4>& d, int maxAniso) {
    return isa::AnisoRhoSquared(d, maxAniso);
}
AnisoEllipse AnisoEllipseOf(const std::array<float, 4>& d) {
    return isa::AnisoEllipseOf(d);
}
std::vector<AnisoProbe> AnisoProbesOf(const AnisoEllipse& e, float texU, float texV,
                                      int64_t maxProbes) {
    return isa::AnisoProbesOf(e, texU, texV, maxProbes);
}
void SampleLanes(const PreparedFrame& frame, int textureIndex, const RenderOptions& options,
                 const LaneCoords& coords, std::array<RgbaF, kLanes>* colour,
                 std::array<PixelTaps, kLanes>* taps, unsigned live) {
    isa::SampleLanes(frame, textureIndex, options, coords, colour, taps, live);
}

}  // namespace pem::raster
