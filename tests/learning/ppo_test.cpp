// PpoLearner: it solves a contextual bandit with a known optimum; it is
// deterministic for a seed and resumes from a checkpoint bit for bit; its
// actor becomes a policy file that gives the same actions; a zero last layer
// starts at exactly zero; the learning rate follows the KL.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "pronk/error.h"
#include "pronk/policy.h"
#include "pronk/ppo.h"

namespace {

namespace fs = std::filesystem;
using pronk::PpoConfig;
using pronk::PpoLearner;

// r = exp(-|a - (A o + b)|^2 / sigma^2) for o in [-1, 1]^2: the best action
// is A o + b, where r = 1.
struct Bandit {
  Eigen::Matrix2d a;
  Eigen::Vector2d b;
  double sigma = 1.0;

  Bandit() {
    a << 0.8, -0.4,
         0.3, 0.6;
    b << 0.5, -0.3;
  }
  Eigen::MatrixXd optimum(const Eigen::MatrixXd& o) const { return (a * o).colwise() + b; }
  Eigen::VectorXd reward(const Eigen::MatrixXd& o, const Eigen::MatrixXd& actions) const {
    return (-(actions - optimum(o)).colwise().squaredNorm().array() / (sigma * sigma)).exp().transpose();
  }
  static Eigen::MatrixXd observations(int n, pronk::Rng& rng) {
    Eigen::MatrixXd o(2, n);
    for (Eigen::Index i = 0; i < o.size(); ++i) o.data()[i] = 2 * rng.uniform() - 1;
    return o;
  }
};

PpoConfig smallConfig() {
  PpoConfig c;
  c.actor_hidden_sizes = {64, 64};
  c.critic_hidden_sizes = {64, 64};
  c.epochs = 5;
  c.minibatches = 4;
  return c;
}

// One iteration: observations from env_rng, actions from the learner.
pronk::PpoUpdateStats iterate(PpoLearner& learner, const Bandit& bandit, pronk::Rng& env_rng, int batch) {
  pronk::PpoBatch b;
  b.observations = Bandit::observations(batch, env_rng);
  const pronk::PpoSample s = learner.sample(b.observations);
  b.actions = s.actions;
  b.log_probs = s.log_probs;
  b.rewards = bandit.reward(b.observations, b.actions);
  return learner.update(b);
}

// The root-mean-square distance of the mean action from the optimum.
double rmsError(const PpoLearner& learner, const Bandit& bandit, const Eigen::MatrixXd& o) {
  return std::sqrt((learner.means(o) - bandit.optimum(o)).squaredNorm() / static_cast<double>(o.cols()));
}

TEST(PpoLearner, SolvesAContextualBanditWithAKnownOptimum) {
  const Bandit bandit;
  PpoLearner learner(smallConfig(), 2, 2, 1);
  pronk::Rng env_rng(2), held_out_rng(99);
  const Eigen::MatrixXd held_out = Bandit::observations(1000, held_out_rng);
  const double initial_rms = rmsError(learner, bandit, held_out);

  const int iterations = 150, batch = 256;
  const auto start = std::chrono::steady_clock::now();
  pronk::PpoUpdateStats stats;
  for (int i = 0; i < iterations; ++i) stats = iterate(learner, bandit, env_rng, batch);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const double rms = rmsError(learner, bandit, held_out);
  const double worst = (learner.means(held_out) - bandit.optimum(held_out)).colwise().norm().maxCoeff();
  const double mean_action_reward = bandit.reward(held_out, learner.means(held_out)).mean();
  std::printf("bandit: %d iterations x %d samples, %.2f s; held-out |mean - optimum| rms %.4f (at the start %.4f), "
              "max %.4f; reward of the mean %.4f, of the exploring batch %.4f; std %.3f; lr %.2e\n",
              iterations, batch, seconds, rms, initial_rms, worst, mean_action_reward, stats.reward_mean,
              stats.std_mean, stats.learning_rate);
  // Seeds 1-8 measured: rms 0.018-0.036, max 0.047-0.115, reward of the mean
  // >= 0.9987, of the exploring batch 0.947-0.969, std 0.127-0.164.
  EXPECT_GT(initial_rms, 0.5);  // the start is far from the optimum
  EXPECT_LT(rms, 0.06);
  EXPECT_LT(worst, 0.2);
  EXPECT_GT(mean_action_reward, 0.995);
  EXPECT_GT(stats.reward_mean, 0.85);
  EXPECT_LT(stats.std_mean, 0.3);  // from 1.0: exploration narrowed
}

TEST(PpoLearner, IsDeterministicForASeed) {
  PpoConfig c = smallConfig();
  c.actor_hidden_sizes = c.critic_hidden_sizes = {16, 16};
  const Bandit bandit;
  PpoLearner a(c, 2, 2, 7), b(c, 2, 2, 7), other(c, 2, 2, 8);
  pronk::Rng ra(3), rb(3), ro(3);
  for (int i = 0; i < 3; ++i) {
    iterate(a, bandit, ra, 64);
    iterate(b, bandit, rb, 64);
    iterate(other, bandit, ro, 64);
  }
  EXPECT_EQ(a.actor().parameters(), b.actor().parameters());
  EXPECT_EQ(a.critic().parameters(), b.critic().parameters());
  EXPECT_EQ(a.checkpoint().dump(), b.checkpoint().dump());
  EXPECT_NE(a.actor().parameters(), other.actor().parameters());
}

TEST(PpoLearner, ResumedFromACheckpointEqualsAnUninterruptedRunBitForBit) {
  PpoConfig c = smallConfig();
  c.actor_hidden_sizes = c.critic_hidden_sizes = {16, 16};
  c.actor_init = pronk::MlpInit::orthogonal(0.01);
  const Bandit bandit;
  const int k = 3;
  // The environment's generator is the test's, seeded per iteration, so both
  // runs see the same observations without checkpointing it.
  const auto run = [&](PpoLearner& learner, int from, int to) {
    for (int i = from; i < to; ++i) {
      pronk::Rng env(1000 + static_cast<unsigned>(i));
      iterate(learner, bandit, env, 64);
    }
  };
  PpoLearner straight(c, 2, 2, 5);
  run(straight, 0, 2 * k);

  PpoLearner first(c, 2, 2, 5);
  run(first, 0, k);
  const fs::path path = fs::path(PRONK_BINARY_DIR) / "tests" / "learning" / "ppo_resume.json";
  pronk::savePpoCheckpoint(first, path.string());
  PpoLearner resumed = pronk::loadPpoCheckpoint(path.string());
  EXPECT_EQ(resumed.iteration(), k);
  run(resumed, k, 2 * k);

  EXPECT_EQ(resumed.actor().parameters(), straight.actor().parameters());
  EXPECT_EQ(resumed.critic().parameters(), straight.critic().parameters());
  EXPECT_EQ(resumed.actorOptimizer().state().second_moment, straight.actorOptimizer().state().second_moment);
  EXPECT_EQ(resumed.learningRate(), straight.learningRate());
  EXPECT_EQ(resumed.rng().state(), straight.rng().state());
  EXPECT_EQ(resumed.checkpoint().dump(), straight.checkpoint().dump());  // everything else too
  fs::remove(path);
}

TEST(PpoLearner, CheckpointErrorsNameTheKey) {
  PpoLearner learner(smallConfig(), 2, 2, 1);
  nlohmann::json doc = learner.checkpoint();
  doc["actor"]["parameters"].erase(0);
  try {
    PpoLearner::fromCheckpoint(doc);
    FAIL() << "no error";
  } catch (const pronk::Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("checkpoint: actor.parameters: ", 0), 0u) << e.what();
  }
  doc = learner.checkpoint();
  doc["rng"][2] = "not hex at all!!";
  EXPECT_THROW(PpoLearner::fromCheckpoint(doc), pronk::Error);
  doc = learner.checkpoint();
  doc["format"] = "pronk-policy";
  EXPECT_THROW(PpoLearner::fromCheckpoint(doc), pronk::Error);
}

TEST(PpoLearner, PolicyFileReproducesTheActorsMeanActionBitForBit) {
  const Bandit bandit;
  PpoConfig c = smallConfig();
  Eigen::VectorXd low(2), high(2);
  low << -1, -2;
  high << 1, 3;
  PpoLearner learner(c, pronk::ObservationScaling::fromBox(low, high), 2, 4);
  pronk::Rng env(6);
  for (int i = 0; i < 2; ++i) iterate(learner, bandit, env, 64);

  const fs::path path = fs::path(PRONK_BINARY_DIR) / "tests" / "learning" / "ppo_policy.json";
  pronk::savePolicy(learner.policy(), path.string());
  const pronk::MlpPolicy loaded = pronk::loadPolicy(path.string());
  fs::remove(path);
  EXPECT_EQ(loaded.actionLogStd(), learner.actor().logStd());
  EXPECT_EQ(loaded.observationMean(), learner.scaling().mean());

  const PpoLearner restarted = PpoLearner::fromPolicy(c, loaded, 4);
  const Eigen::MatrixXd o = Bandit::observations(20, env);
  for (Eigen::Index j = 0; j < o.cols(); ++j) {
    const Eigen::VectorXd obs = o.col(j);
    EXPECT_EQ(loaded.act(obs), learner.mean(obs));
    EXPECT_EQ(restarted.mean(obs), learner.mean(obs));
  }
  EXPECT_EQ(restarted.actor().parameters(), learner.actor().parameters());
}

TEST(PpoLearner, ZeroInitialisedActorStartsAtExactlyZero) {
  PpoConfig c = smallConfig();
  c.actor_init.zero_last_layer = true;
  const PpoLearner learner(c, 2, 13, 3);
  pronk::Rng env(1);
  const Eigen::MatrixXd means = learner.means(Bandit::observations(50, env));
  EXPECT_EQ(means, Eigen::MatrixXd::Zero(13, 50));
  EXPECT_EQ(learner.policy().act(Eigen::Vector2d(0.3, -0.9)), Eigen::VectorXd::Zero(13));
}

TEST(PpoLearner, CriticWarmUpFitsTheValueAndLeavesTheActorAlone) {
  PpoLearner learner(smallConfig(), 2, 2, 5);
  pronk::Rng env(2);
  const Bandit bandit;
  const Eigen::MatrixXd o = Bandit::observations(256, env);
  const Eigen::VectorXd rewards = bandit.reward(o, bandit.optimum(o) * 0.5);
  const auto valueError = [&] { return (learner.values(o) - rewards).squaredNorm() / static_cast<double>(o.cols()); };
  const double before = valueError();
  const Eigen::VectorXd actor_before = learner.actor().parameters();
  const double rate = learner.learningRate();
  const double last_epoch_loss = learner.fitCritic(o, rewards, 30);
  EXPECT_LT(valueError(), 0.1 * before) << "before " << before;
  EXPECT_LT(last_epoch_loss, 0.2 * before);
  EXPECT_EQ(learner.actor().parameters(), actor_before);
  EXPECT_EQ(learner.learningRate(), rate);
  EXPECT_EQ(learner.iteration(), 0);
  EXPECT_EQ(learner.criticOptimizer().state().step, 30 * smallConfig().minibatches);
}

// Hindsight and behaviour cloning: fitMean regresses the mean onto given
// actions (here the bandit's optimum, a known linear map) and touches nothing else.
TEST(PpoLearner, FitMeanRegressesTheMeanOntoGivenActionsAndLeavesTheRestAlone) {
  PpoConfig c = smallConfig();
  c.actor_init.zero_last_layer = true;
  PpoLearner learner(c, 2, 2, 6);
  pronk::Rng env(4);
  const Bandit bandit;
  const Eigen::MatrixXd o = Bandit::observations(512, env);
  const Eigen::MatrixXd held_out = Bandit::observations(200, env);
  const double before = rmsError(learner, bandit, held_out);
  const Eigen::VectorXd log_std = learner.actor().logStd();
  const Eigen::VectorXd critic = learner.critic().parameters();
  const double rate = learner.learningRate();
  const double loss = learner.fitMean(o, bandit.optimum(o), 60, 64, 3e-3);
  EXPECT_LT(rmsError(learner, bandit, held_out), 0.05 * before) << "before " << before;
  EXPECT_LT(loss, 1e-2);
  EXPECT_EQ(learner.actor().logStd(), log_std);
  EXPECT_EQ(learner.critic().parameters(), critic);
  EXPECT_EQ(learner.learningRate(), rate);
  EXPECT_EQ(learner.iteration(), 0);
  EXPECT_EQ(learner.meanFitOptimizer().state().step, 60 * 8);
  EXPECT_EQ(learner.actorOptimizer().state().step, 0) << "PPO's own Adam is not stepped";
  // Its Adam travels with the checkpoint.
  const PpoLearner back = PpoLearner::fromCheckpoint(learner.checkpoint());
  EXPECT_EQ(back.meanFitOptimizer().state().first_moment, learner.meanFitOptimizer().state().first_moment);
  EXPECT_EQ(back.meanFitOptimizer().state().step, learner.meanFitOptimizer().state().step);
  EXPECT_THROW(learner.fitMean(o, bandit.optimum(o).topRows(1), 1, 64, 1e-3), pronk::Error);
}

TEST(PpoLearner, WithoutActorUpdatesPpoStepsTheCriticOnly) {
  PpoConfig c = smallConfig();
  c.update_actor = false;
  PpoLearner learner(c, 2, 2, 7);
  pronk::Rng env(5);
  const Bandit bandit;
  const Eigen::VectorXd actor = learner.actor().parameters();
  const Eigen::VectorXd critic = learner.critic().parameters();
  iterate(learner, bandit, env, 128);
  EXPECT_EQ(learner.actor().parameters(), actor);
  EXPECT_NE(learner.critic().parameters(), critic);
  EXPECT_FALSE(PpoLearner::fromCheckpoint(learner.checkpoint()).config().update_actor);
}

TEST(AdaptiveLearningRate, FollowsRslRlsRule) {
  const PpoConfig c;  // desired KL 0.01, bounds 1e-5 .. 1e-2
  EXPECT_DOUBLE_EQ(pronk::adaptLearningRate(1e-3, 0.03, c), 1e-3 / 1.5);   // kl > 2 target
  EXPECT_DOUBLE_EQ(pronk::adaptLearningRate(1e-3, 0.004, c), 1.5e-3);      // kl < target / 2
  EXPECT_EQ(pronk::adaptLearningRate(1e-3, 0.01, c), 1e-3);                // in between
  EXPECT_EQ(pronk::adaptLearningRate(1e-3, 0.0, c), 1e-3);                 // no change, no KL: kept
  EXPECT_EQ(pronk::adaptLearningRate(1e-2, 0.001, c), 1e-2);               // bounded above
  EXPECT_EQ(pronk::adaptLearningRate(1.2e-5, 1.0, c), 1e-5);               // and below
}

TEST(AdaptiveLearningRate, FallsWhenStepsAreTooLargeAndRisesWhenTheyAreSmall) {
  const Bandit bandit;
  PpoConfig c = smallConfig();
  c.actor_hidden_sizes = c.critic_hidden_sizes = {16, 16};
  c.learning_rate = 1e-2;  // large steps: the KL overshoots
  PpoLearner fast(c, 2, 2, 1);
  pronk::Rng env(1);
  const pronk::PpoUpdateStats big = iterate(fast, bandit, env, 256);
  EXPECT_GT(big.kl, 2 * c.desired_kl);
  EXPECT_LT(big.learning_rate, 1e-2);

  c.learning_rate = 1e-5;  // tiny steps: the KL stays far below the target
  PpoLearner slow(c, 2, 2, 1);
  const pronk::PpoUpdateStats small = iterate(slow, bandit, env, 256);
  EXPECT_GT(small.learning_rate, 1e-5);
}

}  // namespace
