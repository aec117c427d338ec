// SPDX-License-Identifier: MIT
// matrix_rows.h — how one fragment enters the rendering matrix's rows (render.h
// BuildRenderingMatrix), for every profile's matrix mode. The rows are kept per pixel while the
// frame is drawn: every tap once, with the fragment's multiplier per channel (row 4p + c of A is
// pixel p's taps at columns 4 * texel + c with values weight * modulation[c]):
//
//   AddFragmentRows(matrix, rows, pixel, pass, colour, [&](std::vector<MatrixTap>& row) {
//       for (each texel t of unit 0) row.push_back({t, weight, modulation});
//   });
//
// An unblended pass replaces the pixel's rows and offsets, an "add" pass adds to them (the
// caller has refused other blends); an untextured fragment adds its colour to the offset, a
// textured one its unit-0 texels (appendTaps). fragments[pixel] counts the fragments written
// since the last unblended one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "raster/blend.h"
#include "raster/render.h"

namespace pem::raster {

// One tap of a fragment on unit 0: its texel (TexelIndexer), filter weight and what multiplies
// the sample per channel. A's entry for channel c: weight * double(modulation[c]).
struct MatrixTap {
    uint32_t texel;
    double weight;
    RgbaF modulation;
};

using MatrixRows = std::vector<std::vector<MatrixTap>>;  // per pixel

template <class AppendTaps>
void AddFragmentRows(RenderingMatrix* matrix, MatrixRows* rows, size_t pixel, const Pass& pass,
                     const RgbaF& colour, AppendTaps&& appendTaps) {
    uint16_t& frags = matrix->fragments[pixel];
    frags = pass.blend.enabled ? static_cast<uint16_t>(frags + 1) : 1;
    std::vector<MatrixTap>& row = (*rows)[pixel];
    double* off = &matrix->offset[4 * pixel];
    if (!pass.blend.enabled) {
        row.clear();
        for (int c = 0; c < 4; ++c) off[c] = 0.0;
    }
    if (pass.numUnits == 0) {
        for (int c = 0; c < 4; ++c) off[c] += static_cast<double>(colour[static_cast<size_t>(c)]);
        return;
    }
    appendTaps(row);
}

}  // namespace pem::raster
