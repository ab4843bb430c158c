// Element erosion seen by the contact (docs/theory.md 11.6): the faces of eroded elements leave
// the contact surfaces and the interior faces they expose join them, at the next search. Every
// rank holds the same list of eroded elements, so a face is active on every rank alike.
#include "contact/ContactSystem.hpp"
#include "io/RestartFile.hpp"

#include <algorithm>
#include <iterator>

namespace scpdyn
{

void ContactSystem::elementsEroded(const std::vector<Index> &global_elements)
{
  _eroded_pending.insert(_eroded_pending.end(), global_elements.begin(), global_elements.end());
}

bool ContactSystem::applyErosion()
{
  if (_eroded_pending.empty())
    return false;
  std::sort(_eroded_pending.begin(), _eroded_pending.end());
  std::vector<Index> all;
  std::set_union(_eroded.begin(), _eroded.end(), _eroded_pending.begin(), _eroded_pending.end(),
                 std::back_inserter(all));
  _eroded.swap(all);
  _eroded_pending.clear();
  activateExposedFaces();
  return true;
}

void ContactSystem::activateExposedFaces()
{
  auto eroded = [&](Index e) {
    return e >= 0 && std::binary_search(_eroded.begin(), _eroded.end(), e);
  };
  // an interior face is searched once the element across it has gone, while its own stays
  auto active = Kokkos::create_mirror_view(_own.active);
  for (Index f = 0; f < _own.count; ++f)
  {
    const ContactFaceInfo &i = _own_info[size_t(f)];
    active(f) = !eroded(i.mesh_element) && (i.twin < 0 || eroded(i.twin)) ? 1 : 0;
  }
  Kokkos::deep_copy(_own.active, active);
}

void ContactSystem::loadErosion(const RestartReader &in)
{
  auto ids = [&](const char *name) {
    const std::vector<double> v = in.reals(name);
    return std::vector<Index>(v.begin(), v.end());
  };
  _eroded = ids("contact.eroded");
  _eroded_pending = ids("contact.eroded_pending");
  activateExposedFaces();
}

} // namespace scpdyn
