// OpenMesh subdivision driver for bench/peers (not part of CI).
//
// Usage: subdivide_openmesh SCHEME LEVELS FILE.obj [REPS]
//   SCHEME: loop | catmull-clark | sqrt3
// Loads FILE once per repetition (not timed), runs OpenMesh's uniform subdivider LEVELS times
// (timed with std::chrono::steady_clock and std::clock for CPU time), and prints one JSON line:
// {"tool": "openmesh", "scheme": .., "levels": .., "input_faces": .., "faces": ..,
//  "wall_s": [..], "cpu_s": [..], "median_wall_s": .., "median_cpu_s": .., "peak_rss_bytes": ..}
// peak_rss_bytes is getrusage(RUSAGE_SELF).ru_maxrss (KiB on Linux) times 1024: the whole
// process, so it includes the loaded input.
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/CatmullClarkT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/Sqrt3T.hh>

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <cstdlib>
#include <string>
#include <vector>

typedef OpenMesh::TriMesh_ArrayKernelT<> TriMesh;
typedef OpenMesh::PolyMesh_ArrayKernelT<> PolyMesh;

struct Run {
  double wall;
  double cpu;
  size_t faces;
  size_t input_faces;
};

template <class Mesh, class Subdivider>
static bool run_once(const char* file, size_t levels, Run& out) {
  Mesh mesh;
  if (!OpenMesh::IO::read_mesh(mesh, file)) {
    std::fprintf(stderr, "error: cannot read %s\n", file);
    return false;
  }
  out.input_faces = mesh.n_faces();
  Subdivider sub;
  std::clock_t c0 = std::clock();
  auto t0 = std::chrono::steady_clock::now();
  sub.attach(mesh);
  bool ok = sub(levels);
  sub.detach();
  auto t1 = std::chrono::steady_clock::now();
  std::clock_t c1 = std::clock();
  if (!ok) {
    std::fprintf(stderr, "error: subdivision failed\n");
    return false;
  }
  out.wall = std::chrono::duration<double>(t1 - t0).count();
  out.cpu = double(c1 - c0) / CLOCKS_PER_SEC;
  out.faces = mesh.n_faces();
  return true;
}

static double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: %s loop|catmull-clark|sqrt3 LEVELS FILE.obj [REPS]\n", argv[0]);
    return 2;
  }
  std::string scheme = argv[1];
  size_t levels = std::strtoul(argv[2], nullptr, 10);
  const char* file = argv[3];
  int reps = argc > 4 ? std::atoi(argv[4]) : 3;
  std::vector<double> wall, cpu;
  Run r{};
  for (int i = 0; i < reps; ++i) {
    bool ok;
    if (scheme == "loop") {
      ok = run_once<TriMesh, OpenMesh::Subdivider::Uniform::LoopT<TriMesh>>(file, levels, r);
    } else if (scheme == "sqrt3") {
      ok = run_once<TriMesh, OpenMesh::Subdivider::Uniform::Sqrt3T<TriMesh>>(file, levels, r);
    } else if (scheme == "catmull-clark") {
      ok = run_once<PolyMesh, OpenMesh::Subdivider::Uniform::CatmullClarkT<PolyMesh>>(file, levels, r);
    } else {
      std::fprintf(stderr, "error: unknown scheme %s\n", scheme.c_str());
      return 2;
    }
    if (!ok) return 3;
    wall.push_back(r.wall);
    cpu.push_back(r.cpu);
  }
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  std::printf("{\"tool\": \"openmesh\", \"scheme\": \"%s\", \"levels\": %zu, \"input_faces\": %zu, "
              "\"faces\": %zu, \"wall_s\": [",
              scheme.c_str(), levels, r.input_faces, r.faces);
  for (size_t i = 0; i < wall.size(); ++i) std::printf("%s%.6f", i ? ", " : "", wall[i]);
  std::printf("], \"cpu_s\": [");
  for (size_t i = 0; i < cpu.size(); ++i) std::printf("%s%.6f", i ? ", " : "", cpu[i]);
  std::printf("], \"median_wall_s\": %.6f, \"median_cpu_s\": %.6f, \"peak_rss_bytes\": %ld}\n",
              median(wall), median(cpu), long(ru.ru_maxrss) * 1024L);
  return 0;
}
