// osd_driver: the OpenSubdiv reference for subcount's differential tests.
//
// Reads an OBJ mesh (only `v` and `f` lines; texture and normal indices, groups, materials and
// crease tags are ignored), refines it uniformly with OpenSubdiv's Far::TopologyRefiner, moves
// the positions down every level with Far::PrimvarRefiner in double precision, and writes the
// last level to stdout as OBJ: `v x y z` with %.17g (every double round-trips) and `f` lines
// with 1-based indices, in OpenSubdiv's own vertex and face order.
//
// Usage: osd_driver SCHEME LEVEL FILE.obj [BOUNDARY]
//   SCHEME    loop | catmark | bilinear
//   LEVEL     0..10 (0 writes the base mesh as OpenSubdiv read it)
//   BOUNDARY  edge-only (default) | edge-and-corner | none: Sdc::Options::VtxBoundaryInterpolation
//
// Errors go to stderr, one line, with exit status 1 (bad input) or 2 (usage).

#include <opensubdiv/far/error.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

using namespace OpenSubdiv;

namespace {

// One vertex position; the interface PrimvarRefiner::Interpolate expects of its data.
struct Point {
    double x, y, z;
    void Clear() { x = y = z = 0.0; }
    void AddWithWeight(Point const& p, double w) {
        x += w * p.x;
        y += w * p.y;
        z += w * p.z;
    }
};

struct Mesh {
    std::vector<Point> points;
    std::vector<int> faceSizes;
    std::vector<int> corners;
};

[[noreturn]] void fail(int status, std::string const& message) {
    std::fprintf(stderr, "osd_driver: %s\n", message.c_str());
    std::exit(status);
}

// Parses one OBJ vertex reference ("7", "7/2", "7//3", "-1/..."): the 0-based vertex index.
bool parseIndex(std::string const& token, int vertexCount, int& index) {
    std::string head = token.substr(0, token.find('/'));
    if (head.empty()) return false;
    char* end = nullptr;
    errno = 0;
    long value = std::strtol(head.c_str(), &end, 10);
    if (errno != 0 || *end != '\0' || value == 0) return false;
    long resolved = value > 0 ? value - 1 : vertexCount + value;
    if (resolved < 0 || resolved >= vertexCount) return false;
    index = static_cast<int>(resolved);
    return true;
}

Mesh readObj(char const* path) {
    std::ifstream in(path);
    if (!in) fail(1, std::string(path) + ": cannot open: " + std::strerror(errno));
    Mesh mesh;
    std::string line;
    long lineNumber = 0;
    while (std::getline(in, line)) {
        ++lineNumber;
        std::istringstream words(line);
        std::string keyword;
        if (!(words >> keyword)) continue;
        std::string where = std::string(path) + ": line " + std::to_string(lineNumber) + ": ";
        if (keyword == "v") {
            Point p;
            if (!(words >> p.x >> p.y >> p.z)) fail(1, where + "a vertex needs three numbers");
            mesh.points.push_back(p);
        } else if (keyword == "f") {
            int size = 0;
            std::string token;
            while (words >> token) {
                int index = 0;
                if (!parseIndex(token, static_cast<int>(mesh.points.size()), index)) {
                    fail(1, where + "bad vertex reference '" + token + "'");
                }
                mesh.corners.push_back(index);
                ++size;
            }
            if (size < 3) fail(1, where + "a face needs at least three vertices");
            mesh.faceSizes.push_back(size);
        }
    }
    if (in.bad()) fail(1, std::string(path) + ": read error");
    if (mesh.faceSizes.empty()) fail(1, std::string(path) + ": no faces");
    return mesh;
}

void reportError(Far::ErrorType, char const* message) {
    std::fprintf(stderr, "osd_driver: OpenSubdiv: %s\n", message);
}

void reportWarning(char const* message) {
    std::fprintf(stderr, "osd_driver: OpenSubdiv warning: %s\n", message);
}

Sdc::SchemeType parseScheme(std::string const& name) {
    if (name == "loop") return Sdc::SCHEME_LOOP;
    if (name == "catmark") return Sdc::SCHEME_CATMARK;
    if (name == "bilinear") return Sdc::SCHEME_BILINEAR;
    fail(2, "unknown scheme '" + name + "' (loop, catmark or bilinear)");
}

Sdc::Options::VtxBoundaryInterpolation parseBoundary(std::string const& name) {
    if (name == "edge-only") return Sdc::Options::VTX_BOUNDARY_EDGE_ONLY;
    if (name == "edge-and-corner") return Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER;
    if (name == "none") return Sdc::Options::VTX_BOUNDARY_NONE;
    fail(2, "unknown boundary interpolation '" + name + "' (edge-only, edge-and-corner or none)");
}

int parseLevel(std::string const& text) {
    char* end = nullptr;
    long level = std::strtol(text.c_str(), &end, 10);
    // UniformOptions keeps the level in 4 bits; 10 is far beyond any mesh worth writing out.
    if (text.empty() || *end != '\0' || level < 0 || level > 10) {
        fail(2, "level must be an integer from 0 to 10, got '" + text + "'");
    }
    return static_cast<int>(level);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 4 || argc > 5) {
        fail(2, "usage: osd_driver loop|catmark|bilinear LEVEL FILE.obj "
                "[edge-only|edge-and-corner|none]");
    }
    Sdc::SchemeType scheme = parseScheme(argv[1]);
    int level = parseLevel(argv[2]);
    Sdc::Options::VtxBoundaryInterpolation boundary =
        parseBoundary(argc == 5 ? argv[4] : "edge-only");
    Mesh mesh = readObj(argv[3]);

    if (scheme == Sdc::SCHEME_LOOP) {
        for (size_t f = 0; f < mesh.faceSizes.size(); ++f) {
            if (mesh.faceSizes[f] != 3) {
                fail(1, std::string(argv[3]) + ": face " + std::to_string(f) + " has " +
                            std::to_string(mesh.faceSizes[f]) +
                            " vertices: Loop needs triangles");
            }
        }
    }

    Far::SetErrorCallback(reportError);
    Far::SetWarningCallback(reportWarning);

    Far::TopologyDescriptor desc;
    desc.numVertices = static_cast<int>(mesh.points.size());
    desc.numFaces = static_cast<int>(mesh.faceSizes.size());
    desc.numVertsPerFace = mesh.faceSizes.data();
    desc.vertIndicesPerFace = mesh.corners.data();

    Sdc::Options sdcOptions;
    sdcOptions.SetVtxBoundaryInterpolation(boundary);
    using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
    std::unique_ptr<Far::TopologyRefiner> refiner(
        Factory::Create(desc, Factory::Options(scheme, sdcOptions)));
    if (!refiner) fail(1, std::string(argv[3]) + ": OpenSubdiv refused the topology");

    Far::TopologyRefiner::UniformOptions uniform(level);
    // The last level's face-vertex lists are all this driver reads.
    uniform.fullTopologyInLastLevel = false;
    refiner->RefineUniform(uniform);

    // Level 0 first, then each level right after the one before: one buffer for all levels.
    std::vector<Point> points(refiner->GetNumVerticesTotal());
    std::copy(mesh.points.begin(), mesh.points.end(), points.begin());
    Far::PrimvarRefinerReal<double> primvar(*refiner);
    Point* src = points.data();
    for (int l = 1; l <= level; ++l) {
        Point* dst = src + refiner->GetLevel(l - 1).GetNumVertices();
        primvar.Interpolate(l, src, dst);
        src = dst;
    }

    Far::TopologyLevel const& last = refiner->GetLevel(level);
    std::string out;
    out.reserve(static_cast<size_t>(last.GetNumVertices()) * 64);
    char buffer[96];
    for (int v = 0; v < last.GetNumVertices(); ++v) {
        Point const& p = src[v];
        std::snprintf(buffer, sizeof buffer, "v %.17g %.17g %.17g\n", p.x, p.y, p.z);
        out += buffer;
    }
    for (int f = 0; f < last.GetNumFaces(); ++f) {
        Far::ConstIndexArray face = last.GetFaceVertices(f);
        out += 'f';
        for (int i = 0; i < face.size(); ++i) {
            std::snprintf(buffer, sizeof buffer, " %d", face[i] + 1);
            out += buffer;
        }
        out += '\n';
    }
    if (std::fwrite(out.data(), 1, out.size(), stdout) != out.size() || std::fflush(stdout) != 0) {
        fail(1, "cannot write to stdout");
    }
    return 0;
}
