// Contact set-up (step 2 of the paper's cycle): surfaces -> contact faces on device.
#include "contact/ContactSetup.hpp"
#include "core/HostCopy.hpp"

#include "mesh/MeshOps.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace scpdyn
{
namespace
{

constexpr Real kDegree = 3.14159265358979323846 / 180.0;
constexpr Real kGPa = 1.0e9;

/// part `name` or the parts a generator expanded from it ("name.<...>"), as node/face sets do
bool partMatches(const std::string &part_name, const std::string &pattern)
{
  if (!pattern.empty() && pattern.back() == '*')
    return part_name.rfind(pattern.substr(0, pattern.size() - 1), 0) == 0;
  return part_name == pattern ||
         (part_name.size() > pattern.size() && part_name.compare(0, pattern.size(), pattern) == 0 &&
          part_name[pattern.size()] == '.');
}

long long globalCount(const ContactMeshInput &in, size_t count)
{
  return in.global_count ? in.global_count((long long)count) : (long long)count;
}

std::array<Index, kMaxFaceNodes> sortedNodes(const HostFace &f)
{
  std::array<Index, kMaxFaceNodes> s = f.nodes; // unused slots are -1 and sort first
  std::sort(s.begin(), s.end());
  return s;
}

} // namespace

JointParams jointParamsOf(const SurfaceSpec &s, int bc_id)
{
  JointParams p;
  p.a = s.a * 1e-3;
  p.E0 = s.E0 * kGPa;
  p.G = s.G * kGPa;
  p.C = s.C * kGPa;
  p.phi0 = s.phi0 * kDegree;
  p.phi1 = s.phi1 * kDegree;
  p.usp0 = s.usp0;
  p.psi0 = s.psi0 * kDegree;
  p.sigma_cr = s.sigma_cr * kGPa;
  p.Emax = s.Emax < 0 ? -1.0 : s.Emax * kGPa;
  p.sigma_t = s.sigma_t < 0 ? -1.0 : s.sigma_t * kGPa;
  p.C_safe = std::isinf(s.C_safe) ? 1e300 : s.C_safe;
  p.option = s.option == "slide_line" ? ContactOption::SlideLine
             : s.option == "sticky"   ? ContactOption::Sticky
             : s.option == "sleepy"   ? ContactOption::Sleepy
             : s.option == "explicit" ? ContactOption::Explicit
                                      : ContactOption::Implicit;
  p.dilation_update =
      s.dilation_update == "explicit" ? DilationUpdate::Explicit : DilationUpdate::Consistent;
  p.dt_form = s.dt_form == "paper" ? DtContactForm::Paper : DtContactForm::MassSpring;
  p.distribution = s.distribution == "poc" ? DistributionRule::Poc : DistributionRule::Penetration;
  p.velocity = s.velocity == "average" ? VelocityRule::Average : VelocityRule::Weighted;
  p.traction_history = s.traction_history;
  p.implicit_shear = s.implicit_shear;
  p.brittle_tension = s.brittle_tension;
  p.bc_id = bc_id;
  p.mu_s = s.mu_static;
  p.mu_k = s.mu_kinetic < 0 ? s.mu_static : s.mu_kinetic;
  p.mu_dc = s.mu_decay;
  p.failure_measure = s.failure_measure == "plastic_strain" ? FailureMeasure::PlasticStrain
                      : s.failure_measure == "damage"       ? FailureMeasure::Damage
                      : s.failure_measure == "time"         ? FailureMeasure::Time
                                                            : FailureMeasure::None;
  p.failure_threshold = s.failure_threshold;
  p.failure_both = s.failure_sides == "both";
  return resolveParams(p);
}

ContactFaceData buildContactFaces(const ContactMeshInput &in, std::vector<ContactFaceInfo> &info)
{
  const Deck &deck = *in.deck;
  const HostMesh &mesh = *in.mesh;
  // the external faces, then the interior faces of eroding parts (11.6): index k < n_external
  // is an external face
  std::vector<HostFace> faces = *in.external_faces;
  const size_t n_external = faces.size();
  if (in.interior_faces)
    faces.insert(faces.end(), in.interior_faces->begin(), in.interior_faces->end());

  // external faces by their node set, so faces of any face set (box, part, gmsh group) map back
  std::map<std::array<Index, kMaxFaceNodes>, size_t> by_nodes;
  for (size_t k = 0; k < n_external; ++k)
    by_nodes[sortedNodes(faces[k])] = k;

  std::vector<int> surface_of(faces.size(), -1);
  for (size_t s = 0; s < deck.contact.surfaces.size(); ++s)
  {
    const SurfaceSpec &spec = deck.contact.surfaces[s];
    const std::string key = deck.path + ": contact.surfaces[" + std::to_string(s) + "]";
    // the interior faces erosion may expose do not count: a part enclosed by the parts merged
    // to it has nothing to contact with until something erodes
    size_t selected = 0;
    auto take = [&](size_t k) {
      selected += k < n_external ? 1 : 0;
      if (surface_of[k] < 0)
        surface_of[k] = int(s);
    };
    if (!spec.part.empty())
    {
      for (size_t k = 0; k < faces.size(); ++k)
        if (partMatches(mesh.parts[size_t(faces[k].part)].name, spec.part))
          take(k);
      if (globalCount(in, selected) == 0)
        throw InputError(key + ".part: no external face belongs to a part matching '" + spec.part +
                         "'");
    }
    else
    {
      const auto it = in.face_sets->find(spec.face_set);
      if (it == in.face_sets->end())
        throw InputError(key + ".face_set: unknown face set '" + spec.face_set + "'");
      for (const HostFace &f : it->second)
      {
        const auto e = by_nodes.find(sortedNodes(f));
        if (e == by_nodes.end())
          throw InputError(key + ".face_set: face set '" + spec.face_set +
                           "' holds a face that is not an external element face");
        take(e->second);
      }
      if (globalCount(in, selected) == 0)
        throw InputError(key + ".face_set: face set '" + spec.face_set + "' is empty");
    }
  }

  std::vector<size_t> chosen;
  for (size_t k = 0; k < faces.size(); ++k)
    if (surface_of[k] >= 0)
      chosen.push_back(k);
  auto globalElement = [&](Index e) {
    return in.global_element ? (*in.global_element)[size_t(e)] : e;
  };
  auto keyOf = [&](size_t k) {
    return long(globalElement(faces[k].element)) * 8 + faces[k].local_face;
  };
  std::sort(chosen.begin(), chosen.end(), [&](size_t a, size_t b) { return keyOf(a) < keyOf(b); });

  ContactFaceData F;
  const size_t nf = chosen.size();
  allocateFaces(F, nf);
  ContactFaceHost hf(F);
  auto h_emass = Kokkos::create_mirror_view_and_copy(HostSpace(), in.elems.mass);
  auto h_bc = Kokkos::create_mirror_view_and_copy(HostSpace(), in.nodes.bc);
  auto h_x = Kokkos::create_mirror_view_and_copy(HostSpace(), in.nodes.x);
  const int dim = deck.dimension;
  std::vector<Index> first_element(mesh.parts.size() + 1, 0); // global element ids per part
  for (size_t p = 0; p < mesh.parts.size(); ++p)
    first_element[p + 1] = first_element[p] + mesh.parts[p].numElements();
  std::vector<Index> used;
  info.assign(nf, ContactFaceInfo());
  for (size_t i = 0; i < nf; ++i)
  {
    const HostFace &f = faces[chosen[i]];
    const Index d = (*in.host_to_device_element)[size_t(f.element)];
    const ElementType type = mesh.parts[size_t(f.part)].type;
    hf.num_nodes(i) = f.num_nodes;
    hf.element(i) = d;
    hf.surface(i) = surface_of[chosen[i]];
    hf.part(i) = f.part;
    // (10.1): the element's mass per node times the face's nodes
    hf.mass(i) = h_emass(d) * Real(f.num_nodes) / Real(nodesPerElement(type));
    { // (3.2 rule 5) twice the distance between the face's and the element's centroids
      const HostPart &part = mesh.parts[size_t(f.part)];
      const int npe = nodesPerElement(type);
      const Index e = f.element - first_element[size_t(f.part)];
      Real ce[3] = {0, 0, 0}, cf[3] = {0, 0, 0};
      for (int a = 0; a < npe; ++a)
        for (int c = 0; c < 3; ++c)
          ce[c] += h_x(part.connectivity[size_t(npe * e + a)], c) / npe;
      for (int a = 0; a < f.num_nodes; ++a)
        for (int c = 0; c < 3; ++c)
          cf[c] += h_x(f.nodes[size_t(a)], c) / f.num_nodes;
      hf.depth(i) =
          2 * std::sqrt((ce[0] - cf[0]) * (ce[0] - cf[0]) + (ce[1] - cf[1]) * (ce[1] - cf[1]) +
                        (ce[2] - cf[2]) * (ce[2] - cf[2]));
    }
    int prescribed = 0;
    for (int a = 0; a < kMaxFaceNodes; ++a)
    {
      hf.nodes(i, a) = a < f.num_nodes ? f.nodes[size_t(a)] : -1;
      if (a < f.num_nodes)
      {
        used.push_back(f.nodes[size_t(a)]);
        for (int c = 0; c < dim; ++c)
          prescribed += h_bc(f.nodes[size_t(a)], c) >= 0 ? 1 : 0;
      }
    }
    hf.rigid(i) = prescribed == f.num_nodes * dim ? 1 : 0;
    hf.active(i) = f.twin < 0 ? 1 : 0; // an interior face waits for its twin to erode
    hf.back(i) = -1;
    if (type == ElementType::Line2)
    { // 1D point face: the element's other node orients it
      const HostPart &part = mesh.parts[size_t(f.part)];
      const Index e = f.element - first_element[size_t(f.part)];
      hf.back(i) = part.connectivity[size_t(2 * e + (1 - f.local_face))];
    }
    hf.key(i) = keyOf(chosen[i]);
    info[i] = {keyOf(chosen[i]), globalElement(f.element), f.local_face, f.part, f.twin};
  }
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  F.nodes_used = toDevice(used, "contact_nodes");

  F.params = DeviceView<JointParams *>("contact_surface_params", deck.contact.surfaces.size());
  auto h_params = Kokkos::create_mirror_view(F.params);
  for (size_t s = 0; s < deck.contact.surfaces.size(); ++s)
    h_params(s) = jointParamsOf(deck.contact.surfaces[s], int(s));

  hf.copyTo(F);
  Kokkos::deep_copy(F.params, h_params);
  return F;
}

} // namespace scpdyn
