// SPDX-License-Identifier: MIT
// map_coding.h — predictive coding of one PEM map's 8-bit copy (every MIP level, the bytes the
// hardware samples), the inner code of the packed PEM (pem_pack.h).
//
//   MapCode code = EncodeMap(texture, previous, {});   // lossless, predictive
//   raster::Texture t = DecodeMap(code, texture.width, texture.NumLevels(), previous, 0);
//   // t.levels == texture.levels
//
// Each level and channel picks the predictor that leaves the smallest residuals (PEM paper §4:
// levels coded as residuals from decimated versions of the finest level; and across the
// viewpoint samples, each map from its neighbour's):
//   base  zero | previous (the same map at the previous sample, as decoded) |
//         decimated (the decoded finest level, box-filtered 2×2 per level, rounded)
//   plus, optionally, the median edge detector (LOCO-I) of the base's residuals of the left,
//   upper and upper-left texels of the same face (spatial prediction).
// Residuals are quantized with step 2·maxError + 1 against the decoded values (closed loop), so
// every decoded byte lies within maxError of the original; maxError 0 is lossless (residuals
// modulo 256). The stream holds one zigzag byte per texel and channel, level by level, channel
// by channel, face by face, row by row — for a byte codec (base/byte_codec.h) to compress.
// With a ratio, every level whose faces are at least kMinTransformSize wide is instead coded as
// one JPEG 2000 image (n × 6n, RGBA; base/j2k_codec.h) at that compression ratio (1: lossless),
// the levels below the finest at twice the ratio (they weigh less in the frames: on the demo's
// maps 16.2:1 instead of 14.5:1 against the PNG maps at the same frame PSNR), the decimated
// predictor of the smaller levels starting from the decoded finest level.
// Not here: files, the byte codec, the sampler (the caller sets it).
#pragma once

#include <cstdint>
#include <vector>

#include "base/j2k_codec.h"
#include "raster/frame.h"

namespace pem::pipeline {

// The largest maxError accepted (steps above 2·31+1 = 63 leave little of an 8-bit map).
constexpr int kMaxMapError = 31;

struct MapCode {
    std::vector<uint8_t> predictors;  // per level and channel: base * 2 + spatial
    std::vector<uint8_t> residuals;   // see the header comment
    // Per level: its JPEG 2000 codestream, or empty when the level is predicted.
    std::vector<std::vector<uint8_t>> transformed;
};

// Levels with faces at least this wide are transform-coded when a ratio is given.
constexpr int kMinTransformSize = 8;

// `previous` (may be null) must be a cube of the same width and levels to be used.
// How a map is coded: the predicted levels' largest error, and the transform-coded levels'
// compression ratio (0: none; 1: lossless; the levels below the finest at twice the ratio) and
// wavelet (base/j2k_codec.h).
struct MapCodeOptions {
    int maxError = 0;
    double ratio = 0.0;
    base::J2kWavelet wavelet = base::J2kWavelet::Irreversible97;
};

MapCode EncodeMap(const raster::Texture& texture, const raster::Texture* previous,
                  const MapCodeOptions& options);

// The decoded cube (sampler left default). std::runtime_error when the code does not fit the
// size and levels (a corrupt or truncated pack).
raster::Texture DecodeMap(const MapCode& code, int width, int levels,
                          const raster::Texture* previous, int maxError);

// The bytes of the residual stream of a cube of this size and level count (every level
// predicted), and of the predicted levels only.
size_t ResidualBytes(int width, int levels);
size_t PredictedBytes(int width, const std::vector<std::vector<uint8_t>>& transformed);

}  // namespace pem::pipeline
