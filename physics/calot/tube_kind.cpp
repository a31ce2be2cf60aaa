#include "physics/calot/tube_kind.h"

namespace vesica::physics::calot {

const char* TubeKindName(TubeKind kind) {
  switch (kind) {
    case TubeKind::kCysticDuct:
      return "cystic duct";
    case TubeKind::kCysticArtery:
      return "cystic artery";
    case TubeKind::kCommonHepaticDuct:
      return "common hepatic duct";
    case TubeKind::kCommonBileDuct:
      return "common bile duct";
  }
  return "tube";
}

}  // namespace vesica::physics::calot
