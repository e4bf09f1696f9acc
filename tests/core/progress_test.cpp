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

TEST(Progress, DurationsReadLikeAPersonWouldSayThem) {
  EXPECT_EQ(formatDuration(0.4), "0 s");
  EXPECT_EQ(formatDuration(42.0), "42 s");
  EXPECT_EQ(formatDuration(200.0), "3 min 20 s");
  EXPECT_EQ(formatDuration(3900.0), "1 h 05 min");
  EXPECT_EQ(formatDuration(-1.0), "");
}

TEST(Progress, LineHasStagePercentStatusAndTimeLeft) {
  // A quarter done in 10 s: 30 s left.
  EXPECT_EQ(ProgressPrinter::line({"solve", 0.25, "shots 12"}, 10.0), "solve  25% shots 12, 30 s left");
  // Too early to tell, or finished: no time left.
  EXPECT_EQ(ProgressPrinter::line({"solve", 0.004, ""}, 10.0), "solve   0%");
  EXPECT_EQ(ProgressPrinter::line({"views", 1.0, "A"}, 10.0), "views 100% A");
  // The stage's own estimate wins over the extrapolation, from its first report.
  Progress own{"solve", 0.5, "shots 3"};
  own.secondsLeft = 9.0;
  EXPECT_EQ(ProgressPrinter::line(own, 10.0), "solve  50% shots 3, 9 s left");
  own.fraction = 0.0;
  EXPECT_EQ(ProgressPrinter::line(own, 0.0), "solve   0% shots 3, 9 s left");
}

TEST(Progress, PlainLinesComeEveryPeriodOnly) {
  Recorder r;
  ProgressPrinter p = r.make(false, 10.0);
  r.now = 1.0;
  p.report({"solve", 0.1, ""});
  r.now = 9.0;
  p.report({"solve", 0.5, ""});
  EXPECT_EQ(r.text, "");  // a short run prints nothing
  r.now = 10.5;
  p.report({"solve", 0.6, "round 2"});
  // 0.6 done 9.5 s after the stage began: 6.3 s left.
  EXPECT_EQ(r.text, "progress: solve  60% round 2, 6 s left\n");
  r.now = 15.0;
  p.report({"solve", 0.7, ""});
  r.now = 21.0;
  p.report({"views", 0.5, "A"});
  EXPECT_EQ(r.text, "progress: solve  60% round 2, 6 s left\nprogress: views  50% A\n");
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
