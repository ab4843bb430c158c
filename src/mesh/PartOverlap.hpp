#pragma once
/// \file PartOverlap.hpp
/// \brief Parts that overlap at t = 0: element centroids of one part strictly inside an element
/// of another. Two such parts have no valid contact (the search skips pairs that penetrate
/// deeper than a face) and interpenetrate in silence, so the set-up warns.
#include "mesh/HostMesh.hpp"

#include <vector>

namespace scpdyn
{

struct PartOverlap
{
  int part_a = -1, part_b = -1; ///< part_a's centroids inside part_b's elements
  long count = 0;               ///< how many of them
  Index element = -1;           ///< one such element of part_a (global id)
};

/// \brief Every ordered pair of parts with at least one centroid of the first inside an element
/// of the second (inside: behind every face plane by more than 1e-6 of the element's size;
/// exact for convex elements). Linear in elements (a uniform grid of the largest element).
std::vector<PartOverlap> overlappingParts(const HostMesh &mesh);

} // namespace scpdyn
