// scpdyn command line: scpdyn DECK.yaml [-o DIR] [--restart FILE]; Kokkos flags (--kokkos-...) pass through.
// Exit status: 0 done, 1 internal error, 2 input error, 3 the run failed (outputs kept),
// 130 / 143 stopped by SIGINT / SIGTERM at the end of a cycle (outputs complete to it).
// Under mpirun every rank runs this; the mesh is decomposed over the ranks, rank 0 prints and
// writes the outputs, and the errors are collective, so all ranks exit with the same status.
#include "BuildCommit.hpp"
#include "driver/Interruption.hpp"
#include "driver/Solver.hpp"
#include "parallel/Mpi.hpp"

#include <Kokkos_Core.hpp>
#include <mpi.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <unistd.h>

namespace
{
const char *kUsage =
    "usage: scpdyn DECK.yaml [-o DIR] [--restart FILE] [--kokkos-... options]\n"
    "  Explicit Lagrangian finite elements with Simple Common Plane contact.\n"
    "  DECK.yaml   input deck (keys: docs/input.md)\n"
    "  -o DIR      output directory (default: output.directory of the deck, else out/<deck name>)\n"
    "  --restart FILE  continue the run of DECK.yaml from restart file FILE (written with\n"
    "              output.restart_interval, or when a signal stopped the run; one rank)\n"
    "  --help      this text;  --version  the version\n"
    "  Threads: OMP_NUM_THREADS=T (or --kokkos-num-threads=T); binding: OMP_PROC_BIND=spread\n"
    "           and OMP_PLACES=threads unless set.\n"
    "  Ranks:   mpirun -np R scpdyn DECK.yaml (hybrid: R ranks x OMP_NUM_THREADS threads).\n"
    "  Signals: SIGINT / SIGTERM stop the run at the end of the cycle, outputs complete\n"
    "           (exit status 130 / 143).\n"
    "  Outputs: fields.xmf/.h5 (ParaView), history.csv, gauges.csv (with gauges),\n"
    "           contacts.xmf/.h5 (with contact), summary.json, deck.resolved.yaml,\n"
    "           restart_<cycle>.h5 (with output.restart_interval, and on a signal).\n";

std::string deckStem(const std::string &path)
{
  std::string name = path.substr(path.find_last_of('/') + 1);
  const auto dot = name.find_last_of('.');
  return dot == std::string::npos ? name : name.substr(0, dot);
}
} // namespace

int main(int argc, char **argv)
{
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h"))
    {
      std::fputs(kUsage, stdout);
      return 0;
    }
    if (!std::strcmp(argv[i], "--version"))
    {
      std::printf("scpdyn %s (%s)\n", SCPDYN_VERSION, SCPDYN_COMMIT);
      return 0;
    }
  }
  // The binding Kokkos recommends (and warns without, on every run) unless the user chose one.
  // The OpenMP runtime reads its environment when it is loaded, before main, so the process
  // starts itself again with the variables set; if that is not possible, it runs unbound.
  if (!std::getenv("OMP_PROC_BIND"))
  {
    setenv("OMP_PROC_BIND", "spread", 1);
    setenv("OMP_PLACES", "threads", 0);
    execv("/proc/self/exe", argv);
  }
  scpdyn::MpiSession mpi(argc, argv);
  Kokkos::initialize(argc, argv);
  int status = 0;
  {
    const bool root = scpdyn::mpiRank() == 0;
    std::string deck_path, out_dir, restart_file;
    for (int i = 1; i < argc; ++i)
    {
      const std::string a = argv[i];
      if (a == "-o" && i + 1 < argc)
        out_dir = argv[++i];
      else if (a == "--restart" && i + 1 < argc)
        restart_file = argv[++i];
      else if (a == "--restart")
      {
        if (root)
          std::fprintf(stderr, "scpdyn: --restart needs a restart file\n%s", kUsage);
        status = 2;
      }
      else if (a == "-o")
      {
        if (root)
          std::fprintf(stderr, "scpdyn: -o needs a directory\n%s", kUsage);
        status = 2;
      }
      else if (!a.empty() && a[0] == '-')
      {
        if (root)
          std::fprintf(stderr, "scpdyn: unknown option '%s'\n%s", a.c_str(), kUsage);
        status = 2;
      }
      else if (deck_path.empty())
        deck_path = a;
      else
      {
        if (root)
          std::fprintf(stderr, "scpdyn: more than one deck given ('%s')\n", a.c_str());
        status = 2;
      }
    }
    if (status == 0 && deck_path.empty())
    {
      if (root)
        std::fputs(kUsage, stderr);
      status = 2;
    }
    if (status == 0)
    {
      try
      {
        const scpdyn::Deck deck = scpdyn::parseDeck(deck_path);
        if (out_dir.empty())
          out_dir = deck.output_dir.empty() ? "out/" + deckStem(deck_path) : deck.output_dir;
        scpdyn::Solver solver(deck);
        const int threads = int(scpdyn::ExecSpace().concurrency());
        if (root && solver.numRanks() == 1)
          std::fprintf(stderr, "scpdyn: %s: %d nodes, %d elements, %d thread%s -> %s\n",
                       deck_path.c_str(), solver.nodes().count, solver.elements().count, threads,
                       threads == 1 ? "" : "s", out_dir.c_str());
        else if (root)
          std::fprintf(stderr,
                       "scpdyn: %s: %ld nodes, %ld elements, %d ranks x %d thread%s -> %s\n",
                       deck_path.c_str(), solver.globalNodeCount(), solver.globalElementCount(),
                       solver.numRanks(), threads, threads == 1 ? "" : "s", out_dir.c_str());
        long cycles = 0;
        {
          const scpdyn::InterruptionHandlers interruption;
          cycles = solver.run(out_dir, restart_file);
        }
        if (const int signal = solver.interruptedBy())
        {
          if (root)
            std::fprintf(stderr,
                         "scpdyn: interrupted by %s at cycle %ld, t = %.6e s; outputs are "
                         "complete to that cycle\n",
                         scpdyn::signalName(signal).c_str(), cycles, solver.time());
          status = scpdyn::interruptedExitStatus(signal);
        }
        else if (root)
          std::printf("scpdyn: done, %ld cycles to t = %.6e s; results in %s\n", cycles,
                      solver.time(), out_dir.c_str());
      }
      catch (const scpdyn::InputError &e)
      {
        if (root)
          std::fprintf(stderr, "scpdyn: input error: %s\n", e.what());
        status = 2;
      }
      catch (const scpdyn::SimulationError &e)
      {
        if (root)
          std::fprintf(stderr, "scpdyn: run stopped: %s (outputs so far are kept)\n", e.what());
        status = 3;
      }
      catch (const std::exception &e)
      {
        status = 1;
        if (scpdyn::mpiSize() == 1)
          std::fprintf(stderr, "scpdyn: error: %s\n", e.what());
        else
        { // not known to be collective: the other ranks may wait for this one forever
          std::fprintf(stderr, "scpdyn: error on rank %d: %s\n", scpdyn::mpiRank(), e.what());
          MPI_Abort(MPI_COMM_WORLD, status);
        }
      }
    }
  }
  Kokkos::finalize();
  return status;
}
