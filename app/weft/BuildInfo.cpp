#include "BuildInfo.h"

namespace weft::cli {

namespace {
nlohmann::json orNull(const char* s) {
  return *s ? nlohmann::json(s) : nlohmann::json(nullptr);
}
}  // namespace

nlohmann::json buildInfoJson() {
  const BuildInfo& b = buildInfo();
  return {{"commit", orNull(b.commit)},
          {"engine", orNull(b.engineTree)},
          {"app", orNull(b.appTree)},
          {"assets", orNull(b.assetsTree)},
          {"modified", orNull(b.modification)}};
}

}  // namespace weft::cli
