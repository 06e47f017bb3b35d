#include <weft/record/ContactPoint.h>

namespace weft {

const char* branchName(ContactBranch branch) {
  switch (branch) {
    case ContactBranch::TakeOff:
      return "takeoff";
    case ContactBranch::Stick:
      return "stick";
    case ContactBranch::Slip:
      return "slip";
    default:
      return "none";
  }
}

}  // namespace weft
