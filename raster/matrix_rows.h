// SPDX-License-Identifier: MIT
// matrix_rows.h — how one fragment enters the rendering matrix's rows (render.h
// BuildRenderingMatrix), for every profile's matrix mode:
//
//   AddFragmentRows(matrix, rows, pixel, pass, colour, [&](auto& row, int c) {
//       for (each texel t of unit 0) row.push_back({4 * t + c, weight * modulation[c]});
//   });
//
// An unblended pass replaces the pixel's rows and offsets, an "add" pass adds to them (the
// caller has refused other blends); an untextured fragment adds its colour to the offset, a
// textured one its unit-0 texels (appendTaps). fragments[pixel] counts the fragments written
// since the last unblended one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "raster/blend.h"
#include "raster/render.h"

namespace pem::raster {

using MatrixRows = std::vector<std::vector<std::pair<uint32_t, double>>>;

template <class AppendTaps>
void AddFragmentRows(RenderingMatrix* matrix, MatrixRows* rows, size_t pixel, const Pass& pass,
                     const RgbaF& colour, AppendTaps&& appendTaps) {
    uint16_t& frags = matrix->fragments[pixel];
    frags = pass.blend.enabled ? static_cast<uint16_t>(frags + 1) : 1;
    for (int c = 0; c < 4; ++c) {
        auto& row = (*rows)[4 * pixel + static_cast<size_t>(c)];
        double& off = matrix->offset[4 * pixel + static_cast<size_t>(c)];
        if (!pass.blend.enabled) {
            row.clear();
            off = 0.0;
        }
        if (pass.numUnits == 0) {
            off += static_cast<double>(colour[static_cast<size_t>(c)]);
            continue;
        }
        appendTaps(row, c);
    }
}

}  // namespace pem::raster
