// SPDX-License-Identifier: MIT
// fuzz_pack.cpp — packed PEMs: the input read as a pack (header, checksums, blobs), and, since a
// damaged payload stops at the checksum, also straight through the decoders behind it: as a JPEG
// 2000 codestream of a 16 × 96 RGBA level and as the code of a 16² cube map of five levels and
// of a tennis map (two 16 × 4 bands, five levels).
#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "base/input_error.h"
#include "base/j2k_codec.h"
#include "pipeline/map_coding.h"
#include "pipeline/pem_pack.h"
#include "tests/fuzz/fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace pem;
    try {
        pipeline::ReadPemPack(fuzz::WriteInput("p.pempack", data, size));
    } catch (const base::InputError&) {
    }
    try {
        base::DecodeJ2k({data, size}, 16, 96, 4);
    } catch (const std::runtime_error&) {
    }
    try {
        const size_t np = std::min<size_t>(size, 20);
        pipeline::MapCode code{{data, data + np}, {data + np, data + size}, {}};
        code.transformed.resize(5);
        for (int maxError : {0, 3})
            pipeline::DecodeMap(code, {raster::TextureKind::Cube, 6, 16, 16}, 5, {}, maxError);
    } catch (const std::runtime_error&) {
    }
    try {
        const size_t np = std::min<size_t>(size, 20);
        pipeline::MapCode code{{data, data + np}, {data + np, data + size}, {}};
        code.transformed.resize(5);
        pipeline::DecodeMap(code, {raster::TextureKind::Tex2D, 2, 16, 4}, 5, {}, 0);
    } catch (const std::runtime_error&) {
    }
    return 0;
}
