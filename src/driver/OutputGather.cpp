// Gather of a decomposed run's fields to rank 0 (see OutputGather.hpp).
#include "driver/OutputGather.hpp"

#include "parallel/Decomposition.hpp"

#include <stdexcept>

namespace scpdyn
{

std::vector<long> ownedNodeRows(const DomainDecomposition &dd)
{
  std::vector<long> rows(dd.owned.size(), -1);
  for (size_t n = 0; n < rows.size(); ++n)
    if (dd.owned[n])
      rows[n] = dd.global_node[n];
  return rows;
}

std::vector<long> cellRows(const DomainDecomposition &dd)
{
  return std::vector<long>(dd.output_cell.begin(), dd.output_cell.end());
}

OutputGather::OutputGather(MPI_Comm comm, const DomainDecomposition &dd)
    : OutputGather(comm, dd.global_nodes, dd.global_elements, ownedNodeRows(dd), cellRows(dd))
{
}

OutputGather::OutputGather(MPI_Comm comm, long global_nodes, long global_cells,
                           std::vector<long> node_rows, std::vector<long> cell_rows)
    : _comm(comm)
{
  MPI_Comm_rank(comm, &_rank);
  MPI_Comm_size(comm, &_size);
  build(_nodes, std::move(node_rows), global_nodes);
  build(_cells, std::move(cell_rows), global_cells);
}

void OutputGather::build(Plan &p, std::vector<long> local_rows, long global)
{
  p.global = global;
  p.local_rows = std::move(local_rows);
  std::vector<long> sent;
  for (long r : p.local_rows)
    if (r >= 0)
      sent.push_back(r);
  int mine = int(sent.size());
  if (_rank == 0)
    p.counts.resize(size_t(_size));
  MPI_Gather(&mine, 1, MPI_INT, p.counts.data(), 1, MPI_INT, 0, _comm);
  if (_rank == 0)
  {
    p.displs.assign(size_t(_size), 0);
    for (int r = 1; r < _size; ++r)
      p.displs[size_t(r)] = p.displs[size_t(r - 1)] + p.counts[size_t(r - 1)];
    p.rows.resize(size_t(p.displs.back() + p.counts.back()));
    if (long(p.rows.size()) != global)
      throw std::runtime_error("OutputGather: the ranks hold " + std::to_string(p.rows.size()) +
                               " rows of " + std::to_string(global));
  }
  MPI_Gatherv(sent.data(), mine, MPI_LONG, p.rows.data(), p.counts.data(), p.displs.data(),
              MPI_LONG, 0, _comm);
}

template <class T>
std::vector<T> OutputGather::gather(const Plan &p, const std::vector<T> &local, int ncomp,
                                    MPI_Datatype type) const
{
  std::vector<T> sent;
  sent.reserve(local.size());
  for (size_t k = 0; k < p.local_rows.size(); ++k)
    if (p.local_rows[k] >= 0)
      sent.insert(sent.end(), local.begin() + long(k) * ncomp, local.begin() + long(k + 1) * ncomp);
  std::vector<int> counts, displs;
  std::vector<T> all;
  if (_rank == 0)
  {
    for (int r = 0; r < _size; ++r)
    {
      counts.push_back(p.counts[size_t(r)] * ncomp);
      displs.push_back(p.displs[size_t(r)] * ncomp);
    }
    all.resize(p.rows.size() * size_t(ncomp));
  }
  MPI_Gatherv(sent.data(), int(sent.size()), type, all.data(), counts.data(), displs.data(), type,
              0, _comm);
  std::vector<T> out;
  if (_rank == 0)
  {
    out.resize(size_t(p.global) * size_t(ncomp));
    for (size_t k = 0; k < p.rows.size(); ++k)
      for (int c = 0; c < ncomp; ++c)
        out[size_t(p.rows[k]) * size_t(ncomp) + size_t(c)] = all[k * size_t(ncomp) + size_t(c)];
  }
  return out;
}

std::vector<double> OutputGather::nodes(const std::vector<double> &local, int ncomp) const
{
  return gather(_nodes, local, ncomp, MPI_DOUBLE);
}

std::vector<double> OutputGather::cells(const std::vector<double> &local, int ncomp) const
{
  return gather(_cells, local, ncomp, MPI_DOUBLE);
}

std::vector<int> OutputGather::cellsInt(const std::vector<int> &local, int ncomp) const
{
  return gather(_cells, local, ncomp, MPI_INT);
}

} // namespace scpdyn
