// SPDX-License-Identifier: MIT
// problem.cpp — assembling the stacked system from raster's rendering matrix (problem.h).
#include "infer/problem.h"

#include <cmath>
#include <stdexcept>

#include "raster/texel_index.h"

namespace pem::infer {
namespace {

struct ImageBlock {
    CsrMatrix a;        // kept rows, local columns
    Vector rhs;         // b - offset - known taps
    Vector sqrtWeight;  // sqrt(w) per kept row
    std::vector<int64_t> rowOf;
    double weightSum = 0.0;
};

// Keep whole pixels (4 rows, so row % 4 stays the channel) that have a row with confidence > 0
// and a tap on the unknown texture; fold the other textures' taps (known texels) into the
// right-hand side.
ImageBlock SelectImageRows(const raster::RenderingMatrix& a, const Vector& known,
                           const CubeLayout& layout, uint32_t firstTexel, const Target& target) {
    const uint64_t colBegin = uint64_t{kChannels} * firstTexel;
    const uint64_t colEnd =
        colBegin + uint64_t{kChannels} * static_cast<uint64_t>(layout.TexelCount());
    auto weight = [&](int64_t r) {
        const double w =
            target.confidence.empty() ? 1.0 : target.confidence[static_cast<size_t>(r)];
        return w > 0.0 ? w : 0.0;
    };
    auto unknownTaps = [&](int64_t r) {
        for (int64_t k = a.rowPtr[static_cast<size_t>(r)]; k < a.rowPtr[static_cast<size_t>(r) + 1];
             ++k)
            if (a.col[static_cast<size_t>(k)] >= colBegin && a.col[static_cast<size_t>(k)] < colEnd)
                return true;
        return false;
    };
    ImageBlock blk;
    blk.a.cols = static_cast<int64_t>(colEnd - colBegin);
    std::vector<uint32_t> cols;
    std::vector<double> vals;
    for (int64_t p = 0; p < a.rows / kChannels; ++p) {
        // Step 1: is the pixel in the mask?
        bool keep = false;
        for (int64_t r = kChannels * p; r < kChannels * (p + 1); ++r)
            keep |= weight(r) > 0.0 && unknownTaps(r);
        if (!keep) continue;
        // Step 2: its 4 rows, local columns, known taps folded into the constant.
        for (int64_t r = kChannels * p; r < kChannels * (p + 1); ++r) {
            cols.clear();
            vals.clear();
            double constant = a.offset[static_cast<size_t>(r)];
            for (int64_t k = a.rowPtr[static_cast<size_t>(r)];
                 k < a.rowPtr[static_cast<size_t>(r) + 1]; ++k) {
                const uint32_t c = a.col[static_cast<size_t>(k)];
                const double v = a.val[static_cast<size_t>(k)];
                if (c >= colBegin && c < colEnd) {
                    cols.push_back(static_cast<uint32_t>(c - colBegin));
                    vals.push_back(v);
                } else {
                    constant += v * known[c];
                }
            }
            blk.a.AddRow(cols, vals);
            blk.rhs.push_back(target.b[static_cast<size_t>(r)] - constant);
            blk.sqrtWeight.push_back(std::sqrt(weight(r)));
            blk.rowOf.push_back(r);
            blk.weightSum += weight(r);
        }
    }
    return blk;
}

// Confidence-weighted mean of the target per channel over the kept rows.
Channels TargetMean(const ImageBlock& blk) {
    Channels sum{}, weight{};
    for (size_t r = 0; r < blk.rhs.size(); ++r) {
        const size_t c = r % kChannels;
        const double w = blk.sqrtWeight[r] * blk.sqrtWeight[r];
        sum[c] += w * blk.rhs[r];
        weight[c] += w;
    }
    for (int c = 0; c < kChannels; ++c)
        sum[static_cast<size_t>(c)] =
            weight[static_cast<size_t>(c)] > 0.0
                ? sum[static_cast<size_t>(c)] / weight[static_cast<size_t>(c)]
                : 0.0;
    return sum;
}

}  // namespace

LinearSystem BuildSystem(const raster::RenderingMatrix& a, const raster::Frame& frame, int texture,
                         const Target& target, const RegularizerWeights& weights) {
    // Check the inputs: a cube map, one target value (and confidence) per row of A.
    const raster::Texture& tex = frame.textures.at(static_cast<size_t>(texture));
    if (tex.kind != raster::TextureKind::Cube)
        throw std::invalid_argument("BuildSystem: the unknown texture must be a cube map");
    if (static_cast<int64_t>(target.b.size()) != a.rows ||
        (!target.confidence.empty() && static_cast<int64_t>(target.confidence.size()) != a.rows))
        throw std::invalid_argument("BuildSystem: target size differs from the matrix rows");
    if (a.rows % kChannels != 0) throw std::invalid_argument("BuildSystem: rows not RGBA");

    // Image block: kept rows, local columns, weighted by sqrt(confidence).
    LinearSystem sys;
    sys.layout.size = tex.width;
    sys.layout.levels = tex.NumLevels();
    sys.globalFirstTexel = raster::TexelIndexer(frame.textures).LevelBase(texture, 0);
    ImageBlock img =
        SelectImageRows(a, TexelVector(frame), sys.layout, sys.globalFirstTexel, target);
    if (!IsChannelDiagonal(img.a))
        throw std::invalid_argument("BuildSystem: taps mix colour channels");
    sys.imageRowOf = img.rowOf;
    sys.imageWeightSum = img.weightSum;
    sys.priorValue = weights.priorValue ? *weights.priorValue : TargetMean(img);

    // Regularizer blocks (omitted when their weight is 0).
    const int64_t cols = img.a.cols;
    const CsrMatrix smooth = weights.smooth > 0 ? SmoothnessRows(sys.layout, cols) : CsrMatrix{};
    const CsrMatrix pyramid = weights.pyramid > 0 ? PyramidRows(sys.layout, cols) : CsrMatrix{};
    const CsrMatrix prior = weights.prior > 0 ? PriorRows(sys.layout, cols) : CsrMatrix{};
    std::vector<RowBlock> blocks{{&img.a, 1.0, &img.sqrtWeight}};
    if (weights.smooth > 0) blocks.push_back({&smooth, std::sqrt(weights.smooth), nullptr});
    if (weights.pyramid > 0) blocks.push_back({&pyramid, std::sqrt(weights.pyramid), nullptr});
    if (weights.prior > 0) blocks.push_back({&prior, std::sqrt(weights.prior), nullptr});
    CsrMatrix k = StackRows(blocks);

    // Right-hand side in the same row order.
    sys.imageRows = img.a.rows;
    sys.h.assign(static_cast<size_t>(k.rows), 0.0);
    for (int64_t r = 0; r < img.a.rows; ++r)
        sys.h[static_cast<size_t>(r)] =
            img.sqrtWeight[static_cast<size_t>(r)] * img.rhs[static_cast<size_t>(r)];
    if (weights.prior > 0) {
        const int64_t first = k.rows - prior.rows;
        for (int64_t r = 0; r < prior.rows; ++r)
            sys.h[static_cast<size_t>(first + r)] =
                std::sqrt(weights.prior) * sys.priorValue[static_cast<size_t>(r % kChannels)];
    }
    sys.k = SparseOperator(std::move(k));
    return sys;
}

Vector InitialGuess(const LinearSystem& system) {
    Vector x(static_cast<size_t>(system.Cols()));
    for (size_t j = 0; j < x.size(); ++j) x[j] = system.priorValue[j % kChannels];
    return x;
}

Vector TexelVector(const raster::Frame& frame) {
    Vector x;
    for (const raster::Texture& t : frame.textures)
        for (const auto& level : t.levels)
            for (uint8_t b : level) x.push_back(b / 255.0);
    return x;
}

Vector ExpandSolution(const LinearSystem& system, const raster::Frame& frame, const Vector& x) {
    Vector full = TexelVector(frame);
    const size_t base = size_t{kChannels} * system.globalFirstTexel;
    for (size_t j = 0; j < x.size(); ++j) full[base + j] = x[j];
    return full;
}

Vector ApplyRendering(const raster::RenderingMatrix& a, const Vector& xFull, int threads) {
    CsrMatrix m = CsrFromRendering(a);
    Vector y;
    Multiply(m, xFull, &y, threads);
    for (size_t r = 0; r < y.size(); ++r) y[r] += a.offset[r];
    return y;
}

double MaskedImageRmse(const LinearSystem& system, const Vector& x, int threads) {
    Vector kx;
    system.k.Apply(x, &kx, threads);
    double sum = 0.0;
    for (int64_t r = 0; r < system.imageRows; ++r) {
        const double d = kx[static_cast<size_t>(r)] - system.h[static_cast<size_t>(r)];
        sum += d * d;
    }
    return system.imageWeightSum > 0.0 ? std::sqrt(sum / system.imageWeightSum) : 0.0;
}

}  // namespace pem::infer
