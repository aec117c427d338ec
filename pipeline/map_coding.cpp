// SPDX-License-Identifier: MIT
// map_coding.cpp — predictive coding of 8-bit cube maps (map_coding.h).
#include "pipeline/map_coding.h"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#include "base/j2k_codec.h"

namespace pem::pipeline {
namespace {

enum Base : uint8_t { kZero = 0, kPrevious = 1, kDecimated = 2, kBases = 3 };

using Level = std::vector<uint8_t>;

size_t LevelBytes(int width, int level) {
    const size_t n = static_cast<size_t>(std::max(1, width >> level));
    return 6 * n * n * 4;
}

// The next coarser level of a box-filtered chain: 2×2 means, rounded (a 1×1 face stays).
Level Decimate(const Level& fine, int n) {
    if (n == 1) return fine;
    const int m = n / 2;
    Level out(6 * static_cast<size_t>(m) * m * 4);
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < m; ++j)
            for (int i = 0; i < m; ++i)
                for (int c = 0; c < 4; ++c) {
                    auto at = [&](int x, int y) {
                        return static_cast<int>(
                            fine[((static_cast<size_t>(f) * n + y) * n + x) * 4 + c]);
                    };
                    const int sum = at(2 * i, 2 * j) + at(2 * i + 1, 2 * j) + at(2 * i, 2 * j + 1) +
                                    at(2 * i + 1, 2 * j + 1);
                    out[((static_cast<size_t>(f) * m + j) * m + i) * 4 + c] =
                        static_cast<uint8_t>((sum + 2) >> 2);
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
template <class Step>
void CodeChannel(Level& recon, const Level* base, int n, int c, bool spatial, const Step& value) {
    auto residual = [&](size_t idx) {
        return static_cast<int>(recon[idx]) - (base ? static_cast<int>((*base)[idx]) : 0);
    };
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const size_t idx = ((static_cast<size_t>(f) * n + j) * n + i) * 4 + c;
                int pred = base ? (*base)[idx] : 0;
                if (spatial && (i > 0 || j > 0)) {
                    const size_t left = idx - 4, up = idx - 4 * static_cast<size_t>(n);
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

Bases BasesAt(int level, const raster::Texture* previous, const Level* decimated) {
    Bases b;
    if (previous) b.of[kPrevious] = &previous->levels[static_cast<size_t>(level)];
    if (level > 0) b.of[kDecimated] = decimated;
    return b;
}

// Open-loop cost of a predictor on the original bytes: the sum of |residual|.
long Cost(const Level& original, const Level* base, int n, int c, bool spatial) {
    Level scratch = original;
    long cost = 0;
    CodeChannel(scratch, base, n, c, spatial, [&](size_t idx, int pred) {
        cost += std::abs(static_cast<int>(original[idx]) - pred);
        return original[idx];
    });
    return cost;
}

bool UsablePrevious(const raster::Texture* previous, int width, int levels) {
    return previous && previous->kind == raster::TextureKind::Cube && previous->width == width &&
           previous->NumLevels() == levels;
}

}  // namespace

size_t ResidualBytes(int width, int levels) {
    size_t total = 0;
    for (int l = 0; l < levels; ++l) total += LevelBytes(width, l);
    return total;
}

size_t PredictedBytes(int width, const std::vector<std::vector<uint8_t>>& transformed) {
    size_t total = 0;
    for (size_t l = 0; l < transformed.size(); ++l)
        if (transformed[l].empty()) total += LevelBytes(width, static_cast<int>(l));
    return total;
}

MapCode EncodeMap(const raster::Texture& texture, const raster::Texture* previous,
                  const MapCodeOptions& options) {
    const int maxError = options.maxError;
    const double ratio = options.ratio;
    const int levels = texture.NumLevels();
    if (!UsablePrevious(previous, texture.width, levels)) previous = nullptr;
    const Quantizer quant{maxError};
    MapCode code;
    code.residuals.reserve(ResidualBytes(texture.width, levels));
    Level decimated;
    for (int l = 0; l < levels; ++l) {
        const int n = texture.LevelWidth(l);
        const Level& original = texture.levels[static_cast<size_t>(l)];
        if (l > 0) decimated = Decimate(decimated, texture.LevelWidth(l - 1));
        const Bases bases = BasesAt(l, previous, &decimated);
        Level recon(original.size());
        code.transformed.emplace_back();
        if (ratio > 0.0 && n >= kMinTransformSize) {
            // The level by the transform codec (the finest level's decoded bytes: the base of
            // the decimated predictor below).
            const double levelRatio = l == 0 || ratio <= 1.0 ? ratio : 2.0 * ratio;
            code.transformed.back() =
                base::EncodeJ2k({n, 6 * n, 4, original}, levelRatio, options.wavelet);
            recon = base::DecodeJ2k(code.transformed.back(), n, 6 * n, 4).data;
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
                const long cost = Cost(original, bases.of[p / 2], n, c, p % 2 == 1);
                if (bestCost < 0 || cost < bestCost) best = p, bestCost = cost;
            }
            code.predictors.push_back(static_cast<uint8_t>(best));
            // Step 2: code the channel against the decoded values.
            CodeChannel(recon, bases.of[best / 2], n, c, best % 2 == 1, [&](size_t idx, int pred) {
                const int k = quant.Index(original[idx], pred);
                code.residuals.push_back(Zigzag(k));
                return quant.Value(k, pred);
            });
        }
        if (l == 0) decimated = recon;
    }
    return code;
}

raster::Texture DecodeMap(const MapCode& code, int width, int levels,
                          const raster::Texture* previous, int maxError) {
    int chain = 1;  // the levels of a full MIP chain of this width
    while ((width >> chain) > 0) ++chain;
    if (width < 1 || levels < 1 || levels > chain ||
        code.predictors.size() != 4 * static_cast<size_t>(levels) ||
        code.transformed.size() != static_cast<size_t>(levels) ||
        code.residuals.size() != PredictedBytes(width, code.transformed))
        throw std::runtime_error("the map's code does not fit its size");
    if (!UsablePrevious(previous, width, levels)) previous = nullptr;
    const Quantizer quant{maxError};
    raster::Texture tex;
    tex.kind = raster::TextureKind::Cube;
    tex.width = tex.height = width;
    size_t next = 0;
    Level decimated;
    for (int l = 0; l < levels; ++l) {
        const int n = tex.LevelWidth(l);
        if (l > 0) decimated = Decimate(decimated, tex.LevelWidth(l - 1));
        const Bases bases = BasesAt(l, previous, &decimated);
        Level recon(LevelBytes(width, l));
        if (!code.transformed[static_cast<size_t>(l)].empty()) {
            recon = base::DecodeJ2k(code.transformed[static_cast<size_t>(l)], n, 6 * n, 4).data;
            if (recon.size() != LevelBytes(width, l))
                throw std::runtime_error("a transformed level of the map has another size");
            if (l == 0) decimated = recon;
            tex.levels.push_back(std::move(recon));
            continue;
        }
        for (int c = 0; c < 4; ++c) {
            const int p = code.predictors[4 * static_cast<size_t>(l) + static_cast<size_t>(c)];
            if (p >= 2 * kBases || (p / 2 != kZero && !bases.of[p / 2]))
                throw std::runtime_error("the map names a predictor it cannot have");
            CodeChannel(recon, bases.of[p / 2], n, c, p % 2 == 1, [&](size_t, int pred) {
                return quant.Value(Unzigzag(code.residuals[next++]), pred);
            });
        }
        if (l == 0) decimated = recon;
        tex.levels.push_back(std::move(recon));
    }
    return tex;
}

}  // namespace pem::pipeline
