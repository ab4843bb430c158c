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
/// Up to this many deck parts are listed one per line; with more, runs of parts numbered alike
/// (b000, b001, ...) of one material are one line each.
constexpr size_t kListedParts = 12;

/// A line of the parts table: a deck part, a sub-part, or a run of deck parts.
struct TableRow
{
  std::string name, material, note;
  long elements = 0;
  double mass = 0;
};

/// "b" of "b042", "wall_" of "wall_7": the name without its trailing number ("" without one).
std::string numberedStem(const std::string &name)
{
  const size_t last = name.find_last_not_of("0123456789");
  if (last + 1 == name.size() || last == std::string::npos)
    return "";
  return name.substr(0, last + 1);
}

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

/// "4 elements each", "2 to 4 elements each" of the parts.
std::string elementsEach(const std::vector<PartTally> &parts)
{
  long least = parts.front().elements, most = least;
  for (const PartTally &t : parts)
    least = std::min(least, t.elements), most = std::max(most, t.elements);
  const char *noun = most == 1 ? "element" : "elements";
  return least == most ? format("%ld %s each", least, noun)
                       : format("%ld to %ld %s each", least, most, noun);
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
  std::vector<TableRow> rows;
  const bool group_parts = p.parts.size() > kListedParts;
  for (size_t i = 0; i < p.parts.size();)
  {
    const DeckPartTally &d = p.parts[i];
    const std::string stem = numberedStem(d.name);
    size_t end = i + 1;
    while (group_parts && !stem.empty() && end < p.parts.size() &&
           numberedStem(p.parts[end].name) == stem && p.parts[end].material == d.material)
      ++end;
    if (end - i > 1)
    {
      const std::vector<PartTally> run(p.parts.begin() + long(i), p.parts.begin() + long(end));
      TableRow r{d.name + " .. " + p.parts[end - 1].name, d.material, "", 0, 0};
      for (const PartTally &t : run)
        r.elements += t.elements, r.mass += t.mass;
      r.note = format("%zu parts, ", run.size()) + elementsEach(run);
      rows.push_back(r);
    }
    else if (d.sub_parts.size() > kListedSubParts)
      rows.push_back({d.name, d.material,
                      format("%zu sub-parts %s .. %s, ", d.sub_parts.size(),
                             d.sub_parts.front().name.c_str(), d.sub_parts.back().name.c_str()) +
                          elementsEach(d.sub_parts),
                      d.elements, d.mass});
    else
    {
      rows.push_back({d.name, d.material, "", d.elements, d.mass});
      for (const PartTally &t : d.sub_parts) // indented under their part
        rows.push_back({"  " + t.name, "", "", t.elements, t.mass});
    }
    i = end;
  }
  rows.push_back({"total", "", "", p.elements, p.mass});

  size_t name_width = 4, material_width = 8; // "part", "material"
  for (const TableRow &r : rows)
  {
    name_width = std::max(name_width, r.name.size());
    material_width = std::max(material_width, r.material.size());
  }
  const int nw = int(name_width), mw = int(material_width);
  std::string out = "scpdyn: pre-flight\n";
  out += format("  %-*s  %-*s  %9s  mass [%s]\n", nw, "part", mw, "material", "elements",
                p.mass_unit.c_str());
  for (const TableRow &r : rows)
    out += format("  %-*s  %-*s  %9ld  %.6g%s%s\n", nw, r.name.c_str(), mw, r.material.c_str(),
                  r.elements, r.mass, r.note.empty() ? "" : "  ", r.note.c_str());
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
