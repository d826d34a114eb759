// `libfive-mesh DEPTH [REPEAT [STL_DIR]]`: meshes each comparison shape with libfive's mesher
// (dual contouring with feature edges, libfive::Mesh::render, default settings but one worker
// per core) over [-1, 1]³ with 2^DEPTH cells a side, the fastest of REPEAT runs, and prints one
// line per shape in the format of bench/fidget-mesh: name, seconds, triangles, vertices, and
// the largest and RMS distance of the vertices to the exact surface, and the largest of the
// triangles' centroids (our own exact distance functions below, in f64). Diagnostics (octree
// level, open edges, vertices on the box) go to stderr. With STL_DIR, each shape's mesh is also
// written there as <name>.stl (spaces as '_').
//
// Written against libfive's public headers (libfive/tree/tree.hpp, render/brep/mesh.hpp,
// region.hpp, settings.hpp); build it as bench/libfive-mesh/README.md says.

#include <libfive/tree/tree.hpp>
#include <libfive/render/brep/mesh.hpp>
#include <libfive/render/brep/region.hpp>
#include <libfive/render/brep/settings.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

using libfive::Tree;
using P = std::array<double, 3>;

// Exact signed distance to a box of half-size `b` at the origin.
static double box_exact(P p, P b) {
    double q[3] = {std::fabs(p[0]) - b[0], std::fabs(p[1]) - b[1], std::fabs(p[2]) - b[2]};
    double out = std::sqrt(std::pow(std::max(q[0], 0.0), 2) + std::pow(std::max(q[1], 0.0), 2) +
                           std::pow(std::max(q[2], 0.0), 2));
    return out + std::min(std::max(std::max(q[0], q[1]), q[2]), 0.0);
}

static double len(P p) { return std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]); }

// Rotation of `p` by `a` radians about y then by `b` about x, inverted (the field's argument).
static P unturn(P p, double a, double b) {
    double s = std::sin(-b), c = std::cos(-b);
    P q = {p[0], c * p[1] - s * p[2], s * p[1] + c * p[2]};
    s = std::sin(-a);
    c = std::cos(-a);
    return {c * q[0] + s * q[2], q[1], -s * q[0] + c * q[2]};
}

// The box as fidget's examples write it: max of the slabs (its zero set is the box's).
static Tree tree_box(Tree x, Tree y, Tree z, P b) {
    return libfive::max(libfive::max(libfive::abs(x) - b[0], libfive::abs(y) - b[1]),
                        libfive::abs(z) - b[2]);
}

static std::array<Tree, 3> turn_tree(double a, double b) {
    Tree x = Tree::X(), y = Tree::Y(), z = Tree::Z();
    double s = std::sin(-b), c = std::cos(-b);
    Tree y1 = y * c - z * s, z1 = y * s + z * c;
    s = std::sin(-a);
    c = std::cos(-a);
    return {x * c + z1 * s, y1, -(x * s) + z1 * c};
}

struct Shape {
    const char* name;
    Tree tree;
    double (*exact)(P);
};

static const P BOX = {0.8, 0.48, 0.64};
// The same box smaller, its corners (0.99 from the centre) inside [-1, 1]³: no cut.
static const P WHOLE = {0.7, 0.42, 0.56};
static const double A = 30.0 * M_PI / 180.0;
static const double B = 20.0 * M_PI / 180.0;

static std::vector<Shape> shapes() {
    Tree x = Tree::X(), y = Tree::Y(), z = Tree::Z();
    Tree r = libfive::sqrt(libfive::square(x) + libfive::square(y) + libfive::square(z));
    auto t = turn_tree(A, B);
    auto t2 = turn_tree(A, B);
    Tree ring = libfive::sqrt(libfive::square(x) + libfive::square(z)) - 0.72;
    return {
        {"ball", r - 0.8, [](P p) { return len(p) - 0.8; }},
        {"turned box", tree_box(t[0], t[1], t[2], BOX),
         [](P p) { return box_exact(unturn(p, A, B), BOX); }},
        {"whole turned box", tree_box(t2[0], t2[1], t2[2], WHOLE),
         [](P p) { return box_exact(unturn(p, A, B), WHOLE); }},
        {"box less a ball", libfive::max(tree_box(x, y, z, {0.8, 0.8, 0.8}), -(r - 0.48)),
         [](P p) { return std::max(box_exact(p, {0.8, 0.8, 0.8}), -(len(p) - 0.48)); }},
        {"torus", libfive::sqrt(libfive::square(ring) + libfive::square(y)) - 0.24,
         [](P p) {
             double q = std::sqrt(p[0] * p[0] + p[2] * p[2]) - 0.72;
             return std::sqrt(q * q + p[1] * p[1]) - 0.24;
         }},
    };
}

// Rust's `{:.2e}` (e.g. 1.23e-3, 0.00e0), so the lines read like fidget-mesh's.
static std::string rust_e(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.2e", v);
    std::string s(buf);
    auto e = s.find('e');
    std::string mant = s.substr(0, e), ex = s.substr(e + 1);
    bool neg = ex[0] == '-';
    ex = ex.substr(1);
    while (ex.size() > 1 && ex[0] == '0') ex.erase(0, 1);
    return mant + "e" + (neg ? "-" : "") + ex;
}

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: libfive-mesh DEPTH [REPEAT [STL_DIR]]\n");
        return 2;
    }
    const int depth = std::atoi(argv[1]);
    const int repeat = argc > 2 ? std::atoi(argv[2]) : 3;
    const char* stl_dir = argc > 3 ? argv[3] : nullptr;
    const unsigned workers = std::max(1u, std::thread::hardware_concurrency());

    const libfive::Region<3> region({-1, -1, -1}, {1, 1, 1});
    // libfive's C API sets min_feature = 1 / res (res: cells per unit length); the octree's
    // depth is then ceil(log2(side / min_feature)) (Region::withResolution). So res = 2^DEPTH / 2
    // over a side of 2 gives 2^DEPTH cells a side; checked below, as that log2 is in f32.
    const double min_feature = 1.0 / (double(1u << depth) / 2.0);
    const int level = region.withResolution(min_feature).level;
    std::fprintf(stderr, "depth %d: min_feature %.9g, octree level %d, workers %u\n", depth,
                 min_feature, level, workers);
    if (level != depth) {
        std::fprintf(stderr, "octree level %d is not DEPTH %d\n", level, depth);
        return 1;
    }

    for (auto& s : shapes()) {
        libfive::BRepSettings settings;  // defaults: dual contouring, max_err 1e-8
        settings.min_feature = min_feature;
        settings.workers = workers;
        double best = std::numeric_limits<double>::infinity();
        std::unique_ptr<libfive::Mesh> m;
        for (int i = 0; i < std::max(repeat, 1); ++i) {
            m.reset();
            auto start = std::chrono::steady_clock::now();
            m = libfive::Mesh::render(s.tree, region, settings);
            std::chrono::duration<double> dt = std::chrono::steady_clock::now() - start;
            best = std::min(best, dt.count());
        }
        if (!m) {
            std::fprintf(stderr, "%s: no mesh\n", s.name);
            return 1;
        }
        // verts[0] is libfive's reserved marker, not a vertex of the mesh.
        const size_t nv = m->verts.size() - 1;
        auto pt = [&](uint32_t i) {
            const auto& v = m->verts[i];
            return P{double(v.x()), double(v.y()), double(v.z())};
        };
        double max = 0, sum = 0;
        for (size_t i = 1; i <= nv; ++i) {
            double d = std::fabs(s.exact(pt(i)));
            max = std::max(max, d);
            sum += d * d;
        }
        double rms = std::sqrt(sum / double(std::max<size_t>(nv, 1)));
        // The triangles' centroids: how far the mesh's faces (not only its vertices) lie.
        // Computed in f32 as fidget's harness does (its Vector3<f32>), then measured in f64.
        double face_max = 0;
        std::vector<char> used(m->verts.size(), 0);
        std::map<std::pair<uint32_t, uint32_t>, int> edges;
        for (const auto& t : m->branes) {
            auto c = (m->verts[t[0]] + m->verts[t[1]] + m->verts[t[2]]) / 3.0f;
            face_max = std::max(face_max, std::fabs(s.exact({c.x(), c.y(), c.z()})));
            for (int k = 0; k < 3; ++k) {
                used[t[k]] = 1;
                uint32_t a = t[k], b = t[(k + 1) % 3];
                edges[{std::min(a, b), std::max(a, b)}] += 1;
            }
        }
        size_t open = 0, nonmanifold = 0, unused = 0, on_box = 0;
        for (auto& e : edges) {
            open += e.second == 1;
            nonmanifold += e.second > 2;
        }
        for (size_t i = 1; i <= nv; ++i) {
            unused += !used[i];
            P p = pt(i);
            on_box += std::max({std::fabs(p[0]), std::fabs(p[1]), std::fabs(p[2])}) > 1 - 1e-6;
        }
        std::fprintf(stderr,
                     "  %s: open edges %zu, edges on >2 triangles %zu, unused vertices %zu, "
                     "vertices on the box's sides %zu\n",
                     s.name, open, nonmanifold, unused, on_box);
        if (stl_dir) {
            std::string f = std::string(stl_dir) + "/" + s.name + ".stl";
            std::replace(f.begin() + std::string(stl_dir).size(), f.end(), ' ', '_');
            if (!m->saveSTL(f)) std::fprintf(stderr, "could not write %s\n", f.c_str());
        }
        std::printf("%s\t%.3f\t%zu\t%zu\t%s\t%s\t%s\n", s.name, best, m->branes.size(), nv,
                    rust_e(max).c_str(), rust_e(rms).c_str(), rust_e(face_max).c_str());
        std::fflush(stdout);
    }
    return 0;
}
