// Round-robin flood fill: a true partition into face-connected pieces, deterministic per seed,
// seeds spread over disconnected components, and input errors for impossible piece counts.
#include "prescore/partition.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <string>

#include "core/error.h"
#include "prescore/graded_seeds.h"
#include "prescore/tet_test_meshes.h"

namespace shatter {
namespace {

// Checks every invariant of a partition of `mesh` into `pieces`.
void expect_valid(const TetMesh& mesh, const TetTopology& topology, const Partition& p, uint32_t pieces) {
    ASSERT_EQ(p.tet_piece.size(), mesh.tets.size());
    ASSERT_EQ(p.seeds.size(), pieces);
    ASSERT_EQ(p.piece_tets.size(), pieces);
    std::vector<uint32_t> counted(pieces, 0);
    for (uint32_t piece : p.tet_piece) {
        ASSERT_LT(piece, pieces);
        ++counted[piece];
    }
    EXPECT_EQ(counted, p.piece_tets);
    EXPECT_EQ(std::accumulate(p.piece_tets.begin(), p.piece_tets.end(), size_t(0)), mesh.tets.size());
    for (uint32_t piece = 0; piece < pieces; ++piece) {
        EXPECT_EQ(p.tet_piece[p.seeds[piece]], piece);
        if (piece > 0) {
            EXPECT_LT(p.seeds[piece - 1], p.seeds[piece]);
        }
        std::vector<char> mask(mesh.tets.size());
        for (size_t t = 0; t < mask.size(); ++t) mask[t] = p.tet_piece[t] == piece;
        int32_t components = 0;
        tet_components(topology, mask, &components);
        EXPECT_EQ(components, 1) << "piece " << piece << " is not face-connected";
    }
}

TEST(Partition, EveryTetInExactlyOneFaceConnectedPiece) {
    const TetMesh mesh = test::cube_grid(10, 10, 10, 0.1);
    const TetTopology topology = build_topology(mesh);
    for (uint32_t pieces : {1u, 2u, 10u, 57u}) {
        SCOPED_TRACE(pieces);
        expect_valid(mesh, topology, partition(mesh, topology, pieces, 42), pieces);
    }
}

TEST(Partition, SameSeedSameOutputDifferentSeedDifferentOutput) {
    const TetMesh mesh = test::spherical_shell(1.0, 0.7, 2, 2);
    const TetTopology topology = build_topology(mesh);
    const Partition a = partition(mesh, topology, 10, 7);
    const Partition b = partition(mesh, topology, 10, 7);
    const Partition c = partition(mesh, topology, 10, 8);
    EXPECT_EQ(a.tet_piece, b.tet_piece);
    EXPECT_EQ(a.seeds, b.seeds);
    EXPECT_EQ(a.piece_tets, b.piece_tets);
    EXPECT_NE(a.seeds, c.seeds);
    EXPECT_NE(a.tet_piece, c.tet_piece);
}

TEST(Partition, SeedsArePinnedForAFixedSeed) {
    // The Rng is ours (not std::), so these numbers are the same on every platform.
    const TetMesh mesh = test::cube_grid(4, 4, 4, 1.0);
    const Partition p = partition(mesh, build_topology(mesh), 4, 1);
    EXPECT_EQ(p.seeds, (std::vector<uint32_t>{172, 217, 286, 372}));
}

TEST(Partition, NarrowBarWithManyPiecesIsFullyClaimedWhenSeedsGetEnclosed) {
    // In a 1-cell bar, pieces soon wall each other in; the others must claim what is left.
    const TetMesh mesh = test::cube_grid(10, 1, 1, 1.0);
    const TetTopology topology = build_topology(mesh);
    bool uneven = false;
    for (uint64_t seed = 0; seed < 20; ++seed) {
        const Partition p = partition(mesh, topology, 30, seed);
        expect_valid(mesh, topology, p, 30);
        uneven |= *std::min_element(p.piece_tets.begin(), p.piece_tets.end()) == 1 &&
                  *std::max_element(p.piece_tets.begin(), p.piece_tets.end()) > 2;
    }
    EXPECT_TRUE(uneven);  // some piece was enclosed at its seed while others grew on
}

TEST(Partition, OnePiecePerTetWorks) {
    const TetMesh mesh = test::cube_grid(2, 2, 1, 1.0);
    const TetTopology topology = build_topology(mesh);
    const auto n = uint32_t(mesh.tets.size());
    const Partition p = partition(mesh, topology, n, 3);
    expect_valid(mesh, topology, p, n);
    EXPECT_EQ(p.piece_tets, std::vector<uint32_t>(n, 1));
}

TEST(Partition, ImpossiblePieceCountsAreInputErrors) {
    const TetMesh mesh = test::cube_grid(1, 1, 1, 1.0);  // 6 tets
    const TetTopology topology = build_topology(mesh);
    EXPECT_THROW(partition(mesh, topology, 0, 1), Error);
    EXPECT_THROW(partition(mesh, topology, 7, 1), Error);
    EXPECT_NO_THROW(partition(mesh, topology, 6, 1));
}

TEST(Partition, FewerPiecesThanComponentsIsAnErrorNamingTheMinimum) {
    TetMesh mesh = test::cube_grid(2, 2, 2, 1.0);
    test::append(mesh, test::cube_grid(2, 2, 2, 1.0, Vec3(5, 0, 0)));
    const TetTopology topology = build_topology(mesh);
    try {
        partition(mesh, topology, 1, 1);
        FAIL() << "expected an Error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::BadInput);
        EXPECT_NE(std::string(e.what()).find("2 separate components"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("at least 2"), std::string::npos) << e.what();
    }
}

TEST(Partition, DisconnectedComponentsGetSeedsInProportionToSize) {
    TetMesh mesh = test::cube_grid(4, 4, 4, 1.0);  // 384 tets
    const auto big = uint32_t(mesh.tets.size());
    test::append(mesh, test::cube_grid(2, 2, 2, 1.0, Vec3(10, 0, 0)));  // 48 tets
    const TetTopology topology = build_topology(mesh);

    const Partition two = partition(mesh, topology, 2, 5);
    expect_valid(mesh, topology, two, 2);
    EXPECT_LT(two.seeds[0], big);  // one seed in each component
    EXPECT_GE(two.seeds[1], big);
    EXPECT_EQ(two.piece_tets, (std::vector<uint32_t>{384, 48}));

    const Partition nine = partition(mesh, topology, 9, 5);  // 9 * 384/432 = 8, 9 * 48/432 = 1
    expect_valid(mesh, topology, nine, 9);
    EXPECT_EQ(std::count_if(nine.seeds.begin(), nine.seeds.end(), [&](uint32_t s) { return s >= big; }), 1);
}

// The mean volume of the pieces whose centres lie within `within` of `contact`, over the rest's.
double near_over_far(const TetMesh& mesh, const Partition& p, const Vec3& contact, double within) {
    const size_t n = p.piece_tets.size();
    std::vector<double> volume(n, 0.0);
    std::vector<Vec3> moment(n, Vec3::Zero());
    for (size_t t = 0; t < mesh.tets.size(); ++t) {
        const Tet& k = mesh.tets[t];
        const Vec3 a = mesh.vertices[k[0]], b = mesh.vertices[k[1]], c = mesh.vertices[k[2]], d = mesh.vertices[k[3]];
        const double v = tet_volume(a, b, c, d);
        volume[p.tet_piece[t]] += v;
        moment[p.tet_piece[t]] += v * (a + b + c + d) / 4;
    }
    double near = 0, far = 0;
    int near_count = 0, far_count = 0;
    for (size_t i = 0; i < n; ++i) {
        if ((moment[i] / volume[i] - contact).norm() <= within) near += volume[i], ++near_count;
        else far += volume[i], ++far_count;
    }
    EXPECT_GT(near_count, 0);
    EXPECT_GT(far_count, 0);
    return (near / near_count) / (far / far_count);
}

TEST(Partition, ImpactDensityMakesThePiecesNearTheContactSmallAndUniformSeedsDoNot) {
    // A 30 x 15 x 15 cm brick in 12,000 tets, 40 pieces, hit at the middle of its bottom face.
    const TetMesh mesh = test::cube_grid(20, 10, 10, 0.015);
    const TetTopology topology = build_topology(mesh);
    const Vec3 contact(0.15, 0, 0.075);
    const double diagonal = Vec3(0.3, 0.15, 0.15).norm();
    const std::vector<double> density = impact_density(mesh, {contact}, 20, 0.2 * diagonal);  // the demo's
    const Partition graded = partition(mesh, topology, 40, 1, density);
    expect_valid(mesh, topology, graded, 40);
    const double graded_ratio = near_over_far(mesh, graded, contact, 0.3 * diagonal);
    const double uniform_ratio = near_over_far(mesh, partition(mesh, topology, 40, 1), contact, 0.3 * diagonal);
    EXPECT_LE(graded_ratio, 0.3);
    EXPECT_GT(uniform_ratio, 0.6);
    EXPECT_LT(uniform_ratio, 1.6);
    std::printf("near / far mean volume: graded %.3f, uniform %.3f\n", graded_ratio, uniform_ratio);
    // Same inputs, same pieces.
    const Partition again = partition(mesh, topology, 40, 1, density);
    EXPECT_EQ(again.tet_piece, graded.tet_piece);
    EXPECT_EQ(again.seeds, graded.seeds);
}

TEST(Partition, ImpactDensityKeepsEachComponentsShareOfSeeds) {
    TetMesh mesh = test::cube_grid(4, 4, 4, 1.0);  // 384 tets
    const auto big = uint32_t(mesh.tets.size());
    test::append(mesh, test::cube_grid(2, 2, 2, 1.0, Vec3(10, 0, 0)));  // 48 tets, far from the contact
    const TetTopology topology = build_topology(mesh);
    const Partition nine = partition(mesh, topology, 9, 5, impact_density(mesh, {Vec3(0, 0, 0)}, 100, 0.5));
    expect_valid(mesh, topology, nine, 9);
    EXPECT_EQ(std::count_if(nine.seeds.begin(), nine.seeds.end(), [&](uint32_t s) { return s >= big; }), 1);
}

}  // namespace
}  // namespace shatter
