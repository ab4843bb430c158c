// Element erosion seen by the contact (docs/theory.md 11.6): the faces of eroded elements leave
// the contact surfaces and the faces they expose join them, at the next search.
#include "contact/ContactSystem.hpp"

namespace scpdyn
{

void ContactSystem::elementsEroded(const std::vector<Index> &global_elements)
{
  (void)global_elements;
}

} // namespace scpdyn
