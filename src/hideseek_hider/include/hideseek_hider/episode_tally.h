// Collects the outcomes of the episodes with seeds first_seed..first_seed+N-1.
#pragma once

#include <cstdint>
#include <map>
#include <string>

namespace hideseek_hider {

struct EpisodeRecord {
  uint32_t seed = 0;
  uint32_t living_steps = 0;
  bool survived = false;
};

struct EvaluationSummary {
  int episodes = 0;
  double avg_living_steps = 0.0;
  double success_rate = 0.0;  // fraction of episodes that reached the step limit
};

// Feed it the world's episode results (world/episodes); it keeps the first result of each seed
// in first_seed..first_seed+N-1 and ignores the rest.
class EpisodeTally {
 public:
  explicit EpisodeTally(uint32_t episodes, uint32_t first_seed = 0) : wanted_(episodes), first_seed_(first_seed) {}

  void record(uint32_t seed, uint32_t living_steps, bool survived);
  bool complete() const { return records_.size() >= wanted_; }
  size_t collected() const { return records_.size(); }
  const std::map<uint32_t, EpisodeRecord>& records() const { return records_; }
  EvaluationSummary summary() const;

 private:
  uint32_t wanted_;
  uint32_t first_seed_;
  std::map<uint32_t, EpisodeRecord> records_;
};

// episodes.csv: one row per episode in seed order (columns seed,living_steps,outcome; outcome is
// captured or survived), so that single episodes can be compared and replayed.
std::string episodesCsv(const std::map<uint32_t, EpisodeRecord>& records);

// evaluation.csv (columns variant,policy,episodes,avg_living_steps,success_rate,game: the game last,
// so that the columns of evaluations written before it came keep their places) and evaluation.md
// (variant, game, policy, ...). `game` is the game played, as config/games.yaml or a game file names it.
std::string evaluationCsv(const std::string& variant, const std::string& policy, const std::string& game,
                          const EvaluationSummary& s);
std::string evaluationMarkdown(const std::string& variant, const std::string& policy, const std::string& game,
                               const EvaluationSummary& s);

}  // namespace hideseek_hider
