#include "fx/membrane_removal.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace vesica::fx {
namespace {

using ::testing::HasSubstr;

// Three elements, two springs; the middle element belongs to both.
MembraneRemoval ThreeElementsTwoSprings(double rate) {
  return MembraneRemoval({{0}, {0, 1}, {1}}, 2, MembraneParams{.fade_rate_per_s = rate});
}

TEST(MembraneRemovalTest, FadeTimeIsHealthOverRateExactly) {
  // Health 1 at 0.5 per second: removed after exactly 2 s of contact, not a hair earlier.
  MembraneRemoval early = ThreeElementsTwoSprings(0.5);
  early.Touch(0, std::nextafter(2.0, 0.0), 2.0);
  EXPECT_FALSE(early.element_removed(0));
  EXPECT_GT(early.health()[0], 0.0f);

  MembraneRemoval on_time = ThreeElementsTwoSprings(0.5);
  on_time.Touch(0, 2.0, 2.0);
  EXPECT_TRUE(on_time.element_removed(0));
  EXPECT_EQ(on_time.health()[0], 0.0f);

  // The same in steps: 8 touches of 0.25 s.
  MembraneRemoval stepped = ThreeElementsTwoSprings(0.5);
  for (int k = 1; k <= 7; ++k) stepped.Touch(2, 0.25, 0.25 * k);
  EXPECT_FALSE(stepped.element_removed(2));
  EXPECT_EQ(stepped.health()[2], 0.125f);
  stepped.Touch(2, 0.25, 2.0);
  EXPECT_TRUE(stepped.element_removed(2));
  ASSERT_EQ(stepped.element_removals().size(), 1u);
  EXPECT_EQ(stepped.element_removals()[0].element, 2);
  EXPECT_EQ(stepped.element_removals()[0].time_s, 2.0);
}

TEST(MembraneRemovalTest, SpringIsCutWhenItsLastElementGoesAndGallbladderFreedAtTheEnd) {
  MembraneRemoval m = ThreeElementsTwoSprings(1.0);
  EXPECT_EQ(m.num_springs_remaining(), 2);
  EXPECT_FALSE(m.gallbladder_free());

  m.Touch(0, 1.0, 1.0);  // spring 0 still holds by element 1
  EXPECT_TRUE(m.element_removed(0));
  EXPECT_FALSE(m.spring_cut(0));
  EXPECT_TRUE(m.spring_cuts().empty());

  m.Touch(1, 1.0, 2.0);  // last element of spring 0; spring 1 keeps element 2
  EXPECT_TRUE(m.spring_cut(0));
  EXPECT_FALSE(m.spring_cut(1));
  ASSERT_EQ(m.spring_cuts().size(), 1u);
  EXPECT_EQ(m.spring_cuts()[0].spring, 0);
  EXPECT_EQ(m.spring_cuts()[0].time_s, 2.0);
  EXPECT_FALSE(m.gallbladder_free());

  m.Touch(1, 1.0, 2.5);  // touching a removed element changes nothing
  EXPECT_EQ(m.element_removals().size(), 2u);
  EXPECT_EQ(m.spring_cuts().size(), 1u);

  m.Touch(2, 1.0, 3.0);
  ASSERT_EQ(m.spring_cuts().size(), 2u);
  EXPECT_EQ(m.spring_cuts()[1].spring, 1);
  EXPECT_EQ(m.num_springs_remaining(), 0);
  EXPECT_TRUE(m.gallbladder_free());
}

TEST(MembraneRemovalTest, ZeroDtTouchDoesNothing) {
  MembraneRemoval m = ThreeElementsTwoSprings(1.0);
  m.Touch(1, 0.0, 0.0);
  EXPECT_EQ(m.health()[1], 1.0f);
}

TEST(MembraneRemovalTest, RejectsBadInput) {
  MembraneRemoval m = ThreeElementsTwoSprings(1.0);
  EXPECT_THAT([&] { m.Touch(3, 0.1, 0.1); }, ::testing::ThrowsMessage<std::invalid_argument>(
                                                 HasSubstr("MembraneRemoval: element 3 out of range [0, 3)")));
  EXPECT_THAT([&] { m.Touch(0, -0.1, 0.1); }, ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("dt_s")));
  EXPECT_THAT([&] { m.Touch(0, 0.1, std::nan("")); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("time_s")));
  EXPECT_EQ(m.health()[0], 1.0f);
  EXPECT_THAT(
      [] {
        MembraneRemoval({{0}, {2}}, 2, {});
      },
      ::testing::ThrowsMessage<std::invalid_argument>(
          HasSubstr("MembraneRemoval: element 1: spring 2 out of range [0, 2)")));
  EXPECT_THAT(
      [] {
        MembraneRemoval({{0}, {0}}, 2, {});
      },
      ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("spring 1 has no membrane element")));
  EXPECT_THAT([] { MembraneRemoval({{0}}, 1, MembraneParams{.fade_rate_per_s = 0}); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("fade_rate_per_s")));
}

}  // namespace
}  // namespace vesica::fx
