// Pareto fronts (tune/front.hpp): what the front holds, and that it depends on the seed alone --
// not on the threads, not on the ranks sharing the runs, not on a stop and a resume.
#include "fuzzypid/tune/front.hpp"

#include <gtest/gtest.h>

#include <condition_variable>
#include <deque>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "fuzzypid/controller/families.hpp"
#include "fuzzypid/controller_file/controller_file.hpp"
#include "fuzzypid/robot/robot_model.hpp"
#include "fuzzypid/sim/experiment.hpp"

namespace {

namespace cf = fuzzypid::controller_file;
namespace controller = fuzzypid::controller;
namespace tune = fuzzypid::tune;

TEST(NonDominated, KeepsExactlyTheMembersNoOtherBeatsAndTheFirstOfEqualOnes) {
  const std::vector<std::vector<double>> f = {{1, 5}, {2, 2}, {5, 1},  {3, 3},
                                              {2, 2}, {1, 6}, {0.5, 9}};
  // {3,3} is dominated by {2,2}; the second {2,2} is a repeat; {1,6} is dominated by {1,5}.
  EXPECT_EQ(tune::non_dominated(f), (std::vector<std::size_t>{0, 1, 2, 6}));
}

// Two ranks in one process: rank 1 serves in a thread, messages pass through queues.
class ThreadRanks {
 public:
  tune::Transport rank(int r) {
    tune::Transport t;
    t.rank = r;
    t.size = 2;
    t.send = [this, r](int to, const std::vector<double>& m) { push(box(r, to), m); };
    t.receive = [this, r](int from) { return pop(box(from, r)); };
    return t;
  }

 private:
  struct Box {
    std::mutex mutex;
    std::condition_variable ready;
    std::deque<std::vector<double>> messages;
  };
  Box& box(int from, int to) { return boxes_[from * 2 + to]; }
  static void push(Box& b, const std::vector<double>& m) {
    {
      const std::lock_guard<std::mutex> lock(b.mutex);
      b.messages.push_back(m);
    }
    b.ready.notify_one();
  }
  static std::vector<double> pop(Box& b) {
    std::unique_lock<std::mutex> lock(b.mutex);
    b.ready.wait(lock, [&] { return !b.messages.empty(); });
    std::vector<double> m = b.messages.front();
    b.messages.pop_front();
    return m;
  }
  Box boxes_[4];
};

class FrontOnTheRobot : public ::testing::Test {
 protected:
  void SetUp() override {
    fuzzypid::sim::Condition behind, ahead, held;
    behind.name = "behind";
    ahead.name = "ahead";
    ahead.initial_error_rad = -0.05;
    ahead.payload_scale = 2.0;
    held.name = "held";
    held.payload_scale = 1.3;
    held.initial_error_rad = 0.03;
    conditions_ = {behind, ahead, held};
    std::string error;
    set_ = fuzzypid::sim::ExperimentSet::create(conditions_, {}, error);
    ASSERT_TRUE(set_) << error;
  }

  tune::FrontOptions options(unsigned threads) const {
    tune::FrontOptions o;
    o.tune.family = *controller::parse_family("pid");
    o.tune.budget = 40;  // the first population and 4 generations of 8
    o.tune.population = 8;
    o.tune.seed = 5;
    o.tune.threads = threads;
    o.tune.validation = 1;
    o.objectives = {tune::Metric::Itae, tune::Metric::Effort, tune::Metric::Chatter};
    return o;
  }

  std::optional<tune::Front> front(const tune::FrontOptions& o) const {
    std::string error;
    auto f = tune::tune_front(*set_, conditions_, o, error);
    EXPECT_TRUE(f) << error;
    return f;
  }

  // Every point's file (the tuner records no thread count).
  static std::string files(const tune::Front& f) {
    std::string all;
    for (const tune::FrontPoint& p : f.points)
      all += cf::to_toml(cf::ControllerFile{p.controller, p.tuning, std::nullopt});
    return all;
  }

  std::vector<fuzzypid::sim::Condition> conditions_;
  std::optional<fuzzypid::sim::ExperimentSet> set_;
};

TEST_F(FrontOnTheRobot, PointsAreMutuallyNonDominatedAndRecordTheirObjectives) {
  const auto f = front(options(2));
  ASSERT_TRUE(f);
  ASSERT_FALSE(f->points.empty());
  EXPECT_EQ(f->evaluations, 40u);
  EXPECT_EQ(f->generations, 4u);
  std::vector<std::vector<double>> training;
  for (const tune::FrontPoint& p : f->points) {
    ASSERT_EQ(p.training.size(), 3u);
    ASSERT_EQ(p.validation.size(), 3u);
    training.push_back(p.training);
    const auto& rec = p.tuning.front;
    ASSERT_EQ(rec.size(), 3u);
    EXPECT_EQ(rec[0].name, "itae");
    EXPECT_EQ(rec[1].name, "effort");
    EXPECT_EQ(rec[2].name, "chatter");
    for (std::size_t m = 0; m < 3; ++m) {
      EXPECT_EQ(rec[m].training, p.training[m]);
      EXPECT_EQ(rec[m].validation, p.validation[m]);
    }
    EXPECT_GT(p.training[0], 0.0);                                // ITAE of two runs
    EXPECT_TRUE(p.training[1] > 0.0 && p.training[1] < 1.0);      // a share of the limit
    EXPECT_TRUE(p.training[2] >= 0.0 && p.training[2] <= 100.0);  // a share of the ticks, %
  }
  EXPECT_EQ(tune::non_dominated(training).size(), training.size());
  for (std::size_t k = 1; k < training.size(); ++k)
    EXPECT_LE(training[k - 1][0], training[k][0]);  // by training ITAE
}

TEST_F(FrontOnTheRobot, APointsFileReadsBackWithItsObjectivesAndABadEntryIsRefused) {
  const auto f = front(options(1));
  ASSERT_TRUE(f && !f->points.empty());
  cf::ControllerFile point{f->points.front().controller, f->points.front().tuning, std::nullopt};
  point.tuning->conditions = "conditions.toml";  // the caller names them, as for tune()
  point.tuning->set = "training";
  const std::string text = cf::to_toml(point);
  cf::ControllerFile back;
  fuzzypid::FileError error;
  ASSERT_TRUE(cf::parse(text, "point.toml", back, error)) << error.to_string() << "\n" << text;
  ASSERT_TRUE(back.tuning);
  const auto& want = f->points.front().tuning.front;
  ASSERT_EQ(back.tuning->front.size(), want.size());
  for (std::size_t m = 0; m < want.size(); ++m) {
    EXPECT_EQ(back.tuning->front[m].name, want[m].name);
    EXPECT_EQ(back.tuning->front[m].training, want[m].training);
    EXPECT_EQ(back.tuning->front[m].validation, want[m].validation);
  }
  const std::size_t at = text.find("\nfront = [");
  ASSERT_NE(at, std::string::npos);
  std::string bad = text;
  bad.insert(text.find('\n', at + 1) + 1, "  1,\n");  // a number where an entry belongs
  EXPECT_FALSE(cf::parse(bad, "bad.toml", back, error));
  EXPECT_NE(error.to_string().find("front entries must be"), std::string::npos)
      << error.to_string();
}

TEST_F(FrontOnTheRobot, TheFrontIsTheSameWithAnyThreadCount) {
  const auto one = front(options(1));
  const auto two = front(options(2));
  ASSERT_TRUE(one && two);
  EXPECT_EQ(files(*one), files(*two));
}

TEST_F(FrontOnTheRobot, AStoppedAndResumedSearchEndsWhereAnUninterruptedOneEnds) {
  const auto whole = front(options(2));
  ASSERT_TRUE(whole);
  tune::FrontOptions first = options(2);
  std::optional<tune::FrontState> saved;
  first.generation_done = [&](const tune::FrontState& s) {
    saved = s;
    return s.generation < 2;  // stop after generation 2
  };
  const auto stopped = front(first);
  ASSERT_TRUE(stopped && saved);
  EXPECT_TRUE(stopped->stopped);
  EXPECT_TRUE(stopped->points.empty());
  EXPECT_EQ(saved->generation, 2u);
  tune::FrontOptions rest = options(2);
  rest.resume = saved;
  const auto resumed = front(rest);
  ASSERT_TRUE(resumed);
  EXPECT_EQ(files(*resumed), files(*whole));
}

TEST_F(FrontOnTheRobot, AStateOfAnotherSearchIsRefused) {
  tune::FrontOptions o = options(1);
  tune::FrontState s;
  s.generation = 1;
  s.evaluations = 16;
  s.x.assign(8, std::vector<double>(2, 0.0));  // pid searches 4 parameters
  s.f.assign(8, std::vector<double>(3, 0.0));
  o.resume = s;
  std::string error;
  EXPECT_FALSE(tune::tune_front(*set_, conditions_, o, error));
  EXPECT_NE(error.find("not one of this search"), std::string::npos) << error;
}

TEST_F(FrontOnTheRobot, TwoRanksGiveTheFrontOfOne) {
  const auto alone = front(options(1));
  ThreadRanks ranks;
  const tune::Transport r0 = ranks.rank(0), r1 = ranks.rank(1);
  std::optional<tune::Front> served;
  std::thread worker([&] {
    tune::FrontOptions o = options(1);
    o.tune.transport = &r1;
    std::string error;
    served = tune::tune_front(*set_, conditions_, o, error);
  });
  tune::FrontOptions o = options(1);
  o.tune.transport = &r0;
  const auto shared = front(o);
  worker.join();
  ASSERT_TRUE(alone && shared && served);
  EXPECT_TRUE(served->served);
  EXPECT_TRUE(served->points.empty());
  EXPECT_EQ(files(*shared), files(*alone));
}

TEST_F(FrontOnTheRobot, TwoRanksGiveTheOneObjectiveResultOfOne) {
  tune::Options o;
  o.family = *controller::parse_family("scheduled");
  o.budget = 60;
  o.population = 20;
  o.seed = 2;
  o.validation = 1;
  std::string error;
  auto alone = tune::tune(*set_, conditions_, o, error);
  ASSERT_TRUE(alone) << error;
  ThreadRanks ranks;
  const tune::Transport r0 = ranks.rank(0), r1 = ranks.rank(1);
  std::optional<tune::Result> served;
  std::thread worker([&] {
    tune::Options w = o;
    w.transport = &r1;
    std::string e;
    served = tune::tune(*set_, conditions_, w, e);
  });
  o.transport = &r0;
  auto shared = tune::tune(*set_, conditions_, o, error);
  worker.join();
  ASSERT_TRUE(shared && served) << error;
  EXPECT_TRUE(served->served);
  EXPECT_EQ(cf::to_toml(cf::ControllerFile{shared->controller, shared->tuning, std::nullopt}),
            cf::to_toml(cf::ControllerFile{alone->controller, alone->tuning, std::nullopt}));
}

}  // namespace
