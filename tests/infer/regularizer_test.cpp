// SPDX-License-Identifier: MIT
// regularizer_test.cpp — the cube surface grid (every texel has 4 neighbours, neighbours are
// adjacent on the sphere of directions, the sampler's bilinear footprints are connected in it),
// pyramid and prior rows, channel interleaving.
#include "infer/regularizer.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <glm/glm.hpp>
#include <map>
#include <set>

#include "raster/render.h"
#include "tests/infer/infer_frames.h"

namespace pem::infer {
namespace {

// Direction of the centre of texel (i, j) of `face` (GL table 8.19 inverted), normalized.
glm::dvec3 CentreDirection(int face, int i, int j, int n) {
    const double sc = 2.0 * (i + 0.5) / n - 1.0, tc = 2.0 * (j + 0.5) / n - 1.0;
    const glm::dvec3 d[6] = {{1, -tc, -sc}, {-1, -tc, sc}, {sc, 1, tc},
                             {sc, -1, -tc}, {sc, -tc, 1},  {-sc, -tc, -1}};
    return glm::normalize(d[face]);
}

TEST(Regularizer, EveryTexelHasFourNeighbours) {
    for (int n : {1, 2, 4, 16}) {
        TexelLayout layout{0, n, 1};
        const auto pairs = NeighbourPairs(layout, 0);
        EXPECT_EQ(pairs.size(), static_cast<size_t>(12 * n * n)) << n;
        std::map<uint32_t, int> degree;
        for (const auto& [a, b] : pairs) {
            ++degree[a];
            ++degree[b];
        }
        ASSERT_EQ(degree.size(), static_cast<size_t>(6 * n * n));
        for (const auto& [t, d] : degree) EXPECT_EQ(d, 4) << "n " << n << " texel " << t;
    }
}

// The pairs as a set built the plain way (every texel, all four neighbours, each pair once),
// for cubes of several levels and first texels: NeighbourPairs lists exactly them, in order.
TEST(Regularizer, NeighbourPairsAreTheSortedSetOfAdjacentTexels) {
    for (uint32_t first : {0u, 37u})
        for (int n : {1, 2, 8, 32}) {
            const TexelLayout layout{
                first, n, std::min(4, static_cast<int>(std::bit_width(static_cast<unsigned>(n))))};
            for (int l = 0; l < layout.levels; ++l) {
                const int m = layout.LevelSize(l);
                std::set<std::pair<uint32_t, uint32_t>> expected;
                for (int f = 0; f < 6; ++f)
                    for (int j = 0; j < m; ++j)
                        for (int i = 0; i < m; ++i)
                            for (Edge e : {Edge::Left, Edge::Right, Edge::Up, Edge::Down}) {
                                const FaceTexel nb = Neighbour({f, i, j}, e, m);
                                const uint32_t a = layout.Texel(l, f, i, j);
                                const uint32_t b = layout.Texel(l, nb.face, nb.i, nb.j);
                                if (a != b) expected.emplace(std::min(a, b), std::max(a, b));
                            }
                using Pairs = std::vector<std::pair<uint32_t, uint32_t>>;
                EXPECT_EQ(NeighbourPairs(layout, l), Pairs(expected.begin(), expected.end()))
                    << "n " << n << " level " << l << " first " << first;
            }
        }
}

TEST(Regularizer, NeighboursAreAdjacentDirections) {
    for (int n : {2, 8, 32}) {
        // Neighbouring centres are at most ~1.5 texel widths apart on the cube (angle at a
        // face centre: 2/n radians per texel; at a seam the two centres are one texel apart).
        const double maxAngle = 1.6 * 2.0 / n;
        for (int f = 0; f < 6; ++f)
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i)
                    for (Edge e : {Edge::Left, Edge::Right, Edge::Up, Edge::Down}) {
                        const FaceTexel nb = Neighbour({f, i, j}, e, n);
                        const double angle = std::acos(
                            std::min(1.0, glm::dot(CentreDirection(f, i, j, n),
                                                   CentreDirection(nb.face, nb.i, nb.j, n))));
                        ASSERT_LT(angle, maxAngle)
                            << "n " << n << " face " << f << " (" << i << "," << j << ")";
                        ASSERT_GT(angle, 0.1 / n);
                    }
    }
}

// The sampler's taps at one level (bilinear 2x2, or 3 texels at a cube corner) must be connected
// through neighbour pairs: the seam table of infer agrees with raster's sampler.
TEST(Regularizer, SamplerFootprintsAreConnected) {
    test::SphereSpec spec;
    spec.cubeSize = 8;
    spec.width = spec.height = 64;
    const raster::Frame frame = test::RandomSphere(spec);
    raster::RenderOptions opt;
    opt.profile = raster::Profile::Linear;
    const raster::RenderingMatrix a =
        raster::BuildRenderingMatrix(raster::PreparedFrame(frame), opt);
    const TexelLayout layout{0, 8, frame.textures[0].NumLevels()};
    std::set<std::pair<uint32_t, uint32_t>> pairs;
    for (int l = 0; l < layout.levels; ++l)
        for (const auto& p : NeighbourPairs(layout, l)) pairs.insert(p);
    int checked = 0, seamRows = 0;
    for (int64_t r = 0; r < a.rows; r += 4) {
        // Group the row's texels by level.
        std::map<int, std::vector<uint32_t>> byLevel;
        for (int64_t k = a.rowPtr[static_cast<size_t>(r)]; k < a.rowPtr[static_cast<size_t>(r) + 1];
             ++k) {
            const uint32_t t = a.col[static_cast<size_t>(k)] / 4;
            int l = 0;
            while (l + 1 < layout.levels && t >= layout.LevelBase(l + 1)) ++l;
            byLevel[l].push_back(t);
        }
        for (auto& [l, texels] : byLevel) {
            std::sort(texels.begin(), texels.end());
            texels.erase(std::unique(texels.begin(), texels.end()), texels.end());
            // Connectivity by flood fill over the pairs.
            std::set<uint32_t> seen{texels[0]};
            for (bool grew = true; grew;) {
                grew = false;
                for (uint32_t a1 : texels)
                    for (uint32_t b1 : texels)
                        if (seen.count(a1) && !seen.count(b1) &&
                            pairs.count({std::min(a1, b1), std::max(a1, b1)})) {
                            seen.insert(b1);
                            grew = true;
                        }
            }
            ASSERT_EQ(seen.size(), texels.size()) << "row " << r << " level " << l;
            const int n = layout.LevelSize(l);
            const uint32_t faceOf0 =
                (texels[0] - layout.LevelBase(l)) / static_cast<uint32_t>(n * n);
            for (uint32_t t : texels)
                seamRows += (t - layout.LevelBase(l)) / static_cast<uint32_t>(n * n) != faceOf0;
            ++checked;
        }
    }
    EXPECT_GT(checked, 1000);
    EXPECT_GT(seamRows, 10);  // footprints that straddle a seam were among them
}

TEST(Regularizer, RowsPerChannel) {
    const TexelLayout layout{0, 4, 3};  // 4x4, 2x2, 1x1
    const int64_t cols = 4 * layout.TexelCount();
    const CsrMatrix smooth = SmoothnessRows(layout, cols), pyr = PyramidRows(layout, cols),
                    prior = PriorRows(layout, cols);
    EXPECT_EQ(smooth.rows, 4 * 12 * (16 + 4 + 1));
    EXPECT_EQ(pyr.rows, 4 * 6 * (4 + 1));
    EXPECT_EQ(prior.rows, cols);
    EXPECT_TRUE(IsChannelDiagonal(smooth));
    EXPECT_TRUE(IsChannelDiagonal(pyr));
    EXPECT_TRUE(IsChannelDiagonal(prior));
    // Constants are in the null space of L and P; a coarse texel equal to its children's mean too.
    Vector x(static_cast<size_t>(cols), 0.7), y;
    Multiply(smooth, x, &y, 1);
    for (double v : y) EXPECT_EQ(v, 0.0);
    Multiply(pyr, x, &y, 1);
    for (double v : y) EXPECT_NEAR(v, 0.0, 1e-15);
}

// 2D layouts: the grid's pairs counted by hand (w x h level: (w - 1) h + w (h - 1), h more when
// s repeats and w > 2), the pyramid's children as the level halves both sizes or one.
TEST(Regularizer, TwoDimensionalGrids) {
    TexelLayout layout{0, 8, 4, raster::TextureKind::Tex2D, 2, false};  // 8x2, 4x1, 2x1, 1x1
    EXPECT_EQ(layout.TexelCount(), 16 + 4 + 2 + 1);
    EXPECT_EQ(NeighbourPairs(layout, 0).size(), 7u * 2 + 8u * 1);
    EXPECT_EQ(NeighbourPairs(layout, 2).size(), 1u);
    layout.wrapS = true;
    EXPECT_EQ(NeighbourPairs(layout, 0).size(), 7u * 2 + 8u * 1 + 2u);  // (7, j)-(0, j)
    EXPECT_EQ(NeighbourPairs(layout, 2).size(), 1u);                    // 2 wide: the same pair
    EXPECT_EQ(layout.NeighbourTexel(0, {0, 0, 1}, Edge::Left), layout.Texel(0, 0, 7, 1));
    EXPECT_EQ(layout.NeighbourTexel(0, {0, 3, 1}, Edge::Down), layout.Texel(0, 0, 3, 1));  // edge
    const int64_t cols = 4 * layout.TexelCount();
    const CsrMatrix pyr = PyramidRows(layout, cols);
    EXPECT_EQ(pyr.rows, 4 * (4 + 2 + 1));
    // Level 1 (4x1) from 8x2: four children of -1/4; level 2 (2x1) from 4x1: two of -1/2.
    EXPECT_EQ(pyr.rowPtr[1] - pyr.rowPtr[0], 5);
    EXPECT_EQ(pyr.val[1], -0.25);
    const int64_t level2 = pyr.rowPtr[4 * 4];
    EXPECT_EQ(pyr.rowPtr[4 * 4 + 1] - level2, 3);
    EXPECT_EQ(pyr.val[static_cast<size_t>(level2) + 1], -0.5);
    Vector x(static_cast<size_t>(cols), 0.3), y;
    Multiply(pyr, x, &y, 1);
    for (double v : y) EXPECT_NEAR(v, 0.0, 1e-15);
}

}  // namespace
}  // namespace pem::infer
