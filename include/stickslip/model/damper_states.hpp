#pragma once
/// \file damper_states.hpp
/// \brief The discrete mode of a friction-damped system: one contact state per damper.

#include "stickslip/contact.hpp"
#include "stickslip/detail/validate.hpp"
#include "stickslip/model/detail/enum_checks.hpp"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <string>

namespace stickslip {

/// The member end a damper rests against (docs/model_separation.md, "Resting at a wall"): a damper in
/// ContactState::Stick at a MemberEnd::Wall whose wall takes the tangential force into it, or a
/// separated one held there along the member while it flies ("Held at a wall in flight").
enum class WallRest : std::uint8_t {
  None,   ///< not resting at a wall (an ordinary stick or flight, or slipping)
  Start,  ///< resting against the wall at X = 0
  Finish  ///< resting against the wall at X = L
};

/// Contact state of every damper of a scene (the hybrid system's discrete mode). Fixed capacity,
/// so copying a mode never allocates. 3^N combinations for N dampers with exact friction laws
/// (the paper's eqs 26-29 are the four stick/slip cases for N = 2).
class DamperStates {
 public:
  /// Largest number of dampers a scene may hold.
  static constexpr Eigen::Index max_dampers = 64;

  DamperStates() = default;
  /// `count` dampers, all in `state`.
  explicit DamperStates(Eigen::Index count, ContactState state = ContactState::Stick) {
    if (count < 0 || count > max_dampers)
      detail::throw_invalid("DamperStates", "count must be in [0, 64]", count);
    detail::require_enumerator("DamperStates", "state", "ContactState", state, ContactState::Separated);
    size_ = static_cast<std::uint8_t>(count);
    states_.fill(state);
  }

  /// Number of dampers (0 for a default-constructed mode).
  Eigen::Index size() const noexcept { return size_; }
  /// State of damper `i` (asserts 0 <= i < size()).
  ContactState operator[](Eigen::Index i) const {
    STICKSLIP_ASSERT(i >= 0 && i < size_);
    return states_[static_cast<std::size_t>(i)];
  }
  /// State of damper `i`, writable (asserts 0 <= i < size()).
  ContactState& operator[](Eigen::Index i) {
    STICKSLIP_ASSERT(i >= 0 && i < size_);
    return states_[static_cast<std::size_t>(i)];
  }
  /// The wall damper `i` rests against: the one set by set_wall() while its state is Stick or
  /// Separated, None otherwise (a damper that slips no longer rests; asserts 0 <= i < size()).
  WallRest wall(Eigen::Index i) const {
    STICKSLIP_ASSERT(i >= 0 && i < size_);
    const ContactState s = states_[static_cast<std::size_t>(i)];
    if (s != ContactState::Stick && s != ContactState::Separated) return WallRest::None;
    const std::uint64_t bit = std::uint64_t(1) << i;
    return (start_ & bit) ? WallRest::Start : ((finish_ & bit) ? WallRest::Finish : WallRest::None);
  }
  /// Marks damper `i` as resting against wall `w` (None: not resting). The mark counts while the
  /// damper's state is Stick or Separated (see wall()); asserts 0 <= i < size(). Throws
  /// std::invalid_argument when w is not a WallRest enumerator.
  void set_wall(Eigen::Index i, WallRest w) {
    STICKSLIP_ASSERT(i >= 0 && i < size_);
    detail::require_enumerator("DamperStates::set_wall", "w", "WallRest", w, WallRest::Finish);
    const std::uint64_t bit = std::uint64_t(1) << i;
    start_ = w == WallRest::Start ? (start_ | bit) : (start_ & ~bit);
    finish_ = w == WallRest::Finish ? (finish_ | bit) : (finish_ & ~bit);
  }

  /// Same number of dampers, each in the same state and resting at the same wall.
  bool operator==(const DamperStates& o) const noexcept {
    if (size_ != o.size_) return false;
    for (std::size_t i = 0; i < size_; ++i)
      if (states_[i] != o.states_[i]) return false;
    if (start_ == o.start_ && finish_ == o.finish_) return true;
    for (Eigen::Index i = 0; i < size_; ++i)  // marks of slipping dampers do not count
      if (wall(i) != o.wall(i)) return false;
    return true;
  }
  /// Not operator==.
  bool operator!=(const DamperStates& o) const noexcept { return !(*this == o); }

  /// "stick,slip+,..." for logs; a damper resting at a wall reads "stick@start" or "stick@finish"
  /// ("separated@start" held there in flight).
  std::string to_string() const {
    std::string s;
    for (std::size_t i = 0; i < size_; ++i) {
      if (i) s += ',';
      s += stickslip::to_string(states_[i]);
      const WallRest w = wall(static_cast<Eigen::Index>(i));
      if (w != WallRest::None) s += w == WallRest::Start ? "@start" : "@finish";
    }
    return s;
  }

 private:
  std::array<ContactState, static_cast<std::size_t>(max_dampers)> states_{};
  std::uint64_t start_ = 0, finish_ = 0;  // bit i: damper i marked as resting at that wall
  std::uint8_t size_ = 0;
};

}  // namespace stickslip
