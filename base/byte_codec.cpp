// SPDX-License-Identifier: MIT
// byte_codec.cpp — Zstandard and XZ byte streams (byte_codec.h).
#include "base/byte_codec.h"

#include <lzma.h>
#include <zstd.h>

#include <stdexcept>

namespace pem::base {
namespace {

constexpr int kZstdLevel = 19;
constexpr uint32_t kXzPreset = 9 | LZMA_PRESET_EXTREME;

std::vector<uint8_t> ZstdCompress(std::span<const uint8_t> raw) {
    std::vector<uint8_t> out(ZSTD_compressBound(raw.size()));
    const size_t n = ZSTD_compress(out.data(), out.size(), raw.data(), raw.size(), kZstdLevel);
    if (ZSTD_isError(n)) throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(n));
    out.resize(n);
    return out;
}

std::vector<uint8_t> ZstdDecompress(std::span<const uint8_t> packed, size_t rawSize) {
    std::vector<uint8_t> out(rawSize);
    const size_t n = ZSTD_decompress(out.data(), out.size(), packed.data(), packed.size());
    if (ZSTD_isError(n)) throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(n));
    if (n != rawSize) throw std::runtime_error("zstd: the stream decodes to the wrong length");
    return out;
}

std::vector<uint8_t> XzCompress(std::span<const uint8_t> raw) {
    std::vector<uint8_t> out(lzma_stream_buffer_bound(raw.size()));
    size_t n = 0;
    const lzma_ret r = lzma_easy_buffer_encode(kXzPreset, LZMA_CHECK_CRC64, nullptr, raw.data(),
                                               raw.size(), out.data(), &n, out.size());
    if (r != LZMA_OK)
        throw std::runtime_error("xz: cannot compress (error " + std::to_string(r) + ")");
    out.resize(n);
    return out;
}

std::vector<uint8_t> XzDecompress(std::span<const uint8_t> packed, size_t rawSize) {
    std::vector<uint8_t> out(rawSize);
    uint64_t memlimit = UINT64_MAX;
    size_t in = 0, n = 0;
    const lzma_ret r = lzma_stream_buffer_decode(&memlimit, 0, nullptr, packed.data(), &in,
                                                 packed.size(), out.data(), &n, out.size());
    if (r != LZMA_OK)
        throw std::runtime_error("xz: corrupt stream (error " + std::to_string(r) + ")");
    if (n != rawSize || in != packed.size())
        throw std::runtime_error("xz: the stream decodes to the wrong length");
    return out;
}

}  // namespace

ByteCodec ByteCodecNamed(const std::string& name) {
    if (name == "zstd") return ByteCodec::Zstd;
    if (name == "xz") return ByteCodec::Xz;
    throw std::invalid_argument("unknown codec '" + name + "' (zstd or xz)");
}

std::string ByteCodecName(ByteCodec codec) {
    return codec == ByteCodec::Zstd ? "zstd" : "xz";
}

std::vector<uint8_t> Compress(ByteCodec codec, std::span<const uint8_t> raw) {
    return codec == ByteCodec::Zstd ? ZstdCompress(raw) : XzCompress(raw);
}

std::vector<uint8_t> Decompress(ByteCodec codec, std::span<const uint8_t> packed, size_t rawSize) {
    return codec == ByteCodec::Zstd ? ZstdDecompress(packed, rawSize)
                                    : XzDecompress(packed, rawSize);
}

}  // namespace pem::base
