#include "invariants/topology_check.h"
#include "kernel/builders.h"
#include "kernel/euler.h"
#include "kernel/transaction.h"

#include <gtest/gtest.h>

namespace kintsugi {
namespace {

using geo::Vec3;

TEST(Transaction, RollbackRestoresTopologyGeometryAndStorage) {
  Body b = build::box();
  Body before = b.clone();
  std::size_t slots = b.edge_slots();
  {
    Transaction tx(b);
    HalfedgeH h = b.halfedges()[0];
    auto s = *euler::semv(b, h, Vec3(0.5, 0, 0));
    b.set_point(s.vertex, Vec3(0.4, 0, 0));
    ASSERT_TRUE(euler::kev(b, b.halfedges()[6]));
    FaceH f = b.faces()[2];
    b.set_surface(f, geo::Sphere{});
    ASSERT_TRUE(euler::kfmb(b, f));
    tx.rollback();
  }
  std::string why;
  EXPECT_TRUE(b.equals(before, &why)) << why;
  EXPECT_EQ(b.edge_slots(), slots);
  EXPECT_TRUE(b.journal().empty());
}

TEST(Transaction, DestructorRollsBackAndCommitKeeps) {
  Body b = build::box();
  Body before = b.clone();
  {
    Transaction tx(b);
    ASSERT_TRUE(euler::semv(b, b.halfedges()[0], Vec3(0.5, 0, 0)));
  }
  EXPECT_TRUE(b.equals(before));
  {
    Transaction tx(b);
    ASSERT_TRUE(euler::semv(b, b.halfedges()[0], Vec3(0.5, 0, 0)));
    tx.commit();
  }
  EXPECT_EQ(b.counts().edges, 13u);
  EXPECT_EQ(b.journal().op_names(), std::vector<std::string>{"semv"});
}

TEST(Transaction, NestedInnerRollbackKeepsOuterWork) {
  Body b = build::box();
  Transaction outer(b);
  ASSERT_TRUE(euler::semv(b, b.halfedges()[0], Vec3(0.5, 0, 0)));
  Body mid = b.clone();
  {
    Transaction inner(b);
    ASSERT_TRUE(euler::kfmb(b, b.faces()[0]));
    inner.rollback();
  }
  EXPECT_TRUE(b.equals(mid));
  outer.commit();
  EXPECT_EQ(b.counts().edges, 13u);
}

TEST(Transaction, JournalSettingsAreRefusedWhileOpen) {
  Body b = build::box();
  Transaction tx(b);
  EXPECT_FALSE(b.clear_journal());
  EXPECT_FALSE(b.set_journaling(false));
  EXPECT_TRUE(b.compact().vertex.empty());
  tx.commit();
  EXPECT_TRUE(b.clear_journal());
}

TEST(Compact, RenumbersAndKeepsTheBodyValid) {
  Body b = build::box();
  ASSERT_TRUE(euler::kev(b, b.halfedges()[0]));
  auto c = b.counts();
  auto map = b.compact();
  EXPECT_EQ(map.vertex.size(), 8u);
  EXPECT_EQ(b.counts(), c);
  EXPECT_EQ(b.vertex_slots(), c.vertices);
  EXPECT_TRUE(check_topology(b).empty());
}

}  // namespace
}  // namespace kintsugi
