// The Shape Distributor's state owners on their own: the sampling state (face and class
// distributions, dead faces, the kill log that taking a shape back replays) and the accepted
// shapes with their vertex indexes (add, take back, remove, reorder by key).
#include "DistributorProbes.h"
#include "SamplingState.h"
#include "ShapeDistributorImpl.h"
#include "TestMeshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

namespace
{
using gs::distribution::Random;
using gs::distribution::SamplingState;
using AcceptedShapes = gs::ShapeDistributorInspector::Impl::AcceptedShapes;
using Record = gs::ShapeDistributorInspector::Impl::Record;

/// Four faces of weights 1, 2, 0, 3 and two classes of weights 1 and `second`.
SamplingState FourFaces(double second)
{
  SamplingState s;
  s.ClassCdf = { 1.0, 1.0 + second };
  s.FaceWeight = { 1.0, 2.0, 0.0, 3.0 };
  s.AllCdf = { 1.0, 3.0, 3.0, 6.0 };
  s.Reset(4, 2);
  s.BuildCdf();
  return s;
}

std::vector<int> FaceCounts(const SamplingState& s, bool live, int draws)
{
  std::vector<int> counts(4, 0);
  for (int i = 0; i < draws; ++i)
  {
    Random rng(7, 1, 0, static_cast<std::uint64_t>(i));
    const gs::SurfacePoint p = s.RandomPoint(rng, live);
    EXPECT_GE(p.Face, 0);
    EXPECT_LT(p.Face, 4);
    for (double b : p.Bary)
    {
      EXPECT_GE(b, 0.0);
      EXPECT_LE(b, 1.0);
    }
    EXPECT_NEAR(p.Bary[0] + p.Bary[1] + p.Bary[2], 1.0, 1e-12);
    ++counts[p.Face];
  }
  return counts;
}
} // namespace

TEST(SamplingState, FacesAreDrawnByWeightAndNeverWithoutOne)
{
  const SamplingState s = FourFaces(1.0);
  EXPECT_EQ(s.FaceCdf, (std::vector<double>{ 1.0, 3.0, 3.0, 6.0 }));
  EXPECT_TRUE(s.AnyLiveFace());
  const int draws = 60000;
  const std::vector<int> counts = FaceCounts(s, true, draws);
  EXPECT_EQ(counts[2], 0);
  const double weights[4] = { 1.0, 2.0, 0.0, 3.0 };
  for (int f : { 0, 1, 3 })
  {
    const double expected = draws * weights[f] / 6.0;
    EXPECT_NEAR(counts[f], expected, 5.0 * std::sqrt(expected)) << "face " << f;
  }
}

TEST(SamplingState, ClassesAreDrawnByWeightAndNeverWithoutOne)
{
  const SamplingState zero = FourFaces(0.0);
  std::vector<int> counts(2, 0);
  for (int i = 0; i < 2000; ++i)
  {
    Random rng(3, 1, 1, static_cast<std::uint64_t>(i));
    ++counts[zero.RandomClass(rng)];
  }
  EXPECT_EQ(counts[1], 0);
  const SamplingState three = FourFaces(3.0);
  counts.assign(2, 0);
  for (int i = 0; i < 40000; ++i)
  {
    Random rng(3, 1, 1, static_cast<std::uint64_t>(i));
    ++counts[three.RandomClass(rng)];
  }
  EXPECT_NEAR(counts[1], 30000, 5.0 * std::sqrt(30000.0));
}

TEST(SamplingState, AFaceDiesWhenDeadForEveryClassAndRevivesWithItsKiller)
{
  SamplingState s = FourFaces(1.0);
  s.BeginShape();
  s.Kill({ { 0, 1 } });
  EXPECT_TRUE(s.DeadForClass(0, 1));
  EXPECT_FALSE(s.DeadForClass(1, 1));
  EXPECT_FALSE(s.DeadFace(1));
  EXPECT_EQ(s.KilledSinceCdf(), 0);
  s.Kill({ { 1, 1 }, { 1, 1 } }); // (a kill twice counts once)
  EXPECT_TRUE(s.DeadFace(1));
  EXPECT_EQ(s.KilledSinceCdf(), 1);
  s.BuildCdf();
  EXPECT_EQ(s.KilledSinceCdf(), 0);
  EXPECT_EQ(s.FaceCdf, (std::vector<double>{ 1.0, 1.0, 1.0, 4.0 }));
  EXPECT_EQ(FaceCounts(s, true, 5000)[1], 0);
  EXPECT_GT(FaceCounts(s, false, 5000)[1], 0); // (all faces: the probes' distribution)

  // A second shape kills face 3 for both classes and face 1 again (already dead).
  s.BeginShape();
  s.Kill({ { 0, 3 }, { 1, 3 }, { 0, 1 } });
  EXPECT_TRUE(s.DeadFace(3));
  EXPECT_EQ(s.LoggedShapes(), 2u);
  s.ReviveLast();
  EXPECT_FALSE(s.DeadFace(3));
  EXPECT_FALSE(s.DeadForClass(0, 3));
  EXPECT_FALSE(s.DeadForClass(1, 3));
  EXPECT_TRUE(s.DeadFace(1)); // (the first shape's)
  EXPECT_GT(s.KilledSinceCdf(), 0);
  s.ReviveLast();
  EXPECT_EQ(s.LoggedShapes(), 0u);
  for (int f = 0; f < 4; ++f)
  {
    EXPECT_FALSE(s.DeadFace(f));
    EXPECT_FALSE(s.DeadForClass(0, f));
    EXPECT_FALSE(s.DeadForClass(1, f));
  }
  s.BuildCdf();
  EXPECT_EQ(s.FaceCdf, (std::vector<double>{ 1.0, 3.0, 3.0, 6.0 }));

  // A class that is never drawn does not keep a face alive.
  SamplingState one = FourFaces(0.0);
  one.BeginShape();
  one.Kill({ { 0, 0 } });
  EXPECT_TRUE(one.DeadFace(0));
  one.BeginShape();
  one.Kill({ { 0, 1 }, { 0, 3 } });
  one.BuildCdf();
  EXPECT_FALSE(one.AnyLiveFace());
}

namespace
{
Record ShapeWithKey(std::uint64_t key)
{
  Record r;
  r.Key = key;
  r.Shape.ClassId = static_cast<int>(key % 3);
  r.Shape.Scale = 1.0 + static_cast<double>(key);
  return r;
}

/// Index lists as (vertex -> keys of the shapes listed), ignoring ids.
std::map<int, std::vector<std::uint64_t>> IndexedKeys(
  const AcceptedShapes& a, const std::vector<std::vector<int>>& index)
{
  std::map<int, std::vector<std::uint64_t>> out;
  for (std::size_t v = 0; v < index.size(); ++v)
  {
    for (int id : index[v])
    {
      out[static_cast<int>(v)].push_back(a.Records.at(id).Key);
    }
    std::sort(out[static_cast<int>(v)].begin(), out[static_cast<int>(v)].end());
  }
  return out;
}
} // namespace

TEST(AcceptedShapes, AddAndTakeLastRestoreTheIndexes)
{
  AcceptedShapes a;
  a.Reset(6);
  EXPECT_EQ(a.Add(ShapeWithKey(5), { 0, 1, 2 }, { 1 }), 0);
  EXPECT_EQ(a.Add(ShapeWithKey(9), { 2, 3 }, { 3 }), 1);
  const auto cover = a.CoverIndex;
  const auto centres = a.CentreIndex;
  EXPECT_EQ(a.Add(ShapeWithKey(2), { 1, 2, 4, 5 }, { 4, 5 }), 2);
  ASSERT_EQ(a.Placed.size(), 3u);
  EXPECT_EQ(a.Placed[2].Scale, 3.0);
  EXPECT_EQ(a.CoverIndex[2], (std::vector<int>{ 0, 1, 2 }));
  const Record r = a.TakeLast({ 1, 2, 4, 5 }, { 4, 5 });
  EXPECT_EQ(r.Key, 2u);
  EXPECT_EQ(a.CoverIndex, cover);
  EXPECT_EQ(a.CentreIndex, centres);
  EXPECT_EQ(a.Records.size(), 2u);
  EXPECT_EQ(a.Placed.size(), 2u);
}

TEST(AcceptedShapes, RemoveLeavesTheSlotAndSortByKeyRenumbers)
{
  AcceptedShapes a;
  a.Reset(5);
  const std::uint64_t keys[4] = { 40, 10, 30, 20 };
  for (int i = 0; i < 4; ++i)
  {
    a.Add(ShapeWithKey(keys[i]), { i, i + 1 }, { i });
  }
  const Record gone = a.Remove(2, { 2, 3 }, { 2 });
  EXPECT_EQ(gone.Key, 30u);
  EXPECT_EQ(a.Records.size(), 4u); // (the slot stays)
  for (const auto* index : { &a.CoverIndex, &a.CentreIndex })
  {
    for (const std::vector<int>& ids : *index)
    {
      EXPECT_EQ(std::count(ids.begin(), ids.end(), 2), 0);
    }
  }
  const auto coverKeys = IndexedKeys(a, a.CoverIndex);
  const auto centreKeys = IndexedKeys(a, a.CentreIndex);
  const std::vector<char> removed = { 0, 0, 1, 0 };
  a.SortByKey(&removed);
  ASSERT_EQ(a.Records.size(), 3u);
  EXPECT_EQ(a.Records[0].Key, 10u);
  EXPECT_EQ(a.Records[1].Key, 20u);
  EXPECT_EQ(a.Records[2].Key, 40u);
  ASSERT_EQ(a.Placed.size(), 3u);
  for (int i = 0; i < 3; ++i)
  {
    EXPECT_EQ(a.Placed[i].Scale, a.Records[i].Shape.Scale);
  }
  EXPECT_EQ(IndexedKeys(a, a.CoverIndex), coverKeys);
  EXPECT_EQ(IndexedKeys(a, a.CentreIndex), centreKeys);
}

TEST(ClassSilhouettes, ClearanceIsTheCentresDistanceToTheOutlineOrNoneOutside)
{
  using ClassSilhouettes = gs::ShapeDistributorInspector::Impl::ClassSilhouettes;
  // A square about its centre, and a U whose centre lies in its slot (outside the silhouette).
  const gs::SafeDistanceTables tables = gs_test::PolygonTables({
    { { -1, -1 }, { 1, -1 }, { 1, 1 }, { -1, 1 } },
    { { -3, -3 }, { 3, -3 }, { 3, 3 }, { 1, 3 }, { 1, -1 }, { -1, -1 }, { -1, 3 }, { -3, 3 } },
  });
  ASSERT_EQ(tables.Classes.size(), 2u);
  ClassSilhouettes s;
  s.Prepare(tables.Classes);
  ASSERT_EQ(s.Regions.size(), 2u);
  ASSERT_EQ(s.Clearance.size(), 2u);
  // The square's centre is an inscribed radius (half the side) from its outline: its
  // circumradius over sqrt 2.
  EXPECT_NEAR(s.Clearance[0], tables.Classes[0].Radius / std::sqrt(2.0), 1e-9 * tables.Classes[0].Radius);
  EXPECT_EQ(s.Clearance[1], -1.0);
  EXPECT_EQ(s.MaxClearance, s.Clearance[0]);
  EXPECT_TRUE(s.Regions[0].Inside(gs::Vec2{ 0.0, 0.0 }));
  EXPECT_FALSE(s.Regions[1].Inside(gs::Vec2{ 0.0, 0.0 }));
  // A second Prepare starts afresh.
  s.Prepare({ tables.Classes[1] });
  EXPECT_EQ(s.Regions.size(), 1u);
  EXPECT_EQ(s.MaxClearance, 0.0);
}
