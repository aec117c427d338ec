// SPDX-License-Identifier: MIT
// regularizer.cpp — neighbour pairs across cube seams, pyramid and prior rows (regularizer.h).
#include "infer/regularizer.h"

#include <algorithm>
#include <array>
#include <span>
#include <stdexcept>

namespace pem::infer {
namespace {

// The adjacency table of docs/hardware-model.md §2.3 (llvmpipe's lp_build_cube_new_coords): where a
// texel that falls off an edge of `face` lands. m = n - 1; (i, j) is the texel that fell off,
// with the coordinate along the edge still in range.
FaceTexel CrossSeam(int face, Edge e, int i, int j, int m) {
    switch (e) {
        case Edge::Left: {
            static const int kFace[6] = {4, 5, 1, 1, 1, 0};
            const int ni[6] = {m, m, j, m - j, m, m};
            const int nj[6] = {j, j, 0, m, j, j};
            return {kFace[face], ni[face], nj[face]};
        }
        case Edge::Right: {
            static const int kFace[6] = {5, 4, 0, 0, 0, 1};
            const int ni[6] = {0, 0, m - j, j, 0, 0};
            const int nj[6] = {j, j, 0, m, j, j};
            return {kFace[face], ni[face], nj[face]};
        }
        case Edge::Up: {
            static const int kFace[6] = {2, 2, 5, 4, 2, 2};
            const int ni[6] = {m, 0, m - i, i, i, m - i};
            const int nj[6] = {m - i, i, 0, m, m, 0};
            return {kFace[face], ni[face], nj[face]};
        }
        case Edge::Down:
        default: {
            static const int kFace[6] = {3, 3, 4, 5, 3, 3};
            const int ni[6] = {m, 0, i, m - i, i, m - i};
            const int nj[6] = {i, m - i, 0, m, 0, m};
            return {kFace[face], ni[face], nj[face]};
        }
    }
}

// One row per channel: sum_k coef[k] * x(texel[k]) (at most kMaxRowTexels texels; no
// allocation per row: the regularizers have millions of them).
constexpr size_t kMaxRowTexels = 5;

// The coefficients of the three kinds of row: a neighbour difference, a level minus the mean
// of its four children, a texel.
constexpr std::array kDifference{1.0, -1.0};
constexpr std::array kPyramid{1.0, -0.25, -0.25, -0.25, -0.25};
constexpr std::array kValue{1.0};

void AddChannelRows(std::span<const uint32_t> texels, std::span<const double> coef, CsrMatrix* m) {
    std::array<uint32_t, kMaxRowTexels> cols{};
    for (uint32_t c = 0; c < kChannels; ++c) {
        for (size_t k = 0; k < texels.size(); ++k) cols[k] = kChannels * texels[k] + c;
        m->AddRow(std::span<const uint32_t>(cols.data(), texels.size()), coef);
    }
}

CsrMatrix EmptyRows(const CubeLayout& layout, int64_t cols) {
    if (static_cast<int64_t>(layout.firstTexel) + layout.TexelCount() > cols / kChannels)
        throw std::invalid_argument("regularizer: layout exceeds the system's columns");
    CsrMatrix m;
    m.cols = cols;
    return m;
}

// Active-set versions: one row per channel over compact columns, when every texel is active.
bool AddActiveRows(std::span<const uint32_t> texels, std::span<const double> coef,
                   const std::vector<int32_t>& index, CsrMatrix* m) {
    std::array<uint32_t, kMaxRowTexels> compact{};
    for (size_t k = 0; k < texels.size(); ++k) {
        const int32_t t = index[texels[k]];
        if (t < 0) return false;
        compact[k] = static_cast<uint32_t>(t);
    }
    AddChannelRows(std::span<const uint32_t>(compact.data(), texels.size()), coef, m);
    return true;
}

CsrMatrix ActiveEmpty(const std::vector<uint32_t>& active) {
    CsrMatrix m;
    m.cols = static_cast<int64_t>(active.size()) * kChannels;
    return m;
}

}  // namespace

uint32_t CubeLayout::LevelBase(int level) const {
    uint32_t base = 0;
    for (int l = 0; l < level; ++l) base += static_cast<uint32_t>(6 * LevelSize(l) * LevelSize(l));
    return base;
}

FaceTexel Neighbour(const FaceTexel& t, Edge e, int n) {
    const int di = e == Edge::Left ? -1 : e == Edge::Right ? 1 : 0;
    const int dj = e == Edge::Up ? -1 : e == Edge::Down ? 1 : 0;
    const int i = t.i + di, j = t.j + dj;
    if (i >= 0 && i < n && j >= 0 && j < n) return {t.face, i, j};
    return CrossSeam(t.face, e, t.i, t.j, n - 1);
}

std::vector<std::pair<uint32_t, uint32_t>> NeighbourPairs(const CubeLayout& layout, int level) {
    const int n = layout.LevelSize(level);
    std::vector<std::pair<uint32_t, uint32_t>> pairs;
    pairs.reserve(static_cast<size_t>(12 * n * n));
    // Right and down neighbour of every texel inside a face. Across seams right/down alone is
    // not enough: some edges are left or up from both faces (+Y's left edge is -X's top row),
    // others right or down from both (-Y's and -Z's bottom rows). So every texel on a face
    // border also crosses its left and up seams, and the pairs are normalised, sorted, unique.
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                for (Edge e : {Edge::Right, Edge::Down, Edge::Left, Edge::Up}) {
                    if ((e == Edge::Left && i > 0) || (e == Edge::Up && j > 0)) continue;
                    const FaceTexel nb = Neighbour({f, i, j}, e, n);
                    const uint32_t a = layout.Texel(level, f, i, j);
                    const uint32_t b = layout.Texel(level, nb.face, nb.i, nb.j);
                    if (a != b) pairs.emplace_back(std::min(a, b), std::max(a, b));
                }
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    return pairs;
}

CsrMatrix SmoothnessRows(const CubeLayout& layout, int64_t cols) {
    CsrMatrix m = EmptyRows(layout, cols);
    for (int l = 0; l < layout.levels; ++l)
        for (const auto& [a, b] : NeighbourPairs(layout, l))
            AddChannelRows(std::array{a, b}, kDifference, &m);
    return m;
}

CsrMatrix PyramidRows(const CubeLayout& layout, int64_t cols) {
    CsrMatrix m = EmptyRows(layout, cols);
    for (int l = 1; l < layout.levels; ++l) {
        const int n = layout.LevelSize(l);
        if (layout.LevelSize(l - 1) != 2 * n) continue;  // not a halving step (size not 2^k)
        for (int f = 0; f < 6; ++f)
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i)
                    AddChannelRows(
                        std::array{layout.Texel(l, f, i, j), layout.Texel(l - 1, f, 2 * i, 2 * j),
                                   layout.Texel(l - 1, f, 2 * i + 1, 2 * j),
                                   layout.Texel(l - 1, f, 2 * i, 2 * j + 1),
                                   layout.Texel(l - 1, f, 2 * i + 1, 2 * j + 1)},
                        kPyramid, &m);
    }
    return m;
}

CsrMatrix PriorRows(const CubeLayout& layout, int64_t cols) {
    CsrMatrix m = EmptyRows(layout, cols);
    const uint32_t end = layout.firstTexel + static_cast<uint32_t>(layout.TexelCount());
    for (uint32_t t = layout.firstTexel; t < end; ++t) AddChannelRows(std::array{t}, kValue, &m);
    return m;
}

CsrMatrix SmoothnessRows(const CubeLayout& layout, const std::vector<uint32_t>& active,
                         const std::vector<int32_t>& index) {
    CsrMatrix m = ActiveEmpty(active);
    auto on = [&](uint32_t t) { return index[t] >= 0; };
    size_t k = 0;  // walks `active` level by level
    std::vector<std::pair<uint32_t, uint32_t>> pairs;
    for (int l = 0; l < layout.levels; ++l) {
        // NeighbourPairs' rule from every active texel of the level; both ends must be active.
        const uint32_t base = layout.LevelBase(l), end = layout.LevelBase(l + 1);
        const int n = layout.LevelSize(l);
        const CubeLayout local{0, layout.size, layout.levels};
        pairs.clear();
        for (; k < active.size() && active[k] < end; ++k) {
            const uint32_t a = active[k], r = a - base;
            const auto nn = static_cast<uint32_t>(n * n);
            const int f = static_cast<int>(r / nn), i = static_cast<int>(r % nn) % n,
                      j = static_cast<int>((r % nn) / static_cast<uint32_t>(n));
            for (Edge e : {Edge::Right, Edge::Down, Edge::Left, Edge::Up}) {
                if ((e == Edge::Left && i > 0) || (e == Edge::Up && j > 0)) continue;
                const FaceTexel nb = Neighbour({f, i, j}, e, n);
                const uint32_t b = local.Texel(l, nb.face, nb.i, nb.j);
                if (a != b && on(b)) pairs.emplace_back(std::min(a, b), std::max(a, b));
            }
        }
        std::sort(pairs.begin(), pairs.end());
        pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
        for (const auto& [a, b] : pairs) AddActiveRows(std::array{a, b}, kDifference, index, &m);
    }
    return m;
}

CsrMatrix PyramidRows(const CubeLayout& layout, const std::vector<uint32_t>& active,
                      const std::vector<int32_t>& index) {
    CsrMatrix m = ActiveEmpty(active);
    const CubeLayout local{0, layout.size, layout.levels};
    for (int l = 1; l < layout.levels; ++l) {
        const int n = layout.LevelSize(l);
        if (layout.LevelSize(l - 1) != 2 * n) continue;
        for (int f = 0; f < 6; ++f)
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i) {
                    if (index[local.Texel(l, f, i, j)] < 0) continue;
                    AddActiveRows(
                        std::array{local.Texel(l, f, i, j), local.Texel(l - 1, f, 2 * i, 2 * j),
                                   local.Texel(l - 1, f, 2 * i + 1, 2 * j),
                                   local.Texel(l - 1, f, 2 * i, 2 * j + 1),
                                   local.Texel(l - 1, f, 2 * i + 1, 2 * j + 1)},
                        kPyramid, index, &m);
                }
    }
    return m;
}

CsrMatrix PriorRows(const CubeLayout& /*layout*/, const std::vector<uint32_t>& active,
                    const std::vector<int32_t>& index) {
    CsrMatrix m = ActiveEmpty(active);
    for (uint32_t t : active) AddActiveRows(std::array{t}, kValue, index, &m);
    return m;
}

}  // namespace pem::infer
