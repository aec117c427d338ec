// SPDX-License-Identifier: MIT
// j2k_codec.h — 8-bit multi-channel images as JPEG 2000 codestreams (OpenJPEG, Debian's
// libopenjp2): lossless, or lossy at a compression ratio, always with the reversible 5/3 integer
// wavelet, so decoding is integer arithmetic and gives the same bytes on every machine.
//
//   std::vector<uint8_t> j = EncodeJ2k(image, /*ratio=*/20);   // 0: lossless
//   Image8Planes back = DecodeJ2k(j);
//
// Errors: std::runtime_error (bad sizes, a codestream OpenJPEG cannot read).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace pem::base {

enum class J2kWavelet { Reversible53, Irreversible97 };

struct Image8Planes {
    int width = 0, height = 0, channels = 0;
    std::vector<uint8_t> data;  // interleaved: (y * width + x) * channels + c
};

// ratio <= 1: lossless (always 5/3).
std::vector<uint8_t> EncodeJ2k(const Image8Planes& image, double ratio, J2kWavelet wavelet);
// The image of a codestream that must be width × height with `channels` channels (checked before
// anything is decoded, so a hostile header cannot make it allocate more).
Image8Planes DecodeJ2k(std::span<const uint8_t> codestream, int width, int height, int channels);

}  // namespace pem::base
