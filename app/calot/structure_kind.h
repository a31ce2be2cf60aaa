#pragma once
// The tubular structures of Calot's (hepatocystic) triangle that the training logic tells apart.
// A scenario may hold more than one of a kind (a double cystic artery is a common variant).

#include <string>

namespace vesica::app::calot {

enum class StructureKind {
  kCysticDuct,         // gallbladder to the common duct: clipped and divided
  kCysticArtery,       // right hepatic artery to the gallbladder: clipped and divided
  kCommonHepaticDuct,  // must not be clipped or cut (bile duct injury)
  kCommonBileDuct,     // must not be clipped or cut (bile duct injury)
};

/// What a person reads: "cystic duct", "cystic artery", "common hepatic duct", "common bile duct".
const char* StructureKindName(StructureKind kind);

/// The common hepatic or common bile duct: a clip or cut on it is a bile duct injury.
constexpr bool IsMainBileDuct(StructureKind kind) {
  return kind == StructureKind::kCommonHepaticDuct || kind == StructureKind::kCommonBileDuct;
}

/// The cystic duct or artery: the two structures the trainee clips and divides.
constexpr bool IsCysticStructure(StructureKind kind) { return !IsMainBileDuct(kind); }

/// Blood (the artery) rather than bile (the ducts): an open cut bleeds instead of leaking bile.
constexpr bool CarriesBlood(StructureKind kind) { return kind == StructureKind::kCysticArtery; }

}  // namespace vesica::app::calot
