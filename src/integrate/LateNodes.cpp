#include "integrate/LateNodes.hpp"
#include "core/RealText.hpp"
#include "integrate/NodeSweep.hpp"

#include <cstdlib>

namespace scpdyn
{

void LateNodes::declare(const std::string &writer, const std::vector<Index> &nodes)
{
  for (const Index n : nodes)
    if (n >= 0 && size_t(n) < _mark.size())
      _mark[size_t(n)] = 1;
  _writers.push_back(writer);
}

void LateNodes::declare(const std::string &writer, const IndexView &nodes)
{
  auto h = Kokkos::create_mirror_view_and_copy(HostSpace(), nodes);
  declare(writer, std::vector<Index>(h.data(), h.data() + h.extent(0)));
}

void LateNodes::declareFlagged(const std::string &writer, const std::vector<char> &flag)
{
  for (size_t n = 0; n < flag.size() && n < _mark.size(); ++n)
    _mark[n] = char(_mark[n] | (flag[n] != 0));
  _writers.push_back(writer);
}

bool nodeSweepCheckEnabled()
{
  const char *s = std::getenv("SCPDYN_CHECK_NODE_SWEEP");
  return s && *s && std::string(s) != "0";
}

void snapshotEarlyNodes(const NodeFields &nodes, EarlyNodeSnapshot &snap)
{
  if (snap.x.extent(0) != nodes.x.extent(0))
  {
    snap.x = VectorView("check_x", nodes.x.extent(0));
    snap.v = VectorView("check_v", nodes.v.extent(0));
  }
  Kokkos::deep_copy(snap.x, nodes.x);
  Kokkos::deep_copy(snap.v, nodes.v);
}

Index earlyNodeWrittenLate(const NodeSweep &sweep, const NodeFields &nodes,
                           const EarlyNodeSnapshot &snap, const bool loads, const Real g[3],
                           std::string *what)
{
  if (!sweep.active)
    return -1;
  auto runs = sweep.runs;
  auto x = nodes.x, v = nodes.v, f_int = nodes.f_int, f_ext = nodes.f_ext;
  auto f_contact = nodes.f_contact;
  auto x0 = snap.x, v0 = snap.v;
  auto mass = nodes.mass;
  const bool contact = f_contact.extent(0) != 0;
  const Real g0 = g[0], g1 = g[1], g2 = g[2];
  // per node: 1 x or v, 2 f_int, 4 f_ext, 8 f_contact; the lowest node id wins
  Index first = Kokkos::reduction_identity<Index>::min();
  Kokkos::parallel_reduce(
      "checkEarlyNodes", Kokkos::RangePolicy<ExecSpace>(0, Index(runs.extent(0))),
      KOKKOS_LAMBDA(const Index r, Index &low) {
        for (Index n = runs(r, 0); n < runs(r, 1); ++n)
        {
          bool bad = false;
          const Real gn[3] = {g0, g1, g2};
          for (int i = 0; i < 3; ++i)
          {
            bad = bad || x(n, i) != x0(n, i) || v(n, i) != v0(n, i) || f_int(n, i) != 0;
            bad = bad || f_ext(n, i) != (loads ? mass(n) * gn[i] : Real(0));
            bad = bad || (contact && f_contact(n, i) != 0);
          }
          if (bad && n < low)
            low = n;
        }
      },
      Kokkos::Min<Index>(first));
  if (first == Kokkos::reduction_identity<Index>::min())
    return -1;
  if (what)
  {
    auto pick = [&](const VectorView &f) {
      Real h[3];
      for (int i = 0; i < 3; ++i)
      {
        auto s = Kokkos::subview(f, first, i);
        auto m = Kokkos::create_mirror_view_and_copy(HostSpace(), s);
        h[i] = m();
      }
      return formatReal(h[0]) + ", " + formatReal(h[1]) + ", " + formatReal(h[2]);
    };
    *what = "x (" + pick(x) + "), v (" + pick(v) + "), f_int (" + pick(f_int) + "), f_ext (" +
            pick(f_ext) + ")" + (contact ? ", f_contact (" + pick(f_contact) + ")" : "");
  }
  return first;
}

} // namespace scpdyn
