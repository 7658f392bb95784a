#include "hideseek_hider/episode_tally.h"

#include <cstdio>

namespace hideseek_hider {

void EpisodeTally::record(uint32_t seed, uint32_t living_steps, bool survived) {
  if (seed < first_seed_ || seed - first_seed_ >= wanted_ || records_.count(seed)) return;
  records_[seed] = {seed, living_steps, survived};
}

EvaluationSummary EpisodeTally::summary() const {
  EvaluationSummary s;
  s.episodes = static_cast<int>(records_.size());
  if (records_.empty()) return s;
  double steps = 0.0, wins = 0.0;
  for (const auto& [seed, r] : records_) {
    steps += r.living_steps;
    wins += r.survived;
  }
  s.avg_living_steps = steps / s.episodes;
  s.success_rate = wins / s.episodes;
  return s;
}

std::string episodesCsv(const std::map<uint32_t, EpisodeRecord>& records) {
  std::string out = "seed,living_steps,outcome\n";
  for (const auto& [seed, r] : records) {
    out += std::to_string(seed) + ',' + std::to_string(r.living_steps) + ',' + (r.survived ? "survived" : "captured") +
           '\n';
  }
  return out;
}

std::string evaluationCsv(const std::string& variant, const std::string& policy, const std::string& game,
                          const EvaluationSummary& s) {
  char numbers[64];
  std::snprintf(numbers, sizeof(numbers), "%d,%.2f,%.4f", s.episodes, s.avg_living_steps, s.success_rate);
  return "variant,policy,episodes,avg_living_steps,success_rate,game\n" + variant + "," + policy + "," + numbers + "," +
         game + "\n";
}

std::string evaluationMarkdown(const std::string& variant, const std::string& policy, const std::string& game,
                               const EvaluationSummary& s) {
  char numbers[96];
  std::snprintf(numbers, sizeof(numbers), "%d | %.1f | %.2f %%", s.episodes, s.avg_living_steps,
                100.0 * s.success_rate);
  return "| variant | game | policy | episodes | average living steps | success rate |\n"
         "| --- | --- | --- | --- | --- | --- |\n| " +
         variant + " | " + game + " | " + policy + " | " + numbers + " |\n";
}

}  // namespace hideseek_hider
