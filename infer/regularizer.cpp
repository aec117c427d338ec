// SPDX-License-Identifier: MIT
// regularizer.cpp — neighbour pairs across cube seams, pyramid and prior rows (regularizer.h).
#include "infer/regularizer.h"

#include <algorithm>
#include <array>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

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

// The coefficients of two kinds of row: a neighbour difference, a texel (the pyramid's: a
// texel minus the mean of its children, PyramidRowOf).
constexpr std::array kDifference{1.0, -1.0};
constexpr std::array kValue{1.0};

void AddChannelRows(std::span<const uint32_t> texels, std::span<const double> coef, CsrMatrix* m) {
    std::array<uint32_t, kMaxRowTexels> cols{};
    for (uint32_t c = 0; c < kChannels; ++c) {
        for (size_t k = 0; k < texels.size(); ++k) cols[k] = kChannels * texels[k] + c;
        m->AddRow(std::span<const uint32_t>(cols.data(), texels.size()), coef);
    }
}

// The pyramid row of coarse texel (l, f, i, j): the texel, then its children at level l - 1
// (rows then columns: 4, 2 or 1 as the level halves both sizes, one or neither), coefficients 1
// and -1 / children. No texels when the level halves neither size exactly.
struct PyramidRow {
    std::array<uint32_t, kMaxRowTexels> texels{};
    std::array<double, kMaxRowTexels> coef{};
    size_t count = 0;
    std::span<const uint32_t> Texels() const { return {texels.data(), count}; }
    std::span<const double> Coef() const { return {coef.data(), count}; }
};

// 2 when a size halves from level l - 1 to l, 1 when it stays, 0 otherwise.
int Halving(int finer, int coarser) {
    return finer == 2 * coarser ? 2 : finer == coarser ? 1 : 0;
}

PyramidRow PyramidRowOf(const TexelLayout& layout, int l, int f, int i, int j) {
    PyramidRow row;
    const int sx = Halving(layout.LevelSize(l - 1), layout.LevelSize(l));
    const int sy = Halving(layout.LevelHeight(l - 1), layout.LevelHeight(l));
    if (sx * sy < 2) return row;
    row.texels[0] = layout.Texel(l, f, i, j);
    row.coef[0] = 1.0;
    row.count = 1;
    const double share = -1.0 / (sx * sy);
    for (int dj = 0; dj < sy; ++dj)
        for (int di = 0; di < sx; ++di) {
            row.texels[row.count] = layout.Texel(l - 1, f, sx * i + di, sy * j + dj);
            row.coef[row.count++] = share;
        }
    return row;
}

CsrMatrix EmptyRows(const TexelLayout& layout, int64_t cols) {
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

// The layout numbered from 0 (the active sets' texels are relative to firstTexel).
TexelLayout Local(TexelLayout layout) {
    layout.firstTexel = 0;
    return layout;
}

CsrMatrix ActiveEmpty(const std::vector<uint32_t>& active) {
    CsrMatrix m;
    m.cols = static_cast<int64_t>(active.size()) * kChannels;
    return m;
}

// The neighbour pairs of a walk over texels in increasing order, normalised (smaller texel
// first), sorted and unique — what sorting them all gives, without sorting them all: the pairs
// led by the walking texel come in order of their first texel already (the few of one texel
// are sorted among themselves); the others (a seam reaching back to a smaller texel) are sorted
// apart and merged in.
class PairWalk {
  public:
    using Pair = std::pair<uint32_t, uint32_t>;
    // A pair of the walking texel a (a >= every earlier walking texel).
    void Add(uint32_t a, uint32_t b) {
        if (a < b) {
            if (!ahead_.empty() && ahead_.back().first > a) inOrder_ = false;
            ahead_.emplace_back(a, b);
        } else {
            behind_.emplace_back(b, a);
        }
    }
    std::vector<Pair> Take() {
        // Step 1: each run of one first texel sorted (a walk out of order: all of it).
        if (!inOrder_) {
            std::sort(ahead_.begin(), ahead_.end());
        } else {
            for (size_t r = 0; r < ahead_.size();) {
                size_t e = r + 1;
                while (e < ahead_.size() && ahead_[e].first == ahead_[r].first) ++e;
                std::sort(ahead_.begin() + static_cast<std::ptrdiff_t>(r),
                          ahead_.begin() + static_cast<std::ptrdiff_t>(e));
                r = e;
            }
        }
        // Step 2: the pairs reaching back, sorted and merged in; duplicates dropped.
        std::sort(behind_.begin(), behind_.end());
        std::vector<Pair> pairs(ahead_.size() + behind_.size());
        std::merge(ahead_.begin(), ahead_.end(), behind_.begin(), behind_.end(), pairs.begin());
        pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
        ahead_.clear(), behind_.clear(), inOrder_ = true;
        return pairs;
    }
    void Reserve(size_t n) { ahead_.reserve(n); }

  private:
    std::vector<Pair> ahead_, behind_;
    bool inOrder_ = true;
};

}  // namespace

uint32_t TexelLayout::LevelBase(int level) const {
    uint32_t base = 0;
    for (int l = 0; l < level; ++l)
        base += static_cast<uint32_t>(Faces() * LevelSize(l) * LevelHeight(l));
    return base;
}

FaceTexel TexelLayout::Locate(int level, uint32_t r) const {
    const auto w = static_cast<uint32_t>(LevelSize(level));
    const uint32_t perFace = w * static_cast<uint32_t>(LevelHeight(level));
    return {static_cast<int>(r / perFace), static_cast<int>((r % perFace) % w),
            static_cast<int>((r % perFace) / w)};
}

uint32_t TexelLayout::NeighbourTexel(int level, const FaceTexel& t, Edge e) const {
    if (kind == raster::TextureKind::Cube) {
        const FaceTexel nb = Neighbour(t, e, LevelSize(level));
        return Texel(level, nb.face, nb.i, nb.j);
    }
    const int w = LevelSize(level), h = LevelHeight(level);
    int i = t.i + (e == Edge::Left ? -1 : e == Edge::Right ? 1 : 0);
    const int j = t.j + (e == Edge::Up ? -1 : e == Edge::Down ? 1 : 0);
    if (wrapS) i = (i + w) % w;
    if (i < 0 || i >= w || j < 0 || j >= h) return Texel(level, t.face, t.i, t.j);
    return Texel(level, t.face, i, j);
}

uint32_t TexelLayout::LocalOfFrameOrder(uint32_t r) const {
    if (Faces() == 1 || kind == raster::TextureKind::Cube) return r;
    // Step: the chart and the offset inside its texture (all levels of one chart).
    const uint32_t perChart = LevelBase(levels) / static_cast<uint32_t>(charts);
    const uint32_t chart = r / perChart;
    uint32_t rest = r % perChart;
    // Step: the level, then the texel's place among that level's charts.
    for (int l = 0;; ++l) {
        const auto n = static_cast<uint32_t>(LevelSize(l) * LevelHeight(l));
        if (rest < n || l + 1 == levels) return LevelBase(l) + chart * n + rest;
        rest -= n;
    }
}

uint32_t TexelLayout::FrameOrderOfLocal(uint32_t t) const {
    if (Faces() == 1 || kind == raster::TextureKind::Cube) return t;
    const uint32_t perChart = LevelBase(levels) / static_cast<uint32_t>(charts);
    // Step: the level, then the chart and the offset inside that chart's level image.
    uint32_t before = 0;  // texels of one chart in the finer levels
    for (int l = 0;; ++l) {
        const auto n = static_cast<uint32_t>(LevelSize(l) * LevelHeight(l));
        if (t < LevelBase(l + 1) || l + 1 == levels) {
            const uint32_t o = t - LevelBase(l);
            return (o / n) * perChart + before + o % n;
        }
        before += n;
    }
}

TexelLayout LayoutOfTexture(const raster::Texture& texture, uint32_t firstTexel, int charts) {
    TexelLayout l;
    l.charts = texture.kind == raster::TextureKind::Tex2D ? charts : 1;
    l.firstTexel = firstTexel;
    l.size = texture.width;
    l.levels = texture.NumLevels();
    l.kind = texture.kind;
    l.height = texture.height;
    l.wrapS =
        texture.kind == raster::TextureKind::Tex2D && texture.sampler.wrapS == raster::Wrap::Repeat;
    return l;
}

FaceTexel Neighbour(const FaceTexel& t, Edge e, int n) {
    const int di = e == Edge::Left ? -1 : e == Edge::Right ? 1 : 0;
    const int dj = e == Edge::Up ? -1 : e == Edge::Down ? 1 : 0;
    const int i = t.i + di, j = t.j + dj;
    if (i >= 0 && i < n && j >= 0 && j < n) return {t.face, i, j};
    return CrossSeam(t.face, e, t.i, t.j, n - 1);
}

std::vector<std::pair<uint32_t, uint32_t>> NeighbourPairs(const TexelLayout& layout, int level) {
    const int w = layout.LevelSize(level), h = layout.LevelHeight(level);
    PairWalk walk;
    walk.Reserve(static_cast<size_t>(2 * layout.Faces() * w * h));
    // Right and down neighbour of every texel inside a face. Across seams right/down alone is
    // not enough: some edges are left or up from both faces (+Y's left edge is -X's top row),
    // others right or down from both (-Y's and -Z's bottom rows). So every texel on a face
    // border also crosses its left and up seams, and the pairs are normalised, sorted, unique.
    for (int f = 0; f < layout.Faces(); ++f)
        for (int j = 0; j < h; ++j)
            for (int i = 0; i < w; ++i)
                for (Edge e : {Edge::Right, Edge::Down, Edge::Left, Edge::Up}) {
                    if ((e == Edge::Left && i > 0) || (e == Edge::Up && j > 0)) continue;
                    const uint32_t a = layout.Texel(level, f, i, j);
                    const uint32_t b = layout.NeighbourTexel(level, {f, i, j}, e);
                    if (a != b) walk.Add(a, b);
                }
    return walk.Take();
}

CsrMatrix SmoothnessRows(const TexelLayout& layout, int64_t cols) {
    CsrMatrix m = EmptyRows(layout, cols);
    for (int l = 0; l < layout.levels; ++l)
        for (const auto& [a, b] : NeighbourPairs(layout, l))
            AddChannelRows(std::array{a, b}, kDifference, &m);
    return m;
}

CsrMatrix PyramidRows(const TexelLayout& layout, int64_t cols) {
    CsrMatrix m = EmptyRows(layout, cols);
    for (int l = 1; l < layout.levels; ++l)
        for (int f = 0; f < layout.Faces(); ++f)
            for (int j = 0; j < layout.LevelHeight(l); ++j)
                for (int i = 0; i < layout.LevelSize(l); ++i) {
                    const PyramidRow row = PyramidRowOf(layout, l, f, i, j);
                    if (row.count > 0) AddChannelRows(row.Texels(), row.Coef(), &m);
                }
    return m;
}

CsrMatrix PriorRows(const TexelLayout& layout, int64_t cols) {
    CsrMatrix m = EmptyRows(layout, cols);
    const uint32_t end = layout.firstTexel + static_cast<uint32_t>(layout.TexelCount());
    for (uint32_t t = layout.firstTexel; t < end; ++t) AddChannelRows(std::array{t}, kValue, &m);
    return m;
}

CsrMatrix SmoothnessRows(const TexelLayout& layout, const std::vector<uint32_t>& active,
                         const std::vector<int32_t>& index) {
    CsrMatrix m = ActiveEmpty(active);
    auto on = [&](uint32_t t) { return index[t] >= 0; };
    size_t k = 0;  // walks `active` level by level
    PairWalk walk;
    for (int l = 0; l < layout.levels; ++l) {
        // NeighbourPairs' rule from every active texel of the level; both ends must be active.
        const uint32_t base = layout.LevelBase(l), end = layout.LevelBase(l + 1);
        const TexelLayout local = Local(layout);
        for (; k < active.size() && active[k] < end; ++k) {
            const uint32_t a = active[k];
            const FaceTexel t = layout.Locate(l, a - base);
            for (Edge e : {Edge::Right, Edge::Down, Edge::Left, Edge::Up}) {
                if ((e == Edge::Left && t.i > 0) || (e == Edge::Up && t.j > 0)) continue;
                const uint32_t b = local.NeighbourTexel(l, t, e);
                if (a != b && on(b)) walk.Add(a, b);
            }
        }
        for (const auto& [a, b] : walk.Take())
            AddActiveRows(std::array{a, b}, kDifference, index, &m);
    }
    return m;
}

CsrMatrix PyramidRows(const TexelLayout& layout, const std::vector<uint32_t>& active,
                      const std::vector<int32_t>& index) {
    CsrMatrix m = ActiveEmpty(active);
    const TexelLayout local = Local(layout);
    for (int l = 1; l < layout.levels; ++l)
        for (int f = 0; f < layout.Faces(); ++f)
            for (int j = 0; j < layout.LevelHeight(l); ++j)
                for (int i = 0; i < layout.LevelSize(l); ++i) {
                    if (index[local.Texel(l, f, i, j)] < 0) continue;
                    const PyramidRow row = PyramidRowOf(local, l, f, i, j);
                    if (row.count > 0) AddActiveRows(row.Texels(), row.Coef(), index, &m);
                }
    return m;
}

CsrMatrix PriorRows(const TexelLayout& /*layout*/, const std::vector<uint32_t>& active,
                    const std::vector<int32_t>& index) {
    CsrMatrix m = ActiveEmpty(active);
    for (uint32_t t : active) AddActiveRows(std::array{t}, kValue, index, &m);
    return m;
}

}  // namespace pem::infer
