// SPDX-License-Identifier: MIT
// pem_pack.h — the packed PEM: a whole PEM directory in one file, its maps coded predictively
// (map_coding.h: MIP levels from the decimated finest level, each sample from its neighbour's)
// and compressed by a byte codec (base/byte_codec.h), or its larger levels by JPEG 2000 at a
// compression ratio (lossy). Its one writer and its one reader.
//
//   PackStats s = PackPem("out/pem", "out/pem.pempack", {});   // lossless
//   PemPack p = ReadPemPack("out/pem.pempack");                 // p.maps: the 8-bit copies
//   UnpackPem("out/pem.pempack", "out/pem2", 2);                // a PEM directory again
//
// What is kept: the maps' 8-bit copies, every level — the bytes the hardware samples, so a
// lossless pack renders byte-identically to its directory — the manifest (paths relative to the
// pack's folder) and every other file (infer.json, sample.json, the solvers' .csv) verbatim.
// The float maps are not kept: unpack writes each EXR as the 8-bit copy / 255 (which converts
// back to the same bytes) and the PNG preview from it.
//
// File: "PEMPACK1", the header's length (8 bytes, little-endian), the header (JSON: format
// pemref_pack, version, codec, max_error, ratio, manifest text, payload size and SHA-256, the
// files and the maps (with their size: the manifest's layout's size parameter, a cube's face
// size, and levels) with their blobs' offsets and sizes: the byte-coded predictors and residuals,
// and per level the JPEG 2000 codestream or null), then the blobs. Errors: base::InputError naming
// the file and the cause (not a pack, truncated, checksum, corrupt blob, bad map size).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "base/byte_codec.h"
#include "pipeline/map_coding.h"
#include "pipeline/pem_manifest.h"
#include "raster/frame.h"

namespace pem::pipeline {

struct PackOptions {
    base::ByteCodec codec = base::ByteCodec::Zstd;
    MapCodeOptions map;                    // max error, JPEG 2000 ratio and wavelet (map_coding.h)
    std::function<void(double)> progress;  // share of the samples coded, after each one
};

// What packing measured: the pack against the directory's map files.
struct PackStats {
    int samples = 0, maps = 0;
    uint64_t packBytes = 0;
    uint64_t mapBytes = 0;  // the maps' blobs
    uint64_t exrBytes = 0;  // the directory's map EXRs
    uint64_t pngBytes = 0;  // the directory's map PNGs (8-bit, every level)
    uint64_t rawBytes = 0;  // the 8-bit copies uncompressed
    int maxError = 0;       // the largest |decoded - original| over every byte
};

// (view, group, map name).
using MapKey = std::tuple<int, int, std::string>;

struct PemPack {
    PemManifest manifest;                                 // dir: the folder the pack lies in
    std::map<MapKey, std::vector<raster::Texture>> maps;  // a map's textures (MapSet::map)
    std::map<std::string, std::string> files;             // relative path -> bytes
    std::string codec;
    int maxError = 0;
};

// True when `path` is a regular file that starts like a pack.
bool IsPemPack(const std::string& path);

PackStats PackPem(const std::string& pemDir, const std::string& packFile, const PackOptions& opt);
PemPack ReadPemPack(const std::string& packFile);

// A PEM directory at outDir (which must not exist yet; it appears whole or not at all).
void UnpackPem(const std::string& packFile, const std::string& outDir, int threads);

}  // namespace pem::pipeline
