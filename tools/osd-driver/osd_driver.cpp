// osd_driver: the OpenSubdiv reference for subcount's differential tests and its peer in
// bench/peers.
//
// Reads an OBJ mesh (`v` and `f` lines, and with --tags OpenSubdiv's `t` tag lines; with
// --fvar also `vt` lines and every corner's `vt` index, else texture coordinates are ignored;
// normals, groups and materials are ignored), refines it uniformly with OpenSubdiv's
// Far::TopologyRefiner (fullTopologyInLastLevel = false) and moves the positions down every
// level with Far::PrimvarRefiner in double precision (and with --fvar the texture coordinates,
// as one face-varying channel, with InterpolateFaceVarying).
//
// Usage: osd_driver [OPTIONS] SCHEME LEVEL FILE.obj [BOUNDARY]
//   writes the last level to stdout as OBJ: `v x y z`, each the shortest text that reads back
//   as the same double (std::to_chars), and `f` lines with 1-based indices, in OpenSubdiv's
//   own vertex and face order; then `# hole F` (0-based) for each face tagged as a hole.
//   SCHEME    loop | catmark | bilinear
//   LEVEL     0..10 (0 writes the base mesh as OpenSubdiv read it)
//   BOUNDARY  edge-only | edge-and-corner | none: Sdc::Options::VtxBoundaryInterpolation
//             (default: the file's interpolateboundary tag with --tags, else edge-only)
//   OPTIONS   --tags: read crease, corner, hole, interpolateboundary, creasemethod,
//                     smoothtriangles and facevaryinginterpolateboundary tags (see README.md)
//             --crease-method uniform|chaikin, --triangle-rule catmark|smooth: Sdc::Options,
//                     over the file's tags
//             --fvar MODE: carry the `vt` coordinates as one face-varying channel, MODE
//                     none | corners-only | corners-plus1 | corners-plus2 | boundaries | all
//                     (Sdc::Options::FVarLinearInterpolation) or tag (the file's
//                     facevaryinginterpolateboundary tag, needs --tags; without the tag
//                     corners-plus1); writes `vt u v` after the `v` lines and `f v/vt` faces
//             --fvar-counts: with --fvar, print one JSON line of GetNumFVarValues at every
//                     level 0..LEVEL instead of the mesh
//             --limit: also PrimvarRefiner::Limit on the last level (refined with its full
//                     topology): after the `v` lines, one `# limit px py pz ux uy uz vx vy vz`
//                     line per vertex (limit position, first and second tangent), and with
//                     --fvar one `# limituv u v` line per value (LimitFaceVarying)
//
// Usage: osd_driver --time SCHEME LEVEL FILE.obj [REPS [FRAMES [limit]]]
//   times the same work (VTX_BOUNDARY_EDGE_ONLY) and prints one JSON line (see README.md):
//   REPS (default 3) one-shot runs, each timing TopologyRefinerFactory::Create, RefineUniform
//   and the level-by-level Interpolate into a fresh buffer separately, then FRAMES (default 0)
//   evaluations of the positions on the last run's refiner, the base positions perturbed
//   before each (untimed), the buffer reused; with `limit`, the last level refined with its
//   full topology and each frame followed by Limit (positions and both tangents, into kept
//   buffers), timed apart (frame_limit_s).
//
// Errors go to stderr, one line, with exit status 1 (bad input) or 2 (usage).

#include <opensubdiv/far/error.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <sys/resource.h>

#include <algorithm>
#include <charconv>
#include <cerrno>
#include <chrono>
#include <cmath>
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

// One texture coordinate; the interface PrimvarRefiner::InterpolateFaceVarying expects.
struct Uv {
    double u, v;
    void Clear() { u = v = 0.0; }
    void AddWithWeight(Uv const& p, double w) {
        u += w * p.u;
        v += w * p.v;
    }
};

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

// OpenSubdiv's OBJ tags (`t NAME nInts/nFloats/nStrings ints floats strings`), as its shape
// loader reads them; kept only with --tags.
struct Tags {
    std::vector<int> creasePairs;  // two vertex indices (0-based) per crease
    std::vector<float> creaseWeights;
    std::vector<int> corners;
    std::vector<float> cornerWeights;
    std::vector<int> holes;        // face indices (0-based)
    int boundary = -1;             // interpolateboundary: 0 none, 1 edge-and-corner, 2 edge-only
    std::string creaseMethod;      // creasemethod: normal | chaikin
    std::string triangles;         // smoothtriangles: catmark | smooth
    // facevaryinginterpolateboundary's integers as written (checked only when --fvar tag
    // uses them, so a file's output without --fvar does not depend on them).
    std::vector<int> fvarInterpolation;
    bool hasFvarInterpolation = false;
};

struct Mesh {
    std::vector<Point> points;
    std::vector<int> faceSizes;
    std::vector<int> corners;
    // With --fvar only: the `vt` entries (all of them, used or not) and each corner's 0-based
    // `vt` index, in the order of `corners`.
    std::vector<Uv> uvs;
    std::vector<int> uvCorners;
    Tags tags;
};

[[noreturn]] void fail(int status, std::string const& message) {
    std::fprintf(stderr, "osd_driver: %s\n", message.c_str());
    std::exit(status);
}

// Resolves one OBJ index ("7", "-1": 1-based, or relative to the `count` entries so far) to
// a 0-based index below `count`.
bool resolveIndex(std::string const& text, int count, int& index) {
    if (text.empty()) return false;
    char* end = nullptr;
    errno = 0;
    long value = std::strtol(text.c_str(), &end, 10);
    if (errno != 0 || *end != '\0' || value == 0) return false;
    long resolved = value > 0 ? value - 1 : count + value;
    if (resolved < 0 || resolved >= count) return false;
    index = static_cast<int>(resolved);
    return true;
}

// Parses one OBJ vertex reference ("7", "7/2", "7//3", "-1/..."): the 0-based vertex index.
bool parseIndex(std::string const& token, int vertexCount, int& index) {
    return resolveIndex(token.substr(0, token.find('/')), vertexCount, index);
}

// The texture part of an OBJ vertex reference ("7/2", "7/2/3", "-1/-1"): false when there is
// none ("7", "7//3"); `valid` says whether it names one of the `uvCount` entries so far.
bool parseUvIndex(std::string const& token, int uvCount, int& index, bool& valid) {
    size_t slash = token.find('/');
    if (slash == std::string::npos) return false;
    size_t next = token.find('/', slash + 1);
    std::string text = token.substr(slash + 1, next == std::string::npos ? next : next - slash - 1);
    if (text.empty()) return false;
    valid = resolveIndex(text, uvCount, index);
    return true;
}

// One `t` line (after the keyword): the counts, then that many ints, floats and strings.
void parseTag(std::istringstream& words, Tags& tags, std::string const& where) {
    std::string name, counts;
    if (!(words >> name >> counts)) fail(1, where + "a tag needs a name and counts");
    int nInts = 0, nFloats = 0, nStrings = 0;
    if (std::sscanf(counts.c_str(), "%d/%d/%d", &nInts, &nFloats, &nStrings) != 3 || nInts < 0 ||
        nFloats < 0 || nStrings < 0) {
        fail(1, where + "bad tag counts '" + counts + "'");
    }
    std::vector<int> ints(nInts);
    std::vector<float> floats(nFloats);
    std::vector<std::string> strings(nStrings);
    for (int& i : ints) if (!(words >> i)) fail(1, where + "tag '" + name + "' lacks an integer");
    for (float& f : floats) if (!(words >> f)) fail(1, where + "tag '" + name + "' lacks a number");
    for (std::string& t : strings) if (!(words >> t)) fail(1, where + "tag '" + name + "' lacks a string");
    // A float list is one value for every element or one per element.
    auto weights = [&](size_t elements, std::vector<float>& out) {
        if (floats.size() != 1 && floats.size() != elements) {
            fail(1, where + "tag '" + name + "' needs one sharpness or one per element");
        }
        for (size_t k = 0; k < elements; ++k) out.push_back(floats.size() == 1 ? floats[0] : floats[k]);
    };
    if (name == "crease") {
        if (ints.size() % 2 != 0) fail(1, where + "a crease lists vertex pairs");
        tags.creasePairs.insert(tags.creasePairs.end(), ints.begin(), ints.end());
        weights(ints.size() / 2, tags.creaseWeights);
    } else if (name == "corner") {
        tags.corners.insert(tags.corners.end(), ints.begin(), ints.end());
        weights(ints.size(), tags.cornerWeights);
    } else if (name == "hole") {
        tags.holes.insert(tags.holes.end(), ints.begin(), ints.end());
    } else if (name == "interpolateboundary") {
        if (ints.size() != 1 || ints[0] < 0 || ints[0] > 2) fail(1, where + "interpolateboundary takes 0, 1 or 2");
        tags.boundary = ints[0];
    } else if (name == "creasemethod") {
        if (strings.size() != 1) fail(1, where + "creasemethod takes one string");
        tags.creaseMethod = strings[0];
    } else if (name == "smoothtriangles") {
        if (strings.size() != 1) fail(1, where + "smoothtriangles takes one string");
        tags.triangles = strings[0];
    } else if (name == "facevaryinginterpolateboundary") {
        tags.fvarInterpolation = ints;
        tags.hasFvarInterpolation = true;
    }
    // Other tags (vertexedit, ...) do not move vertices here.
}

// Reads the mesh; `withUvs` also reads `vt` lines and requires a `vt` index at every corner.
Mesh readObj(char const* path, bool withTags, bool withUvs) {
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
        } else if (keyword == "vt" && withUvs) {
            // `vt u [v [w]]`: v defaults to 0 (as OBJ says), w is dropped.
            Uv uv{0.0, 0.0};
            if (!(words >> uv.u)) fail(1, where + "a texture coordinate needs a number");
            std::string second;
            if (words >> second) {
                char* end = nullptr;
                uv.v = std::strtod(second.c_str(), &end);
                if (*end != '\0') fail(1, where + "bad texture coordinate '" + second + "'");
            }
            mesh.uvs.push_back(uv);
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
                if (withUvs) {
                    int uv = 0;
                    bool valid = false;
                    if (!parseUvIndex(token, static_cast<int>(mesh.uvs.size()), uv, valid)) {
                        fail(1, where + "corner " + std::to_string(size) + " '" + token +
                                    "' has no texture coordinate index (--fvar needs one at "
                                    "every corner)");
                    }
                    if (!valid) {
                        fail(1, where + "corner " + std::to_string(size) + " '" + token +
                                    "': texture coordinate index out of range (" +
                                    std::to_string(mesh.uvs.size()) + " vt so far)");
                    }
                    mesh.uvCorners.push_back(uv);
                }
            }
            if (size < 3) fail(1, where + "a face needs at least three vertices");
            mesh.faceSizes.push_back(size);
        } else if (keyword == "t" && withTags) {
            parseTag(words, mesh.tags, where);
        }
    }
    if (in.bad()) fail(1, std::string(path) + ": read error");
    if (mesh.faceSizes.empty()) fail(1, std::string(path) + ": no faces");
    // OpenSubdiv does not check the tags' indices: out of range is refused here.
    int nv = static_cast<int>(mesh.points.size()), nf = static_cast<int>(mesh.faceSizes.size());
    for (int v : mesh.tags.creasePairs) {
        if (v < 0 || v >= nv) fail(1, std::string(path) + ": crease vertex " + std::to_string(v) + " out of range");
    }
    for (int v : mesh.tags.corners) {
        if (v < 0 || v >= nv) fail(1, std::string(path) + ": corner vertex " + std::to_string(v) + " out of range");
    }
    for (int f : mesh.tags.holes) {
        if (f < 0 || f >= nf) fail(1, std::string(path) + ": hole face " + std::to_string(f) + " out of range");
    }
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

// Rejects a non-triangle under Loop, naming the face.
void requireTriangles(Mesh const& mesh, char const* path) {
    for (size_t f = 0; f < mesh.faceSizes.size(); ++f) {
        if (mesh.faceSizes[f] != 3) {
            fail(1, std::string(path) + ": face " + std::to_string(f) + " has " +
                        std::to_string(mesh.faceSizes[f]) + " vertices: Loop needs triangles");
        }
    }
}

// The refiner of the mesh's base level; the mesh's arrays must outlive the call only.
std::unique_ptr<Far::TopologyRefiner> createRefiner(Mesh const& mesh, Sdc::SchemeType scheme,
                                                    Sdc::Options sdcOptions, char const* path) {
    Far::TopologyDescriptor desc;
    desc.numVertices = static_cast<int>(mesh.points.size());
    desc.numFaces = static_cast<int>(mesh.faceSizes.size());
    desc.numVertsPerFace = mesh.faceSizes.data();
    desc.vertIndicesPerFace = mesh.corners.data();
    Tags const& tags = mesh.tags;
    desc.numCreases = static_cast<int>(tags.creaseWeights.size());
    desc.creaseVertexIndexPairs = tags.creasePairs.data();
    desc.creaseWeights = tags.creaseWeights.data();
    desc.numCorners = static_cast<int>(tags.cornerWeights.size());
    desc.cornerVertexIndices = tags.corners.data();
    desc.cornerWeights = tags.cornerWeights.data();
    desc.numHoles = static_cast<int>(tags.holes.size());
    desc.holeIndices = tags.holes.data();
    // The texture coordinates, when read, as face-varying channel 0: one value per `vt`
    // entry (used or not), one value index per corner.
    Far::TopologyDescriptor::FVarChannel uvChannel;
    if (!mesh.uvCorners.empty()) {
        uvChannel.numValues = static_cast<int>(mesh.uvs.size());
        uvChannel.valueIndices = mesh.uvCorners.data();
        desc.numFVarChannels = 1;
        desc.fvarChannels = &uvChannel;
    }

    using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
    std::unique_ptr<Far::TopologyRefiner> refiner(
        Factory::Create(desc, Factory::Options(scheme, sdcOptions)));
    if (!refiner) fail(1, std::string(path) + ": OpenSubdiv refused the topology");
    return refiner;
}

// Uniform refinement to `level`; the last level's face-vertex lists are all either mode reads,
// its full topology only for the limit (`full`).
void refine(Far::TopologyRefiner& refiner, int level, bool full = false) {
    Far::TopologyRefiner::UniformOptions uniform(level);
    uniform.fullTopologyInLastLevel = full;
    refiner.RefineUniform(uniform);
}

// Moves the positions down level by level: `points` holds every level, level 0 first (already
// filled), each level right after the one before. Returns the last level's first vertex.
Point* interpolate(Far::TopologyRefiner const& refiner, Point* points) {
    Far::PrimvarRefinerReal<double> primvar(refiner);
    Point* src = points;
    for (int l = 1; l <= refiner.GetMaxLevel(); ++l) {
        Point* dst = src + refiner.GetLevel(l - 1).GetNumVertices();
        primvar.Interpolate(l, src, dst);
        src = dst;
    }
    return src;
}

// Moves the face-varying values of channel 0 down level by level, as `interpolate` does the
// positions: `values` holds every level's values, level 0 first (already filled). Returns the
// last level's first value.
Uv* interpolateUvs(Far::TopologyRefiner const& refiner, Uv* values) {
    Far::PrimvarRefinerReal<double> primvar(refiner);
    Uv* src = values;
    for (int l = 1; l <= refiner.GetMaxLevel(); ++l) {
        Uv* dst = src + refiner.GetLevel(l - 1).GetNumFVarValues(0);
        primvar.InterpolateFaceVarying(l, src, dst, 0);
        src = dst;
    }
    return src;
}

// The modes of Sdc::Options::FVarLinearInterpolation, in its order (the order of the
// facevaryinginterpolateboundary tag's integer).
char const* const fvarModeNames[] = {"none",          "corners-only", "corners-plus1",
                                     "corners-plus2", "boundaries",   "all"};

// The face-varying mode `name` names (index into fvarModeNames), or -1 for "tag".
int parseFvarMode(std::string const& name) {
    if (name == "tag") return -1;
    for (int m = 0; m < 6; ++m) {
        if (name == fvarModeNames[m]) return m;
    }
    fail(2, "unknown face-varying interpolation '" + name +
                "' (none, corners-only, corners-plus1, corners-plus2, boundaries, all or tag)");
}

Sdc::Options::CreasingMethod parseCreaseMethod(std::string const& name) {
    if (name == "uniform" || name == "normal") return Sdc::Options::CREASE_UNIFORM;
    if (name == "chaikin") return Sdc::Options::CREASE_CHAIKIN;
    fail(2, "unknown crease method '" + name + "' (uniform or chaikin)");
}

Sdc::Options::TriangleSubdivision parseTriangleRule(std::string const& name) {
    if (name == "catmark") return Sdc::Options::TRI_SUB_CATMARK;
    if (name == "smooth") return Sdc::Options::TRI_SUB_SMOOTH;
    fail(2, "unknown triangle rule '" + name + "' (catmark or smooth)");
}

int reference(int argc, char** argv) {
    // Options first: --tags, --crease-method M, --triangle-rule R, --fvar MODE, --fvar-counts;
    // a flag wins over the tag.
    bool withTags = false, fvarCounts = false, limit = false;
    std::string creaseMethod, triangles, fvar;
    int at = 1;
    for (; at < argc && std::strncmp(argv[at], "--", 2) == 0; ++at) {
        std::string flag = argv[at];
        if (flag == "--tags") {
            withTags = true;
        } else if (flag == "--fvar-counts") {
            fvarCounts = true;
        } else if (flag == "--limit") {
            limit = true;
        } else if ((flag == "--crease-method" || flag == "--triangle-rule" || flag == "--fvar") &&
                   at + 1 < argc) {
            (flag == "--crease-method" ? creaseMethod : flag == "--fvar" ? fvar : triangles) =
                argv[++at];
        } else {
            fail(2, "unknown option '" + flag + "'");
        }
    }
    int rest = argc - at;
    if (rest < 3 || rest > 4) {
        fail(2, "usage: osd_driver [--tags] [--crease-method uniform|chaikin] "
                "[--triangle-rule catmark|smooth] [--limit] [--fvar none|corners-only|corners-plus1|"
                "corners-plus2|boundaries|all|tag [--fvar-counts]] loop|catmark|bilinear LEVEL "
                "FILE.obj [edge-only|edge-and-corner|none]\n"
                "       osd_driver --time loop|catmark|bilinear LEVEL FILE.obj [REPS [FRAMES [limit]]]");
    }
    bool withUvs = !fvar.empty();
    int fvarMode = withUvs ? parseFvarMode(fvar) : 0;
    if (fvarCounts && !withUvs) fail(2, "--fvar-counts needs --fvar MODE");
    if (fvarMode < 0 && !withTags) fail(2, "--fvar tag reads the file's tag: it needs --tags");
    char** args = argv + at;
    Sdc::SchemeType scheme = parseScheme(args[0]);
    int level = parseLevel(args[1]);
    Mesh mesh = readObj(args[2], withTags, withUvs);
    if (scheme == Sdc::SCHEME_LOOP) requireTriangles(mesh, args[2]);

    Tags const& tags = mesh.tags;
    static char const* const boundaryNames[] = {"none", "edge-and-corner", "edge-only"};
    Sdc::Options sdcOptions;
    sdcOptions.SetVtxBoundaryInterpolation(parseBoundary(
        rest == 4 ? args[3] : tags.boundary >= 0 ? boundaryNames[tags.boundary] : "edge-only"));
    if (creaseMethod.empty()) creaseMethod = tags.creaseMethod;
    if (!creaseMethod.empty()) sdcOptions.SetCreasingMethod(parseCreaseMethod(creaseMethod));
    if (triangles.empty()) triangles = tags.triangles;
    if (!triangles.empty()) sdcOptions.SetTriangleSubdivision(parseTriangleRule(triangles));
    if (fvarMode < 0) {
        // --fvar tag: facevaryinginterpolateboundary's integer, else corners-plus1 (the default
        // of USD, RenderMan and `subcount subdivide`; Sdc::Options() itself defaults to all).
        fvarMode = Sdc::Options::FVAR_LINEAR_CORNERS_PLUS1;
        if (tags.hasFvarInterpolation) {
            std::vector<int> const& ints = tags.fvarInterpolation;
            if (ints.size() != 1 || ints[0] < 0 || ints[0] > 5) {
                fail(1, std::string(args[2]) + ": facevaryinginterpolateboundary takes one "
                                               "integer from 0 to 5");
            }
            fvarMode = ints[0];
        }
    }
    if (withUvs) {
        sdcOptions.SetFVarLinearInterpolation(
            static_cast<Sdc::Options::FVarLinearInterpolation>(fvarMode));
    }

    std::unique_ptr<Far::TopologyRefiner> refiner = createRefiner(mesh, scheme, sdcOptions, args[2]);
    refine(*refiner, level, limit);

    if (fvarCounts) {
        std::string line = std::string("{\"scheme\": \"") + args[0] + "\", \"level\": " +
                           std::to_string(level) + ", \"fvar\": \"" + fvarModeNames[fvarMode] +
                           "\", \"fvar_values\": [";
        for (int l = 0; l <= level; ++l) {
            line += (l ? ", " : "") + std::to_string(refiner->GetLevel(l).GetNumFVarValues(0));
        }
        line += "]}\n";
        if (std::fwrite(line.data(), 1, line.size(), stdout) != line.size() ||
            std::fflush(stdout) != 0) {
            fail(1, "cannot write to stdout");
        }
        return 0;
    }

    std::vector<Point> points(refiner->GetNumVerticesTotal());
    std::copy(mesh.points.begin(), mesh.points.end(), points.begin());
    Point const* src = interpolate(*refiner, points.data());

    // std::to_chars writes the shortest text that reads back as the same double (and is much
    // faster than printf's %.17g, which the differential tests would otherwise wait for).
    Far::TopologyLevel const& last = refiner->GetLevel(level);
    std::string out;
    out.reserve(static_cast<size_t>(last.GetNumVertices()) * 64);
    char buffer[96];
    auto put = [&](auto value) {
        std::to_chars_result r = std::to_chars(buffer, buffer + sizeof buffer, value);
        out.append(buffer, r.ptr);
    };
    for (int v = 0; v < last.GetNumVertices(); ++v) {
        Point const& p = src[v];
        out += 'v';
        for (double c : {p.x, p.y, p.z}) {
            out += ' ';
            put(c);
        }
        out += '\n';
    }
    Far::PrimvarRefinerReal<double> primvar(*refiner);
    if (limit) {
        int n = last.GetNumVertices();
        std::vector<Point> position(n), tangent1(n), tangent2(n);
        primvar.Limit(src, position, tangent1, tangent2);
        for (int v = 0; v < n; ++v) {
            out += "# limit";
            for (Point const* p : {&position[v], &tangent1[v], &tangent2[v]}) {
                for (double c : {p->x, p->y, p->z}) {
                    out += ' ';
                    put(c);
                }
            }
            out += '\n';
        }
    }
    if (withUvs) {
        std::vector<Uv> uvs(refiner->GetNumFVarValuesTotal(0));
        std::copy(mesh.uvs.begin(), mesh.uvs.end(), uvs.begin());
        Uv const* uvSrc = interpolateUvs(*refiner, uvs.data());
        for (int i = 0; i < last.GetNumFVarValues(0); ++i) {
            out += "vt ";
            put(uvSrc[i].u);
            out += ' ';
            put(uvSrc[i].v);
            out += '\n';
        }
        if (limit) {
            std::vector<Uv> limitUvs(last.GetNumFVarValues(0));
            primvar.LimitFaceVarying(uvSrc, limitUvs, 0);
            for (Uv const& uv : limitUvs) {
                out += "# limituv ";
                put(uv.u);
                out += ' ';
                put(uv.v);
                out += '\n';
            }
        }
    }
    for (int f = 0; f < last.GetNumFaces(); ++f) {
        Far::ConstIndexArray face = last.GetFaceVertices(f);
        Far::ConstIndexArray faceUvs = withUvs ? last.GetFaceFVarValues(f, 0) : face;
        out += 'f';
        for (int i = 0; i < face.size(); ++i) {
            out += ' ';
            put(face[i] + 1);
            if (withUvs) {
                out += '/';
                put(faceUvs[i] + 1);
            }
        }
        out += '\n';
    }
    // Faces OpenSubdiv tags as holes (tagged ones and, under VTX_BOUNDARY_NONE, every face at
    // a boundary vertex, and their descendants): still refined and written above, listed
    // here as comments (`# hole F`, 0-based) that OBJ readers skip.
    if (refiner->HasHoles()) {
        for (int f = 0; f < last.GetNumFaces(); ++f) {
            if (last.IsFaceHole(f)) {
                out += "# hole ";
                put(f);
                out += '\n';
            }
        }
    }
    if (std::fwrite(out.data(), 1, out.size(), stdout) != out.size() || std::fflush(stdout) != 0) {
        fail(1, "cannot write to stdout");
    }
    return 0;
}

int parseCount(char const* text, char const* what, int max) {
    char* end = nullptr;
    errno = 0;
    long value = std::strtol(text, &end, 10);
    if (errno != 0 || *text == '\0' || *end != '\0' || value < 0 || value > max) {
        fail(2, std::string(what) + " must be an integer from 0 to " + std::to_string(max) +
                    ", got '" + text + "'");
    }
    return static_cast<int>(value);
}

double since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void printList(char const* key, std::vector<double> const& values) {
    std::printf(", \"%s\": [", key);
    for (size_t i = 0; i < values.size(); ++i) std::printf("%s%.6f", i ? ", " : "", values[i]);
    std::printf("]");
}

// --time: the peer of `subcount subdivide --timings [--frames N]` in bench/peers/compare.py.
int timing(int argc, char** argv) {
    if (argc < 5 || argc > 8) {
        fail(2, "usage: osd_driver --time loop|catmark|bilinear LEVEL FILE.obj [REPS [FRAMES [limit]]]");
    }
    bool limit = argc > 7 && std::strcmp(argv[7], "limit") == 0;
    if (argc > 7 && !limit) fail(2, std::string("unknown timing mode '") + argv[7] + "' (limit)");
    Sdc::SchemeType scheme = parseScheme(argv[2]);
    int level = parseLevel(argv[3]);
    char const* path = argv[4];
    int reps = argc > 5 ? parseCount(argv[5], "REPS", 1000) : 3;
    int frames = argc > 6 ? parseCount(argv[6], "FRAMES", 100000) : 0;
    if (reps < 1) fail(2, "REPS must be at least 1");
    Mesh mesh = readObj(path, false, false);
    if (scheme == Sdc::SCHEME_LOOP) requireTriangles(mesh, path);

    using Clock = std::chrono::steady_clock;
    std::vector<double> createS, refineS, interpolateS, frameS, limitS;
    int vertices = 0, faces = 0;
    double checksum = 0.0;
    for (int rep = 0; rep < reps; ++rep) {
        Clock::time_point start = Clock::now();
        Sdc::Options edgeOnly;
        edgeOnly.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
        std::unique_ptr<Far::TopologyRefiner> refiner = createRefiner(mesh, scheme, edgeOnly, path);
        createS.push_back(since(start));

        start = Clock::now();
        refine(*refiner, level, limit);
        refineS.push_back(since(start));

        // A fresh buffer, as a caller's: `new Point[n]` leaves the pages untouched, so the first
        // Interpolate pays their faults, as any one-shot run does.
        size_t total = static_cast<size_t>(refiner->GetNumVerticesTotal());
        std::unique_ptr<Point[]> points(new Point[total]);
        std::copy(mesh.points.begin(), mesh.points.end(), points.get());
        start = Clock::now();
        Point const* last = interpolate(*refiner, points.get());
        interpolateS.push_back(since(start));

        Far::TopologyLevel const& top = refiner->GetLevel(level);
        vertices = top.GetNumVertices();
        faces = top.GetNumFaces();
        checksum = 0.0;
        for (int v = 0; v < vertices; ++v) checksum += last[v].x + last[v].y + last[v].z;

        bool lastRep = rep + 1 == reps || createS.back() + refineS.back() + interpolateS.back() > 10;
        if (lastRep) {
            // Per-frame evaluation on the refiner built once: the base positions moved by a
            // small deterministic amount (not timed), then every level interpolated again.
            std::vector<Point> position, tangent1, tangent2;
            if (limit) {
                position.resize(vertices);
                tangent1.resize(vertices);
                tangent2.resize(vertices);
            }
            Far::PrimvarRefinerReal<double> primvar(*refiner);
            for (int frame = 0; frame < frames; ++frame) {
                double amount = 1e-6 * static_cast<double>(frame + 1);
                for (size_t v = 0; v < mesh.points.size(); ++v) {
                    Point p = mesh.points[v];
                    double s = amount * std::sin(static_cast<double>(v));
                    points[v] = Point{p.x + s, p.y - s, p.z + 0.5 * s};
                }
                start = Clock::now();
                last = interpolate(*refiner, points.get());
                frameS.push_back(since(start));
                checksum += last[0].x;
                if (limit) {
                    start = Clock::now();
                    primvar.Limit(last, position, tangent1, tangent2);
                    limitS.push_back(since(start));
                    checksum += position[0].x + tangent1[0].y + tangent2[0].z;
                }
            }
            break;
        }
    }

    struct rusage usage;
    getrusage(RUSAGE_SELF, &usage);
    std::printf("{\"tool\": \"opensubdiv\", \"scheme\": \"%s\", \"levels\": %d, "
                "\"input_faces\": %zu, \"vertices\": %d, \"faces\": %d",
                argv[2], level, mesh.faceSizes.size(), vertices, faces);
    printList("create_s", createS);
    printList("refine_s", refineS);
    printList("interpolate_s", interpolateS);
    printList("frame_interpolate_s", frameS);
    if (limit) printList("frame_limit_s", limitS);
    std::printf(", \"peak_rss_bytes\": %ld, \"checksum\": %.17g}\n", long(usage.ru_maxrss) * 1024L,
                checksum);
    if (std::fflush(stdout) != 0) fail(1, "cannot write to stdout");
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    Far::SetErrorCallback(reportError);
    Far::SetWarningCallback(reportWarning);
    if (argc > 1 && std::strcmp(argv[1], "--time") == 0) return timing(argc, argv);
    return reference(argc, argv);
}
