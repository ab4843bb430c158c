#include "driver/Preflight.hpp"

#include "driver/Solver.hpp"
#include "parallel/Mpi.hpp"

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace scpdyn
{
namespace
{
/// Up to this many sub-parts are listed one per line; more are one group on the part's line.
constexpr size_t kListedSubParts = 8;

std::string format(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
std::string format(const char *fmt, ...)
{
  va_list args, again;
  va_start(args, fmt);
  va_copy(again, args);
  std::string text(size_t(std::max(0, std::vsnprintf(nullptr, 0, fmt, args))), '\0');
  std::vsnprintf(&text[0], text.size() + 1, fmt, again);
  va_end(again);
  va_end(args);
  return text;
}
} // namespace

std::string massUnit(const Deck &deck)
{
  if (deck.dimension == 3)
    return "kg";
  if (deck.dimension == 1)
    return "kg per square metre of cross-section (uniaxial strain)";
  return deck.geometry == Geometry2D::Axisymmetric ? "kg per radian (axisymmetric)"
                                                   : "kg per metre (plane strain)";
}

double residentBytes()
{
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmRSS:", 0) == 0)
    {
      std::istringstream in(line.substr(6));
      double kib = 0;
      std::string unit;
      if (in >> kib >> unit && unit == "kB") // the kernel's "kB" are KiB
        return kib * 1024;
    }
  return 0;
}

Preflight preflight(const Solver &solver, const RunEstimate &estimate)
{
  Preflight p;
  p.mass_unit = massUnit(solver.deck());
  p.first_step = solver.firstStep();
  p.estimate = estimate;
  p.ranks = solver.numRanks();

  // elements and mass of every mesh part on this rank (each element on one rank), then summed
  const std::vector<HostPart> &mesh_parts = solver.mesh().parts;
  const size_t n = mesh_parts.size();
  std::vector<double> tally(2 * n, 0.0); // elements, then masses
  auto mass = Kokkos::create_mirror_view_and_copy(HostSpace(), solver.elements().mass);
  auto part = Kokkos::create_mirror_view_and_copy(HostSpace(), solver.elements().part);
  for (Index e = 0; e < solver.elements().count; ++e)
  {
    tally[size_t(part(e))] += 1;
    tally[n + size_t(part(e))] += mass(e);
  }
  const double resident = residentBytes();
  p.resident_bytes = p.resident_bytes_largest = resident;
  if (solver.numRanks() > 1)
  {
    allReduceSum(tally.data(), int(tally.size()), solver.comm());
    p.resident_bytes = allReduceSum(resident, solver.comm());
    p.resident_bytes_largest = allReduceMax(resident, solver.comm());
  }

  const Deck &deck = solver.deck();
  const std::vector<int> &spec_of = solver.model().part_spec;
  for (size_t s = 0; s < deck.parts.size(); ++s)
  {
    DeckPartTally d;
    d.name = deck.parts[s].name;
    d.material = deck.parts[s].material;
    for (size_t m = 0; m < n; ++m)
      if (spec_of[m] == int(s))
      {
        PartTally t{mesh_parts[m].name, long(tally[m]), tally[n + m]};
        d.elements += t.elements;
        d.mass += t.mass;
        d.sub_parts.push_back(t);
      }
    if (d.sub_parts.size() == 1 && d.sub_parts[0].name == d.name)
      d.sub_parts.clear();
    p.elements += d.elements;
    p.mass += d.mass;
    p.parts.push_back(d);
  }
  return p;
}

std::string preflightText(const Preflight &p)
{
  // a table whose first column fits the longest name listed on a line of its own
  size_t name_width = std::string("total").size(), material_width = 8;
  for (const DeckPartTally &d : p.parts)
  {
    name_width = std::max(name_width, d.name.size());
    material_width = std::max(material_width, d.material.size());
    if (d.sub_parts.size() <= kListedSubParts)
      for (const PartTally &s : d.sub_parts)
        name_width = std::max(name_width, s.name.size() + 2);
  }
  const int nw = int(name_width), mw = int(material_width);
  std::string out = "scpdyn: pre-flight\n";
  out += format("  %-*s  %-*s  %9s  mass [%s]\n", nw, "part", mw, "material", "elements",
                p.mass_unit.c_str());
  for (const DeckPartTally &d : p.parts)
  {
    std::string line = format("  %-*s  %-*s  %9ld  %.6g", nw, d.name.c_str(), mw,
                              d.material.c_str(), d.elements, d.mass);
    if (d.sub_parts.size() > kListedSubParts)
    {
      long least = d.sub_parts[0].elements, most = least;
      for (const PartTally &s : d.sub_parts)
        least = std::min(least, s.elements), most = std::max(most, s.elements);
      line += format("  %zu sub-parts %s .. %s, ", d.sub_parts.size(),
                     d.sub_parts.front().name.c_str(), d.sub_parts.back().name.c_str());
      line += least == most ? format("%ld elements each", least)
                            : format("%ld to %ld elements each", least, most);
    }
    out += line + "\n";
    if (d.sub_parts.size() <= kListedSubParts)
      for (const PartTally &s : d.sub_parts)
        out += format("    %-*s  %-*s  %9ld  %.6g\n", nw - 2, s.name.c_str(), mw, "", s.elements,
                      s.mass);
  }
  out += format("  %-*s  %-*s  %9ld  %.6g\n", nw, "total", mw, "", p.elements, p.mass);
  const RunEstimate &e = p.estimate;
  // the estimate (Outputs.hpp), with what set the first step
  out += format("  estimate: %.0f cycles (first dt %.3e s, set by %s), %.0f history rows, %.0f "
                "frames, %s of output\n",
                e.cycles, e.first_dt, p.first_step.control.c_str(), e.history_rows, e.frames,
                formatBytes(e.bytes).c_str());
  if (p.resident_bytes > 0)
    out +=
        p.ranks == 1
            ? format("  memory after set-up: %s resident\n", formatBytes(p.resident_bytes).c_str())
            : format("  memory after set-up: %s resident over %d ranks (largest rank %s)\n",
                     formatBytes(p.resident_bytes).c_str(), p.ranks,
                     formatBytes(p.resident_bytes_largest).c_str());
  return out;
}

JsonObject preflightJson(const Preflight &p)
{
  JsonObject parts;
  for (const DeckPartTally &d : p.parts)
  {
    JsonObject part;
    part.add("material", d.material).add("elements", d.elements).add("mass", d.mass);
    JsonObject subs;
    for (const PartTally &s : d.sub_parts)
    {
      JsonObject sub;
      sub.add("elements", s.elements).add("mass", s.mass);
      subs.add(s.name, sub);
    }
    part.add("sub_parts", subs);
    parts.add(d.name, part);
  }
  JsonObject first_dt;
  first_dt.add("value", p.first_step.dt).add("control", p.first_step.control);
  const RunEstimate &e = p.estimate;
  JsonObject estimate;
  estimate.add("cycles", e.cycles)
      .add("history_rows", e.history_rows)
      .add("frames", e.frames)
      .add("output_bytes", e.bytes);
  JsonObject memory;
  memory.add("resident_bytes", p.resident_bytes)
      .add("resident_bytes_largest_rank", p.resident_bytes_largest)
      .add("ranks", p.ranks);
  JsonObject out;
  out.add("mass_unit", p.mass_unit)
      .add("parts", parts)
      .add("elements", p.elements)
      .add("mass", p.mass)
      .add("first_dt", first_dt)
      .add("estimate", estimate)
      .add("memory", memory);
  return out;
}

} // namespace scpdyn
