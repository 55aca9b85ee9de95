#pragma once
/// \file dof_map.hpp
/// \brief Map between the nodal DOFs (3 per node) and the free DOFs kept after eliminating the
/// constrained ones.

#include "stickslip/beam/dof.hpp"
#include "stickslip/beam/ids.hpp"
#include "stickslip/detail/validate.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace stickslip {

/// Numbering of the free DOFs of a frame. Global DOF g = 3 * node + dof; free DOFs are numbered
/// in ascending order of g, constrained DOFs get free index -1.
class DofMap {
 public:
  /// Index type (Eigen's).
  using Index = Eigen::Index;

  DofMap() = default;

  /// \param constrained one flag per global DOF (size 3 * num_nodes)
  /// \throws std::invalid_argument when the size is not a multiple of 3
  explicit DofMap(const std::vector<bool>& constrained)
      : num_nodes_(static_cast<Index>(constrained.size()) / dofs_per_node),
        free_index_(constrained.size(), -1) {
    if (constrained.size() % static_cast<std::size_t>(dofs_per_node) != 0)
      detail::throw_invalid("DofMap", "constrained.size() must be a multiple of 3", constrained.size());
    for (std::size_t g = 0; g < constrained.size(); ++g) {
      if (constrained[g]) continue;
      free_index_[g] = static_cast<Index>(global_of_free_.size());
      global_of_free_.push_back(static_cast<Index>(g));
    }
  }

  /// Number of nodes (3 global DOFs each).
  Index num_nodes() const noexcept { return num_nodes_; }
  /// Number of free (unconstrained) DOFs.
  Index num_free() const noexcept { return static_cast<Index>(global_of_free_.size()); }
  /// Number of constrained DOFs: 3 num_nodes() - num_free().
  Index num_constrained() const noexcept { return dofs_per_node * num_nodes_ - num_free(); }

  /// Free index of a nodal DOF, -1 when it is constrained.
  /// \throws std::invalid_argument when the node does not exist
  Index free_index(NodeId node, Dof dof) const {
    check_node(node);
    return free_index_[static_cast<std::size_t>(global_dof(node, dof))];
  }

  /// True when the nodal DOF is free. \throws std::invalid_argument for an unknown node
  bool is_free(NodeId node, Dof dof) const { return free_index(node, dof) >= 0; }

  /// Node and DOF of a free index. \throws std::invalid_argument when out of range
  std::pair<Index, Dof> node_dof(Index free) const {
    if (free < 0 || free >= num_free())
      throw std::invalid_argument("DofMap::node_dof: free index " + std::to_string(free) +
                                  " is out of range [0, " + std::to_string(num_free()) + ")");
    const Index g = global_of_free_[static_cast<std::size_t>(free)];
    return {g / dofs_per_node, static_cast<Dof>(g % dofs_per_node)};
  }

  /// Global DOF index (3 * node + dof) of a free index (no range check beyond an assert).
  Index global_index(Index free) const {
    STICKSLIP_ASSERT(free >= 0 && free < num_free());
    return global_of_free_[static_cast<std::size_t>(free)];
  }

  /// Full nodal vector (size 3 * num_nodes, constrained entries 0) from a free-DOF vector.
  /// \throws std::invalid_argument on a size mismatch
  template <class Derived>
  Eigen::Matrix<typename Derived::Scalar, Eigen::Dynamic, 1> scatter(
      const Eigen::MatrixBase<Derived>& free) const {
    if (free.size() != num_free())
      throw std::invalid_argument("DofMap::scatter: free.size() = " + std::to_string(free.size()) +
                                  " must equal num_free() = " + std::to_string(num_free()));
    Eigen::Matrix<typename Derived::Scalar, Eigen::Dynamic, 1> full =
        Eigen::Matrix<typename Derived::Scalar, Eigen::Dynamic, 1>::Zero(dofs_per_node * num_nodes_);
    for (Index i = 0; i < num_free(); ++i) full(global_index(i)) = free(i);
    return full;
  }

  /// Free-DOF part of a full nodal vector (size 3 * num_nodes).
  /// \throws std::invalid_argument on a size mismatch
  template <class Derived>
  Eigen::Matrix<typename Derived::Scalar, Eigen::Dynamic, 1> gather(
      const Eigen::MatrixBase<Derived>& full) const {
    if (full.size() != dofs_per_node * num_nodes_)
      throw std::invalid_argument("DofMap::gather: full.size() = " + std::to_string(full.size()) +
                                  " must equal 3 * num_nodes() = " +
                                  std::to_string(dofs_per_node * num_nodes_));
    Eigen::Matrix<typename Derived::Scalar, Eigen::Dynamic, 1> free(num_free());
    for (Index i = 0; i < num_free(); ++i) free(i) = full(global_index(i));
    return free;
  }

 private:
  void check_node(Index node) const {
    if (node < 0 || node >= num_nodes_)
      throw std::invalid_argument("DofMap: node = " + std::to_string(node) +
                                  " does not exist (map has " + std::to_string(num_nodes_) +
                                  " nodes)");
  }

  Index num_nodes_ = 0;
  std::vector<Index> free_index_;      // per global DOF, -1 when constrained
  std::vector<Index> global_of_free_;  // per free DOF
};

}  // namespace stickslip
