// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_CONCURRENT_NODE_ORDER_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_CONCURRENT_NODE_ORDER_H

#include <CGAL/Trivial_connections/internal/concurrency.h>
#include <CGAL/Trivial_connections/internal/factorization/fill_reducing_ordering.h>
#include <CGAL/Trivial_connections/internal/mesh/mesh_arrays.h>
#include <CGAL/Trivial_connections/internal/topology/tree_cotree.h>
#include <CGAL/Trivial_connections/solver_traits.h>

#include <chrono>
#include <exception>
#include <future>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  The backend's fill-reducing order of the node rows, computed on a second thread (concurrently()) while the
  caller sets up the geometry, the trees and the rows. It needs only the connectivity, which the caller does
  not write meanwhile. The task first makes the pattern of the node rows (Mesh_topology::node_adjacency()),
  then orders it: the caller fills the system's values on that pattern while the order is computed, both
  reading it only. The task never calls user code; the destructor waits for it (also when the caller throws).
*/
template <class SolverTraits>
class Concurrent_node_order
{
public:
  template <class TriangleMesh>
  Concurrent_node_order(const Mesh_arrays<TriangleMesh>& m, const Mesh_topology& topology)
    : m_pattern_ready(m_pattern_made.get_future())
  {
    m_task = concurrently([this, &m, &topology] {
      try {
        topology.node_adjacency(m, m_node_start, m_node_rows);
      } catch(...) {
        m_pattern_made.set_exception(std::current_exception());
        throw;
      }
      m_pattern_made.set_value();
      std::vector<int> order;
      Fill_reducing_ordering<SolverTraits>::compute(topology.number_of_nodes, m_node_start, m_node_rows, order);
      return order;
    });
  }
  Concurrent_node_order(const Concurrent_node_order&) = delete;
  Concurrent_node_order& operator=(const Concurrent_node_order&) = delete;

  // Waits for the pattern of the node rows (compressed columns, see Mesh_topology::node_adjacency()); without a
  // second thread, the whole task runs here, now.
  void wait_for_pattern()
  {
    m_deferred = m_task.wait_for(std::chrono::seconds(0)) == std::future_status::deferred;
    if(m_deferred)
      m_order = m_task.get();
    else
      m_pattern_ready.get();
  }
  const std::vector<int>& node_start() const { return m_node_start; }
  const std::vector<int>& node_rows() const { return m_node_rows; }

  // Waits for the order (after wait_for_pattern()) and releases the pattern.
  std::vector<int> order()
  {
    if(!m_deferred)
      m_order = m_task.get();
    std::vector<int>().swap(m_node_start);
    std::vector<int>().swap(m_node_rows);
    return std::move(m_order);
  }

private:
  std::vector<int> m_node_start, m_node_rows, m_order;
  bool m_deferred = false;
  std::promise<void> m_pattern_made;
  std::future<void> m_pattern_ready;
  std::future<std::vector<int>> m_task; // last: destroyed (and waited for) first
};

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_CONCURRENT_NODE_ORDER_H
