// The command line of the project's C++ tools, through Boost.Program_options: named options, the
// positional arguments a tool maps onto some of them, and --help.
#pragma once

#include <boost/program_options.hpp>
#include <optional>
#include <string>

namespace hideseek_game {

struct CommandLine {
  std::string tool;   // the program's name, at the start of every message
  std::string about;  // what it does: the first lines of --help
  boost::program_options::options_description options{"options"};
  boost::program_options::positional_options_description positional;  // onto named options
};

// Parses argv. --help prints the usage (`about` and every option with its default) to stdout and
// returns std::nullopt with *exit_code 0; a bad command line (an unknown option, a missing value
// or required option, a value of the wrong type) prints "TOOL: what is wrong" and the options to
// stderr and returns std::nullopt with *exit_code 2.
std::optional<boost::program_options::variables_map> parseCommandLine(int argc, const char* const* argv,
                                                                      CommandLine& line, int* exit_code);

}  // namespace hideseek_game
