// SPDX-License-Identifier: MIT
// map_coding.cpp — predictive coding of 8-bit environment maps (map_coding.h).
#include "pipeline/map_coding.h"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#include "base/j2k_codec.h"

namespace pem::pipeline {
namespace {

enum Base : uint8_t { kZero = 0, kPrevious = 1, kDecimated = 2, kBases = 3 };

using Level = std::vector<uint8_t>;

// The next coarser level (level + 1) of a box-filtered chain: 2×2 means (2×1 or 1×2 where one
// size stays at 1), rounded; a 1×1 face stays.
Level Decimate(const Level& fine, const MapShape& shape, int level) {
    const int w = shape.LevelWidth(level), h = shape.LevelHeight(level);
    if (w == 1 && h == 1) return fine;
    const int mw = shape.LevelWidth(level + 1), mh = shape.LevelHeight(level + 1);
    const int sx = w / mw, sy = h / mh, count = sx * sy;
    Level out(static_cast<size_t>(shape.faces) * static_cast<size_t>(mw) * mh * 4);
    for (int f = 0; f < shape.faces; ++f)
        for (int j = 0; j < mh; ++j)
            for (int i = 0; i < mw; ++i)
                for (int c = 0; c < 4; ++c) {
                    int sum = 0;
                    for (int dj = 0; dj < sy; ++dj)
                        for (int di = 0; di < sx; ++di)
                            sum += fine[((static_cast<size_t>(f) * h + sy * j + dj) * w + sx * i +
                                         di) *
                                            4 +
                                        c];
                    out[((static_cast<size_t>(f) * mh + j) * mw + i) * 4 + c] =
                        static_cast<uint8_t>((sum + count / 2) / count);
                }
    return out;
}

// A map's textures as one level list (every face of each level, texture after texture), and
// back.
std::vector<Level> Stacked(std::span<const raster::Texture> map) {
    std::vector<Level> levels(map.empty() ? 0 : map[0].levels.size());
    for (size_t l = 0; l < levels.size(); ++l)
        for (const raster::Texture& t : map)
            levels[l].insert(levels[l].end(), t.levels[l].begin(), t.levels[l].end());
    return levels;
}

std::vector<raster::Texture> Unstacked(std::vector<Level> levels, const MapShape& shape) {
    const size_t textures = shape.kind == raster::TextureKind::Cube ? 1 : size_t(shape.faces);
    std::vector<raster::Texture> out(textures);
    for (size_t k = 0; k < textures; ++k) {
        out[k].kind = shape.kind;
        out[k].width = shape.width;
        out[k].height = shape.height;
        for (Level& level : levels) {
            const size_t n = level.size() / textures;
            out[k].levels.emplace_back(level.begin() + static_cast<std::ptrdiff_t>(k * n),
                                       level.begin() + static_cast<std::ptrdiff_t>((k + 1) * n));
        }
    }
    return out;
}

// LOCO-I's median edge detector of the left (a), upper (b) and upper-left (c) values.
int Med(int a, int b, int c) {
    if (c >= std::max(a, b)) return std::min(a, b);
    if (c <= std::min(a, b)) return std::max(a, b);
    return a + b - c;
}

uint8_t Zigzag(int k) {  // k in [-128, 127]
    return static_cast<uint8_t>(k >= 0 ? 2 * k : -2 * k - 1);
}
int Unzigzag(uint8_t z) {
    return (z & 1) ? -static_cast<int>((z + 1) >> 1) : z >> 1;
}

// One channel of one level, texel by texel in stream order: `value(index, prediction)` returns
// the decoded byte of the texel at `index` given its prediction (and codes it).
// The level's faces and texels: faces of w × h.
struct LevelSize {
    int faces, w, h;
};

template <class Step>
void CodeChannel(Level& recon, const Level* base, LevelSize size, int c, bool spatial,
                 const Step& value) {
    auto residual = [&](size_t idx) {
        return static_cast<int>(recon[idx]) - (base ? static_cast<int>((*base)[idx]) : 0);
    };
    const int w = size.w, h = size.h;
    for (int f = 0; f < size.faces; ++f)
        for (int j = 0; j < h; ++j)
            for (int i = 0; i < w; ++i) {
                const size_t idx = ((static_cast<size_t>(f) * h + j) * w + i) * 4 + c;
                int pred = base ? (*base)[idx] : 0;
                if (spatial && (i > 0 || j > 0)) {
                    const size_t left = idx - 4, up = idx - 4 * static_cast<size_t>(w);
                    if (j == 0)
                        pred += residual(left);
                    else if (i == 0)
                        pred += residual(up);
                    else
                        pred += Med(residual(left), residual(up), residual(up - 4));
                }
                recon[idx] = value(idx, std::clamp(pred, 0, 255));
            }
}

// The quantizer: residual index of x against pred, and the value it decodes to.
struct Quantizer {
    int maxError;
    int Index(int x, int pred) const {
        const int r = x - pred;
        if (maxError == 0) return static_cast<int8_t>(static_cast<uint8_t>(r));  // modulo 256
        const int q = 2 * maxError + 1;
        return r >= 0 ? (r + maxError) / q : -((-r + maxError) / q);
    }
    uint8_t Value(int k, int pred) const {
        if (maxError == 0) return static_cast<uint8_t>(pred + k);
        return static_cast<uint8_t>(std::clamp(pred + k * (2 * maxError + 1), 0, 255));
    }
};

// The bases available at a level, index by Base (null: not available).
struct Bases {
    const Level* of[kBases] = {nullptr, nullptr, nullptr};
};

Bases BasesAt(int level, const std::vector<Level>* previous, const Level* decimated) {
    Bases b;
    if (previous) b.of[kPrevious] = &(*previous)[static_cast<size_t>(level)];
    if (level > 0) b.of[kDecimated] = decimated;
    return b;
}

// Open-loop cost of a predictor on the original bytes: the sum of |residual|.
long Cost(const Level& original, const Level* base, LevelSize size, int c, bool spatial) {
    Level scratch = original;
    long cost = 0;
    CodeChannel(scratch, base, size, c, spatial, [&](size_t idx, int pred) {
        cost += std::abs(static_cast<int>(original[idx]) - pred);
        return original[idx];
    });
    return cost;
}

// The previous sample's map as levels, when it has the map's shape and levels (else empty).
std::vector<Level> UsablePrevious(std::span<const raster::Texture> previous, const MapShape& shape,
                                  int levels) {
    if (previous.empty() ||
        previous.size() !=
            (shape.kind == raster::TextureKind::Cube ? 1 : static_cast<size_t>(shape.faces)))
        return {};
    for (const raster::Texture& t : previous)
        if (t.kind != shape.kind || t.width != shape.width || t.height != shape.height ||
            t.NumLevels() != levels)
            return {};
    return Stacked(previous);
}

LevelSize SizeAt(const MapShape& shape, int level) {
    return {shape.faces, shape.LevelWidth(level), shape.LevelHeight(level)};
}

// A level the transform codec takes: faces at least kMinTransformSize wide and tall.
bool Transformed(const MapShape& shape, int level, double ratio) {
    return ratio > 0.0 && shape.LevelWidth(level) >= kMinTransformSize &&
           shape.LevelHeight(level) >= kMinTransformSize;
}

}  // namespace

size_t MapShape::LevelBytes(int level) const {
    return static_cast<size_t>(faces) * static_cast<size_t>(LevelWidth(level)) *
           static_cast<size_t>(LevelHeight(level)) * 4;
}

int MapShape::ChainLevels() const {
    int levels = 1;
    for (int m = std::max(width, height); m > 1; m >>= 1) ++levels;
    return levels;
}

MapShape ShapeOf(std::span<const raster::Texture> map) {
    if (map.empty()) throw std::invalid_argument("ShapeOf: a map has a texture");
    const raster::Texture& t = map[0];
    if (t.kind == raster::TextureKind::Cube && map.size() != 1)
        throw std::invalid_argument("ShapeOf: a cube map is one texture");
    for (const raster::Texture& o : map)
        if (o.kind != t.kind || o.width != t.width || o.height != t.height ||
            o.NumLevels() != t.NumLevels())
            throw std::invalid_argument("ShapeOf: a map's textures differ in shape");
    return {t.kind, t.kind == raster::TextureKind::Cube ? 6 : static_cast<int>(map.size()), t.width,
            t.height};
}

size_t ResidualBytes(const MapShape& shape, int levels) {
    size_t total = 0;
    for (int l = 0; l < levels; ++l) total += shape.LevelBytes(l);
    return total;
}

size_t PredictedBytes(const MapShape& shape, const std::vector<std::vector<uint8_t>>& transformed) {
    size_t total = 0;
    for (size_t l = 0; l < transformed.size(); ++l)
        if (transformed[l].empty()) total += shape.LevelBytes(static_cast<int>(l));
    return total;
}

MapCode EncodeMap(std::span<const raster::Texture> map, std::span<const raster::Texture> previous,
                  const MapCodeOptions& options) {
    const MapShape shape = ShapeOf(map);
    const int maxError = options.maxError;
    const double ratio = options.ratio;
    const int levels = map[0].NumLevels();
    const std::vector<Level> original = Stacked(map);
    const std::vector<Level> prev = UsablePrevious(previous, shape, levels);
    const std::vector<Level>* before = prev.empty() ? nullptr : &prev;
    const Quantizer quant{maxError};
    MapCode code;
    code.residuals.reserve(ResidualBytes(shape, levels));
    Level decimated;
    for (int l = 0; l < levels; ++l) {
        const LevelSize size = SizeAt(shape, l);
        const Level& level = original[static_cast<size_t>(l)];
        if (l > 0) decimated = Decimate(decimated, shape, l - 1);
        const Bases bases = BasesAt(l, before, &decimated);
        Level recon(level.size());
        code.transformed.emplace_back();
        if (Transformed(shape, l, ratio)) {
            // The level by the transform codec (the finest level's decoded bytes: the base of
            // the decimated predictor below).
            const double levelRatio = l == 0 || ratio <= 1.0 ? ratio : 2.0 * ratio;
            code.transformed.back() = base::EncodeJ2k({size.w, size.faces * size.h, 4, level},
                                                      levelRatio, options.wavelet);
            recon = base::DecodeJ2k(code.transformed.back(), size.w, size.faces * size.h, 4).data;
            code.predictors.insert(code.predictors.end(), 4, 0);
            if (l == 0) decimated = recon;
            continue;
        }
        for (int c = 0; c < 4; ++c) {
            // Step 1: the predictor with the smallest open-loop residuals.
            int best = 0;
            long bestCost = -1;
            for (int p = 0; p < 2 * kBases; ++p) {
                if (p / 2 != kZero && !bases.of[p / 2]) continue;
                const long cost = Cost(level, bases.of[p / 2], size, c, p % 2 == 1);
                if (bestCost < 0 || cost < bestCost) best = p, bestCost = cost;
            }
            code.predictors.push_back(static_cast<uint8_t>(best));
            // Step 2: code the channel against the decoded values.
            CodeChannel(recon, bases.of[best / 2], size, c, best % 2 == 1,
                        [&](size_t idx, int pred) {
                            const int k = quant.Index(level[idx], pred);
                            code.residuals.push_back(Zigzag(k));
                            return quant.Value(k, pred);
                        });
        }
        if (l == 0) decimated = recon;
    }
    return code;
}

std::vector<raster::Texture> DecodeMap(const MapCode& code, const MapShape& shape, int levels,
                                       std::span<const raster::Texture> previous, int maxError) {
    const bool cube = shape.kind == raster::TextureKind::Cube;
    if (shape.width < 1 || shape.height < 1 ||
        (cube && (shape.faces != 6 || shape.height != shape.width)) ||
        (!cube && (shape.faces < 1 || shape.faces > 2)) || levels < 1 ||
        levels > shape.ChainLevels() || code.predictors.size() != 4 * static_cast<size_t>(levels) ||
        code.transformed.size() != static_cast<size_t>(levels) ||
        code.residuals.size() != PredictedBytes(shape, code.transformed))
        throw std::runtime_error("the map's code does not fit its size");
    const std::vector<Level> prev = UsablePrevious(previous, shape, levels);
    const std::vector<Level>* before = prev.empty() ? nullptr : &prev;
    const Quantizer quant{maxError};
    std::vector<Level> out;
    size_t next = 0;
    Level decimated;
    for (int l = 0; l < levels; ++l) {
        const LevelSize size = SizeAt(shape, l);
        if (l > 0) decimated = Decimate(decimated, shape, l - 1);
        const Bases bases = BasesAt(l, before, &decimated);
        Level recon(shape.LevelBytes(l));
        if (!code.transformed[static_cast<size_t>(l)].empty()) {
            recon = base::DecodeJ2k(code.transformed[static_cast<size_t>(l)], size.w,
                                    size.faces * size.h, 4)
                        .data;
            if (recon.size() != shape.LevelBytes(l))
                throw std::runtime_error("a transformed level of the map has another size");
            if (l == 0) decimated = recon;
            out.push_back(std::move(recon));
            continue;
        }
        for (int c = 0; c < 4; ++c) {
            const int p = code.predictors[4 * static_cast<size_t>(l) + static_cast<size_t>(c)];
            if (p >= 2 * kBases || (p / 2 != kZero && !bases.of[p / 2]))
                throw std::runtime_error("the map names a predictor it cannot have");
            CodeChannel(recon, bases.of[p / 2], size, c, p % 2 == 1, [&](size_t, int pred) {
                return quant.Value(Unzigzag(code.residuals[next++]), pred);
            });
        }
        if (l == 0) decimated = recon;
        out.push_back(std::move(recon));
    }
    return Unstacked(std::move(out), shape);
}

}  // namespace pem::pipeline
