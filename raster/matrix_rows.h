// SPDX-License-Identifier: MIT
// matrix_rows.h — how one fragment enters the rendering matrix's rows (render.h
// BuildRenderingMatrix), for every profile's matrix mode. While the frame is drawn, every tap is
// appended to the log of its pixel's row band (the 8 pixel rows one band worker owns, so no two
// threads append to one log), with the fragment's multiplier per channel (row 4p + c of A is
// pixel p's taps at columns 4 * texel + c with values weight * modulation[c]):
//
//   AddFragmentRows(matrix, rows, pixel, y, pass, colour, [&](MatrixRows::Appender& row) {
//       for (each texel t of unit 0) row.Add(t, weight, modulation);
//   });
//   rows.GroupBand(band, ...);  // render.cpp: each band's log grouped by pixel, then CSR
//
// An unblended pass replaces the pixel's rows and offsets (the taps logged before it no longer
// count), an "add" pass adds to them (the caller has refused other blends); an untextured
// fragment adds its colour to the offset, a textured one its unit-0 texels (appendTaps).
// fragments[pixel] counts the fragments written since the last unblended one. A pixel's taps are
// kept in the order they were logged: one growing vector per band, not one per pixel.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "raster/blend.h"
#include "raster/render.h"

namespace pem::raster {

// One tap of a fragment on unit 0: its pixel, texel (TexelIndexer), filter weight and what
// multiplies the sample per channel. A's entry for channel c: weight * double(modulation[c]).
struct MatrixTap {
    uint32_t pixel;
    uint32_t texel;
    double weight;
    RgbaF modulation;
};

class MatrixRows {
  public:
    static constexpr int kBandRows = 8;  // fragment.h kBandQuadRows quad rows

    // A frame of `pixels` pixels and `height` rows; GL row y belongs to band y / kBandRows.
    MatrixRows(size_t pixels, int height)
        : start_(pixels, 0), logs_(static_cast<size_t>((height + kBandRows - 1) / kBandRows)) {}

    // Appends one fragment's taps to its band's log.
    class Appender {
      public:
        Appender(std::vector<MatrixTap>* log, uint32_t pixel) : log_(log), pixel_(pixel) {}
        void Add(uint32_t texel, double weight, const RgbaF& modulation) {
            log_->push_back({pixel_, texel, weight, modulation});
        }

      private:
        std::vector<MatrixTap>* log_;
        uint32_t pixel_;
    };

    // The taps logged so far for `pixel` (GL row y) no longer count.
    void Restart(size_t pixel, int y) {
        start_[pixel] = static_cast<uint32_t>(logs_[static_cast<size_t>(y / kBandRows)].size());
    }
    Appender Append(size_t pixel, int y) {
        return {&logs_[static_cast<size_t>(y / kBandRows)], static_cast<uint32_t>(pixel)};
    }

    size_t Bands() const { return logs_.size(); }
    // Band b's log rewritten so that each pixel's counting taps are consecutive, pixels in
    // increasing order, each pixel's taps still in logged order; `first` receives, per pixel of
    // [p0, p1) (the band's pixels), the index of its first tap in the rewritten log, and entry
    // p1 - p0 the log's size. `scratch` is working storage (it receives the old log).
    void GroupBand(size_t b, size_t p0, size_t p1, std::vector<uint32_t>* first,
                   std::vector<MatrixTap>* scratch);
    std::vector<MatrixTap>& Log(size_t b) { return logs_[b]; }

  private:
    std::vector<uint32_t> start_;  // per pixel: where its counting taps begin in its band's log
    std::vector<std::vector<MatrixTap>> logs_;  // per band
};

inline void MatrixRows::GroupBand(size_t b, size_t p0, size_t p1, std::vector<uint32_t>* first,
                                  std::vector<MatrixTap>* scratch) {
    std::vector<MatrixTap>& log = logs_[b];
    // Step 1: the counting taps per pixel (those logged since the pixel's last restart).
    first->assign(p1 - p0 + 1, 0);
    for (size_t k = 0; k < log.size(); ++k)
        if (k >= start_[log[k].pixel]) ++(*first)[log[k].pixel - p0 + 1];
    for (size_t p = 1; p < first->size(); ++p) (*first)[p] += (*first)[p - 1];
    // Step 2: scattered in logged order (stable), the log replaced by the grouped taps.
    scratch->resize(first->back());
    std::vector<uint32_t> next(first->begin(), first->end() - 1);
    for (size_t k = 0; k < log.size(); ++k)
        if (k >= start_[log[k].pixel]) (*scratch)[next[log[k].pixel - p0]++] = log[k];
    log.swap(*scratch);
}

template <class AppendTaps>
void AddFragmentRows(RenderingMatrix* matrix, MatrixRows* rows, size_t pixel, int y,
                     const Pass& pass, const RgbaF& colour, AppendTaps&& appendTaps) {
    uint16_t& frags = matrix->fragments[pixel];
    frags = pass.blend.enabled ? static_cast<uint16_t>(frags + 1) : 1;
    double* off = &matrix->offset[4 * pixel];
    if (!pass.blend.enabled) {
        rows->Restart(pixel, y);
        for (int c = 0; c < 4; ++c) off[c] = 0.0;
    }
    if (pass.numUnits == 0) {
        for (int c = 0; c < 4; ++c) off[c] += static_cast<double>(colour[static_cast<size_t>(c)]);
        return;
    }
    MatrixRows::Appender row = rows->Append(pixel, y);
    appendTaps(row);
}

}  // namespace pem::raster
