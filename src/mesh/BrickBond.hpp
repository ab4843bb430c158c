#pragma once
/// \file BrickBond.hpp
/// \brief How a 3D brick wall's courses are laid (mesh/MeshGenerators.hpp, docs/input.md).
namespace scpdyn
{
enum class BrickBond : int
{
  Running = 0, ///< stretchers only, every other course shifted by the stagger
  English = 1  ///< stretcher courses of two leaves alternate with header courses
};
} // namespace scpdyn
