// hideseek_game::packageExecutable and packageDirectory: how installed and devel-space nodes find
// the files other packages ship. Runs in the workspace's environment (catkin's test targets
// source it), so hideseek_game itself is on ROS_PACKAGE_PATH.
#include "hideseek_game/package_paths.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace fs = std::filesystem;

namespace {

// Two fake prefixes in a fresh temporary folder, each able to hold lib/PACKAGE/NAME.
class PackageExecutable : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("hideseek_package_paths_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_ / "first");
    fs::create_directories(root_ / "second");
    const char* old = std::getenv("CMAKE_PREFIX_PATH");
    saved_ = old ? old : "";
    had_ = old != nullptr;
    ::setenv("CMAKE_PREFIX_PATH", ((root_ / "first").string() + "::" + (root_ / "second").string()).c_str(), 1);
  }
  void TearDown() override {
    if (had_)
      ::setenv("CMAKE_PREFIX_PATH", saved_.c_str(), 1);
    else
      ::unsetenv("CMAKE_PREFIX_PATH");
    fs::remove_all(root_);
  }
  fs::path put(const std::string& prefix, const std::string& package, const std::string& name) {
    const fs::path file = root_ / prefix / "lib" / package / name;
    fs::create_directories(file.parent_path());
    std::ofstream(file) << "#!/bin/sh\n";
    return file;
  }
  fs::path root_;
  std::string saved_;
  bool had_ = false;
};

TEST_F(PackageExecutable, TakesTheFirstPrefixThatHoldsIt) {
  put("second", "pkg", "tool.py");
  EXPECT_EQ(hideseek_game::packageExecutable("pkg", "tool.py"), (root_ / "second/lib/pkg/tool.py").string());
  put("first", "pkg", "tool.py");
  EXPECT_EQ(hideseek_game::packageExecutable("pkg", "tool.py"), (root_ / "first/lib/pkg/tool.py").string());
}

TEST_F(PackageExecutable, AMissingFileIsAnErrorNamingPackageAndFile) {
  put("first", "other_pkg", "tool.py");  // the right name in another package does not count
  try {
    hideseek_game::packageExecutable("pkg", "tool.py");
    FAIL() << "no error for a missing executable";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("tool.py"), std::string::npos) << what;
    EXPECT_NE(what.find("'pkg'"), std::string::npos) << what;
    EXPECT_NE(what.find("CMAKE_PREFIX_PATH"), std::string::npos) << what;
  }
}

TEST(PackageDirectory, FindsTheGameConfigurationAndNamesAnUnknownPackage) {
  EXPECT_TRUE(fs::is_regular_file(hideseek_game::configDirectory() + "/game.yaml"));
  EXPECT_TRUE(fs::is_directory(hideseek_game::configDirectory() + "/variants"));
  try {
    hideseek_game::packageDirectory("hideseek_no_such_package");
    FAIL() << "no error for an unknown package";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("'hideseek_no_such_package'"), std::string::npos) << e.what();
  }
}

}  // namespace
