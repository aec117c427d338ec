// SPDX-License-Identifier: MIT
// byte_codec.h — lossless compression of byte streams by a library Debian ships: Zstandard
// (libzstd) or XZ/LZMA2 (liblzma). The packed PEM (pipeline/pem_pack.h) codes its residual
// streams with it.
//
//   std::vector<uint8_t> z = Compress(ByteCodec::Zstd, bytes);
//   std::vector<uint8_t> b = Decompress(ByteCodec::Zstd, z, bytes.size());   // b == bytes
//
// Conventions: single-threaded and at a fixed level per codec (zstd 19, xz preset 9 extreme),
// so the compressed bytes depend only on the input and the library's version. Decompress
// throws std::runtime_error when the data is corrupt or does not decode to exactly `rawSize`
// bytes.
// Not here: containers, checksums of whole files (the caller's).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace pem::base {

enum class ByteCodec { Zstd, Xz };

// "zstd" / "xz"; std::invalid_argument for another name.
ByteCodec ByteCodecNamed(const std::string& name);
std::string ByteCodecName(ByteCodec codec);

std::vector<uint8_t> Compress(ByteCodec codec, std::span<const uint8_t> raw);
std::vector<uint8_t> Decompress(ByteCodec codec, std::span<const uint8_t> packed, size_t rawSize);

}  // namespace pem::base
