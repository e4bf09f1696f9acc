#include "core/progress.h"

#include <gtest/gtest.h>

namespace cpgi {
namespace {

struct Recorder {
  double now = 0.0;
  std::string text;
  ProgressPrinter make(bool live, double period) {
    return ProgressPrinter(
        {.live = live, .periodSeconds = period}, [this](const std::string& t) { text += t; },
        [this] { return now; });
  }
};

// The clock at `t` seconds, then the ticker's turn.
void tickAt(Recorder& r, ProgressPrinter& p, double t) {
  r.now = t;
  p.tick();
}

TEST(Progress, DurationsReadLikeAPersonWouldSayThem) {
  EXPECT_EQ(formatDuration(0.4), "0 s");
  EXPECT_EQ(formatDuration(42.0), "42 s");
  EXPECT_EQ(formatDuration(200.0), "3 min 20 s");
  EXPECT_EQ(formatDuration(3900.0), "1 h 05 min");
  EXPECT_EQ(formatDuration(-1.0), "");
}

TEST(Progress, LineHasStagePercentStatusAndTimeLeft) {
  // A quarter done in 10 s: 30 s left.
  EXPECT_EQ(ProgressPrinter::line({"atlas", 0.25, "shots 12"}, 10.0), "atlas  25% shots 12, 30 s left");
  // Too early to tell: the time so far; finished: neither.
  EXPECT_EQ(ProgressPrinter::line({"atlas", 0.004, ""}, 10.0), "atlas   0%, 10 s so far");
  EXPECT_EQ(ProgressPrinter::line({"load", 0.0, "a.glb"}, 0.5), "load   0% a.glb");
  EXPECT_EQ(ProgressPrinter::line({"views", 1.0, "A"}, 10.0), "views 100% A");
  // The stage's own estimate wins over the extrapolation, from its first report, less the time since.
  Progress own{"solve", 0.5, "shots 3"};
  own.secondsLeft = 9.0;
  EXPECT_EQ(ProgressPrinter::line(own, 10.0), "solve  50% shots 3, 9 s left");
  EXPECT_EQ(ProgressPrinter::line(own, 12.0, 2.0), "solve  50% shots 3, 7 s left");
  own.fraction = 0.0;
  EXPECT_EQ(ProgressPrinter::line(own, 0.0), "solve   0% shots 3, 9 s left");
  // A stage that models its own time left is never extrapolated from its fraction (a solve's log scale
  // said 5 s where 11 s were left), even before its model has a figure.
  own.secondsLeft = -1.0;
  own.ownsTimeLeft = true;
  own.fraction = 0.2;
  EXPECT_EQ(ProgressPrinter::line(own, 3.0), "solve  20% shots 3, 3 s so far");
}

TEST(Progress, PlainLinesShowAStageAfterItsFirstSecondThenEveryPeriod) {
  Recorder r;
  ProgressPrinter p = r.make(false, 10.0);
  r.now = 1.0;
  p.report({"atlas", 0.1, ""});
  r.now = 1.5;
  p.report({"atlas", 1.0, ""});  // over in half a second: no line
  p.report({"solve", 0.1, ""});
  r.now = 2.0;
  p.report({"solve", 0.2, ""});
  EXPECT_EQ(r.text, "");
  r.now = 2.6;
  p.report({"solve", 0.3, "round 2"});  // 1.1 s into the stage: its first line
  EXPECT_EQ(r.text, "progress: solve  30% round 2, 3 s left\n");
  r.text.clear();
  r.now = 9.0;
  p.report({"solve", 0.5, ""});
  EXPECT_EQ(r.text, "");  // then one a period
  r.now = 12.7;
  p.report({"solve", 0.6, ""});
  EXPECT_EQ(r.text, "progress: solve  60%, 7 s left\n");
}

// Between reports the ticker shows a stage that says nothing for a while (the loader): its first line
// after a second, then one a period with the time so far; a finished stage is not repeated.
TEST(Progress, TheTickerShowsAQuietStage) {
  Recorder r;
  ProgressPrinter p = r.make(false, 5.0);
  p.report({"load", 0.0, "house.glb"});
  tickAt(r, p, 0.5);
  EXPECT_EQ(r.text, "");
  tickAt(r, p, 1.2);
  EXPECT_EQ(r.text, "progress: load   0% house.glb, 1 s so far\n");
  tickAt(r, p, 3.0);
  tickAt(r, p, 6.3);
  EXPECT_EQ(r.text, "progress: load   0% house.glb, 1 s so far\nprogress: load   0% house.glb, 6 s so far\n");
  r.text.clear();
  p.report({"views", 1.0, "A written"});
  tickAt(r, p, 30.0);
  EXPECT_EQ(r.text, "");  // over as it began: neither shown late nor repeated
}

// On a terminal the ticker redraws the live line when its text changes (the time so far), not otherwise.
TEST(Progress, TheTickerRedrawsALiveLineWhenItsTextChanges) {
  Recorder r;
  ProgressPrinter p = r.make(true, 5.0);
  p.report({"load", 0.0, "house.glb"});
  tickAt(r, p, 0.5);
  EXPECT_EQ(r.text, "\rload   0% house.glb\033[K");
  tickAt(r, p, 1.2);
  tickAt(r, p, 1.3);
  EXPECT_EQ(r.text, "\rload   0% house.glb\033[K\rload   0% house.glb, 1 s so far\033[K");
}

// A pre-pass's solve is shown as its stage: never "solve 0% -> 100%" before the bake's solve, and its
// shots and time left are not the bake's.
TEST(Progress, AStageScopeRenamesWhatRunsInside) {
  std::vector<Progress> seen;
  Context ctx;
  ctx.setProgress([&](const Progress& p) { seen.push_back(p); });
  {
    const ProgressStage stage(ctx, "auto density", "a pilot");
    Progress inner{"solve", 0.4, "shots 2"};
    inner.shots = 2;
    inner.secondsLeft = 3.0;
    ctx.progress(inner);
    ctx.progress("auto density", 0.5, "layout");
  }
  ctx.progress("solve", 0.1, "shots 1");
  ASSERT_EQ(seen.size(), 4u);
  EXPECT_EQ(ProgressPrinter::line(seen[0], 0.0), "auto density   0% a pilot");
  EXPECT_EQ(ProgressPrinter::line(seen[1], 0.0), "auto density  40% solve: shots 2");
  EXPECT_LT(seen[1].shots, 0);
  EXPECT_LT(seen[1].secondsLeft, 0.0);
  EXPECT_EQ(ProgressPrinter::line(seen[2], 0.0), "auto density  50% layout");
  EXPECT_EQ(seen[3].stage, "solve");  // the scope's end gives the reports back
}

TEST(Progress, PeriodZeroPrintsEveryCall) {
  Recorder r;
  ProgressPrinter p = r.make(false, 0.0);
  p.report({"a", 0.5, ""});
  p.report({"a", 1.0, ""});
  EXPECT_EQ(r.text, "progress: a  50%\nprogress: a 100%\n");
}

TEST(Progress, LiveLineIsRewrittenAndEndsWithItsStage) {
  Recorder r;
  ProgressPrinter p = r.make(true, 10.0);
  p.report({"solve", 0.5, ""});
  p.report({"solve", 1.0, ""});
  p.report({"views", 0.5, "A"});
  r.now = 2.0;
  p.report({"write", 0.5, ""});
  EXPECT_EQ(r.text, "\rsolve  50%\033[K\rsolve 100%\033[K\n\rviews  50% A\033[K\n\rwrite  50%\033[K");
}

TEST(Progress, AStageThatStartsOverIsTimedAfresh) {
  Recorder r;
  ProgressPrinter p = r.make(false, 0.0);
  p.report({"solve", 0.9, ""});
  r.now = 100.0;
  p.report({"solve", 0.1, ""});  // the next cell's solve: 0.1 in 0 s, no estimate from the first's 100 s
  r.now = 102.0;
  p.report({"solve", 0.5, ""});
  EXPECT_EQ(r.text, "progress: solve  90%\nprogress: solve  10%\nprogress: solve  50%, 2 s left\n");
}

}  // namespace
}  // namespace cpgi
