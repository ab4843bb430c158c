#pragma once
/// \file Deck.hpp
/// \brief The typed, validated input deck. Parsed once from YAML (DeckParser.cpp); nothing in
/// the cycle reads YAML. All values SI. Every key is documented in docs/input.md.
#include "core/InputError.hpp"
#include "core/Types.hpp"
#include "material/MaterialSpec.hpp" // materials[]: the material room owns their contents
#include "mesh/BrickBond.hpp"

#include <array>
#include <map>
#include <string>
#include <vector>

namespace scpdyn
{

/// \brief The deck's choices, stored as enums once the parser has checked the word (the cycle
/// compares enums, never deck text); deckName() gives the word back for the resolved deck and
/// for messages.
enum class MeshType : int
{
  Block,
  BrickWall,
  Gmsh
};
enum class ConditionType : int
{
  Velocity,
  Force,
  Pressure
};
enum class GaugeKind : int
{
  Node,
  Element,
  Joint
};
enum class HourglassForm : int
{
  Viscous,
  Stiffness
};
enum class ScatterMode : int
{
  Gather, ///< deterministic: corner gather with threads, plain adds on one thread
  Atomic
};
enum class NodeUpdateMode : int
{
  Fused, ///< step 12 in step 6's sweep where the order allows it
  Separate
};

const char *deckName(MeshType t);       ///< block | brick_wall | gmsh
const char *deckName(ConditionType t);  ///< velocity | force | pressure
const char *deckName(GaugeKind k);      ///< node | element | joint
const char *deckName(HourglassForm f);  ///< viscous | stiffness
const char *deckName(ScatterMode s);    ///< gather | atomic
const char *deckName(NodeUpdateMode m); ///< fused | separate
const char *deckName(ElementType t);    ///< line2 | quad4 | hex8 | tet4
const char *deckName(BrickBond b);      ///< running | english

/// \brief Piecewise-linear time function (constant beyond its ends).
struct TimeFunction
{
  std::string name;
  std::vector<Real> t, value;
};

/// \brief How a part's mesh is made.
struct MeshSpec
{
  MeshType type = MeshType::Block;
  ElementType element = ElementType::Quad4; ///< block, brick_wall (gmsh: from the file)
  std::array<int, 3> elements{{1, 1, 1}};   ///< block: cells per direction
  std::array<Real, 3> origin{{0, 0, 0}};
  std::array<Real, 3> size{{0, 0, 0}};
  // brick_wall: bricks of `brick_size`, `elements` cells per brick, `count` bricks per direction,
  // every other course (a line of bricks along the stagger axis) shifted along that axis by
  // stagger * brick length
  std::array<Real, 3> brick_size{{0, 0, 0}};
  std::array<int, 3> count{{1, 1, 1}};
  Real stagger = 0.5;
  int stagger_axis = 0;                ///< 0 = x, 1 = y
  BrickBond bond = BrickBond::Running; ///< 3D: english alternates stretcher and header courses
  std::string file;                    ///< gmsh: path to .msh 4.1 ASCII (relative to the deck)
};

/// \brief A part's mesh moved as a rigid body: rotated by `angle` about the line through
/// `point` along `axis` (2D: about z), then translated.
struct PartPlacement
{
  Real angle = 0;                           ///< [deg], right-handed about `axis`
  std::array<Real, 3> axis{{0, 0, 1}};      ///< unit vector
  std::array<Real, 3> point{{0, 0, 0}};     ///< [m]
  std::array<Real, 3> translate{{0, 0, 0}}; ///< [m]
  bool moves() const
  {
    return angle != 0 || translate[0] != 0 || translate[1] != 0 || translate[2] != 0;
  }
};

struct PartSpec
{
  std::string name;
  std::string material;
  MeshSpec mesh;
  std::array<Real, 3> initial_velocity{{0, 0, 0}};
  bool merge_nodes = false; ///< merge nodes coincident with other merge_nodes parts
  PartPlacement placement;  ///< where the generated or read mesh is put
  /// [s]: held fixed (v = 0) until this time, then moves from rest with its initial velocity
  /// (bc/PartRelease.hpp); 0: free from the start
  Real release_time = 0;
};

/// \brief A named set selected by part, by box, or by both (the part's nodes/faces in the box).
struct SetSpec
{
  std::string name;
  std::string part; ///< all nodes/external faces of this part (or prefix*); empty: every part
  bool has_box = false;
  std::array<Real, 3> box_min{{0, 0, 0}}, box_max{{0, 0, 0}}; ///< inclusive, with tolerance
};

/// \brief An initial velocity of a node set, uniform or linear in position:
/// v = velocity + gradient (x - about); applied after the parts' initial velocities, in order.
struct InitialVelocitySpec
{
  std::string node_set;
  std::array<Real, 3> velocity{{0, 0, 0}};       ///< [m/s]
  std::array<std::array<Real, 3>, 3> gradient{}; ///< dv_i/dx_j [1/s]
  std::array<Real, 3> about{{0, 0, 0}};          ///< [m]
  int set_line = 0; ///< the deck's line of the set name (messages after meshing)
};

struct BoundaryConditionSpec
{
  ConditionType type = ConditionType::Velocity;
  std::string set;                       ///< node set (velocity, force) or face set (pressure)
  int component = -1;                    ///< velocity: 0,1,2 for x,y,z
  Real value = 0;                        ///< velocity (m/s) or pressure (Pa)
  std::array<Real, 3> vector{{0, 0, 0}}; ///< force (N) per node
  std::string function;                  ///< optional TimeFunction name multiplying the value
  int set_line = 0; ///< the deck's line of the set name (messages after meshing)
};

struct GaugeSpec
{
  std::string name;
  GaugeKind kind = GaugeKind::Node;
  Index id = -1; ///< node or element id (0-based), or -1 when `point` is given
  bool has_point = false;
  std::array<Real, 3> point{{0, 0, 0}}; ///< nearest node / containing-or-nearest element
  Real radius = 0; ///< joint gauges: CPs within this distance of `point` [m]; 0: default
  std::vector<std::string> quantities; ///< see docs/input.md
};

/// \brief The quantities of each gauge kind (docs/input.md), in the order of their codes: a
/// quantity's index here is what the driver evaluates (driver/Diagnostics.cpp; for joint
/// gauges contact/JointGauge.hpp).
inline const std::vector<std::string> &nodeGaugeQuantities()
{
  static const std::vector<std::string> names = {"x", "y", "z", "dx", "dy", "dz", "vx", "vy", "vz"};
  return names;
}
inline const std::vector<std::string> &elementGaugeQuantities()
{
  static const std::vector<std::string> names = {
      "sxx",    "syy", "szz", "sxy", "syz", "szx", "pressure", "density", "plastic_strain",
      "energy", "q"};
  return names;
}
inline const std::vector<std::string> &jointGaugeQuantities()
{
  static const std::vector<std::string> names = {"normal_stress", "shear_stress", "normal_force",
                                                 "shear_force",   "area",         "closure",
                                                 "slip",          "count"};
  return names;
}
/// \brief The quantity list of a gauge kind.
inline const std::vector<std::string> &gaugeQuantities(GaugeKind kind)
{
  return kind == GaugeKind::Node      ? nodeGaugeQuantities()
         : kind == GaugeKind::Element ? elementGaugeQuantities()
                                      : jointGaugeQuantities();
}

/// \brief One contact surface (docs/input.md, `contact.surfaces[]`): the external faces it covers
/// (a part, a `prefix*` of parts, or a face set) and the face-based contact condition they
/// carry. Joint parameters are kept in the units of the paper's Table 1, as written in the deck
/// (mm, GPa, degrees); the contact room converts them to SI (contact/ContactSetup.cpp).
struct SurfaceSpec
{
  std::string name;
  std::string part;     ///< part name or `prefix*` (exactly one of part, face_set is set)
  std::string face_set; ///< face set name
  std::string option = "implicit"; ///< slide_line | sticky | sleepy | explicit | implicit
  Real a = 0.1;                    ///< aperture [mm]
  Real E0 = 0.05;                  ///< initial normal modulus E0 = Kn a [GPa]
  Real G = 0.05;                   ///< shear modulus G = Ks a [GPa]
  Real C = 0.001;                  ///< cohesion [GPa]
  Real phi0 = 40;                  ///< initial friction angle [deg]
  Real phi1 = 10;                  ///< residual friction angle [deg]
  Real usp0 = 100;                 ///< characteristic slip of softening, in apertures [-]
  Real psi0 = 0;                   ///< initial dilation angle [deg]
  Real sigma_cr = 0.1;             ///< no dilation above this normal stress [GPa]
  Real Emax = -1;                  ///< modulus cut-off [GPa]; < 0: auto (1e4 E0)
  Real sigma_t = -1;               ///< tensile strength [GPa]; < 0: auto (C/tan(phi0))
  Real C_safe = 0.5;               ///< safety factor of the explicit time-step limit; infinity: off
  std::string dt_form = "mass_spring";        ///< mass_spring | paper
  std::string dilation_update = "consistent"; ///< consistent | explicit
  std::string distribution = "penetration";   ///< penetration | poc
  std::string velocity = "weighted";          ///< weighted | average (face velocities)
  bool traction_history = true;
  bool implicit_shear = true;
  bool brittle_tension = false;
  // slide_line (and sleepy once failed): Coulomb friction
  // mu = mu_kinetic + (mu_static - mu_kinetic) exp(-mu_decay |v|)
  Real mu_static = 0;   ///< static coefficient [-]; 0: frictionless
  Real mu_kinetic = -1; ///< kinetic coefficient [-]; < 0: mu_static
  Real mu_decay = 0;    ///< decay coefficient [s/m]
  // sleepy: tied until the switch, then a slide line
  std::string failure_measure;          ///< plastic_strain | damage | time
  Real failure_threshold = -1;          ///< the measure's value that fails the tie
  std::string failure_sides = "either"; ///< either | both (elements of the two faces)
};

/// \brief The contact section: no surfaces means no contact.
struct ContactSpec
{
  std::vector<SurfaceSpec> surfaces;
  long search_interval = 1;   ///< cycles between CP searches; 0 = once, at the first cycle
  int constraint_passes = 30; ///< sticky/slide-line solve iterations (docs/theory.md 10.8)
  Real search_gap = -1;       ///< largest gap at which a CP is created [m]; < 0: largest face size
  /// `search_gap: motion`: the gap from the contact nodes' speed over search_interval cycles,
  /// and a search whenever they may have moved a quarter of it (docs/theory.md 3.1a)
  bool search_gap_motion = false;
};

/// \brief Velocity decay factor of every underdamped mode over the settling stage with the
/// default damping, alpha = 2 ln(kSettlingDecay) / settling.end (docs/theory.md 2.4).
constexpr Real kSettlingDecay = 1e4;

/// \brief The settling stage (docs/theory.md 2.4): mass-proportional damping of the nodal
/// velocities for 0 <= t < end, so that the model comes to rest under gravity.
struct SettlingSpec
{
  Real end = 0;     ///< [s]; 0: no settling stage
  Real damping = 0; ///< mass-damping coefficient alpha [1/s] (the parser fills in the default)
  bool active() const { return end > 0; }
};

struct Deck
{
  std::string title;
  std::string path; ///< deck file path
  int dimension = 2;
  Geometry2D geometry = Geometry2D::PlaneStrain;

  // time
  Real end_time = 0;
  Real courant = 0.5; ///< S in (0, 1]
  Real dt_max = 1e30;
  long max_cycles = -1;
  Real max_estimated_cycles = 1e9; ///< refuse a run estimated to need more cycles

  // numerics
  Real hourglass_coefficient = 0.05;
  HourglassForm hourglass_type = HourglassForm::Stiffness;
  Real bulk_viscosity_linear = 0.06;
  Real bulk_viscosity_quadratic = 1.5;
  ScatterMode scatter = ScatterMode::Gather;
  NodeUpdateMode node_update = NodeUpdateMode::Fused;
  std::array<Real, 3> gravity{{0, 0, 0}};
  std::string gravity_function; ///< scales gravity in time; empty: constant
  SettlingSpec settling;

  // output
  std::string output_dir;       ///< default out/<deck stem>
  Real field_interval = 0;      ///< 0: first and last only
  Real history_interval = 0;    ///< 0: every cycle
  Real progress_interval = 2.0; ///< wall seconds between progress lines
  Real max_output_bytes = 50e9; ///< refuse a run estimated to write more
  Real restart_interval = 0;    ///< simulated seconds between restart files; 0: none
  int restart_keep = 2;         ///< restart files kept (the newest)

  std::vector<MaterialSpec> materials;
  std::vector<PartSpec> parts;
  std::vector<SetSpec> node_sets;
  std::vector<SetSpec> face_sets;
  std::vector<TimeFunction> functions;
  std::vector<BoundaryConditionSpec> boundary_conditions;
  std::vector<InitialVelocitySpec> initial_velocities; ///< the deck's initial_conditions
  std::vector<GaugeSpec> gauges;
  ContactSpec contact;
};

/// \brief `numerics.scatter: gather` on more than one thread or rank: the assemblies that sum
/// in a fixed order run (the element corners, ModelSetup.cpp; the joint CPs' node shares,
/// ContactShares.cpp). On one thread of one rank plain adds in index order give their sums bit
/// for bit, so they are skipped; a decomposed run needs the terms of its shared nodes.
inline bool orderedAssembly(const Deck &deck, bool decomposed = false)
{
  return deck.scatter == ScatterMode::Gather && (ExecSpace().concurrency() > 1 || decomposed);
}

/// \brief Parse and validate a deck; throws InputError naming key path and line.
Deck parseDeck(const std::string &path);
/// \brief Parse from a YAML string (tests); `path` only names the source in messages.
Deck parseDeckString(const std::string &yaml_text, const std::string &path);
/// \brief The resolved deck (all defaults filled in) as YAML text.
std::string resolvedDeckText(const Deck &deck);
/// \brief Write resolvedDeckText() to `file`.
void writeResolvedDeck(const Deck &deck, const std::string &file);

} // namespace scpdyn
