// SPDX-License-Identifier: MIT
// pem_file.cpp — OpenEXR environment-map writer and reader (pem_file.h).
#include "infer/pem_file.h"

#include <ImfChannelList.h>
#include <ImfEnvmap.h>
#include <ImfEnvmapAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIntAttribute.h>
#include <ImfStandardAttributes.h>
#include <ImfThreading.h>
#include <ImfTiledInputFile.h>
#include <ImfTiledOutputFile.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "base/atomic_file.h"
#include "base/exr_header.h"
#include "raster/cube_lookup.h"

namespace pem::infer {
namespace {

constexpr const char* kLevelsAttribute = "pemrefLevels";
constexpr const char* kChartsAttribute = "pemrefCharts";
constexpr const char* kChannelNames[kChannels] = {"R", "G", "B", "A"};
constexpr int kTileSize = 32;

// The direction of face coordinates (s, t) (raster::FaceDirection, GL 4.6 table 8.19).
Imath::V3f GlDirection(int face, double s, double t) {
    const raster::Vec3f d = raster::FaceDirection(face, static_cast<float>(2.0 * s - 1.0),
                                                  static_cast<float>(2.0 * t - 1.0));
    return {d[0], d[1], d[2]};
}

// One of the 8 symmetries of the square: (i, j) -> (x, y) inside an n x n face.
struct FaceTransform {
    bool transpose = false, flipX = false, flipY = false;
    ExrPixel Apply(int i, int j, int n) const {
        int x = transpose ? j : i, y = transpose ? i : j;
        if (flipX) x = n - 1 - x;
        if (flipY) y = n - 1 - y;
        return {x, y};
    }
};

// Derive each face's transform from OpenEXR's own helpers on an 8 x 48 probe level.
std::array<FaceTransform, 6> DeriveFaceTransforms() {
    constexpr int n = 8;
    const Imath::Box2i dw(Imath::V2i(0, 0), Imath::V2i(n - 1, 6 * n - 1));
    std::array<FaceTransform, 6> out;
    for (int f = 0; f < 6; ++f) {
        bool found = false;
        for (int k = 0; k < 8 && !found; ++k) {
            const FaceTransform tr{(k & 1) != 0, (k & 2) != 0, (k & 4) != 0};
            bool ok = true;
            for (int j = 0; j < n && ok; ++j)
                for (int i = 0; i < n && ok; ++i) {
                    Imf::CubeMapFace face;
                    Imath::V2f pif;
                    Imf::CubeMap::faceAndPixelPosition(GlDirection(f, (i + 0.5) / n, (j + 0.5) / n),
                                                       dw, face, pif);
                    const Imath::V2f pos = Imf::CubeMap::pixelPosition(face, dw, pif);
                    const Imath::Box2i fw = Imf::CubeMap::dataWindowForFace(face, dw);
                    const ExrPixel p = tr.Apply(i, j, n);
                    ok = static_cast<int>(face) == f &&
                         static_cast<int>(std::lround(pos.x)) == fw.min.x + p.x &&
                         static_cast<int>(std::lround(pos.y)) == fw.min.y + p.y;
                }
            if (ok) {
                out[static_cast<size_t>(f)] = tr;
                found = true;
            }
        }
        if (!found)
            throw std::logic_error("pem_file: no face transform matches OpenEXR's cube layout");
    }
    return out;
}

const std::array<FaceTransform, 6>& FaceTransforms() {
    static const std::array<FaceTransform, 6> transforms = DeriveFaceTransforms();
    return transforms;
}

// The mean RGBA of the coarsest level (the fill of levels the map does not have).
std::array<float, kChannels> CoarsestMean(const EnvMapF& map) {
    const std::vector<float>& level = map.levels.back();
    std::array<double, kChannels> sum{};
    for (size_t k = 0; k < level.size(); ++k) sum[k % kChannels] += static_cast<double>(level[k]);
    std::array<float, kChannels> mean{};
    const double count = static_cast<double>(level.size() / kChannels);
    for (size_t c = 0; c < kChannels; ++c) mean[c] = static_cast<float>(sum[c] / count);
    return mean;
}

// A 2D level's charts between face-major order (chart after chart) and one image of them side by
// side (chart c at columns [c w, (c + 1) w)), toward the image when `toImage`.
std::vector<float> RearrangeCharts(const std::vector<float>& from, int charts, int w, int h,
                                   bool toImage) {
    std::vector<float> to(from.size());
    const size_t row = static_cast<size_t>(w) * kChannels;
    for (size_t c = 0; c < static_cast<size_t>(charts); ++c)
        for (size_t j = 0; j < static_cast<size_t>(h); ++j) {
            const size_t faceRow = (c * h + j) * row, imageRow = (j * charts + c) * row;
            std::copy_n(from.begin() + static_cast<std::ptrdiff_t>(toImage ? faceRow : imageRow),
                        row,
                        to.begin() + static_cast<std::ptrdiff_t>(toImage ? imageRow : faceRow));
        }
    return to;
}

// The interleaved RGBA image of EXR level l (w x h).
std::vector<float> LevelImage(const EnvMapF& map, int l, int w, int h,
                              const std::array<float, kChannels>& fill) {
    std::vector<float> px(static_cast<size_t>(w) * static_cast<size_t>(h) * kChannels);
    if (l >= map.NumLevels()) {
        for (size_t k = 0; k < px.size(); ++k) px[k] = fill[k % kChannels];
        return px;
    }
    const std::vector<float>& level = map.levels[static_cast<size_t>(l)];
    if (!map.IsCube() && map.charts == 1) return level;  // the EXR level, rows top-down
    if (!map.IsCube()) return RearrangeCharts(level, map.charts, map.LevelSize(l), h, true);
    const int n = map.LevelSize(l);
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const ExrPixel p = ExrPixelOf(f, i, j, n);
                const size_t src = static_cast<size_t>(((f * n + j) * n + i) * kChannels);
                const size_t dst =
                    (static_cast<size_t>(p.y) * static_cast<size_t>(w) + static_cast<size_t>(p.x)) *
                    kChannels;
                for (size_t c = 0; c < kChannels; ++c) px[dst + c] = level[src + c];
            }
    return px;
}

// Slices of an interleaved RGBA buffer whose first pixel is the data window's minimum.
Imf::FrameBuffer RgbaFrameBuffer(std::vector<float>* px, const Imath::Box2i& dw) {
    const size_t w = static_cast<size_t>(dw.max.x - dw.min.x + 1);
    const size_t xStride = kChannels * sizeof(float), yStride = xStride * w;
    // The data window's origin at the buffer's start (Slice::Make: no pointer arithmetic
    // outside the buffer, whatever origin a file claims).
    Imf::FrameBuffer fb;
    for (size_t c = 0; c < kChannels; ++c)
        fb.insert(kChannelNames[c], Imf::Slice::Make(Imf::FLOAT, px->data() + c, dw, xStride,
                                                     yStride, 1, 1, c == 3 ? 1.0 : 0.0));
    return fb;
}

bool IsPowerOfTwo(int n) {
    return n > 0 && (n & (n - 1)) == 0;
}

// Levels of the MIP chain of a w x h texture (GL's and OpenEXR's ROUND_DOWN chain).
int ChainLevels(int w, int h) {
    int levels = 1;
    for (int m = std::max(w, h); m > 1; m >>= 1) ++levels;
    return levels;
}

void CheckWritable(const EnvMapF& map) {
    if (!IsPowerOfTwo(map.size) || !IsPowerOfTwo(map.LevelHeight(0)) || map.levels.empty())
        throw std::invalid_argument(
            "WriteEnvMapExr: width and height must be powers of two with >= 1 level");
    const int chain =
        map.IsCube() ? ChainLevels(map.size, map.size) : ChainLevels(map.size, map.LevelHeight(0));
    if (!map.IsCube() &&
        (map.charts < 1 || map.charts > 2 || (map.charts > 1 && map.LevelHeight(0) > map.size)))
        throw std::invalid_argument(
            "WriteEnvMapExr: a 2D map has 1 or 2 charts, no taller than wide");
    if (map.NumLevels() > chain)
        throw std::invalid_argument("WriteEnvMapExr: more levels than the MIP chain has");
    for (int l = 0; l < map.NumLevels(); ++l)
        if (map.levels[static_cast<size_t>(l)].size() != map.LevelTexels(l) * kChannels)
            throw std::invalid_argument("WriteEnvMapExr: level sizes differ from the MIP chain");
}

void WriteExr(const EnvMapF& map, const std::string& path, int threads) {
    // Header: N x 6N (a cube envmap) or (charts W) x H, float RGBA, tiled with every ROUND_DOWN
    // MIP level.
    Imf::Header header(map.IsCube() ? map.size : map.charts * map.size,
                       map.IsCube() ? 6 * map.size : map.LevelHeight(0));
    for (const char* name : kChannelNames) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    header.setTileDescription(
        Imf::TileDescription(kTileSize, kTileSize, Imf::MIPMAP_LEVELS, Imf::ROUND_DOWN));
    header.compression() = Imf::ZIP_COMPRESSION;
    header.zipCompressionLevel() = 1;
    if (map.IsCube()) Imf::addEnvmap(header, Imf::ENVMAP_CUBE);
    header.insert(kLevelsAttribute, Imf::IntAttribute(map.NumLevels()));
    if (!map.IsCube() && map.charts > 1)
        header.insert(kChartsAttribute, Imf::IntAttribute(map.charts));
    if (threads > 1 && Imf::globalThreadCount() < threads) Imf::setGlobalThreadCount(threads);
    Imf::TiledOutputFile out(path.c_str(), header, threads > 1 ? threads : 0);
    // Every level, the degenerate tail included.
    const std::array<float, kChannels> fill = CoarsestMean(map);
    for (int l = 0; l < out.numLevels(); ++l) {
        const Imath::Box2i dw = out.dataWindowForLevel(l);
        std::vector<float> px =
            LevelImage(map, l, dw.max.x - dw.min.x + 1, dw.max.y - dw.min.y + 1, fill);
        out.setFrameBuffer(RgbaFrameBuffer(&px, dw));
        out.writeTiles(0, out.numXTiles(l) - 1, 0, out.numYTiles(l) - 1, l);
    }
}

// One level of an open file as interleaved RGBA (rows top-down) and its width.
std::vector<float> ReadLevelPixels(Imf::TiledInputFile& in, int l, int* width) {
    const Imath::Box2i ldw = in.dataWindowForLevel(l);
    *width = ldw.max.x - ldw.min.x + 1;
    std::vector<float> px(static_cast<size_t>(*width) *
                          static_cast<size_t>(ldw.max.y - ldw.min.y + 1) * kChannels);
    in.setFrameBuffer(RgbaFrameBuffer(&px, ldw));
    in.readTiles(0, in.numXTiles(l) - 1, 0, in.numYTiles(l) - 1, l);
    return px;
}

// Cube level l from its EXR level image (the face layout undone).
std::vector<float> CubeLevel(const std::vector<float>& px, int w, int ln) {
    std::vector<float> level(static_cast<size_t>(6 * ln * ln * kChannels));
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < ln; ++j)
            for (int i = 0; i < ln; ++i) {
                const ExrPixel p = ExrPixelOf(f, i, j, ln);
                const size_t src =
                    (static_cast<size_t>(p.y) * static_cast<size_t>(w) + static_cast<size_t>(p.x)) *
                    kChannels;
                const size_t dst = static_cast<size_t>(((f * ln + j) * ln + i) * kChannels);
                for (size_t c = 0; c < kChannels; ++c) level[dst + c] = px[src + c];
            }
    return level;
}

}  // namespace

int ExrLevelCount(int size) {
    int levels = 1;
    for (int h = 6 * size; h > 1; h >>= 1) ++levels;
    return levels;
}

ExrPixel ExrPixelOf(int face, int i, int j, int n) {
    const ExrPixel p = FaceTransforms()[static_cast<size_t>(face)].Apply(i, j, n);
    return {p.x, face * n + p.y};
}

void WriteEnvMapExr(const EnvMapF& map, const std::string& path, int threads) {
    CheckWritable(map);
    base::WriteAtomically(path, [&](const std::string& tmp) { WriteExr(map, tmp, threads); });
}

ExrLevelImage ReadExrLevel(const std::string& path, int level) {
    Imf::TiledInputFile in(path.c_str());
    if (level < 0 || level >= in.numLevels()) throw std::runtime_error(path + ": no such level");
    const Imath::Box2i dw = in.dataWindowForLevel(level);
    ExrLevelImage img;
    img.width = dw.max.x - dw.min.x + 1;
    img.height = dw.max.y - dw.min.y + 1;
    img.rgba.resize(static_cast<size_t>(img.width) * static_cast<size_t>(img.height) * kChannels);
    in.setFrameBuffer(RgbaFrameBuffer(&img.rgba, dw));
    in.readTiles(0, in.numXTiles(level) - 1, 0, in.numYTiles(level) - 1, level);
    return img;
}

EnvMapF ReadEnvMapExr(const std::string& path) {
    base::CheckExrHeader(path);
    Imf::TiledInputFile in(path.c_str());
    const Imf::Header& header = in.header();
    // Check: a mip-mapped cube map of N x 6N, or a 2D map of W x H, powers of two.
    const bool cube = Imf::hasEnvmap(header);
    if (cube && Imf::envmap(header) != Imf::ENVMAP_CUBE)
        throw std::runtime_error(path + ": an environment map, but not a cube");
    const Imath::Box2i dw = header.dataWindow();
    base::CheckExrSize(path, int64_t{dw.max.x} - dw.min.x + 1, int64_t{dw.max.y} - dw.min.y + 1);
    const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
    if (cube && (h != 6 * w || !IsPowerOfTwo(w)))
        throw std::runtime_error(path + ": data window is not N x 6N with N a power of two");
    if (!cube && (!IsPowerOfTwo(w) || !IsPowerOfTwo(h)))
        throw std::runtime_error(path + ": data window is not W x H with powers of two");
    if (in.levelMode() != Imf::MIPMAP_LEVELS) throw std::runtime_error(path + ": not mip-mapped");
    // A 2D map of two charts (textures) stores them side by side.
    int charts = 1;
    if (const auto* attr = header.findTypedAttribute<Imf::IntAttribute>(kChartsAttribute))
        charts = attr->value();
    if (charts != 1 && (cube || charts != 2 || w < 2 || h > w / 2))
        throw std::runtime_error(path + ": " + kChartsAttribute + " " + std::to_string(charts) +
                                 " (a 2D map has 1, or 2 charts no taller than wide)");
    const int cw = w / charts;                                   // a chart's width
    int levels = cube ? ChainLevels(w, w) : ChainLevels(cw, h);  // the texture's MIP chain
    if (const auto* attr = header.findTypedAttribute<Imf::IntAttribute>(kLevelsAttribute))
        levels = std::min(levels, attr->value());
    if (levels < 1 || levels > in.numLevels()) throw std::runtime_error(path + ": missing levels");
    // Read each level (a cube's with its face layout undone).
    EnvMapF map;
    map.kind = cube ? raster::TextureKind::Cube : raster::TextureKind::Tex2D;
    map.size = cw;
    map.height = cube ? w : h;
    map.charts = charts;
    for (int l = 0; l < levels; ++l) {
        int lw = 0;
        std::vector<float> px = ReadLevelPixels(in, l, &lw);
        map.levels.push_back(
            cube         ? CubeLevel(px, lw, map.LevelSize(l))
            : charts > 1 ? RearrangeCharts(px, charts, map.LevelSize(l), map.LevelHeight(l), false)
                         : std::move(px));
    }
    return map;
}

}  // namespace pem::infer
