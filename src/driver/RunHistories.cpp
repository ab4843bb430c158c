#include "driver/RunHistories.hpp"

#include "contact/ContactSystem.hpp"
#include "driver/Solver.hpp"
#include "parallel/Decomposition.hpp"
#include "parallel/Mpi.hpp"

#include <algorithm>

namespace scpdyn
{
namespace
{
constexpr int kPartValues = 6; // kinetic, internal, hourglass, momentum x y z

template <class View>
auto onHost(const View &v)
{
  return Kokkos::create_mirror_view_and_copy(HostSpace(), v);
}
} // namespace

RunHistoryColumns runHistoryColumns(const Deck &deck)
{
  RunHistoryColumns c;
  const auto &surfaces = deck.contact.surfaces;
  for (size_t a = 0; a < surfaces.size(); ++a)
    for (size_t b = a; b < surfaces.size(); ++b)
      for (const char *q : {"fx1", "fy1", "fz1", "fx2", "fy2", "fz2"})
        c.contact.push_back(surfaces[a].name + "-" + surfaces[b].name + ":" + q);
  for (const auto &b : deck.boundary_conditions)
    if (b.type == ConditionType::Velocity)
      c.reactions.push_back(b.set + ":" + std::string(1, "xyz"[b.component]));
  for (const auto &p : deck.parts)
    for (const char *q :
         {"kinetic", "internal", "hourglass", "momentum_x", "momentum_y", "momentum_z"})
      c.parts.push_back(p.name + ":" + q);
  return c;
}

RunHistories::RunHistories(const Solver &solver)
    : _solver(solver), _columns(runHistoryColumns(solver.deck()))
{
  // a node counts, with its whole mass, in the first deck part (deck order) of the elements
  // that hold it: a node merged between parts (merge_nodes) is counted once
  const Model &m = solver.model();
  const size_t nodes = size_t(m.nodes.count);
  const auto conn = onHost(m.elems.conn);
  const auto part = onHost(m.elems.part);
  const int parts = int(m.deck.parts.size());
  std::vector<int> first(nodes, parts);
  for (Index e = 0; e < m.elems.count; ++e)
    for (int a = 0; a < kMaxElementNodes && conn(e, a) >= 0; ++a)
    {
      int &f = first[size_t(conn(e, a))];
      f = std::min(f, m.part_spec[size_t(part(e))]);
    }
  if (m.dd) // a shared node's elements may be on other ranks: the first part over all copies
  {
    std::vector<int> local = first;
    first.assign(nodes, parts);
    RealView held("node_in_part", nodes);
    auto h = Kokkos::create_mirror_view(held);
    for (int p = 0; p < parts; ++p)
    {
      for (size_t n = 0; n < nodes; ++n)
        h(n) = local[n] == p ? 1.0 : 0.0;
      Kokkos::deep_copy(held, h);
      m.dd->halo->sum(held);
      Kokkos::deep_copy(h, held);
      for (size_t n = 0; n < nodes; ++n)
        if (first[n] == parts && h(n) > 0)
          first[n] = p;
    }
  }
  _node_part.assign(nodes, -1);
  for (size_t n = 0; n < nodes; ++n)
    if (!m.dd || m.dd->owned[n])
      _node_part[n] = first[n] < parts ? first[n] : -1;
}

RunHistories::Rows RunHistories::rows() const
{
  Rows r;
  r.contact.assign(_columns.contact.size(), 0.0);
  r.reactions.assign(_columns.reactions.size(), 0.0);
  r.parts.assign(_columns.parts.size(), 0.0);
  contactForces(r.contact);
  reactions(r.reactions);
  partSums(r.parts);
  if (_solver.numRanks() > 1) // one collective for the three rows
  {
    std::vector<double> all = r.contact;
    all.insert(all.end(), r.reactions.begin(), r.reactions.end());
    all.insert(all.end(), r.parts.begin(), r.parts.end());
    allReduceSum(all.data(), int(all.size()), _solver.comm());
    auto next = all.begin();
    for (auto *v : {&r.contact, &r.reactions, &r.parts})
    {
      std::copy(next, next + long(v->size()), v->begin());
      next += long(v->size());
    }
  }
  return r;
}

void RunHistories::contactForces(std::vector<double> &out) const
{
  const ContactSystem *contact = _solver.contact();
  if (!contact || out.empty())
    return;
  // each CP: +F on face 2, -F on face 1; pair (a, b), a <= b in deck order, side 1 = a
  const CommonPlaneData &cp = contact->planes();
  const ContactFaceData &faces = contact->faces();
  const auto force = onHost(cp.force);
  const auto face1 = onHost(cp.face1), face2 = onHost(cp.face2);
  const auto surface = onHost(faces.surface), ghost = onHost(faces.ghost);
  const int S = int(_solver.deck().contact.surfaces.size());
  for (Index p = 0; p < cp.count; ++p)
  {
    if (ghost(face1(p)) != 0)
      continue; // the rank of face 1 counts it (contact_kernels::ownsPlane)
    const int s1 = int(surface(face1(p))), s2 = int(surface(face2(p)));
    const int a = std::min(s1, s2), b = std::max(s1, s2);
    const size_t pair = size_t(a * S - a * (a - 1) / 2 + (b - a)); // (a, b) in row order
    const double sign = s2 == b ? 1.0 : -1.0;                      // the force on surface b's face
    for (int d = 0; d < 3; ++d)
      out[6 * pair + 3 + size_t(d)] += sign * force(p, d);
  }
  for (size_t pair = 0; pair < out.size() / 6; ++pair)
    for (int d = 0; d < 3; ++d)
      out[6 * pair + size_t(d)] = -out[6 * pair + 3 + size_t(d)];
}

void RunHistories::reactions(std::vector<double> &out) const
{
  const NodeFields &nodes = _solver.nodes();
  if (out.empty() || nodes.reaction.extent(0) == 0)
    return;
  const auto bc = onHost(nodes.bc);
  const auto reaction = onHost(nodes.reaction);
  const DomainDecomposition *dd = _solver.decomposition();
  for (Index n = 0; n < nodes.count; ++n)
    if (!dd || dd->owned[size_t(n)]) // a shared node once, on its owner
      for (int i = 0; i < 3; ++i)
        // the BC of this component (its only constrained one); a held part's constraint
        // (bc/PartRelease.hpp) comes after the deck's and has no column
        if (bc(n, i) >= 0 && size_t(bc(n, i)) < out.size())
          out[size_t(bc(n, i))] += reaction(n, i);
}

void RunHistories::partSums(std::vector<double> &out) const
{
  const NodeFields &nodes = _solver.nodes();
  const ElementFields &el = _solver.elements();
  const auto v = onHost(nodes.v);
  const auto mass = onHost(nodes.mass);
  for (Index n = 0; n < nodes.count; ++n)
  {
    const int p = _node_part[size_t(n)];
    if (p < 0)
      continue;
    double *o = &out[kPartValues * size_t(p)];
    const double m = mass(n);
    for (int i = 0; i < 3; ++i)
    {
      o[0] += 0.5 * m * v(n, i) * v(n, i);
      o[3 + i] += m * v(n, i);
    }
  }
  const auto emass = onHost(el.mass), energy = onHost(el.energy);
  const auto hourglass = onHost(el.hourglass_energy);
  const auto part = onHost(el.part);
  const auto eroded = onHost(el.eroded);
  const std::vector<int> &spec = _solver.model().part_spec;
  for (Index e = 0; e < el.count; ++e)
  {
    if (eroded(e) != 0) // its energy is booked as eroded (history.csv), not the part's
      continue;
    double *o = &out[kPartValues * size_t(spec[size_t(part(e))])];
    o[1] += emass(e) * energy(e);
    o[2] += hourglass(e);
  }
}

} // namespace scpdyn
