// Set-up memory of the MPI decomposition, per rank (docs/scaling.md). A plain MPI driver, not
// a Google Benchmark: the peak resident set only grows, so each mesh size needs its own run.
//
//   mpirun -np N bench_setup_memory <cells per edge of a hex cube> [joint|nojoint]
//
// Stages, as set-up will run them on every rank: generate the global mesh from the deck,
// extract its external faces, partition (METIS), cut out the local domain and local faces,
// drop the global mesh, build the shared-node plan. After each stage it prints the stage's own
// peak resident set (VmHWM, reset between stages), the resident set and the live heap, in MiB.
#include "mesh/MeshGenerators.hpp"
#include "mesh/MeshOps.hpp"
#include "parallel/LocalDomain.hpp"
#include "parallel/Mpi.hpp"
#include "parallel/NodeHalo.hpp"
#include "parallel/Partitioner.hpp"

#include <Kokkos_Core.hpp>
#include <mpi.h>

#include <malloc.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace
{

/// VmHWM-style value from /proc/self/status, in MiB (0 if unavailable).
double statusMiB(const char *key)
{
  double kib = 0;
  if (FILE *f = std::fopen("/proc/self/status", "r"))
  {
    char line[256];
    const size_t n = std::strlen(key);
    while (std::fgets(line, sizeof line, f))
      if (std::strncmp(line, key, n) == 0)
        kib = std::atof(line + n);
    std::fclose(f);
  }
  return kib / 1024.0;
}

/// Peak resident set since the last resetPeak() [MiB] (Linux VmHWM; ru_maxrss as fallback).
double peakMiB()
{
  const double hwm = statusMiB("VmHWM:");
  if (hwm > 0)
    return hwm;
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.0; // KiB on Linux
}

/// Reset the peak resident set to the current one (Linux >= 4.0), so each stage's own
/// transient is measured; harmless where unsupported (the peak then accumulates).
void resetPeak()
{
  if (FILE *f = std::fopen("/proc/self/clear_refs", "w"))
  {
    std::fputs("5", f);
    std::fclose(f);
  }
}

double currentMiB()
{
  long pages = 0, resident = 0;
  if (FILE *f = std::fopen("/proc/self/statm", "r"))
  {
    if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2)
      resident = 0;
    std::fclose(f);
  }
  return double(resident) * double(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

/// Bytes the heap has handed out and not taken back (glibc): the live set, which the resident
/// set overstates after frees that malloc keeps for reuse.
double liveHeapMiB()
{
#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 33))
  return double(mallinfo2().uordblks + mallinfo2().hblkhd) / (1024.0 * 1024.0);
#else
  return -1;
#endif
}

} // namespace

int main(int argc, char **argv)
{
  scpdyn::MpiSession mpi(argc, argv);
  Kokkos::initialize(argc, argv);
  {
    using namespace scpdyn;
    const int n = argc > 1 ? std::atoi(argv[1]) : 20;
    PartitionOptions options;
    if (argc > 2 && std::string(argv[2]) == "nojoint")
      options.joint_weight = 0;
    const int rank = mpiRank(), size = mpiSize();
    struct Stage
    {
      const char *name;
      double peak, current, live, seconds;
    };
    std::vector<Stage> stages;
    Kokkos::Timer timer;
    auto mark = [&](const char *name) {
      stages.push_back({name, peakMiB(), currentMiB(), liveHeapMiB(), timer.seconds()});
      resetPeak();
      timer.reset();
    };
    mark("start");
    Index global_elements = 0, global_nodes = 0;
    LocalDomain domain;
    std::vector<HostFace> local_faces;
    {
      HostMesh global;
      appendBlock(global, "cube", ElementType::Hex8, {n, n, n}, {0, 0, 0}, {1, 1, 1});
      global_elements = global.numElements();
      global_nodes = global.numNodes();
      mark("mesh");
      const std::vector<HostFace> faces = extractExternalFaces(global);
      mark("faces");
      const std::vector<int> element_rank = partitionElements(global, faces, size, options);
      mark("partition");
      domain = buildLocalDomain(global, element_rank, rank);
      local_faces = localFaces(faces, domain);
      mark("local");
    }
    mark("global freed");
    NodeHalo halo(domain);
    mark("halo");
    // one report per rank, printed by rank 0 in rank order
    char line[512];
    std::string report;
    std::snprintf(line, sizeof line,
                  "np %d rank %d: %d^3 hex, %d elements, %d nodes global; local %d elements, %d "
                  "nodes, %d shared, %d faces; %d neighbours, %zu B per vector sum\n",
                  size, rank, n, global_elements, global_nodes, domain.mesh.numElements(),
                  domain.mesh.numNodes(), domain.shared.size(), int(local_faces.size()),
                  halo.numNeighbours(), halo.bytesPerVectorSum());
    report += line;
    for (const Stage &s : stages)
    {
      std::snprintf(line, sizeof line,
                    "  %-13s stage peak %8.1f MiB  after %8.1f MiB  live heap %8.1f MiB  %7.3f s\n",
                    s.name, s.peak, s.current, s.live, s.seconds);
      report += line;
    }
    if (rank == 0)
    {
      std::fputs(report.c_str(), stdout);
      for (int r = 1; r < size; ++r)
      {
        MPI_Status status;
        int length = 0;
        MPI_Probe(r, 0, MPI_COMM_WORLD, &status);
        MPI_Get_count(&status, MPI_CHAR, &length);
        std::string text(size_t(length), ' ');
        MPI_Recv(&text[0], length, MPI_CHAR, r, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        std::fputs(text.c_str(), stdout);
      }
      std::fflush(stdout);
    }
    else
      MPI_Send(report.data(), int(report.size()), MPI_CHAR, 0, 0, MPI_COMM_WORLD);
  }
  Kokkos::finalize();
  return 0;
}
