#include "EditorScriptRun.h"

#include <gtest/gtest.h>

#include <fstream>

namespace weft::test {

ProcessResult runEditor(const TempDir& dir, const nlohmann::json& actions, const std::string& size,
                        const std::vector<std::string>& options) {
  const std::string script = dir.write("script.json", nlohmann::json{{"actions", actions}}.dump(2));
  std::vector<std::string> command = {WEFT_EDITOR_BINARY, "--headless", "--script", script,
                                      "--size",           size};
  command.insert(command.end(), options.begin(), options.end());
  return runProcess(command, dir.path());
}

nlohmann::json readJson(const std::string& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in) << path;
  if (!in) return nullptr;
  return nlohmann::json::parse(in);
}

}  // namespace weft::test
