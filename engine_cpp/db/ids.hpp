// Distinct integer id types, so that a net id cannot be passed where a layer id
// is expected. Every id is an index into one vector of Tech or Design.
#pragma once

#include <cstdint>
#include <functional>

namespace xroute {

template <class Tag>
struct Id {
  int32_t value = -1;  // index into the owning vector; -1 = none

  constexpr Id() = default;
  constexpr explicit Id(int32_t v) : value(v) {}
  constexpr bool valid() const { return value >= 0; }
  constexpr int32_t operator*() const { return value; }
  friend constexpr bool operator==(Id, Id) = default;
  friend constexpr auto operator<=>(Id, Id) = default;
};

using LayerId = Id<struct LayerTag>;      // into Tech::layers (all layer types, LEF order)
using ViaId = Id<struct ViaTag>;          // into Tech::vias (LEF fixed vias)
using ViaRuleId = Id<struct ViaRuleTag>;  // into Tech::viaRules
using SiteId = Id<struct SiteTag>;        // into Tech::sites
using MacroId = Id<struct MacroTag>;      // into Tech::macros
using CompId = Id<struct CompTag>;        // into Design::components
using IoPinId = Id<struct IoPinTag>;      // into Design::ioPins
using NetId = Id<struct NetTag>;          // into Design::nets
using DefViaId = Id<struct DefViaTag>;    // into Design::vias (DEF VIAS section)

}  // namespace xroute

template <class Tag>
struct std::hash<xroute::Id<Tag>> {
  size_t operator()(xroute::Id<Tag> id) const noexcept { return std::hash<int32_t>()(id.value); }
};
