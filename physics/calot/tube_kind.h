#pragma once
// The tubes of Calot's (hepatocystic) triangle, and what each carries.

namespace vesica::physics::calot {

enum class TubeKind {
  kCysticDuct,         ///< gallbladder's neck to the common duct
  kCysticArtery,       ///< right hepatic artery to the gallbladder
  kCommonHepaticDuct,  ///< hilum to the junction with the cystic duct
  kCommonBileDuct,     ///< junction to the duodenum
};

enum class Fluid { kBile, kBlood };

constexpr Fluid FluidOf(TubeKind kind) { return kind == TubeKind::kCysticArtery ? Fluid::kBlood : Fluid::kBile; }

/// "cystic duct", "cystic artery", "common hepatic duct", "common bile duct".
const char* TubeKindName(TubeKind kind);

}  // namespace vesica::physics::calot
