#pragma once
/// \file OutputGather.hpp
/// \brief The mesh of a decomposed run's field file: every rank sends its owned nodes and its
/// elements to rank 0, which puts them in the serial order (global node id; cells in the serial
/// device order), once at set-up. The frames are written collectively (io/FieldWriter).
#include <mpi.h>

#include <vector>

namespace scpdyn
{

struct DomainDecomposition;

/// \brief For each local node its global row, -1 where another rank owns it.
std::vector<long> ownedNodeRows(const DomainDecomposition &dd);
/// \brief For each local device element its row in the serial cell order.
std::vector<long> cellRows(const DomainDecomposition &dd);

class OutputGather
{
public:
  /// \brief `node_rows`: for each local node, its global row, or -1 when another rank owns it;
  /// `cell_rows`: the global row of each local cell. Collective over `comm`.
  OutputGather(MPI_Comm comm, long global_nodes, long global_cells, std::vector<long> node_rows,
               std::vector<long> cell_rows);
  /// \brief The owned nodes and the elements of `dd` (ownedNodeRows(), cellRows()).
  OutputGather(MPI_Comm comm, const DomainDecomposition &dd);

  /// \brief A per-node field with `ncomp` components per local node (local node order): the
  /// global field on rank 0, empty elsewhere. Collective.
  std::vector<double> nodes(const std::vector<double> &local, int ncomp) const;
  /// \brief Integers per cell, local device element order (connectivity lists of variable
  /// length are gathered by the caller as fixed-width rows).
  std::vector<int> cellsInt(const std::vector<int> &local, int ncomp) const;
  /// \brief Reals per cell, local device element order.
  std::vector<double> cells(const std::vector<double> &local, int ncomp) const;

  bool root() const { return _rank == 0; }

private:
  struct Plan
  {
    long global = 0;
    std::vector<long> local_rows;    ///< local entry -> global row (-1: not sent)
    std::vector<int> counts, displs; ///< rank 0: entries per rank
    std::vector<long> rows;          ///< rank 0: global row of each gathered entry
  };
  void build(Plan &p, std::vector<long> local_rows, long global);
  template <class T>
  std::vector<T> gather(const Plan &p, const std::vector<T> &local, int ncomp,
                        MPI_Datatype type) const;

  MPI_Comm _comm;
  int _rank = 0, _size = 1;
  Plan _nodes, _cells;
};

} // namespace scpdyn
