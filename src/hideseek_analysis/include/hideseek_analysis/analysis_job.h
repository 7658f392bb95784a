// One analysis, start to finish: read a recording, extract what the statistics need, write the
// report. Shared by the analysis node (after it recorded) and analyze_bag (an existing bag).
#pragma once

#include <string>

#include "hideseek_analysis/analysis_inputs.h"
#include "hideseek_game/game_options.h"

namespace hideseek_analysis {

struct AnalysisJob {
  std::string bag;            // a recording holding world/steps
  std::string policy;         // the checkpoint that played it
  std::string inputs_dir;     // receives the arrays (large: features of every recorded image)
  std::string report_dir;     // receives the report (tables and figures)
  std::string report_script;  // report.py
  hideseek_game::VariantConfig variant;
  AnalysisInputsOptions inputs;
  int tsne_samples = 3000;
  int probe_splits = 5;  // train/test splits by episode each probe is scored over
};

// Runs the job, printing progress; throws (MissingStepsError for a recording with a hole,
// std::runtime_error otherwise) with a message that names the file at fault.
void runAnalysis(const AnalysisJob& job);

}  // namespace hideseek_analysis
