// SPDX-License-Identifier: MIT
// map_coding.h — predictive coding of one PEM map's 8-bit copy (every MIP level, the bytes the
// hardware samples), the inner code of the packed PEM (pem_pack.h).
//
//   MapCode code = EncodeMap(map, previous, {});   // lossless, predictive
//   std::vector<raster::Texture> t = DecodeMap(code, ShapeOf(map), levels, previous, 0);
//   // t[c].levels == map[c].levels
//
// A map is its textures: a cube map, or a 2D map of one or two charts (runtime/
// parameterization.h), coded as one image of faces: a cube's 6, a 2D map's charts, each level
// the faces' images stacked (faces × h_l rows of w_l texels).
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
// With a ratio, every level whose faces are at least kMinTransformSize wide and tall is instead
// coded as one JPEG 2000 image (w × faces·h, RGBA; base/j2k_codec.h) at that compression ratio (1:
// lossless), the levels below the finest at twice the ratio (they weigh less in the frames: on the
// demo's maps 16.2:1 instead of 14.5:1 against the PNG maps at the same frame PSNR), the decimated
// predictor of the smaller levels starting from the decoded finest level.
// Not here: files, the byte codec, the sampler (the caller sets it).
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
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

// Levels with faces at least this wide (and tall) are transform-coded when a ratio is given.
constexpr int kMinTransformSize = 8;

// The shape of a map: its kind, faces (a cube's 6, a 2D map's textures) and level-0 size.
struct MapShape {
    raster::TextureKind kind = raster::TextureKind::Cube;
    int faces = 6;
    int width = 1, height = 1;
    int LevelWidth(int level) const { return std::max(1, width >> level); }
    int LevelHeight(int level) const { return std::max(1, height >> level); }
    size_t LevelBytes(int level) const;  // every face, RGBA
    int ChainLevels() const;             // the levels of a full MIP chain
    bool operator==(const MapShape&) const = default;
};
// The shape of a map's textures (std::invalid_argument unless one cube, or equal 2D textures).
MapShape ShapeOf(std::span<const raster::Texture> map);

// `previous` (may be empty) must have the map's shape and levels to be used.
// How a map is coded: the predicted levels' largest error, and the transform-coded levels'
// compression ratio (0: none; 1: lossless; the levels below the finest at twice the ratio) and
// wavelet (base/j2k_codec.h).
struct MapCodeOptions {
    int maxError = 0;
    double ratio = 0.0;
    base::J2kWavelet wavelet = base::J2kWavelet::Irreversible97;
};

MapCode EncodeMap(std::span<const raster::Texture> map, std::span<const raster::Texture> previous,
                  const MapCodeOptions& options);

// The decoded map's textures (sampler left default). std::runtime_error when the code does not
// fit the shape and levels (a corrupt or truncated pack).
std::vector<raster::Texture> DecodeMap(const MapCode& code, const MapShape& shape, int levels,
                                       std::span<const raster::Texture> previous, int maxError);

// The bytes of the residual stream of a map of this shape and level count (every level
// predicted), and of the predicted levels only.
size_t ResidualBytes(const MapShape& shape, int levels);
size_t PredictedBytes(const MapShape& shape, const std::vector<std::vector<uint8_t>>& transformed);

}  // namespace pem::pipeline
