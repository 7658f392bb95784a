// Default topic and service names of the game graph; launch files remap them.
#pragma once

#include <string>

namespace hideseek_game {

constexpr char kHiderObservationsTopic[] = "hider/observations";
constexpr char kSeekerObservationsTopic[] = "seeker/observations";
constexpr char kHiderActionsTopic[] = "hider/actions";
constexpr char kSeekerActionsTopic[] = "seeker/actions";
constexpr char kHiderImageTopic[] = "hider/camera/image_raw";
constexpr char kSeekerImageTopic[] = "seeker/camera/image_raw";
constexpr char kMarkersTopic[] = "world/markers";
constexpr char kMapTopic[] = "map";
constexpr char kHiderPathTopic[] = "hider/path";
constexpr char kSeekerPathTopic[] = "seeker/path";
constexpr char kSeekerPlanTopic[] = "seeker/plan";      // the scripted seeker's planned path (arena 0)
constexpr char kSeekerTargetTopic[] = "seeker/target";  // the path point it heads for (arena 0)
constexpr char kGameStateTopic[] = "game_state";
constexpr char kEpisodesTopic[] = "world/episodes";
constexpr char kStepsTopic[] = "world/steps";
constexpr char kResetService[] = "world/reset";

// Name of the world's diagnostic status on /diagnostics. A game in a namespace other than the
// root says which, so that two games on one master report apart.
inline std::string worldDiagnosticName(const std::string& ns) {
  return ns.empty() || ns == "/" ? "hideseek world: input" : "hideseek world " + ns + ": input";
}

}  // namespace hideseek_game
