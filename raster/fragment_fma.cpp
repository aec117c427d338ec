// SPDX-License-Identifier: MIT
// fragment_fma.cpp — the fragment stage (fragment.h) built for x86-64 CPUs with AVX2 and FMA.
// Every header with external-linkage inline code is included before the target switch, so only
// this file's internal-linkage functions (shade_impl.h and the *_impl.h it includes) are
// compiled for AVX2/FMA; nothing outside can pick up an AVX2 copy of a shared inline function.
// Unoptimised builds leave it out (they would not inline, and gain nothing).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#include "raster/aniso.h"
#include "raster/blend.h"
#include "raster/cube_lookup.h"
#include "raster/depth.h"
#include "raster/fragment.h"
#include "raster/lod.h"
#include "raster/numeric.h"
#include "raster/sampler.h"
#include "raster/sampler_paths.h"
#include "raster/triangle_setup.h"

#if defined(__x86_64__) && defined(__OPTIMIZE__) && (defined(__GNUC__) || defined(__clang__))
#define PEM_BUILD_FMA 1
#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx2,fma"))), apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx2,fma")
#endif
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include "raster/shade_impl.h"
#pragma GCC diagnostic pop
#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC pop_options
#endif
#endif

namespace pem::raster {

#ifdef PEM_BUILD_FMA
DrawBandsFn DrawBandsFma() {
    return &isa::DrawBands;
}
#else
DrawBandsFn DrawBandsFma() {
    return nullptr;
}
#endif

}  // namespace pem::raster
