#include "app/calot/structure_kind.h"

namespace vesica::app::calot {

const char* StructureKindName(StructureKind kind) {
  switch (kind) {
    case StructureKind::kCysticDuct:
      return "cystic duct";
    case StructureKind::kCysticArtery:
      return "cystic artery";
    case StructureKind::kCommonHepaticDuct:
      return "common hepatic duct";
    case StructureKind::kCommonBileDuct:
      return "common bile duct";
  }
  return "unknown structure";
}

}  // namespace vesica::app::calot
