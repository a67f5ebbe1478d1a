// Traversal benchmark: Mrays/s of kernels/trace_rays.cl (bvh_intersect) on a deterministic
// procedural scene of 100k+ triangles, for coherent primary rays, incoherent diffuse bounces and
// shadow rays, closest-hit and any-hit; BVH build time; optionally Embree 3 on the same rays.
//
//   traversal_bench [--json FILE] [--rays N] [--runs N] [--local N] [--options "-D..."] [--device SPEC]
//                   [--stats] [--quick] [--only NAME] [--leaf N] [--node-cost C]
// --stats: nodes visited and triangles tested per ray (a -DBVH_STATS build of the kernel);
// --quick: only the closest-hit cases, no work-group sweep.
// --only NAME: only the cases whose name contains NAME ("shadow", "any", "diffuse closest"), e.g. to profile one.
// --ab-options S / --ab-leaf N / --ab-node-cost C: an A/B comparison against a second variant
//   (kernel options and/or build options), timed in alternation so that load from other
//   processes hits both alike; prints the speed-up of B and exits.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <sys/resource.h>

#include "device/device.h"
#include "scene/bvh_build.h"
#include "scene/bvh_trace.h"
#include "util/error.h"

#ifdef CLPPM_HAVE_EMBREE
#include <embree3/rtcore.h>
#endif

namespace clppm {
namespace {

struct V {
    double x, y, z;
};
V operator+(V a, V b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V operator-(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V operator*(V a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V cross(V a, V b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
V normalize(V a) { return a * (1 / std::sqrt(dot(a, a))); }
Vec3 f3(V a) { return {float(a.x), float(a.y), float(a.z)}; }
V d3(const float* p) { return {p[0], p[1], p[2]}; }

// ---- the scene: a closed room, a displaced icosphere and four smaller blobs ----------------------

void add_displaced_icosphere(std::vector<Vec3>& out, int subdivisions, V center, double radius, double bumps,
                             double freq) {
    const double g = (1 + std::sqrt(5.0)) / 2;
    std::vector<V> v = {{-1, g, 0},  {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                        {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
    std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                         {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                         {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                         {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (V& p : v) p = normalize(p);
    for (int s = 0; s < subdivisions; ++s) {
        std::vector<std::array<int, 3>> next;
        std::map<std::pair<int, int>, int> mids; // shared edges get one midpoint: a watertight mesh
        auto midpoint = [&](int a, int b) {
            auto [it, fresh] = mids.insert({std::minmax(a, b), int(v.size())});
            if (fresh) v.push_back(normalize((v[a] + v[b]) * 0.5));
            return it->second;
        };
        for (auto& t : f) {
            int a = midpoint(t[0], t[1]), b = midpoint(t[1], t[2]), c = midpoint(t[2], t[0]);
            next.insert(next.end(), {{t[0], a, c}, {t[1], b, a}, {t[2], c, b}, {a, b, c}});
        }
        f.swap(next);
    }
    std::vector<Vec3> pos;
    for (const V& p : v) {
        const double d =
            1 + bumps * (std::sin(freq * p.x) * std::sin(1.3 * freq * p.y + 1) * std::sin(0.7 * freq * p.z + 2) +
                         0.3 * std::sin(3.1 * freq * (p.x + p.y)) * std::sin(2.3 * freq * p.z));
        pos.push_back(f3(center + p * (radius * d)));
    }
    for (auto& t : f) out.insert(out.end(), {pos[t[0]], pos[t[1]], pos[t[2]]});
}

// The box [-w,w] x [-h,h] x [-w,w], each wall an n x n grid with a gentle ripple, facing inwards.
void add_room(std::vector<Vec3>& out, double w, double h, int n) {
    const double half[3] = {w, h, w};
    for (int axis = 0; axis < 3; ++axis)
        for (int side = -1; side <= 1; side += 2) {
            const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
            auto p = [&](int i, int j) {
                double q[3];
                q[a1] = half[a1] * (-1 + 2.0 * i / n);
                q[a2] = half[a2] * (-1 + 2.0 * j / n);
                const bool border = i == 0 || j == 0 || i == n || j == n;
                q[axis] = side * half[axis] * (1 + (border ? 0 : 0.01 * std::sin(0.9 * i) * std::cos(1.1 * j)));
                return Vec3{float(q[0]), float(q[1]), float(q[2])};
            };
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j)
                    out.insert(out.end(),
                               {p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j), p(i + 1, j + 1), p(i, j + 1)});
        }
}

std::vector<Vec3> make_scene() {
    std::vector<Vec3> t;
    add_room(t, 5, 3, 40);                                         // 19,200
    add_displaced_icosphere(t, 6, {0, -0.5, 0}, 1.6, 0.12, 6.0);   // 81,920
    add_displaced_icosphere(t, 4, {-3, -2, -2.5}, 0.8, 0.2, 9.0);  // 5,120
    add_displaced_icosphere(t, 4, {3, -2, -2.5}, 0.8, 0.2, 9.0);   // 5,120
    add_displaced_icosphere(t, 4, {-2.5, 1.5, 1}, 0.6, 0.3, 12.0); // 5,120
    add_displaced_icosphere(t, 4, {2.5, 1.5, 1}, 0.6, 0.3, 12.0);  // 5,120
    return t;
}

// ---- rays ---------------------------------------------------------------------------------------

TraceRay ray(V o, V d, double tmax, bool any) {
    return TraceRay{
        {float(o.x), float(o.y), float(o.z)}, float(tmax), {float(d.x), float(d.y), float(d.z)}, any ? 1.0f : 0.0f};
}

// A pinhole camera in the room looking at the big sphere; rays in scanline order (coherent).
std::vector<TraceRay> primary_rays(size_t n) {
    const int w = int(std::sqrt(double(n))), h = int((n + w - 1) / w);
    const V eye{0.3, 0.4, 4.6}, fwd = normalize(V{0, -0.6, 0} - eye), right = normalize(cross(fwd, {0, 1, 0})),
                                up = cross(right, fwd);
    const double tx = std::tan(0.5 * 1.1), ty = tx * h / w;
    std::vector<TraceRay> rays;
    rays.reserve(n);
    for (int y = 0; y < h && rays.size() < n; ++y)
        for (int x = 0; x < w && rays.size() < n; ++x) {
            const double sx = (2 * (x + 0.5) / w - 1) * tx, sy = (1 - 2 * (y + 0.5) / h) * ty;
            rays.push_back(ray(eye, normalize(fwd + right * sx + up * sy), INFINITY, false));
        }
    return rays;
}

struct Surface {
    V p, n; // hit point and geometric normal facing the incoming ray
};

std::vector<Surface> surfaces(const std::vector<TraceRay>& rays, const std::vector<TraceHit>& hits,
                              const std::vector<std::array<float, 4>>& tris) {
    std::vector<Surface> s;
    for (size_t i = 0; i < rays.size(); ++i) {
        if (!hits[i].hit()) continue;
        const uint32_t p = hits[i].prim;
        V n = normalize(cross(d3(tris[3 * p + 1].data()), d3(tris[3 * p + 2].data())));
        const V d = d3(rays[i].dir);
        if (dot(n, d) > 0) n = n * -1.0;
        s.push_back({d3(rays[i].org) + d * hits[i].t, n});
    }
    return s;
}

// Cosine-weighted bounces from the primary hits (Malley's method), origins offset along the normal.
std::vector<TraceRay> diffuse_rays(const std::vector<Surface>& s, size_t n, double eps) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u01(0, 1);
    std::vector<TraceRay> rays;
    rays.reserve(n);
    for (size_t i = 0; i < n; ++i) {
        const Surface& h = s[i % s.size()];
        const V t = normalize(std::fabs(h.n.x) > 0.5 ? cross(h.n, {0, 1, 0}) : cross(h.n, {1, 0, 0})),
                b = cross(h.n, t);
        const double r = std::sqrt(u01(rng)), phi = 2 * M_PI * u01(rng);
        const V d = t * (r * std::cos(phi)) + b * (r * std::sin(phi)) + h.n * std::sqrt(std::max(0.0, 1 - r * r));
        rays.push_back(ray(h.p + h.n * eps, normalize(d), INFINITY, false));
    }
    return rays;
}

// Shadow rays from the primary hits to points on a small ceiling light: any-hit with finite tmax.
std::vector<TraceRay> shadow_rays(const std::vector<Surface>& s, size_t n, double eps) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u01(-0.5, 0.5);
    std::vector<TraceRay> rays;
    rays.reserve(n);
    for (size_t i = 0; i < n; ++i) {
        const Surface& h = s[i % s.size()];
        const V o = h.p + h.n * eps, light{u01(rng), 2.9, u01(rng)};
        const V d = light - o;
        const double dist = std::sqrt(dot(d, d));
        rays.push_back(ray(o, d * (1 / dist), dist * (1 - 1e-4), true));
    }
    return rays;
}

std::vector<TraceRay> with_any_hit(std::vector<TraceRay> rays, bool any) {
    for (TraceRay& r : rays) r.any_hit = any ? 1.0f : 0.0f;
    return rays;
}

// ---- timing ---------------------------------------------------------------------------------------

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

// CPU seconds used by this process, all threads (PoCL's workers and Embree's included).
double cpu_now() {
    rusage u;
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// Throughput of one timed run: by wall clock, and by CPU time scaled to the 2 cores (what an
// idle machine would give; the wall clock suffers when other processes share the cores).
struct Rate {
    double wall = 0, cpu = 0;
    void best_of(double rays, double wall_s, double cpu_s, int cores) {
        wall = std::max(wall, rays / wall_s * 1e-6);
        cpu = std::max(cpu, rays / (cpu_s / cores) * 1e-6);
    }
};

struct Case {
    std::string name;
    std::vector<TraceRay> rays;
    Rate clppm, embree;
    double hit_fraction = 0;
    double nodes_per_ray = 0, tris_per_ray = 0; // --stats
};

// Best of `runs` launches after one warm-up, wall clock around launch and finish.
Rate time_device(const DeviceContext& dc, RayTracer& tracer, const DeviceBvh& bvh, const std::vector<TraceRay>& rays,
                 size_t local, int runs, double* hit_fraction = nullptr) {
    cl::Buffer rb(dc.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, rays.size() * sizeof(TraceRay),
                  const_cast<TraceRay*>(rays.data()));
    cl::Buffer hb(dc.context, CL_MEM_WRITE_ONLY, rays.size() * sizeof(TraceHit));
    tracer.enqueue(bvh, rb, hb, uint32_t(rays.size()), local);
    dc.queue.finish();
    Rate rate;
    for (int r = 0; r < runs; ++r) {
        const double t0 = now(), c0 = cpu_now();
        tracer.enqueue(bvh, rb, hb, uint32_t(rays.size()), local);
        dc.queue.finish();
        rate.best_of(double(rays.size()), now() - t0, cpu_now() - c0, int(dc.info.compute_units));
    }
    if (hit_fraction) {
        std::vector<TraceHit> hits(rays.size());
        dc.queue.enqueueReadBuffer(hb, CL_TRUE, 0, hits.size() * sizeof(TraceHit), hits.data());
        size_t n = 0;
        for (const TraceHit& h : hits) n += h.hit();
        *hit_fraction = double(n) / double(hits.size());
    }
    return rate;
}

#ifdef CLPPM_HAVE_EMBREE
// Embree 3, single-ray rtcIntersect1 / rtcOccluded1 on the same rays, split over `threads`.
struct EmbreeScene {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    double build_seconds = 0;
    explicit EmbreeScene(const std::vector<Vec3>& p) {
        device = rtcNewDevice(nullptr);
        const double t0 = now();
        scene = rtcNewScene(device);
        RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        const size_t n = p.size() / 3;
        float* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), std::max<size_t>(1, p.size())));
        unsigned* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                       3 * sizeof(unsigned), std::max<size_t>(1, n)));
        for (size_t i = 0; i < p.size(); ++i) v[3 * i] = p[i].x, v[3 * i + 1] = p[i].y, v[3 * i + 2] = p[i].z;
        for (size_t i = 0; i < 3 * n; ++i) idx[i] = unsigned(i);
        rtcCommitGeometry(g);
        rtcAttachGeometry(scene, g);
        rtcReleaseGeometry(g);
        rtcCommitScene(scene);
        build_seconds = now() - t0;
    }
    ~EmbreeScene() {
        rtcReleaseScene(scene);
        rtcReleaseDevice(device);
    }

    Rate run(const std::vector<TraceRay>& rays, int threads) const {
        auto work = [&](size_t begin, size_t end) {
            RTCIntersectContext ctx;
            rtcInitIntersectContext(&ctx);
            for (size_t i = begin; i < end; ++i) {
                const TraceRay& r = rays[i];
                RTCRayHit rh;
                rh.ray.org_x = r.org[0], rh.ray.org_y = r.org[1], rh.ray.org_z = r.org[2];
                rh.ray.dir_x = r.dir[0], rh.ray.dir_y = r.dir[1], rh.ray.dir_z = r.dir[2];
                rh.ray.tnear = 0, rh.ray.tfar = r.tmax, rh.ray.time = 0, rh.ray.mask = ~0u, rh.ray.id = 0,
                rh.ray.flags = 0;
                if (r.any_hit != 0) {
                    rtcOccluded1(scene, &ctx, &rh.ray);
                } else {
                    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                    rtcIntersect1(scene, &ctx, &rh);
                }
            }
        };
        std::vector<std::thread> pool;
        const double t0 = now(), c0 = cpu_now();
        const size_t chunk = (rays.size() + threads - 1) / threads;
        for (int t = 0; t < threads; ++t)
            pool.emplace_back(work, std::min(rays.size(), t * chunk), std::min(rays.size(), (t + 1) * chunk));
        for (std::thread& th : pool) th.join();
        Rate r;
        r.best_of(double(rays.size()), now() - t0, cpu_now() - c0, threads);
        return r;
    }
};
#endif

int run(int argc, char** argv) {
    std::string json_path, options, device_spec = "cpu";
    size_t nrays = 1000000, forced_local = 0;
    int runs = 5;
    bool forced = false, stats = false, quick = false;
    std::string only;
    BvhBuildOptions build_options, ab_build;
    std::string ab_options;
    bool ab = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto next = [&]() -> std::string {
            if (i + 1 >= argc) throw Error(a + ": missing value");
            return argv[++i];
        };
        if (a == "--json") json_path = next();
        else if (a == "--rays") nrays = std::stoul(next());
        else if (a == "--runs") runs = std::stoi(next());
        else if (a == "--local") forced_local = std::stoul(next()), forced = true;
        else if (a == "--options") options = next();
        else if (a == "--device") device_spec = next();
        else if (a == "--stats") stats = true;
        else if (a == "--quick") quick = true, forced = true;
        else if (a == "--only") only = next();
        else if (a == "--leaf") build_options.max_leaf = unsigned(std::stoul(next()));
        else if (a == "--node-cost") build_options.node_cost = std::stof(next());
        else if (a == "--ab-options") ab_options = next(), ab = true;
        else if (a == "--ab-leaf") ab_build.max_leaf = unsigned(std::stoul(next())), ab = true;
        else if (a == "--ab-node-cost") ab_build.node_cost = std::stof(next()), ab = true;
        else throw Error("unknown argument " + a + " (see the comment at the top of bench/traversal_bench.cpp)");
    }

    const std::vector<Vec3> scene = make_scene();
    const size_t ntris = scene.size() / 3;
    const BvhBuildResult bvh = build_bvh(scene, build_options);
    double build_best = bvh.build_seconds;
    for (int r = 0; r < 3; ++r) build_best = std::min(build_best, build_bvh(scene, build_options).build_seconds);
    std::vector<Vec3> ordered;
    ordered.reserve(scene.size());
    for (uint32_t i : bvh.tri_order)
        for (int k = 0; k < 3; ++k) ordered.push_back(scene[3 * i + k]);
    const auto tris = bvh_triangle_data(ordered);
    std::printf("scene: %zu triangles; BVH: %zu nodes, %zu leaves (%.2f triangles/leaf), depth %u, SAH cost %.2f\n",
                ntris, bvh.nodes.size(), bvh.leaf_count, double(ntris) / double(bvh.leaf_count), bvh.max_depth,
                bvh_sah_cost(bvh.nodes));
    std::printf("build: %.1f ms (best of 4)\n", build_best * 1e3);

    const std::vector<DeviceInfo> devices = list_devices();
    DeviceContext dc(select_device(devices, device_spec));
    RayTracer tracer(dc, options);
    DeviceBvh dbvh(dc, bvh.nodes, ordered);
    std::printf("device: %s (%s), %u compute units, kernel options \"%s\"\n", dc.info.name.c_str(),
                dc.info.platform_name.c_str(), dc.info.compute_units, options.c_str());

    std::vector<Case> cases;
    const std::vector<TraceRay> primary = primary_rays(nrays);
    const std::vector<TraceHit> primary_hits = tracer.trace(dbvh, primary);
    const std::vector<Surface> surf = surfaces(primary, primary_hits, tris);
    if (surf.empty()) throw Error("no primary ray hit the scene");
    const double eps = 1e-4 * 10; // scene is ~10 units across
    const std::vector<TraceRay> diffuse = diffuse_rays(surf, nrays, eps);
    auto add = [&](const char* name, std::vector<TraceRay> rays) {
        Case c;
        c.name = name;
        c.rays = std::move(rays);
        cases.push_back(std::move(c));
    };
    add("primary closest", primary);
    if (!quick) add("primary any", with_any_hit(primary, true));
    add("diffuse closest", diffuse);
    if (!quick) {
        add("diffuse any", with_any_hit(diffuse, true));
        add("shadow any", shadow_rays(surf, nrays, eps));
    }
    cases.erase(std::remove_if(cases.begin(), cases.end(),
                               [&](const Case& c) { return c.name.find(only) == std::string::npos; }),
                cases.end());
    if (cases.empty()) throw Error("--only " + only + ": no case has that in its name");
    if (ab) {
        // Variant B: same scene and rays, its own BVH (triangle order differs) and kernel build.
        if (ab_options.empty()) ab_options = options;
        const BvhBuildResult bvh_b = build_bvh(scene, ab_build);
        std::vector<Vec3> ordered_b;
        for (uint32_t i : bvh_b.tri_order)
            for (int k = 0; k < 3; ++k) ordered_b.push_back(scene[3 * i + k]);
        DeviceBvh dbvh_b(dc, bvh_b.nodes, ordered_b);
        RayTracer tracer_b(dc, ab_options);
        std::printf("B: %zu nodes, %zu leaves, options \"%s\"\n", bvh_b.nodes.size(), bvh_b.leaf_count,
                    ab_options.c_str());
        for (const Case& c : cases) {
            Rate a, b;
            for (int r = 0; r < runs; ++r) {
                const Rate ra = time_device(dc, tracer, dbvh, c.rays, forced_local, 1);
                const Rate rb = time_device(dc, tracer_b, dbvh_b, c.rays, forced_local, 1);
                a.wall = std::max(a.wall, ra.wall), a.cpu = std::max(a.cpu, ra.cpu);
                b.wall = std::max(b.wall, rb.wall), b.cpu = std::max(b.cpu, rb.cpu);
            }
            std::printf("%-16s A %6.2f  B %6.2f Mrays/s (cpu)  B/A %.3f   (wall %.2f / %.2f)\n", c.name.c_str(), a.cpu,
                        b.cpu, b.cpu / a.cpu, a.wall, b.wall);
        }
        return 0;
    }
    if (stats) {
        RayTracer counting(dc, options + " -DBVH_STATS");
        std::printf("\n%-18s %12s %12s\n", "rays", "nodes/ray", "tris/ray");
        for (Case& c : cases) {
            const std::vector<TraceHit> h = counting.trace(dbvh, c.rays);
            double n = 0, t = 0;
            for (const TraceHit& x : h) n += x.u, t += x.v;
            c.nodes_per_ray = n / double(h.size());
            c.tris_per_ray = t / double(h.size());
            std::printf("%-18s %12.2f %12.2f\n", c.name.c_str(), c.nodes_per_ray, c.tris_per_ray);
        }
    }

    // Work-group size: NULL (PoCL chooses) against fixed sizes, on the incoherent case.
    std::vector<std::pair<size_t, Rate>> local_sizes;
    size_t local = forced_local;
    if (!forced) {
        double best = 0;
        for (size_t l : {size_t(0), size_t(8), size_t(16), size_t(32), size_t(64), size_t(128), size_t(256)}) {
            const Rate m = time_device(dc, tracer, dbvh, diffuse, l, std::max(2, runs / 2));
            local_sizes.push_back({l, m});
            if (m.cpu > best) best = m.cpu, local = l;
        }
        std::printf("work-group size (diffuse closest, Mrays/s by CPU time):");
        for (auto& [l, m] : local_sizes) std::printf("  %s: %.2f", l ? std::to_string(l).c_str() : "NULL", m.cpu);
        std::printf("  -> %s\n", local ? std::to_string(local).c_str() : "NULL");
    }

#ifdef CLPPM_HAVE_EMBREE
    EmbreeScene embree(scene);
#endif
    std::printf("\nMrays/s, best of %d; 'wall': wall clock; 'cpu': rays per CPU-second times 2 cores, which\n"
                "is what an otherwise idle machine gives when other processes share the cores.\n",
                runs);
    std::printf("%-16s %6s %12s %12s %12s %12s %7s\n", "rays", "hit %", "clppm wall", "clppm cpu", "Embree wall",
                "Embree cpu", "ratio");
    for (Case& c : cases) {
        c.clppm = time_device(dc, tracer, dbvh, c.rays, local, runs, &c.hit_fraction);
#ifdef CLPPM_HAVE_EMBREE
        embree.run(c.rays, 2);
        for (int r = 0; r < runs; ++r) {
            const Rate e = embree.run(c.rays, 2);
            c.embree.wall = std::max(c.embree.wall, e.wall);
            c.embree.cpu = std::max(c.embree.cpu, e.cpu);
        }
        std::printf("%-16s %5.1f%% %12.2f %12.2f %12.2f %12.2f %7.2f\n", c.name.c_str(), 100 * c.hit_fraction,
                    c.clppm.wall, c.clppm.cpu, c.embree.wall, c.embree.cpu, c.clppm.cpu / c.embree.cpu);
#else
        std::printf("%-16s %5.1f%% %12.2f %12.2f %12s %12s %7s\n", c.name.c_str(), 100 * c.hit_fraction, c.clppm.wall,
                    c.clppm.cpu, "-", "-", "-");
#endif
    }
#ifdef CLPPM_HAVE_EMBREE
    std::printf("(Embree 3: rtcIntersect1/rtcOccluded1, 2 threads; its build took %.1f ms)\n",
                embree.build_seconds * 1e3);
#else
    std::printf("(built without Embree: no comparison)\n");
#endif

    if (!json_path.empty()) {
        std::ofstream f(json_path);
        if (!f) throw Error(json_path + ": cannot write");
        f << "{\n  \"triangles\": " << ntris << ",\n  \"nodes\": " << bvh.nodes.size()
          << ",\n  \"leaves\": " << bvh.leaf_count << ",\n  \"max_depth\": " << bvh.max_depth
          << ",\n  \"sah_cost\": " << bvh_sah_cost(bvh.nodes) << ",\n  \"build_ms\": " << build_best * 1e3
          << ",\n  \"device\": \"" << dc.info.name << "\",\n  \"options\": \"" << options
          << "\",\n  \"local_size\": " << local << ",\n  \"local_size_sweep\": {";
        for (size_t i = 0; i < local_sizes.size(); ++i)
            f << (i ? ", " : "") << "\"" << (local_sizes[i].first ? std::to_string(local_sizes[i].first) : "NULL")
              << "\": " << local_sizes[i].second.cpu;
        f << "},\n  \"cases\": [\n";
        for (size_t i = 0; i < cases.size(); ++i) {
            const Case& c = cases[i];
            f << "    {\"name\": \"" << c.name << "\", \"rays\": " << c.rays.size()
              << ", \"hit_fraction\": " << c.hit_fraction << ", \"mrays_per_s\": " << c.clppm.wall
              << ", \"mrays_per_cpu_s_x2\": " << c.clppm.cpu;
            if (stats) f << ", \"nodes_per_ray\": " << c.nodes_per_ray << ", \"tris_per_ray\": " << c.tris_per_ray;
#ifdef CLPPM_HAVE_EMBREE
            f << ", \"embree_mrays_per_s\": " << c.embree.wall << ", \"embree_mrays_per_cpu_s_x2\": " << c.embree.cpu;
#endif
            f << "}" << (i + 1 < cases.size() ? "," : "") << "\n";
        }
        f << "  ]\n}\n";
    }
    return 0;
}

} // namespace
} // namespace clppm

int main(int argc, char** argv) {
    try {
        return clppm::run(argc, argv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "traversal_bench: %s\n", e.what());
        return 1;
    }
}
