#pragma once
/// \file damper_states.hpp
/// \brief The discrete mode of a friction-damped system: one contact state per damper.

#include "stickslip/contact.hpp"
#include "stickslip/detail/validate.hpp"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <string>

namespace stickslip {

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
  /// Same number of dampers, each in the same state.
  bool operator==(const DamperStates& o) const noexcept {
    if (size_ != o.size_) return false;
    for (std::size_t i = 0; i < size_; ++i)
      if (states_[i] != o.states_[i]) return false;
    return true;
  }
  /// Not operator==.
  bool operator!=(const DamperStates& o) const noexcept { return !(*this == o); }

  /// "stick,slip+,..." for logs.
  std::string to_string() const {
    std::string s;
    for (std::size_t i = 0; i < size_; ++i) {
      if (i) s += ',';
      s += stickslip::to_string(states_[i]);
    }
    return s;
  }

 private:
  std::array<ContactState, static_cast<std::size_t>(max_dampers)> states_{};
  std::uint8_t size_ = 0;
};

}  // namespace stickslip
