// SPDX-License-Identifier: MIT
// case_codec.h — the byte-level pieces of the gl_ref_case/1 format: base64 (RFC 4648, padded) and
// hex codecs, the splitmix64 stream and the texel generators (random, random_box, gradient).
// Conventions: texel layout as frame.h (levels[l] = faces x rows x columns x RGBA8, face-major).
// Not here: JSON (case_file.h); decoders report problems as a cause string, never throw.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "raster/frame.h"

namespace pem::conformance {

// Decoded bytes, or a non-empty `error` naming what is wrong with the text.
struct DecodeResult {
    std::vector<uint8_t> bytes;
    std::string error;
};

std::string Base64Encode(const std::vector<uint8_t>& bytes);
DecodeResult Base64Decode(std::string_view text);  // strict: padded, no whitespace
DecodeResult HexDecode(std::string_view text);     // even length, either case

// splitmix64 (Steele, Lea, Flood 2014), exactly as gl_ref_case/1 prints it.
class SplitMix64 {
  public:
    explicit SplitMix64(uint64_t seed) : state_(seed) {}
    uint64_t Next();

  private:
    uint64_t state_;
};

enum class TexelGenKind { Random, RandomBox, Gradient };

struct TexelGen {
    TexelGenKind kind = TexelGenKind::Random;
    uint64_t seed = 0;
    int alpha = -1;  // 0..255 fixed; -1: random (random gens) or per-level default (gradient)
};

// Levels of a texture of `kind` with level-0 size width x height and `numLevels` levels, RGBA8.
std::vector<std::vector<uint8_t>> GenerateTexels(raster::TextureKind kind, int width, int height,
                                                 int numLevels, const TexelGen& gen);

// The RGBA32F level a generator gives for RGBA8 level `bytes`: each byte b becomes the float
// (b - 64) / 64 (exact: -1 .. 2.984375, negative and above 1 alike).
std::vector<uint8_t> FloatLevelFromBytes(const std::vector<uint8_t>& bytes);

}  // namespace pem::conformance
