// SPDX-License-Identifier: MIT
// problem.cpp — assembling the stacked system from raster's rendering matrix (problem.h).
#include "infer/problem.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "raster/texel_index.h"

namespace pem::infer {
namespace {

// A frame's texel bytes (TexelVector's order: textures, levels, bytes) read in place, / 255:
// the known texels a row taps, without a copy of the whole frame.
class KnownTexels {
  public:
    explicit KnownTexels(const raster::Frame& frame) {
        for (const raster::Texture& t : frame.textures)
            for (const auto& level : t.levels) {
                starts_.push_back(next_);
                data_.push_back(level.data());
                next_ += level.size();
            }
    }
    double operator[](uint64_t i) const {
        const size_t s = static_cast<size_t>(std::upper_bound(starts_.begin(), starts_.end(), i) -
                                             starts_.begin() - 1);
        return data_[s][i - starts_[s]] / 255.0;
    }

  private:
    std::vector<uint64_t> starts_;  // each level's first byte in the whole frame
    std::vector<const uint8_t*> data_;
    uint64_t next_ = 0;
};

struct ImageBlock {
    CsrMatrix a;        // kept rows, local columns
    Vector rhs;         // b - offset - known taps
    Vector sqrtWeight;  // sqrt(w) per kept row
    std::vector<int64_t> rowOf;
    double weightSum = 0.0;
};

// Keep whole pixels (4 rows, so row % 4 stays the channel) that have a row with confidence > 0
// and a tap on the unknown texture; fold the other textures' taps (known texels) into the
// right-hand side. The block takes over a's entry storage and compacts it in place (each kept
// entry moves to an index no later than its own), so the matrix is never held twice.
ImageBlock SelectImageRows(raster::RenderingMatrix&& a, const KnownTexels& known,
                           const TexelLayout& layout, uint32_t firstTexel, const Target& target) {
    const uint64_t colBegin = uint64_t{kChannels} * firstTexel;
    const uint64_t colEnd =
        colBegin + uint64_t{kChannels} * static_cast<uint64_t>(layout.TexelCount());
    auto weight = [&](int64_t r) {
        const double w =
            target.confidence.empty() ? 1.0 : target.confidence[static_cast<size_t>(r)];
        return w > 0.0 ? w : 0.0;
    };
    ImageBlock blk;
    blk.a.cols = static_cast<int64_t>(colEnd - colBegin);
    blk.a.col = std::move(a.col);
    blk.a.val = std::move(a.val);
    blk.a.rowPtr.reserve(a.rowPtr.size());  // at most every row
    std::vector<uint32_t>& col = blk.a.col;
    std::vector<double>& val = blk.a.val;
    auto unknownTaps = [&](int64_t r) {
        for (int64_t k = a.rowPtr[static_cast<size_t>(r)]; k < a.rowPtr[static_cast<size_t>(r) + 1];
             ++k)
            if (col[static_cast<size_t>(k)] >= colBegin && col[static_cast<size_t>(k)] < colEnd)
                return true;
        return false;
    };
    size_t at = 0;  // the next kept entry's index (never past the entry being read)
    for (int64_t p = 0; p < a.rows / kChannels; ++p) {
        // Step 1: is the pixel in the mask?
        bool keep = false;
        for (int64_t r = kChannels * p; r < kChannels * (p + 1); ++r)
            keep |= weight(r) > 0.0 && unknownTaps(r);
        if (!keep) continue;
        // Step 2: its 4 rows, local columns, known taps folded into the constant.
        for (int64_t r = kChannels * p; r < kChannels * (p + 1); ++r) {
            double constant = a.offset[static_cast<size_t>(r)];
            for (int64_t k = a.rowPtr[static_cast<size_t>(r)];
                 k < a.rowPtr[static_cast<size_t>(r) + 1]; ++k) {
                const uint32_t c = col[static_cast<size_t>(k)];
                const double v = val[static_cast<size_t>(k)];
                if (c >= colBegin && c < colEnd) {
                    const auto rel = static_cast<uint32_t>(c - colBegin);
                    col[at] = 4u * layout.LocalOfFrameOrder(rel / 4u) + rel % 4u;
                    val[at++] = v;
                } else {
                    constant += v * known[c];
                }
            }
            blk.a.rowPtr.push_back(static_cast<int64_t>(at));
            blk.rhs.push_back(target.b[static_cast<size_t>(r)] - constant);
            blk.sqrtWeight.push_back(std::sqrt(weight(r)));
            blk.rowOf.push_back(r);
            blk.weightSum += weight(r);
        }
    }
    blk.a.rows = static_cast<int64_t>(blk.rowOf.size());
    col.resize(at);
    val.resize(at);
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

// Texel -> (level, face, i, j) of a layout, level by level.
struct TexelCoord {
    int level = 0;
    FaceTexel t;
};

TexelCoord CoordOf(const TexelLayout& layout, uint32_t texel) {
    int level = 0;
    while (level + 1 < layout.levels && layout.LevelBase(level + 1) <= texel) ++level;
    return {level, layout.Locate(level, texel - layout.LevelBase(level))};
}

// The observed texels grown by `rings` rings of neighbours, as compact indices (-1: not active).
std::vector<int32_t> ActiveTexels(const CsrMatrix& image, const TexelLayout& layout, int rings,
                                  std::vector<uint32_t>* active) {
    const auto count = static_cast<size_t>(layout.TexelCount());
    std::vector<uint8_t> on(count, 0);
    for (uint32_t c : image.col) on[c / kChannels] = 1;
    for (int r = 0; r < rings; ++r) {
        std::vector<uint8_t> next = on;
        for (uint32_t t = 0; t < count; ++t) {
            if (!on[t]) continue;
            const TexelCoord tc = CoordOf(layout, t);
            for (Edge e : {Edge::Left, Edge::Right, Edge::Up, Edge::Down})
                next[layout.NeighbourTexel(tc.level, tc.t, e)] = 1;
        }
        on.swap(next);
    }
    std::vector<int32_t> index(count, -1);
    for (uint32_t t = 0; t < count; ++t)
        if (on[t]) {
            index[t] = static_cast<int32_t>(active->size());
            active->push_back(t);
        }
    return index;
}

// In place: the rows whose columns are all active, with compact columns (each kept entry moves to
// an index no later than its own, so one pass over the storage does it).
void RestrictColumns(CsrMatrix* m, const std::vector<int32_t>& index, int64_t cols) {
    size_t at = 0;
    int64_t kept = 0;
    for (int64_t r = 0; r < m->rows; ++r) {
        const auto k0 = static_cast<size_t>(m->rowPtr[static_cast<size_t>(r)]);
        const auto k1 = static_cast<size_t>(m->rowPtr[static_cast<size_t>(r) + 1]);
        const size_t start = at;
        for (size_t k = k0; k < k1; ++k) {
            const uint32_t c = m->col[k];
            const int32_t t = index[c / kChannels];
            if (t < 0) {
                at = start;  // the row is dropped
                break;
            }
            m->col[at] = static_cast<uint32_t>(t) * kChannels + c % kChannels;
            m->val[at++] = m->val[k];
        }
        if (at > start || k0 == k1)
            m->rowPtr[static_cast<size_t>(++kept)] = static_cast<int64_t>(at);
    }
    m->rows = kept;
    m->cols = cols;
    m->rowPtr.resize(static_cast<size_t>(kept) + 1);
    m->col.resize(at);
    m->val.resize(at);
}

}  // namespace

LinearSystem BuildSystem(const raster::RenderingMatrix& a, const raster::Frame& frame, int texture,
                         const Target& target, const RegularizerWeights& weights,
                         const SystemOptions& options) {
    return BuildSystem(raster::RenderingMatrix(a), frame, texture, target, weights, options);
}

LinearSystem BuildSystem(raster::RenderingMatrix&& matrix, const raster::Frame& frame, int texture,
                         const Target& target, const RegularizerWeights& weights,
                         const SystemOptions& options) {
    raster::RenderingMatrix a = std::move(matrix);  // released once its rows are selected
    // Check the inputs: one target value (and confidence) per row of A.
    const raster::Texture& tex = frame.textures.at(static_cast<size_t>(texture));
    if (static_cast<int64_t>(target.b.size()) != a.rows ||
        (!target.confidence.empty() && static_cast<int64_t>(target.confidence.size()) != a.rows))
        throw std::invalid_argument("BuildSystem: target size differs from the matrix rows");
    if (a.rows % kChannels != 0) throw std::invalid_argument("BuildSystem: rows not RGBA");

    // Image block: kept rows, local columns, weighted by sqrt(confidence).
    LinearSystem sys;
    sys.layout = LayoutOfTexture(tex, 0, options.charts);
    for (int c = 1; c < sys.layout.charts; ++c) {
        const raster::Texture& chart = frame.textures.at(static_cast<size_t>(texture + c));
        if (chart.width != tex.width || chart.height != tex.height ||
            chart.levels.size() != tex.levels.size())
            throw std::invalid_argument("BuildSystem: a map's chart textures differ in shape");
    }
    sys.globalFirstTexel = raster::TexelIndexer(frame.textures).LevelBase(texture, 0);
    ImageBlock img =
        SelectImageRows(std::move(a), KnownTexels(frame), sys.layout, sys.globalFirstTexel, target);
    a = raster::RenderingMatrix{};  // its row pointers, offsets and rendered values
    if (!IsChannelDiagonal(img.a))
        throw std::invalid_argument("BuildSystem: taps mix colour channels");
    sys.priorValue = weights.priorValue ? *weights.priorValue : TargetMean(img);
    sys.imageRowOf = std::move(img.rowOf);
    sys.imageSqrtWeight = std::move(img.sqrtWeight);  // the image rows' weights from here on
    sys.imageWeightSum = img.weightSum;

    // Regularizer blocks (omitted when their weight is 0), built over the active texels only.
    int64_t cols = img.a.cols;
    CsrMatrix smooth, pyramid, prior;
    if (options.activeRings >= 0) {
        const std::vector<int32_t> index =
            ActiveTexels(img.a, sys.layout, options.activeRings, &sys.active);
        cols = static_cast<int64_t>(sys.active.size()) * kChannels;
        RestrictColumns(&img.a, index, cols);
        if (weights.smooth > 0) smooth = SmoothnessRows(sys.layout, sys.active, index);
        if (weights.pyramid > 0) pyramid = PyramidRows(sys.layout, sys.active, index);
        if (weights.prior > 0) prior = PriorRows(sys.layout, sys.active, index);
    } else {
        if (weights.smooth > 0) smooth = SmoothnessRows(sys.layout, cols);
        if (weights.pyramid > 0) pyramid = PyramidRows(sys.layout, cols);
        if (weights.prior > 0) prior = PriorRows(sys.layout, cols);
    }
    sys.imageRows = img.a.rows;
    std::vector<RowBlock> blocks;
    if (weights.smooth > 0) blocks.push_back({&smooth, std::sqrt(weights.smooth), nullptr});
    if (weights.pyramid > 0) blocks.push_back({&pyramid, std::sqrt(weights.pyramid), nullptr});
    if (weights.prior > 0) blocks.push_back({&prior, std::sqrt(weights.prior), nullptr});
    // K = [image; regularizers], held as its quad form when it has one (read straight from the
    // blocks: the stack itself, four times that size, is never formed).
    const int64_t priorRows = prior.rows;
    CsrMatrix quads;
    if (StackedQuadForm(img.a, 1.0, &sys.imageSqrtWeight, blocks, &quads)) {
        const int64_t rows = kChannels * quads.rows;
        img.a = CsrMatrix{}, smooth = CsrMatrix{}, pyramid = CsrMatrix{}, prior = CsrMatrix{};
        sys.k = SparseOperator::FromQuadForm(rows, cols, std::move(quads));
    } else {
        sys.k = SparseOperator(StackRows(std::move(img.a), 1.0, &sys.imageSqrtWeight, blocks));
    }

    // Right-hand side in the same row order.
    sys.h.assign(static_cast<size_t>(sys.k.Rows()), 0.0);
    for (int64_t r = 0; r < sys.imageRows; ++r)
        sys.h[static_cast<size_t>(r)] =
            sys.imageSqrtWeight[static_cast<size_t>(r)] * img.rhs[static_cast<size_t>(r)];
    if (weights.prior > 0) {
        const int64_t first = sys.k.Rows() - priorRows;
        for (int64_t r = 0; r < priorRows; ++r)
            sys.h[static_cast<size_t>(first + r)] =
                std::sqrt(weights.prior) * sys.priorValue[static_cast<size_t>(r % kChannels)];
    }
    return sys;
}

Vector InitialGuess(const LinearSystem& system) {
    Vector x(static_cast<size_t>(system.Cols()));
    for (size_t j = 0; j < x.size(); ++j) x[j] = system.priorValue[j % kChannels];
    return x;
}

Vector SplatGuess(const LinearSystem& system, double lo, double hi, int threads) {
    // Step 1: K^T over the image rows of h and of sqrt(w): sum w a b and sum w a per column.
    const size_t rows = static_cast<size_t>(system.k.Rows());
    Vector hImage(rows, 0.0), wImage(rows, 0.0);
    for (int64_t r = 0; r < system.imageRows; ++r) {
        hImage[static_cast<size_t>(r)] = system.h[static_cast<size_t>(r)];
        wImage[static_cast<size_t>(r)] = system.imageSqrtWeight[static_cast<size_t>(r)];
    }
    Vector num, den;
    system.k.ApplyTranspose(hImage, &num, threads);
    system.k.ApplyTranspose(wImage, &den, threads);
    // Step 2: their ratio, the prior where nothing is seen.
    Vector x = InitialGuess(system);
    for (size_t j = 0; j < x.size(); ++j)
        if (den[j] > 0.0) x[j] = std::clamp(num[j] / den[j], lo, hi);
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
    for (size_t j = 0; j < x.size(); ++j)
        full[base + 4 * size_t{system.layout.FrameOrderOfLocal(static_cast<uint32_t>(j / 4))} +
             j % 4] = x[j];
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

Vector FillUnobserved(const LinearSystem& system, const Vector& x, int64_t* filled) {
    const TexelLayout& layout = system.layout;
    const auto count = static_cast<size_t>(layout.TexelCount());
    if (system.active.empty()) {
        if (filled) *filled = 0;
        return x;
    }
    Vector full(count * kChannels, 0.0);
    std::vector<uint8_t> known(count, 0);
    for (size_t k = 0; k < system.active.size(); ++k) {
        const size_t t = system.active[k];
        for (size_t c = 0; c < kChannels; ++c) full[t * kChannels + c] = x[k * kChannels + c];
        known[t] = 1;
    }
    int64_t fills = 0;
    // Step 1: breadth-first within each level that has unknowns. A ring's values come only from
    // texels filled before it, so the order within a ring does not matter.
    std::vector<uint8_t> levelDone(static_cast<size_t>(layout.levels), 0);
    std::vector<uint8_t> queued(count, 0);
    std::vector<uint32_t> frontier, ring;
    std::vector<double> values;
    for (int l = 0; l < layout.levels; ++l) {
        const uint32_t b = layout.LevelBase(l), e = layout.LevelBase(l + 1);
        auto neighbours = [&](uint32_t t, uint32_t out[4]) {
            const FaceTexel ft = layout.Locate(l, t - b);
            int k = 0;
            for (Edge ed : {Edge::Left, Edge::Right, Edge::Up, Edge::Down})
                out[k++] = layout.NeighbourTexel(l, ft, ed);
        };
        frontier.clear();
        for (uint32_t t = b; t < e; ++t)
            if (known[t]) frontier.push_back(t);
        if (frontier.empty()) continue;
        levelDone[static_cast<size_t>(l)] = 1;
        while (!frontier.empty()) {
            // The next ring: unknown neighbours of the frontier.
            ring.clear();
            for (uint32_t t : frontier) {
                uint32_t nb[4];
                neighbours(t, nb);
                for (uint32_t u : nb)
                    if (!known[u] && !queued[u]) {
                        queued[u] = 1;
                        ring.push_back(u);
                    }
            }
            // Each the mean of its neighbours filled before this ring.
            values.assign(ring.size() * kChannels, 0.0);
            for (size_t r = 0; r < ring.size(); ++r) {
                uint32_t nb[4];
                neighbours(ring[r], nb);
                int m = 0;
                for (uint32_t u : nb) {
                    if (!known[u]) continue;
                    ++m;
                    for (size_t c = 0; c < kChannels; ++c)
                        values[r * kChannels + c] += full[size_t{u} * kChannels + c];
                }
                for (size_t c = 0; c < kChannels; ++c) values[r * kChannels + c] /= m;
            }
            for (size_t r = 0; r < ring.size(); ++r) {
                for (size_t c = 0; c < kChannels; ++c)
                    full[size_t{ring[r]} * kChannels + c] = values[r * kChannels + c];
                known[ring[r]] = 1;
            }
            fills += static_cast<int64_t>(ring.size());
            frontier.swap(ring);
        }
    }
    // Step 2: levels without unknowns from their neighbours in the pyramid.
    auto copyLevel = [&](int l, int from) {
        const int w = layout.LevelSize(l), h = layout.LevelHeight(l);
        const int wf = layout.LevelSize(from), hf = layout.LevelHeight(from);
        for (int f = 0; f < layout.Faces(); ++f)
            for (int j = 0; j < h; ++j)
                for (int i = 0; i < w; ++i) {
                    const size_t t = layout.Texel(l, f, i, j);
                    for (size_t c = 0; c < kChannels; ++c) {
                        double v = 0.0;
                        if (from < l) {  // finer: mean of the children
                            const int sx = wf / w, sy = hf / h;
                            for (int dj = 0; dj < sy; ++dj)
                                for (int di = 0; di < sx; ++di)
                                    v += full[size_t{
                                                  layout.Texel(from, f, i * sx + di, j * sy + dj)} *
                                                  kChannels +
                                              c];
                            v /= sx * sy;
                        } else {  // coarser: the parent
                            v = full[size_t{layout.Texel(from, f, i / (w / wf), j / (h / hf))} *
                                         kChannels +
                                     c];
                        }
                        full[t * kChannels + c] = v;
                    }
                }
        fills += layout.Faces() * w * h;
        levelDone[static_cast<size_t>(l)] = 1;
    };
    for (int l = 1; l < layout.levels; ++l)
        if (!levelDone[static_cast<size_t>(l)] && levelDone[static_cast<size_t>(l - 1)])
            copyLevel(l, l - 1);
    for (int l = layout.levels - 2; l >= 0; --l)
        if (!levelDone[static_cast<size_t>(l)] && levelDone[static_cast<size_t>(l + 1)])
            copyLevel(l, l + 1);
    for (int l = 0; l < layout.levels; ++l)
        if (!levelDone[static_cast<size_t>(l)]) {
            for (uint32_t t = layout.LevelBase(l); t < layout.LevelBase(l + 1); ++t)
                for (size_t c = 0; c < kChannels; ++c)
                    full[size_t{t} * kChannels + c] = system.priorValue[c];
            fills += layout.LevelBase(l + 1) - layout.LevelBase(l);
        }
    if (filled) *filled = fills;
    return full;
}

}  // namespace pem::infer
