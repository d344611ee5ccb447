// The timeline: which item, how far into it, from where and how bright, for times the test chooses.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <set>

#include "playback/timeline.h"

using namespace playback;

namespace {

constexpr double t0 = 1000.0;           // the caller's monotonic clock at construction (any origin)
constexpr double wall0 = 1700000000.0;  // a multiple of every cycle used below: position 0

Playlist make(std::vector<double> durations, double fade = 0, bool loop = true) {
  Playlist pl;
  pl.source = "test";
  pl.fade_s = fade;
  pl.loop = loop;
  for (std::size_t i = 0; i < durations.size(); ++i) {
    Item it;
    it.scene = "scene" + std::to_string(i) + ".glb";
    it.duration_s = durations[i];
    pl.items.push_back(it);
  }
  return pl;
}

Cue at(Timeline& tl, double t) {
  return tl.at(t0 + t, wall0 + t);
}

struct Expect {
  double t;  // seconds after construction
  int item;
  double item_time;
};

void check(Timeline& tl, const std::vector<Expect>& table) {
  for (const Expect& e : table) {
    SCOPED_TRACE("t = " + std::to_string(e.t));
    const Cue f = at(tl, e.t);
    EXPECT_EQ(f.item, e.item);
    EXPECT_NEAR(f.item_time, e.item_time, 1e-9);
  }
}

// The items a shuffled looping timeline plays, one pass of `n` unit-length items at a time.
std::vector<std::vector<int>> passes(std::uint64_t seed, int n, int count) {
  Playlist pl = make(std::vector<double>(static_cast<std::size_t>(n), 1.0));
  pl.shuffle = true;
  pl.seed = seed;
  Timeline tl(pl, t0, wall0);
  std::vector<std::vector<int>> out(static_cast<std::size_t>(count));
  for (int p = 0; p < count; ++p)
    for (int i = 0; i < n; ++i) out[static_cast<std::size_t>(p)].push_back(at(tl, p * n + i + 0.5).item);
  return out;
}

}  // namespace

TEST(Timeline, ItemAtTimesAndLoopWrap) {
  Timeline tl(make({4, 6, 10}), t0, wall0);
  check(tl,
        {{0, 0, 0}, {3.5, 0, 3.5}, {4, 1, 0}, {9.75, 1, 5.75}, {10, 2, 0}, {19.5, 2, 9.5}, {20, 0, 0}, {25, 1, 1}, {41, 0, 1}});
}

TEST(Timeline, EarlierNowIsTreatedAsEqual) {
  Timeline tl(make({4, 6}), t0, wall0);
  check(tl, {{5, 1, 1}, {2, 1, 1}, {5.5, 1, 1.5}});
}

TEST(Timeline, NextItemAndSequence) {
  Timeline tl(make({4, 6, 10}), t0, wall0);
  Cue f = at(tl, 0);
  EXPECT_EQ(f.next_item, 1);
  EXPECT_EQ(f.sequence, 1u);
  f = at(tl, 12);
  EXPECT_EQ(f.item, 2);
  EXPECT_EQ(f.next_item, 0);
  EXPECT_EQ(f.sequence, 3u);
  f = at(tl, 21);
  EXPECT_EQ(f.sequence, 4u);  // the same item again is a new play
}

TEST(Timeline, NoLoopFinishesHoldingTheLastPose) {
  Timeline tl(make({4, 6}, 1.0, false), t0, wall0);
  Cue f = at(tl, 9.9);
  EXPECT_EQ(f.item, 1);
  EXPECT_EQ(f.next_item, -1);
  EXPECT_FALSE(f.finished);
  EXPECT_EQ(f.fade, 1.0f);  // nothing follows, so no fade out
  for (double t : {10.0, 50.0}) {
    f = at(tl, t);
    EXPECT_TRUE(f.finished);
    EXPECT_EQ(f.item, 1);
    EXPECT_EQ(f.item_time, 6.0);
    EXPECT_NEAR(f.camera.azimuth_deg, 30 + 360 * 6.0 / 20, 1e-9);
    EXPECT_EQ(f.next_item, -1);
    EXPECT_EQ(f.sequence, 2u);
  }
}

TEST(Timeline, FadeAtBoundaries) {
  // fade_s = 1: out over the last 0.5 s, in over the first 0.5 s of the next.
  Timeline tl(make({4, 6}, 1.0), t0, wall0);
  const std::vector<std::pair<double, float>> table = {
      {0, 1.0f},  // the very first start does not fade in
      {0.25, 1.0f},    {3.5, 1.0f},  {3.75, 0.5f},
      {3.875, 0.25f},  {4.0, 0.0f},  // item 1 starts in black
      {4.25, 0.5f},    {4.5, 1.0f},  {9.5, 1.0f},
      {9.75, 0.5f},    {10.0, 0.0f},  // the loop back to item 0 fades like any other change
      {10.125, 0.25f}, {11, 1.0f}};
  for (const auto& [t, fade] : table) {
    SCOPED_TRACE("t = " + std::to_string(t));
    EXPECT_FLOAT_EQ(at(tl, t).fade, fade);
  }
}

TEST(Timeline, NoFadeWhenZeroOrOnlyOneItem) {
  Timeline zero(make({4, 6}, 0.0), t0, wall0);
  Timeline one(make({4}, 2.0), t0, wall0);
  for (double t : {0.0, 3.9, 4.0, 4.1, 7.99, 8.0}) {
    SCOPED_TRACE(t);
    EXPECT_EQ(at(zero, t).fade, 1.0f);
    EXPECT_EQ(at(one, t).fade, 1.0f);
  }
}

TEST(Timeline, ShortItemsFadeNoFurtherThanBlack) {
  Timeline tl(make({0.5, 0.5}, 2.0), t0, wall0);
  EXPECT_FLOAT_EQ(at(tl, 0.25).fade, 0.25f);  // fading out from the start
  EXPECT_FLOAT_EQ(at(tl, 0.75).fade, 0.25f);  // in and out at once: the darker wins
}

TEST(Timeline, PauseFreezesItemTimeAndCamera) {
  Playlist pl = make({4, 6});
  pl.items[0].camera.period_s = 8;
  pl.items[0].camera.azimuth_deg = 0;
  Timeline tl(pl, t0, wall0);
  Cue f = at(tl, 2);
  EXPECT_NEAR(f.camera.azimuth_deg, 90, 1e-9);
  tl.pause(t0 + 2);
  EXPECT_TRUE(tl.paused());
  for (double t : {2.0, 3.0, 50.0, 5000.0}) {
    f = at(tl, t);
    EXPECT_EQ(f.item, 0);
    EXPECT_EQ(f.item_time, 2.0);
    EXPECT_NEAR(f.camera.azimuth_deg, 90, 1e-9);
    EXPECT_FALSE(f.cut);
  }
  tl.resume(t0 + 5000);
  EXPECT_FALSE(tl.paused());
  f = at(tl, 5001);
  EXPECT_EQ(f.item, 0);
  EXPECT_NEAR(f.item_time, 3, 1e-9);
  EXPECT_NEAR(f.camera.azimuth_deg, 135, 1e-9);
  EXPECT_FALSE(f.cut);
  check(tl, {{5002, 1, 0}});
}

TEST(Timeline, NextPreviousRestart) {
  Timeline tl(make({10, 10, 10}), t0, wall0);
  EXPECT_EQ(at(tl, 0).item, 0);
  tl.next(t0 + 1);
  Cue f = at(tl, 1);
  EXPECT_EQ(f.item, 1);
  EXPECT_EQ(f.item_time, 0.0);
  EXPECT_EQ(f.sequence, 2u);
  EXPECT_TRUE(f.cut);
  // 2 s or more into an item: previous() goes back to its start.
  tl.previous(t0 + 3);
  f = at(tl, 3);
  EXPECT_EQ(f.item, 1);
  EXPECT_EQ(f.item_time, 0.0);
  EXPECT_EQ(f.sequence, 3u);
  // Within the first 2 s: the item before.
  tl.previous(t0 + 4.9);
  check(tl, {{4.9, 0, 0}, {6, 0, 1.1}});
  // Before the first item of a looping playlist comes the last.
  tl.previous(t0 + 6);
  check(tl, {{6, 2, 0}, {16, 0, 0}});
  tl.restart(t0 + 19);
  f = at(tl, 19);
  EXPECT_EQ(f.item, 0);
  EXPECT_EQ(f.item_time, 0.0);
  EXPECT_TRUE(f.cut);
  check(tl, {{28, 0, 9}, {29, 1, 0}});
}

TEST(Timeline, ButtonsAtTheEndsOfANonLoopingPlaylist) {
  Timeline tl(make({10, 10}, 0, false), t0, wall0);
  tl.previous(t0 + 0.5);  // nothing before the first item: its start
  check(tl, {{0.5, 0, 0}});
  tl.next(t0 + 1);
  tl.next(t0 + 2);  // past the last item: finished
  Cue f = at(tl, 2);
  EXPECT_TRUE(f.finished);
  EXPECT_EQ(f.item, 1);
  EXPECT_EQ(f.item_time, 10.0);
  tl.next(t0 + 3);  // nothing further
  EXPECT_TRUE(at(tl, 3).finished);
  tl.previous(t0 + 4);  // from the end: the last item again
  f = at(tl, 4);
  EXPECT_FALSE(f.finished);
  EXPECT_EQ(f.item, 1);
  EXPECT_EQ(f.item_time, 0.0);
}

// At the end of a playlist that does not loop, previous() shows the last item that can be shown:
// the last one itself, or, when its scene has failed since, the one before it.
TEST(Timeline, PreviousAtTheEndSkipsALastItemThatCannotBeShown) {
  Timeline tl(make({10, 10, 10}, 0, false), t0, wall0);
  EXPECT_TRUE(at(tl, 31).finished);
  tl.set_playable(2, false);
  tl.previous(t0 + 32);
  Cue f = at(tl, 32);
  EXPECT_FALSE(f.finished);
  EXPECT_EQ(f.item, 1);
  EXPECT_EQ(f.item_time, 0.0);
  EXPECT_TRUE(f.cut);
}

TEST(Timeline, UnplayableItemsAreSkipped) {
  Timeline tl(make({4, 6, 10}), t0, wall0);
  tl.set_playable(1, false);
  Cue f = at(tl, 0);
  EXPECT_EQ(f.next_item, 2);
  check(tl, {{3.9, 0, 3.9}, {4, 2, 0}, {13.9, 2, 9.9}, {14, 0, 0}, {18, 2, 0}});
  tl.set_playable(1, true);
  check(tl, {{28, 0, 0}, {32, 1, 0}});
}

TEST(Timeline, CurrentItemMarkedUnplayableGivesWay) {
  Timeline tl(make({4, 6, 10}), t0, wall0);
  at(tl, 1);
  tl.set_playable(0, false);  // its scene failed to load
  Cue f = at(tl, 1.5);
  EXPECT_EQ(f.item, 1);
  EXPECT_EQ(f.item_time, 0.0);
  EXPECT_TRUE(f.cut);
  EXPECT_EQ(f.sequence, 2u);
}

TEST(Timeline, NothingPlayable) {
  Timeline tl(make({4, 6}), t0, wall0);
  at(tl, 1);
  tl.set_playable(0, false);
  tl.set_playable(1, false);
  Cue f = at(tl, 2);
  EXPECT_EQ(f.item, -1);
  EXPECT_EQ(f.next_item, -1);
  EXPECT_TRUE(f.cut);
  EXPECT_FALSE(f.finished);
  tl.next(t0 + 3);
  tl.previous(t0 + 3);
  EXPECT_EQ(at(tl, 3).item, -1);
  tl.set_playable(1, true);
  f = at(tl, 5);
  EXPECT_EQ(f.item, 1);
  EXPECT_EQ(f.item_time, 0.0);
  EXPECT_TRUE(f.cut);
}

// A button pressed when the playing item has changed since the last frame counts from the item
// playing at the press, not from the one the last frame showed.
TEST(Timeline, NextCountsFromTheItemPlayingAtThePressEvenWithNoFrameSinceItChanged) {
  Timeline tl(make({1, 1, 10, 10}), t0, wall0);
  EXPECT_EQ(at(tl, 0.5).item, 0);
  tl.next(t0 + 1.5);  // item 1 has played for 0.5 s, unseen
  check(tl, {{1.5, 2, 0}, {2, 2, 0.5}});
}

TEST(Timeline, WallclockWithNothingPlayableShowsNothingThenKeepsTheSchedule) {
  Playlist pl = make({4, 6, 10});
  pl.schedule = Schedule::wallclock;
  Timeline tl(pl, t0, wall0);
  for (int i = 0; i < 3; ++i) tl.set_playable(i, false);
  Cue f = at(tl, 5);
  EXPECT_EQ(f.item, -1);
  EXPECT_EQ(f.next_item, -1);
  tl.set_playable(2, true);
  f = at(tl, 6);  // slot 1 shows the next playable item, 2 s into the slot
  EXPECT_EQ(f.item, 2);
  EXPECT_NEAR(f.item_time, 2, 1e-9);
  EXPECT_TRUE(f.cut);
}

TEST(Timeline, AStallOfTenHoursLandsOnTheRightItem) {
  // Cycle 20 s: 36000 s is 1800 cycles, 13 s more is item 2 at 3 s.
  Timeline tl(make({4, 6, 10}), t0, wall0);
  at(tl, 1);
  Cue f = at(tl, 36013);
  EXPECT_EQ(f.item, 2);
  EXPECT_NEAR(f.item_time, 3, 1e-6);
  EXPECT_EQ(f.sequence, 1u + 1800 * 3 + 2);
  EXPECT_TRUE(f.cut);
  // With an unplayable item the cycle is 14 s: 36013 - 1 = 2572 cycles + 4 s, then 13 more s -> item 2 at 9.
  Timeline skip(make({4, 6, 10}), t0, wall0);
  skip.set_playable(1, false);
  check(skip, {{1, 0, 1}, {36021, 2, 9}});
}

TEST(Timeline, AStallOfDecadesOverTinyItemsIsArithmetic) {
  // 1e9 s over quarter-second items would be billions of steps if walked one by one.
  Timeline tl(make({0.5, 0.25, 0.25}), t0, wall0);
  check(tl, {{0.1, 0, 0.1}, {1e9 + 0.625, 1, 0.125}});
  // A clock that jumps by 2^40 s: a walk item by item would not end today.
  Timeline far(make({0.5, 0.25, 0.25}), t0, wall0);
  check(far, {{0.125, 0, 0.125}, {0x1p40 + 0.625, 1, 0.125}});
}

TEST(Timeline, AStallOfDecadesWithAnUnplayableItemIsArithmeticToo) {
  // The cycle of the items that play (0.5 s) is what a stall skips by: were it lost when an item is
  // marked unplayable, the timeline would walk 2^42 items.
  Timeline tl(make({0.5, 0.25, 0.25}), t0, wall0);
  tl.set_playable(0, false);
  check(tl, {{0.125, 1, 0}, {0x1p40 + 0.5, 2, 0.125}});
}

// A scene that fails marks every item naming it, and may be marked again when it fails again: the
// count and the cycle of playable items are kept up item by item (a playlist of 100,000 items once
// summed them all per mark), so marking twice, or back and forth, must leave them as a fresh mark.
TEST(Timeline, MarkingAnItemTwiceOrBackAndForthKeepsTheCycle) {
  Timeline fresh(make({4, 6, 10}), t0, wall0), marked(make({4, 6, 10}), t0, wall0);
  fresh.set_playable(1, false);
  for (bool playable : {false, false, true, true, false, false}) marked.set_playable(1, playable);
  marked.set_playable(7, false);  // no such item: nothing changes
  marked.set_playable(-1, true);
  // The cycle is 14 s in both; a stall of 36020 s lands on the same item at the same time.
  check(fresh, {{1, 0, 1}, {36021, 2, 9}});
  check(marked, {{1, 0, 1}, {36021, 2, 9}});
  // Every item unplayable, then one back: it alone plays, pass after pass (a 10 s cycle).
  Timeline one(make({4, 6, 10}), t0, wall0);
  for (int item : {0, 1, 2, 2}) one.set_playable(item, false);
  one.set_playable(2, true);
  check(one, {{1, 2, 0}, {10003, 2, 2}});  // it starts when first asked for, at 1 s
}

TEST(Timeline, StallLandsWhereSteppingLands) {
  Playlist pl = make({1, 2, 3, 0.5, 1.5});
  pl.shuffle = true;
  pl.seed = 99;
  Timeline stepped(pl, t0, wall0), stalled(pl, t0, wall0);
  stepped.set_playable(2, false);
  stalled.set_playable(2, false);
  Cue s;
  for (double t = 0; t <= 5000; t += 0.25) s = at(stepped, t);
  const Cue j = at(stalled, 5000);
  EXPECT_EQ(j.item, s.item);
  EXPECT_NEAR(j.item_time, s.item_time, 1e-6);
  EXPECT_EQ(j.sequence, s.sequence);
  EXPECT_EQ(j.next_item, s.next_item);
}

TEST(Timeline, ShuffleIsDeterministicAndAPermutationPerPass) {
  const auto a = passes(7, 5, 6), b = passes(7, 5, 6), c = passes(8, 5, 6);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  // Pinned: mt19937_64 is fixed by the standard and the draws are our own, so every platform agrees.
  EXPECT_EQ(a[0], (std::vector<int>{1, 4, 0, 2, 3}));
  std::set<std::vector<int>> distinct;
  for (std::size_t p = 0; p < a.size(); ++p) {
    SCOPED_TRACE(p);
    std::vector<int> sorted = a[p];
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(sorted, (std::vector<int>{0, 1, 2, 3, 4}));
    if (p > 0) {
      EXPECT_NE(a[p].front(), a[p - 1].back()) << "the same item twice in a row";
    }
    distinct.insert(a[p]);
  }
  EXPECT_GE(distinct.size(), 5u);  // a new order every pass
}

// Whatever the seed and the playlist's length (3 items or more), a shuffled playlist never shows the
// same item twice in a row where one pass ends and the next begins, and each pass still shows every
// item once: the first item of a new pass is swapped with its second when it is the one just shown.
TEST(Timeline, AShuffledPassNeverBeginsWithTheItemThePassBeforeEndedOn) {
  for (int n : {3, 4, 5, 8}) {
    for (std::uint64_t seed = 0; seed < 60; ++seed) {
      const auto shown = passes(seed, n, 12);
      for (std::size_t p = 0; p < shown.size(); ++p) {
        SCOPED_TRACE("n " + std::to_string(n) + ", seed " + std::to_string(seed) + ", pass " + std::to_string(p));
        std::vector<int> sorted = shown[p];
        std::sort(sorted.begin(), sorted.end());
        std::vector<int> every(static_cast<std::size_t>(n));
        std::iota(every.begin(), every.end(), 0);
        ASSERT_EQ(sorted, every);
        if (p > 0) {
          ASSERT_NE(shown[p].front(), shown[p - 1].back()) << "the same item twice in a row";
        }
      }
    }
  }
}

TEST(Timeline, WallclockPlayersAgreeWithoutTalking) {
  Playlist pl = make({4, 6, 10});
  pl.schedule = Schedule::wallclock;
  pl.shuffle = true;  // ignored by the wallclock schedule
  Timeline a(pl, 100.0, wall0);
  Timeline b(pl, 77777.0, wall0 + 3);  // started later, on another machine's monotonic clock
  for (double w : {5.0, 5.5, 13.0, 19.99, 20.0, 36013.0}) {
    SCOPED_TRACE(w);
    const Cue fa = a.at(100.0 + w, wall0 + w), fb = b.at(77777.0 + w, wall0 + w);
    EXPECT_EQ(fa.item, fb.item);
    EXPECT_NEAR(fa.item_time, fb.item_time, 1e-9);
    EXPECT_NEAR(fa.camera.azimuth_deg, fb.camera.azimuth_deg, 1e-6);
  }
  const std::vector<Expect> table = {{36013 + 1, 2, 4}, {36020, 0, 0}, {36020 + 4.5, 1, 0.5}};
  for (const Expect& e : table) {
    const Cue f = a.at(100.0 + e.t, wall0 + e.t);
    EXPECT_EQ(f.item, e.item);
    EXPECT_NEAR(f.item_time, e.item_time, 1e-6);
  }
  // The position comes from the wall clock alone: a 10-hour stall of the caller lands on the slot.
  Timeline c(pl, 0.0, wall0);
  const Cue f = c.at(36000.0, wall0 + 36000 + 13);
  EXPECT_EQ(f.item, 2);
  EXPECT_NEAR(f.item_time, 3, 1e-6);
  EXPECT_EQ(f.next_item, 0);
}

TEST(Timeline, WallclockUnplayableSlotShowsTheNextItem) {
  Playlist pl = make({4, 6, 10});
  pl.schedule = Schedule::wallclock;
  Timeline tl(pl, t0, wall0);
  tl.set_playable(1, false);
  Cue f = at(tl, 1);
  EXPECT_EQ(f.next_item, 2);
  const std::uint64_t seq = f.sequence;
  f = at(tl, 5);  // slot 1 shows item 2
  EXPECT_EQ(f.item, 2);
  EXPECT_NEAR(f.item_time, 1, 1e-9);
  EXPECT_EQ(f.sequence, seq + 1);
  EXPECT_EQ(f.next_item, 2);
  f = at(tl, 10);  // slot 2 starts on time: the schedule has not shifted
  EXPECT_EQ(f.item, 2);
  EXPECT_EQ(f.item_time, 0.0);
  EXPECT_TRUE(f.cut);
  EXPECT_EQ(f.sequence, seq + 2);
  // The next cycle: the first slot's item, and how far into it.
  check(tl, {{20, 0, 0}, {22.5, 0, 2.5}});
}

TEST(Timeline, WallclockButtonsDetachUntilRestart) {
  Playlist pl = make({4, 6, 10});
  pl.schedule = Schedule::wallclock;
  Timeline tl(pl, t0, wall0);
  check(tl, {{5, 1, 1}});
  tl.pause(t0 + 5);
  check(tl, {{9, 1, 1}, {30, 1, 1}});  // the wall clock moved on; this player holds
  tl.resume(t0 + 30);
  check(tl, {{32, 1, 3}, {35, 2, 0}});  // now on its own clock, in playlist order
  tl.next(t0 + 36);
  check(tl, {{36, 0, 0}});
  tl.restart(t0 + 37);  // back on the schedule: wall position 37 mod 20 = 17 is item 2 at 7
  const Cue f = at(tl, 37);
  EXPECT_EQ(f.item, 2);
  EXPECT_NEAR(f.item_time, 7, 1e-9);
  EXPECT_TRUE(f.cut);
  EXPECT_FALSE(tl.paused());
  tl.restart(t0 + 38);  // attached: nothing to do
  EXPECT_FALSE(at(tl, 38).cut);
}

TEST(Timeline, WallclockPreviousUsesTheTwoSecondRule) {
  Playlist pl = make({4, 6, 10});
  pl.schedule = Schedule::wallclock;
  Timeline tl(pl, t0, wall0);
  at(tl, 4.5);
  tl.previous(t0 + 5);  // 1 s into item 1 (extrapolated from the last at()): item 0
  check(tl, {{5, 0, 0}});
}

TEST(Timeline, WallclockStepIsACut) {
  Playlist pl = make({40});
  pl.schedule = Schedule::wallclock;
  Timeline tl(pl, t0, wall0);
  EXPECT_TRUE(tl.at(t0 + 1, wall0 + 1).cut);
  EXPECT_FALSE(tl.at(t0 + 2, wall0 + 2).cut);
  EXPECT_TRUE(tl.at(t0 + 3, wall0 + 13).cut);  // NTP stepped the clock by 10 s
  EXPECT_FALSE(tl.at(t0 + 4, wall0 + 14).cut);
}

// Frames a tenth of a second apart over two cycles: a cut and a new sequence number where the item
// changes and nowhere else (the cycle count must not move inside a cycle).
TEST(Timeline, WallclockCutsOnlyWhereTheItemChanges) {
  Playlist pl = make({4, 6, 10});
  pl.schedule = Schedule::wallclock;
  Timeline tl(pl, t0, wall0);
  int previous_item = -1;
  std::uint64_t previous_sequence = 0;
  for (int step = 0; step < 400; ++step) {
    const double t = 0.05 + 0.1 * step;
    SCOPED_TRACE(t);
    const Cue f = at(tl, t);
    const bool changed = f.item != previous_item;
    EXPECT_EQ(f.cut, changed);
    EXPECT_EQ(f.sequence, previous_sequence + (changed ? 1 : 0));
    previous_item = f.item;
    previous_sequence = f.sequence;
  }
}

TEST(Timeline, CutExactlyAtChanges) {
  Timeline tl(make({4, 6, 10}), t0, wall0);
  struct Step {
    double t;
    bool cut;
  };
  const std::vector<Step> table = {{0, true}, {1, false}, {3.99, false}, {4, true}, {4.01, false}, {9, false}, {10.5, true}};
  for (const Step& s : table) {
    SCOPED_TRACE(s.t);
    EXPECT_EQ(at(tl, s.t).cut, s.cut);
  }
  tl.next(t0 + 11);
  EXPECT_TRUE(at(tl, 11).cut);
  EXPECT_FALSE(at(tl, 11.5).cut);
  tl.pause(t0 + 12);
  EXPECT_FALSE(at(tl, 13).cut);
  tl.resume(t0 + 13);
  EXPECT_FALSE(at(tl, 14).cut);
  tl.restart(t0 + 14);
  EXPECT_TRUE(at(tl, 14).cut);
  tl.replace(make({4, 6, 10}), t0 + 15);
  EXPECT_TRUE(at(tl, 15).cut);
  EXPECT_FALSE(at(tl, 15.5).cut);
}

TEST(Timeline, ReplaceKeepsTheCurrentItem) {
  Timeline tl(make({4, 6, 10}), t0, wall0);
  Cue f = at(tl, 5);
  ASSERT_EQ(f.item, 1);
  const std::uint64_t seq = f.sequence;

  Playlist same_place = make({4, 6, 10});
  same_place.items[0].scene = "new.glb";
  tl.replace(same_place, t0 + 5);
  f = at(tl, 5.5);
  EXPECT_EQ(f.item, 1);
  EXPECT_NEAR(f.item_time, 1.5, 1e-9);
  EXPECT_EQ(f.sequence, seq);  // the same play goes on

  Playlist moved = make({6, 3});
  moved.items[0].scene = "scene1.glb";  // the playing scene is now first
  moved.items[1].scene = "other.glb";
  tl.replace(moved, t0 + 6);
  f = at(tl, 6);
  EXPECT_EQ(f.item, 0);
  EXPECT_NEAR(f.item_time, 2, 1e-9);
  EXPECT_EQ(f.sequence, seq);
  check(tl, {{9.5, 0, 5.5}, {10.5, 1, 0.5}});  // started at 4, the new duration 6 ends it at 10

  Playlist gone = make({5, 5});
  gone.items[0].scene = "x.glb";
  gone.items[1].scene = "y.glb";
  tl.replace(gone, t0 + 11);
  f = at(tl, 11);
  EXPECT_EQ(f.item, 0);
  EXPECT_EQ(f.item_time, 0.0);
  EXPECT_EQ(f.sequence, seq + 2);
  EXPECT_EQ(tl.playlist().items[1].scene, "y.glb");
}

TEST(Timeline, ReplaceMakesEveryItemPlayableAgain) {
  Timeline tl(make({4, 6}), t0, wall0);
  tl.set_playable(1, false);
  tl.replace(make({4, 6}), t0 + 1);
  check(tl, {{4.5, 1, 0.5}});
}

TEST(Timeline, ReplaceKeepsTheFirstItemThatNamesThePlayingScene) {
  Timeline tl(make({4, 6, 10, 5}), t0, wall0);
  ASSERT_EQ(at(tl, 21).item, 3);
  Playlist twice = make({5, 6, 5});
  twice.items[0].scene = twice.items[2].scene = "scene3.glb";
  tl.replace(twice, t0 + 21);
  check(tl, {{22, 0, 2}, {26, 1, 1}});
}

TEST(Timeline, ReplaceOfAWallclockScheduleBySequentialKeepsTheItemShown) {
  Playlist wall = make({4, 6, 10});
  wall.schedule = Schedule::wallclock;
  Timeline tl(wall, t0, wall0);
  ASSERT_EQ(at(tl, 5).item, 1);
  tl.replace(make({4, 6, 10}), t0 + 5.5);
  check(tl, {{6, 1, 2}, {11, 2, 1}});
}

TEST(Timeline, ReplaceOfAOneItemPlaylistGoesOnInTheSamePass) {
  // Two seconds into a one-second item that loops: the third pass. A shuffled playlist that keeps
  // the item goes on with the rest of its own third pass.
  Timeline tl(make({1}), t0, wall0);
  ASSERT_EQ(at(tl, 2.5).item, 0);
  constexpr std::uint64_t seed = 3;
  const auto order = passes(seed, 5, 3);
  const auto& third = order[2];
  const auto pos = static_cast<std::size_t>(std::find(third.begin(), third.end(), 0) - third.begin());
  ASSERT_LT(pos, 4u) << "the seed must leave items after the kept one";
  const std::vector<int> rest(third.begin() + static_cast<std::ptrdiff_t>(pos) + 1, third.end());
  ASSERT_FALSE(std::equal(rest.begin(), rest.end(), order[0].begin() + static_cast<std::ptrdiff_t>(pos) + 1))
      << "the seed must give the first and third passes different endings";
  Playlist shuffled = make({1, 1, 1, 1, 1});
  shuffled.shuffle = true;
  shuffled.seed = seed;
  tl.replace(shuffled, t0 + 2.5);
  for (std::size_t j = 0; j < rest.size(); ++j) EXPECT_EQ(at(tl, 3.5 + static_cast<double>(j)).item, rest[j]) << j;
}

TEST(Timeline, WallclockNextDetachesAndShowsTheNextItem) {
  Playlist pl = make({4, 6, 10});
  pl.schedule = Schedule::wallclock;
  Timeline tl(pl, t0, wall0);
  check(tl, {{5, 1, 1}});
  tl.next(t0 + 5);
  check(tl, {{6, 2, 1}});
}

TEST(Timeline, WallclockButtonOnTheFirstItemHoldsItWhereItIs) {
  Playlist pl = make({4, 6, 10});
  pl.schedule = Schedule::wallclock;
  Timeline tl(pl, t0, wall0);
  check(tl, {{1, 0, 1}});
  tl.pause(t0 + 1);
  check(tl, {{3, 0, 1}});
  tl.resume(t0 + 3);
  check(tl, {{5, 0, 3}, {6, 1, 0}});
}

TEST(Timeline, WallclockJustBeforeTheEpochIsTheCyclesStart) {
  // fmod of a tiny negative time plus the cycle rounds up to the cycle itself: that is position 0.
  Playlist pl = make({4, 6, 10});
  pl.schedule = Schedule::wallclock;
  Timeline tl(pl, t0, -1.0);
  const Cue f = tl.at(t0 + 1, -1e-20);
  EXPECT_EQ(f.item, 0);
  EXPECT_NEAR(f.item_time, 0, 1e-9);
}

TEST(Timeline, ReplaceOfAPlaylistThatDoesNotLoopPlaysTheRestOnce) {
  Timeline tl(make({4, 6, 10}, 0, false), t0, wall0);
  ASSERT_EQ(at(tl, 5).item, 1);
  tl.replace(make({4, 6, 10}, 0, false), t0 + 5);
  check(tl, {{6, 1, 2}, {11, 2, 1}});
  EXPECT_FALSE(at(tl, 19).finished);
  EXPECT_TRUE(at(tl, 21).finished);
}

TEST(Timeline, ReplaceShorterItemMovesOn) {
  Timeline tl(make({10, 10}), t0, wall0);
  at(tl, 7);
  tl.replace(make({5, 10}), t0 + 7);
  check(tl, {{7, 1, 2}});
}

TEST(Timeline, EmptyPlaylistPlaysNothing) {
  Timeline tl(Playlist{}, t0, wall0);
  const Cue f = at(tl, 1);
  EXPECT_EQ(f.item, -1);
  EXPECT_EQ(f.next_item, -1);
  tl.next(t0 + 2);
  tl.previous(t0 + 2);
  tl.restart(t0 + 2);
  EXPECT_EQ(at(tl, 3).item, -1);
  // A playlist that arrives later (a hot reload) starts at its first item.
  tl.replace(make({4, 6}), t0 + 4);
  check(tl, {{4.5, 0, 0.5}, {9, 1, 1}});
}

TEST(Timeline, EmptyWallclockPlaylistPlaysNothing) {
  Playlist empty;
  empty.schedule = Schedule::wallclock;
  Timeline tl(empty, t0, wall0);
  const Cue f = at(tl, 1);
  EXPECT_EQ(f.item, -1);
  EXPECT_EQ(f.next_item, -1);
}

TEST(CameraPath, TurntableStillAndFov) {
  CameraPath turn;
  turn.period_s = 20;
  turn.azimuth_deg = 30;
  turn.fov_deg = 50;
  const std::vector<std::pair<double, double>> table = {{0, 30}, {5, 120}, {16.5, 327}, {20, 30}, {100005, 120}};
  for (const auto& [t, az] : table) {
    SCOPED_TRACE(t);
    const Camera c = camera_at(turn, t);
    EXPECT_NEAR(c.azimuth_deg, az, 1e-9);
    EXPECT_EQ(c.elevation_deg, 20.0);
    EXPECT_EQ(c.distance, 1.0);
    EXPECT_EQ(c.fov_deg, 50.0);
  }
  CameraPath still;
  still.motion = Motion::still;
  still.azimuth_deg = -45;
  for (double t : {0.0, 7.0, 1e6}) EXPECT_NEAR(camera_at(still, t).azimuth_deg, 315, 1e-9);
}

// The azimuth is wrapped into [0, 360): angles within a degree of north are kept as they are.
TEST(CameraPath, AzimuthJustPastNorthIsKept) {
  CameraPath still;
  still.motion = Motion::still;
  for (double az : {0.5, -359.5, 360.5}) {
    SCOPED_TRACE(az);
    still.azimuth_deg = az;
    EXPECT_NEAR(camera_at(still, 1).azimuth_deg, 0.5, 1e-9);
  }
  CameraPath turn;
  turn.azimuth_deg = 0;
  turn.period_s = 36;
  EXPECT_NEAR(camera_at(turn, 0.05).azimuth_deg, 0.5, 1e-9);  // a tenth of a degree per 0.01 s
}

TEST(CameraPath, OrbitThroughKeysThenHolds) {
  CameraPath orbit;
  orbit.motion = Motion::orbit;
  orbit.fov_deg = 40;
  orbit.keys = {{0, 0, 10, 1.2}, {2, 90, 30, 1.0}, {4, 180, 10, 1.2}};
  struct Row {
    double t, az, el, dist;
  };
  // At t = 1: Hermite with tangents 0 (end) and (180 - 0) / 4 = 45 deg/s: 45 - 0.125 * 2 * 45 = 33.75.
  // Elevation and distance peak at the middle key, whose tangent is 0: a plain ease.
  const std::vector<Row> table = {{-1, 0, 10, 1.2},     {0, 0, 10, 1.2},   {1, 33.75, 20, 1.1}, {2, 90, 30, 1.0},
                                  {3, 146.25, 20, 1.1}, {4, 180, 10, 1.2}, {60, 180, 10, 1.2}};
  for (const Row& r : table) {
    SCOPED_TRACE(r.t);
    const Camera c = camera_at(orbit, r.t);
    EXPECT_NEAR(c.azimuth_deg, r.az, 1e-9);
    EXPECT_NEAR(c.elevation_deg, r.el, 1e-9);
    EXPECT_NEAR(c.distance, r.dist, 1e-9);
    EXPECT_EQ(c.fov_deg, 40.0);
  }
}

TEST(CameraPath, OrbitStaysWithinTheKeysRangeAndWrapsAzimuth) {
  CameraPath orbit;
  orbit.motion = Motion::orbit;
  // Uneven spacing makes the spline overshoot below the lowest distance between the last two keys.
  orbit.keys = {{0, 0, 0, 2.0}, {0.1, 400, 89, 0.5}, {10, 720, 89, 0.5}};
  for (double t = 0; t <= 10; t += 0.05) {
    SCOPED_TRACE(t);
    const Camera c = camera_at(orbit, t);
    EXPECT_GE(c.distance, 0.5);
    EXPECT_LE(c.elevation_deg, 89.0);
    EXPECT_GE(c.azimuth_deg, 0.0);
    EXPECT_LT(c.azimuth_deg, 360.0);
  }
  EXPECT_NEAR(camera_at(orbit, 10).azimuth_deg, 0, 1e-9);  // 720 is two turns
}

TEST(Timeline, FrameCameraFollowsTheItem) {
  Playlist pl = make({10, 10});
  pl.items[1].camera.motion = Motion::still;
  pl.items[1].camera.azimuth_deg = 12;
  pl.items[1].camera.elevation_deg = -30;
  Timeline tl(pl, t0, wall0);
  Cue f = at(tl, 5);
  EXPECT_NEAR(f.camera.azimuth_deg, 30 + 90, 1e-9);
  f = at(tl, 15);
  EXPECT_EQ(f.item, 1);
  EXPECT_NEAR(f.camera.azimuth_deg, 12, 1e-9);
  EXPECT_EQ(f.camera.elevation_deg, -30.0);
}

// `player ctl item N`: the item asked for, from its start, now.
TEST(Timeline, AnItemAskedForStartsNowAndThePlaylistGoesOnFromIt) {
  Timeline tl(make({4, 6, 10}), t0, wall0);
  EXPECT_EQ(at(tl, 1).sequence, 1u);
  ASSERT_TRUE(tl.show_item(2, t0 + 2));
  Cue f = at(tl, 2);
  EXPECT_EQ(f.item, 2);
  EXPECT_EQ(f.item_time, 0.0);
  EXPECT_TRUE(f.cut);
  EXPECT_EQ(f.sequence, 2u);
  check(tl, {{11.5, 2, 9.5}, {12.5, 0, 0.5}, {16.5, 1, 0.5}});
  // The item playing, asked for again: its start again.
  ASSERT_TRUE(tl.show_item(1, t0 + 18));
  check(tl, {{18, 1, 0}, {24.5, 2, 0.5}});
}

TEST(Timeline, AnItemThatIsNotThereOrCannotBeShownChangesNothing) {
  Timeline tl(make({4, 6, 10}), t0, wall0);
  EXPECT_EQ(at(tl, 1).item, 0);
  tl.set_playable(1, false);
  EXPECT_FALSE(tl.show_item(1, t0 + 2));
  EXPECT_FALSE(tl.show_item(3, t0 + 2));
  EXPECT_FALSE(tl.show_item(-1, t0 + 2));
  const Cue f = at(tl, 2);
  EXPECT_EQ(f.item, 0);
  EXPECT_EQ(f.item_time, 2.0);
  EXPECT_FALSE(f.cut);
  EXPECT_EQ(f.sequence, 1u);
}

TEST(Timeline, AFinishedPlaylistPlaysAgainFromTheItemAskedFor) {
  Timeline tl(make({4, 6}, 0.0, false), t0, wall0);
  EXPECT_TRUE(at(tl, 30).finished);
  ASSERT_TRUE(tl.show_item(0, t0 + 31));
  check(tl, {{31, 0, 0}, {36, 1, 1}});
  EXPECT_FALSE(at(tl, 40.5).finished);
  EXPECT_TRUE(at(tl, 41.5).finished);
}

TEST(Timeline, AShuffledPassGoesOnFromTheItemAskedForInItsOwnOrder) {
  const std::vector<std::vector<int>> order = passes(7, 5, 2);
  Playlist pl = make(std::vector<double>(5, 1.0));
  pl.shuffle = true;
  pl.seed = 7;
  Timeline tl(pl, t0, wall0);
  EXPECT_EQ(at(tl, 0.5).item, order[0][0]);
  const int asked = order[0][3];
  ASSERT_TRUE(tl.show_item(asked, t0 + 0.75));
  EXPECT_EQ(at(tl, 1.0).item, asked);
  // Then the rest of the first pass in its order, then the second pass.
  EXPECT_EQ(at(tl, 1.8).item, order[0][4]);
  EXPECT_EQ(at(tl, 2.8).item, order[1][0]);
}

TEST(Timeline, AnItemAskedForDetachesAWallclockPlaylist) {
  Playlist pl = make({4, 6, 10});
  pl.schedule = Schedule::wallclock;
  Timeline tl(pl, t0, wall0);
  EXPECT_EQ(at(tl, 1).item, 0);
  ASSERT_TRUE(tl.show_item(2, t0 + 2));
  // On its own clock now: item 2 from its start, not the schedule's item 0.
  check(tl, {{2, 2, 0}, {11.5, 2, 9.5}, {12.5, 0, 0.5}});
  tl.restart(t0 + 13);  // attached again: the schedule's item, 3 s into its slot
  const Cue f = at(tl, 13);
  EXPECT_EQ(f.item, 2);
  EXPECT_NEAR(f.item_time, 3, 1e-9);
}

// Durations that are no binary fractions: a stall that ends on an item boundary lands, within
// rounding, on one of the two items that meet there, and returns (whole passes are skipped by
// division, whose rounding may overshoot by one pass and is stepped back).
TEST(Timeline, AStallThatEndsOnABoundaryLandsBesideItWhateverTheRounding) {
  const std::vector<double> durations = {0.1, 0.2};
  for (int n = 1; n <= 3000; ++n) {
    Timeline tl(make(durations), t0, wall0);
    at(tl, 0);
    // n x 0.1 s, computed as a multiple of the pass where n is one (45 s is one such end).
    const double t = n % 3 == 0 ? (n / 3) * 0.3 : n * 0.1;
    const Cue f = at(tl, t);
    SCOPED_TRACE("t = " + std::to_string(t));
    ASSERT_TRUE(f.item == 0 || f.item == 1);
    const double d = durations[static_cast<std::size_t>(f.item)];
    ASSERT_GE(f.item_time, 0.0);
    ASSERT_LE(f.item_time, d);
    // Where in the 0.3 s pass t lies: 0 (item 0 starts), 0.1 (item 1 starts) or 0.2 (inside item 1).
    const int third = n % 3;
    const double start_of_item = f.item == 0 ? 0.0 : 0.1;
    const double in_pass = start_of_item + f.item_time;
    const double expected = third * 0.1;
    EXPECT_TRUE(std::abs(in_pass - expected) < 1e-6 || (third == 0 && std::abs(in_pass - 0.3) < 1e-6)) << in_pass;
  }
}

// One item on a wallclock schedule: each cycle plays it anew (a cut, the next sequence), also where
// the cycle count's division lands a hair below a whole number (at this wall time, 127499973.99999999
// for the 127499974th cycle).
TEST(Timeline, AOneItemWallclockPlaylistStartsItsItemAnewEachCycle) {
  Playlist pl = make({13.345});
  pl.schedule = Schedule::wallclock;
  const double wall = 1701487146.6378841;
  Timeline tl(pl, t0, wall);
  const Cue first = tl.at(t0, wall);
  const Cue same = tl.at(t0 + 1.0, wall + 1.0);
  EXPECT_FALSE(same.cut);
  EXPECT_EQ(same.sequence, first.sequence);
  const Cue next = tl.at(t0 + 13.345, wall + 13.345);
  EXPECT_EQ(next.item, 0);
  EXPECT_NEAR(next.item_time, first.item_time, 1e-6);
  EXPECT_TRUE(next.cut);
  EXPECT_EQ(next.sequence, first.sequence + 1);
}
