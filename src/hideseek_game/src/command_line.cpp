#include "hideseek_game/command_line.h"

#include <iostream>

namespace hideseek_game {

namespace po = boost::program_options;

std::optional<po::variables_map> parseCommandLine(int argc, const char* const* argv, CommandLine& line,
                                                  int* exit_code) {
  line.options.add_options()("help,h", "print this help and exit");
  po::variables_map values;
  try {
    po::store(po::command_line_parser(argc, argv).options(line.options).positional(line.positional).run(), values);
    if (values.count("help")) {
      std::cout << line.about << "\n\n" << line.options << '\n';
      *exit_code = 0;
      return std::nullopt;
    }
    po::notify(values);  // required options, typed values
  } catch (const po::error& e) {
    std::cerr << line.tool << ": " << e.what() << "\n\n" << line.options << '\n';
    *exit_code = 2;
    return std::nullopt;
  }
  return values;
}

}  // namespace hideseek_game
