// Boolean benchmark (issue 15): the named cases below, each evaluated by
// boolean::evaluate in a forked child process, so that the peak memory of one case is
// its own (the peak resident size is reset through /proc/self/clear_refs after the
// operands are built, and read from VmHWM after the first run). Prints markdown tables:
// time (median of several runs for the quick cases), peak memory, output size,
// validity, rounding crossings, exact fallbacks and the seconds of each stage.
//
// With -DCELLFORGE_PEERS=ON the same cases also run, each in its own child, through
// CGAL corefinement, CGAL Nef_polyhedron_3 and manifold-3d (node), on triangle meshes
// of the same operands (bench/peers/), and the peers' times are printed as ratios to
// cellforge's from the same run.
//
//   bench_boolean [--max-fn N] [--menger4] [--case SUBSTR] [--runs N] [--threads N]
//                 [--timeout S] [--peers coref,nef,manifold|none] [--peer-timeout S]
//                 [--keep-lower-dim] [--chains] [--convex-split]
//
// --keep-lower-dim times cellforge's non-regularized operations (Nef's results are
// not regularized either). --chains times chains of Booleans instead (chain_cases):
// rounded between steps, exact at every step, exact and evaluated once, beside Nef
// evaluating the same chain step by step (exact throughout, as it always is).
// --convex-split times the split of earlier versions (Options::convex_split).
#include <fcntl.h>
#include <malloc.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cellforge/boolean/boolean.h"
#include "cellforge/boolean/exact.h"
#include "cellforge/geom/memory.h"
#include "cellforge/shape/mass.h"
#include "cellforge/shape/primitives.h"
#include "cellforge/io/triangulate.h"
#include "cellforge/topo/builder.h"
#include "cellforge/topo/validate.h"

#ifdef CELLFORGE_PEERS
#include "peers/peers.h"
#endif

namespace {

using namespace cellforge;
using boolean::Expr;
using boolean::Op;

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// --- operands ---

// The axis-aligned box [lo, hi] as a closed cell, faces counterclockwise from outside
// (corner i takes x from bit 0 of i, y from bit 1, z from bit 2).
Model box(Vec3 lo, Vec3 hi) {
  MeshInput in;
  for (int i = 0; i < 8; ++i)
    in.positions.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
  const std::uint32_t quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                     {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& q : quads) in.faces.push_back({.loops = {{q[0], q[1], q[2], q[3]}}, .back = 0});
  in.volumes = 1;
  Model m;
  if (!build_mesh(m, in).ok()) std::abort();
  return m;
}

// A copy of m moved by d (positions rounded to doubles once, as any transform does).
Model translated(const Model& m, Vec3 d) {
  MeshInput in;
  std::vector<std::uint32_t> index;
  for (VertexId v : m.vertices()) {
    if (index.size() <= v.value) index.resize(v.value + 1);
    index[v.value] = static_cast<std::uint32_t>(in.positions.size());
    in.positions.push_back(m.position(v) + d);
  }
  std::map<std::uint32_t, int> cells;
  const auto cell = [&](VolumeId c) {
    return c.is_valid() ? cells.try_emplace(c.value, static_cast<int>(cells.size())).first->second : -1;
  };
  for (FaceId f : m.faces()) {
    MeshFace mf{.loops = {}, .front = cell(m.front_volume(f)), .back = cell(m.back_volume(f))};
    for (LoopId l = m.outer_loop(f); l.is_valid(); l = m.next_loop(l)) {
      auto& loop = mf.loops.emplace_back();
      for (VertexId v : m.loop_vertices(l)) loop.push_back(index[v.value]);
    }
    in.faces.push_back(std::move(mf));
  }
  in.volumes = static_cast<int>(cells.size());
  Model out;
  if (!build_mesh(out, in).ok()) std::abort();
  return out;
}

Model sphere(double r, int fn, Vec3 at = {}) {
  Model m;
  if (!shape::make_sphere(m, {.r = r, .faceting = {.fn = static_cast<double>(fn)}}).ok()) std::abort();
  return at == Vec3{} ? std::move(m) : translated(m, at);
}

Model cylinder(double r, double h, int fn, Vec3 at) {
  Model m;
  if (!shape::make_cylinder(m, {.h = h, .r1 = r, .r2 = r, .faceting = {.fn = static_cast<double>(fn)}}).ok())
    std::abort();
  return translated(m, at);
}

struct Operands {
  std::vector<Model> models;
  Expr expr;
  // A chain (--chains): step i combines the result so far with models[i + 1] by
  // steps[i]; expr is the same chain as one nested expression (the peers' input).
  std::vector<Op> steps;
};

struct Case {
  std::string name;
  std::string series;  // cases of one family by size: a peer that timed out skips the rest
  std::function<Operands()> make;
};

Expr operands_from(int first, int last) {  // the leaves first..last-1
  std::vector<Expr> c;
  for (int i = first; i < last; ++i) c.push_back(Expr::of(i));
  return Expr::op(Op::kUnion, std::move(c));
}

// sphere(r=10) minus the same sphere moved by (5, 3, 2).
Operands spheres(int fn) {
  Operands o;
  o.models.push_back(sphere(10, fn));
  o.models.push_back(sphere(10, fn, {5, 3, 2}));
  o.expr = Expr::over(Op::kDifference, 2);
  return o;
}

// A plate of nx * ny cells of side 5, 5 thick, minus a cylinder (r = 1.5, 32 sides)
// through the middle of every cell, longer than the plate at both ends.
Operands plate_with_holes(int nx, int ny) {
  Operands o;
  o.models.push_back(box({0, 0, 0}, {5.0 * nx, 5.0 * ny, 5}));
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j) o.models.push_back(cylinder(1.5, 7, 32, {5 * i + 2.5, 5 * j + 2.5, -1}));
  o.expr = Expr::over(Op::kDifference, static_cast<int>(o.models.size()));
  return o;
}

// The cube [0, 3^level]^3 minus, at every level l, the bars of side 3^(level-l) through
// it along each axis whose cross-section is a middle square in both other coordinates:
// cube - (union of 3 (1 + 9 + ... + 9^(level-1)) boxes). Bar ends lie on the cube's
// faces, and bars of different axes share side planes, so it is full of coplanar pieces.
Operands menger(int level) {
  Operands o;
  const double side = std::pow(3.0, level);
  o.models.push_back(box({0, 0, 0}, {side, side, side}));
  for (int l = 1; l <= level; ++l) {
    const double c = std::pow(3.0, level - l);
    const int n = static_cast<int>(std::pow(3.0, l - 1));
    for (int axis = 0; axis < 3; ++axis)
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
          double lo[3], hi[3];
          lo[axis] = 0;
          hi[axis] = side;
          const int u = (axis + 1) % 3, v = (axis + 2) % 3;
          lo[u] = (3 * a + 1) * c;
          hi[u] = lo[u] + c;
          lo[v] = (3 * b + 1) * c;
          hi[v] = lo[v] + c;
          o.models.push_back(box({lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}));
        }
  }
  o.expr = Expr::op(Op::kDifference, {Expr::of(0), operands_from(1, static_cast<int>(o.models.size()))});
  return o;
}

// The union of n boxes with corners uniform in [0, 100]^3 and sides uniform in [3, 15]
// (std::mt19937_64 seeded with `seed`; 53-bit fractions so every platform draws the
// same doubles). With `grid`, corners and sides are whole numbers, so many faces are
// coplanar and many edges meet.
Operands random_boxes(int n, std::uint64_t seed, bool grid) {
  std::mt19937_64 rng(seed);
  const auto uniform = [&](double lo, double hi) {
    const double u = static_cast<double>(rng() >> 11) * 0x1p-53;
    const double x = lo + (hi - lo) * u;
    return grid ? std::floor(x) : x;
  };
  Operands o;
  for (int i = 0; i < n; ++i) {
    const Vec3 lo{uniform(0, 100), uniform(0, 100), uniform(0, 100)};
    const Vec3 size{uniform(3, 15), uniform(3, 15), uniform(3, 15)};
    o.models.push_back(box(lo, lo + size));
  }
  o.expr = Expr::over(Op::kUnion, n);
  return o;
}

Operands two_boxes(Op op, Vec3 lo_a, Vec3 hi_a, Vec3 lo_b, Vec3 hi_b) {
  Operands o;
  o.models.push_back(box(lo_a, hi_a));
  o.models.push_back(box(lo_b, hi_b));
  o.expr = Expr::over(op, 2);
  return o;
}

// The chain models[0] op steps[0] models[1] op steps[1] ... as one left-nested
// expression.
Operands as_chain(Operands o, std::vector<Op> steps) {
  Expr e = Expr::of(0);
  for (std::size_t i = 0; i < steps.size(); ++i) e = Expr::op(steps[i], {std::move(e), Expr::of(static_cast<int>(i + 1))});
  o.expr = std::move(e);
  o.steps = std::move(steps);
  return o;
}

// Chains of Booleans (issue 16): a plate minus its cylinders one per step; a sphere
// (fn 32) with ten smaller spheres (fn 32) around its equator taken away and added
// in turn.
std::vector<Case> chain_cases() {
  std::vector<Case> cases;
  for (auto [nx, ny] : {std::pair{5, 2}, std::pair{6, 5}}) {
    const int n = nx * ny;
    cases.push_back({"chain: plate - " + std::to_string(n) + " cylinders, one a step", "chain plate", [nx, ny, n] {
                       return as_chain(plate_with_holes(nx, ny), std::vector<Op>(static_cast<std::size_t>(n), Op::kDifference));
                     }});
  }
  cases.push_back({"chain: sphere -/u 10 spheres in turn", "chain spheres", [] {
                     Operands o;
                     o.models.push_back(sphere(10, 32));
                     std::vector<Op> steps;
                     for (int i = 0; i < 10; ++i) {
                       const double t = 0.6283185307179586 * i;
                       o.models.push_back(sphere(4, 32, {9 * std::cos(t), 9 * std::sin(t), 2.0 * (i % 3 - 1)}));
                       steps.push_back(i % 2 == 0 ? Op::kDifference : Op::kUnion);
                     }
                     return as_chain(std::move(o), std::move(steps));
                   }});
  return cases;
}

std::vector<Case> all_cases(int max_fn, bool menger4) {
  std::vector<Case> cases;
  for (int fn = 64; fn <= max_fn; fn *= 2)
    cases.push_back({"sphere-sphere fn=" + std::to_string(fn), "sphere", [fn] { return spheres(fn); }});
  cases.push_back({"plate - 100 cylinders", "plate", [] { return plate_with_holes(10, 10); }});
  cases.push_back({"plate - 1000 cylinders", "plate", [] { return plate_with_holes(40, 25); }});
  cases.push_back({"menger level 2", "menger", [] { return menger(2); }});
  cases.push_back({"menger level 3", "menger", [] { return menger(3); }});
  if (menger4) cases.push_back({"menger level 4", "menger", [] { return menger(4); }});
  cases.push_back({"union 1000 random boxes", "boxes", [] { return random_boxes(1000, 15, false); }});
  cases.push_back({"union 1000 grid boxes", "grid boxes", [] { return random_boxes(1000, 15, true); }});
  // A sheet through a solid: the common face of two boxes (their intersection, not
  // regularized) across a sphere; regularized, the sheet is empty and the sphere stays.
  cases.push_back({"sphere fn=64 - sheet through it", "sheet", [] {
                     Operands o;
                     o.models.push_back(sphere(10, 64));
                     o.models.push_back(box({-12, -12, -12}, {12, 12, 0.5}));
                     o.models.push_back(box({-12, -12, 0.5}, {12, 12, 12}));
                     o.expr = Expr::op(Op::kDifference, {Expr::of(0), Expr::op(Op::kIntersection, {Expr::of(1), Expr::of(2)})});
                     return o;
                   }});
  cases.push_back({"cubes sharing a face, union", "face",
                   [] { return two_boxes(Op::kUnion, {0, 0, 0}, {1, 1, 1}, {0, 0, 1}, {1, 1, 2}); }});
  cases.push_back({"cubes sharing an edge, union", "edge",
                   [] { return two_boxes(Op::kUnion, {0, 0, 0}, {1, 1, 1}, {1, 1, 0}, {2, 2, 1}); }});
  cases.push_back({"cubes sharing a vertex, union", "vertex",
                   [] { return two_boxes(Op::kUnion, {0, 0, 0}, {1, 1, 1}, {1, 1, 1}, {2, 2, 2}); }});
  cases.push_back({"cube - cube sharing 3 faces", "corner",
                   [] { return two_boxes(Op::kDifference, {0, 0, 0}, {2, 2, 2}, {1, 1, 1}, {2, 2, 2}); }});
  return cases;
}

// --- measuring in a child process ---

long status_kb(const char* field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  const std::size_t n = std::strlen(field);
  while (std::getline(in, line))
    if (line.compare(0, n, field) == 0 && line.size() > n && line[n] == ':') return std::atol(line.c_str() + n + 1);
  return 0;
}

// Resets the peak resident size to the current one; returns the current one in kB.
long reset_peak() {
  malloc_trim(0);
  std::ofstream("/proc/self/clear_refs") << "5";
  return status_kb("VmRSS");
}

double peak_mb_since(long base_kb) { return static_cast<double>(status_kb("VmHWM") - base_kb) / 1024; }

// Runs to take the median of: many for quick cases, one for slow ones; stops early
// once `budget` seconds have been spent.
int runs_after(double first_seconds, int fixed) {
  if (fixed > 0) return fixed;
  return first_seconds < 0.01 ? 31 : (first_seconds < 1 ? 5 : 1);
}

template <class T>
T median(std::vector<T> v) {
  std::sort(v.begin(), v.end());
  return v[(v.size() - 1) / 2];
}

// What a child sends back: plain bytes through a pipe.
struct Outcome {
  enum Status : int { kOk, kRefused, kError, kTimeout, kCrashed, kSkipped, kMissing };
  Status status = kOk;
  int runs = 0;
  double seconds = 0, peak_mb = 0, volume = 0;
  std::uint64_t in_triangles = 0, out_vertices = 0, out_edges = 0, out_faces = 0;
  // cellforge
  int valid = -1;
  std::uint64_t rounding_crossings = 0, exact_fallbacks = 0, candidate_pairs = 0, implicit_points = 0;
  double stages[6] = {};
  // peers
  int self_intersecting = -1;
  std::uint64_t degenerate = 0;
  char message[240] = {};

  void say(const std::string& s) { std::snprintf(message, sizeof message, "%s", s.c_str()); }
};

void write_all(int fd, const void* data, std::size_t n) {
  const char* p = static_cast<const char*>(data);
  while (n > 0) {
    const ssize_t w = write(fd, p, n);
    if (w <= 0) return;
    p += w;
    n -= static_cast<std::size_t>(w);
  }
}

// Forks; the child runs `body(fd)` (writing its answer to fd, or exec'ing a program
// with fd as its standard output) and exits. Returns what the child wrote, with the
// outcome status set on a timeout or a crash.
struct ChildResult {
  std::string bytes;
  Outcome::Status status = Outcome::kOk;
  std::string why;
};

ChildResult in_child(const std::function<void(int)>& body, double timeout_s) {
  int fds[2];
  if (pipe(fds) != 0) std::abort();
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    body(fds[1]);
    _exit(0);
  }
  close(fds[1]);
  ChildResult r;
  const double deadline = now() + timeout_s;
  char buf[4096];
  for (;;) {
    pollfd p{fds[0], POLLIN, 0};
    const double left = deadline - now();
    if (left <= 0 || poll(&p, 1, static_cast<int>(std::min(left, 1e6) * 1000) + 1) == 0) {
      kill(pid, SIGKILL);
      r.status = Outcome::kTimeout;
      break;
    }
    const ssize_t n = read(fds[0], buf, sizeof buf);
    if (n <= 0) break;
    r.bytes.append(buf, static_cast<std::size_t>(n));
  }
  close(fds[0]);
  int ws = 0;
  waitpid(pid, &ws, 0);
  if (r.status == Outcome::kOk && WIFSIGNALED(ws)) {
    r.status = Outcome::kCrashed;
    r.why = std::string("signal ") + strsignal(WTERMSIG(ws));
  } else if (r.status == Outcome::kOk && WIFEXITED(ws) && WEXITSTATUS(ws) != 0) {
    r.status = Outcome::kError;
    r.why = "exit status " + std::to_string(WEXITSTATUS(ws));
  }
  return r;
}

Outcome outcome_of(const ChildResult& c) {
  Outcome o;
  if (c.bytes.size() == sizeof(Outcome)) std::memcpy(static_cast<void*>(&o), c.bytes.data(), sizeof o);
  if (c.status != Outcome::kOk) {
    o.status = c.status;
    o.say(c.why);
  } else if (c.bytes.size() != sizeof(Outcome)) {
    o.status = Outcome::kError;
    o.say("no answer from the child");
  }
  return o;
}

struct Settings {
  int max_fn = 512;
  bool menger4 = false;
  std::string only;
  int runs = 0;  // 0: by the first run's time
  int threads = 1;
  bool keep_lower_dim = false;  // non-regularized, as CGAL Nef computes it
  bool convex_split = false;    // the split of earlier versions (Options::convex_split)
  bool chains = false;          // the chain cases instead
  double timeout = 1800, peer_timeout = 60, budget = 20;
  bool coref = true, nef = true, manifold = true;
};

Outcome run_cellforge(const Case& c, const Settings& s) {
  return outcome_of(in_child(
      [&](int fd) {
        Outcome o;
        Operands ops = c.make();
        std::vector<const Model*> ptrs;
        for (const Model& m : ops.models) ptrs.push_back(&m);
        const boolean::Options options{.threads = s.threads, .keep_lower_dim = s.keep_lower_dim, .convex_split = s.convex_split};
        const long base = reset_peak();
        std::vector<double> times;
        std::vector<boolean::Report> reports;
        for (int target = 1; static_cast<int>(times.size()) < target;) {
          const double t0 = now();
          auto r = boolean::evaluate(ptrs, ops.expr, options);
          times.push_back(now() - t0);
          if (!r.ok()) {
            o.status = Outcome::kError;
            o.say(r.error().message);
            break;
          }
          reports.push_back(r->report);
          if (times.size() == 1) {
            o.peak_mb = peak_mb_since(base);
            const Model& m = r->model;
            o.out_vertices = m.num_vertices();
            o.out_edges = m.num_edges();
            o.out_faces = m.num_faces();
            o.valid = validate(m).empty() ? 1 : 0;
            o.volume = m.num_faces() ? shape::mass_properties(m).volume : 0;
            target = runs_after(times[0], s.runs);
          }
          double total = 0;
          for (double t : times) total += t;
          if (total > s.budget && s.runs == 0) break;
        }
        if (o.status == Outcome::kOk) {
          o.runs = static_cast<int>(times.size());
          o.seconds = median(times);
          // The stages of the run whose total is the median.
          const auto it = std::find(times.begin(), times.end(), o.seconds);
          const boolean::Report& rep = reports[static_cast<std::size_t>(it - times.begin())];
          o.in_triangles = rep.input_triangles;
          o.rounding_crossings = rep.rounding_self_intersections;
          o.exact_fallbacks = rep.exact_fallbacks;
          o.candidate_pairs = rep.candidate_pairs;
          o.implicit_points = rep.implicit_points;
          const boolean::StageTimes& st = rep.seconds;
          const double stages[6] = {st.soup, st.intersect, st.split, st.classify, st.output, st.check};
          std::copy(stages, stages + 6, o.stages);
        }
        write_all(fd, &o, sizeof o);
      },
      s.timeout));
}

// A chain three ways: kRounded makes an operand of each step's rounded model;
// kEveryStep keeps it exact (boolean::chain at every step, each result at hand);
// kOnce composes the steps and evaluates the last (boolean::compose, one arrangement).
enum class ChainWay { kRounded, kEveryStep, kOnce };

Outcome run_chain(const Case& c, const Settings& s, ChainWay way) {
  return outcome_of(in_child(
      [&](int fd) {
        Outcome o;
        const Operands ops = c.make();
        const boolean::Options options{.threads = s.threads};
        std::vector<boolean::Operand> inputs;  // shared models, made before the clock
        for (const Model& m : ops.models) inputs.push_back(boolean::Operand::of(m));
        const long base = reset_peak();
        const double t0 = now();
        Result<boolean::BooleanResult> last = Error{ErrorCode::kInvalidInput, "no step"};
        if (way == ChainWay::kRounded) {
          Model so_far = ops.models[0];
          for (std::size_t i = 0; i < ops.steps.size() && (i == 0 || last.ok()); ++i) {
            const Model* pair[2] = {&so_far, &ops.models[i + 1]};
            last = boolean::evaluate(pair, Expr::over(ops.steps[i], 2), options);
            if (last.ok()) so_far = last->model;
          }
        } else if (way == ChainWay::kEveryStep) {
          boolean::Operand so_far = inputs[0];
          for (std::size_t i = 0; i < ops.steps.size() && (i == 0 || last.ok()); ++i) {
            const boolean::Operand pair[2] = {so_far, inputs[i + 1]};
            last = boolean::chain(pair, Expr::over(ops.steps[i], 2), options);
            if (last.ok()) so_far = boolean::Operand::of(*last);
          }
        } else {
          boolean::Operand so_far = inputs[0];
          Result<std::shared_ptr<const boolean::ExactForm>> form = Error{ErrorCode::kInvalidInput, "no step"};
          for (std::size_t i = 0; i < ops.steps.size(); ++i) {
            const boolean::Operand pair[2] = {so_far, inputs[i + 1]};
            form = boolean::compose(pair, Expr::over(ops.steps[i], 2));
            if (!form.ok()) break;
            so_far = boolean::Operand::of(*form);
          }
          if (form.ok()) last = boolean::evaluate(**form, options);
          else last = form.error();
        }
        o.seconds = now() - t0;
        o.runs = 1;
        if (!last.ok()) {
          o.status = Outcome::kError;
          o.say(last.error().message);
        } else {
          o.peak_mb = peak_mb_since(base);
          const Model& m = last->model;
          o.out_vertices = m.num_vertices();
          o.out_edges = m.num_edges();
          o.out_faces = m.num_faces();
          o.valid = validate(m).empty() ? 1 : 0;
          o.volume = m.num_faces() ? shape::mass_properties(m).volume : 0;
          o.rounding_crossings = last->report.rounding_self_intersections;
        }
        write_all(fd, &o, sizeof o);
      },
      s.timeout));
}

#ifdef CELLFORGE_PEERS

using bench::TriMesh;

// The operand's faces as triangles (io::triangulate_face), outward.
TriMesh triangles_of(const Model& m) {
  TriMesh t;
  std::vector<std::uint32_t> index;
  for (VertexId v : m.vertices()) {
    if (index.size() <= v.value) index.resize(v.value + 1);
    index[v.value] = static_cast<std::uint32_t>(t.num_vertices());
    const Vec3 p = m.position(v);
    t.xyz.insert(t.xyz.end(), {p.x, p.y, p.z});
  }
  for (FaceId f : m.faces()) {
    const bool inward = m.front_volume(f).is_valid() && !m.back_volume(f).is_valid();
    for (const auto& tri : io::triangulate_face(m, f)) {
      const std::uint32_t a = index[tri[0].value], b = index[tri[1].value], c = index[tri[2].value];
      t.tris.insert(t.tris.end(), {a, inward ? c : b, inward ? b : c});
    }
  }
  return t;
}

struct PeerInput {
  std::vector<TriMesh> meshes;
  Expr expr;
  std::size_t triangles = 0;
};

PeerInput peer_input(const Case& c) {
  PeerInput in;
  Operands ops = c.make();
  for (const Model& m : ops.models) {
    in.meshes.push_back(triangles_of(m));
    in.triangles += in.meshes.back().num_triangles();
  }
  in.expr = std::move(ops.expr);
  return in;
}

// "D(0,U(1,2))": the expression as manifold_peer.mjs reads it.
std::string prefix_text(const Expr& e) {
  if (e.kind == Expr::Kind::kOperand) return std::to_string(e.operand);
  std::string s(1, e.kind == Expr::Kind::kUnion ? 'U' : (e.kind == Expr::Kind::kIntersection ? 'I' : 'D'));
  s += '(';
  for (std::size_t i = 0; i < e.children.size(); ++i) s += (i ? "," : "") + prefix_text(e.children[i]);
  return s + ')';
}

Outcome run_cgal(const Case& c, const Settings& s, bool nef) {
  return outcome_of(in_child(
      [&](int fd) {
        Outcome o;
        const PeerInput in = peer_input(c);
        o.in_triangles = in.triangles;
        const long base = reset_peak();
        std::vector<double> times;
        for (int target = 1; static_cast<int>(times.size()) < target;) {
          const bench::PeerRun r = nef ? bench::run_cgal_nef(in.meshes, in.expr)
                                       : bench::run_cgal_corefinement(in.meshes, in.expr, times.empty());
          if (r.status != bench::PeerRun::Status::kOk) {
            o.status = r.status == bench::PeerRun::Status::kRefused ? Outcome::kRefused : Outcome::kError;
            o.say(r.message);
            break;
          }
          times.push_back(r.seconds);
          if (times.size() == 1) {
            o.peak_mb = peak_mb_since(base);
            o.out_vertices = r.out_vertices;
            o.out_faces = r.out_triangles;
            o.volume = r.volume;
            o.self_intersecting = r.self_intersecting;
            o.degenerate = r.degenerate_faces;
            target = runs_after(times[0], s.runs);
          }
          double total = 0;
          for (double t : times) total += t;
          if (total > s.budget && s.runs == 0) break;
        }
        if (!times.empty()) {
          o.runs = static_cast<int>(times.size());
          o.seconds = median(times);
        }
        write_all(fd, &o, sizeof o);
      },
      s.peer_timeout));
}

void write_mesh_file(const std::string& path, const PeerInput& in) {
  std::ofstream f(path, std::ios::binary);
  const auto u32 = [&](std::size_t v) {
    const auto x = static_cast<std::uint32_t>(v);
    f.write(reinterpret_cast<const char*>(&x), 4);
  };
  f.write("CFBOOL1", 8);
  const std::string expr = prefix_text(in.expr);
  u32(in.meshes.size());
  u32(expr.size());
  f.write(expr.data(), static_cast<std::streamsize>(expr.size()));
  for (const TriMesh& t : in.meshes) {
    u32(t.num_vertices());
    u32(t.num_triangles());
    f.write(reinterpret_cast<const char*>(t.xyz.data()), static_cast<std::streamsize>(8 * t.xyz.size()));
    f.write(reinterpret_cast<const char*>(t.tris.data()), static_cast<std::streamsize>(4 * t.tris.size()));
  }
}

Outcome run_manifold(const Case& c, const Settings& s) {
  if (!std::filesystem::exists(CELLFORGE_PEERS_NODE_DIR "/node_modules/manifold-3d/manifold.js")) {
    Outcome o;
    o.status = Outcome::kMissing;
    o.say("manifold-3d not installed: bench/peers/setup.sh " CELLFORGE_PEERS_NODE_DIR);
    return o;
  }
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("cellforge_bench_" + std::to_string(getpid()) + ".bin")).string();
  const std::string budget = std::to_string(s.runs > 0 ? 1e9 : s.budget);
  // The child writes the meshes and becomes node, so node starts with none of its memory.
  const ChildResult child = in_child(
      [&](int fd) {
        write_mesh_file(path, peer_input(c));
        dup2(fd, 1);
        setenv("CELLFORGE_BENCH_BUDGET", budget.c_str(), 1);
        restore_tunables_for_children();  // node as it runs on its own (faster so)
        execlp("node", "node", CELLFORGE_PEERS_SOURCE_DIR "/manifold_peer.mjs", CELLFORGE_PEERS_NODE_DIR,
               path.c_str(), static_cast<char*>(nullptr));
        _exit(127);
      },
      s.peer_timeout);
  std::filesystem::remove(path);
  Outcome o;
  std::istringstream lines(child.bytes);
  std::string key, value;
  std::string status;
  while (lines >> key >> value) {
    if (key == "seconds") o.seconds = std::stod(value);
    if (key == "runs") o.runs = std::stoi(value);
    if (key == "in_triangles") o.in_triangles = std::stoull(value);
    if (key == "peak_mb") o.peak_mb = std::stod(value);
    if (key == "out_vertices") o.out_vertices = std::stoull(value);
    if (key == "out_triangles") o.out_faces = std::stoull(value);
    if (key == "volume") o.volume = std::stod(value);
    if (key == "status") status = value;
  }
  if (child.status != Outcome::kOk) {
    o.status = child.status;
    o.say(child.why);
  } else if (o.runs == 0) {
    o.status = Outcome::kError;
    o.say("node printed no result");
  } else if (status != "NoError") {
    o.status = Outcome::kRefused;
    o.say("status " + status);
  }
  return o;
}

#endif  // CELLFORGE_PEERS

// --- printing ---

std::string fixed(double v, int digits) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", digits, v);
  return b;
}

std::string seconds_text(double s) {
  if (s < 0.001) return fixed(s * 1e6, 0) + " µs";
  if (s < 1) return fixed(s * 1e3, s < 0.01 ? 2 : 1) + " ms";
  return fixed(s, 2) + " s";
}

std::string count_text(std::uint64_t n) {
  std::string s = std::to_string(n);
  for (int i = static_cast<int>(s.size()) - 3; i > 0; i -= 3) s.insert(static_cast<std::size_t>(i), ",");
  return s;
}

const char* status_text(Outcome::Status s) {
  switch (s) {
    case Outcome::kOk: return "ok";
    case Outcome::kRefused: return "refused";
    case Outcome::kError: return "error";
    case Outcome::kTimeout: return "timeout";
    case Outcome::kCrashed: return "crashed";
    case Outcome::kSkipped: return "skipped";
    case Outcome::kMissing: return "missing";
  }
  return "?";
}

struct Row {
  std::string name;
  Outcome cf;
  std::vector<std::pair<std::string, Outcome>> peers;
};

std::string vs_cellforge(const Outcome& peer, const Outcome& cf, const Settings& s) {
  if (peer.status == Outcome::kTimeout) return "> " + fixed(s.peer_timeout, 0) + " s";
  if (peer.status != Outcome::kOk) return status_text(peer.status);
  std::string t = seconds_text(peer.seconds);
  if (cf.status == Outcome::kOk && cf.seconds > 0) t += " (" + fixed(peer.seconds / cf.seconds, 2) + "×)";
  return t;
}

void print_tables(const std::vector<Row>& rows, const Settings& s) {
  std::printf("\ncellforge (threads = %d: soup, pairs, rays and the rounding check on threads)\n\n",
              s.threads);
  std::printf("| case | input tris | runs | time | peak MB | V | E | F | valid | rounding crossings | exact fallbacks | volume |\n");
  std::printf("|---|--:|--:|--:|--:|--:|--:|--:|:-:|--:|--:|--:|\n");
  for (const Row& r : rows) {
    const Outcome& o = r.cf;
    if (o.status != Outcome::kOk) {
      std::printf("| %s | %s: %s |\n", r.name.c_str(), status_text(o.status), o.message);
      continue;
    }
    std::printf("| %s | %s | %d | %s | %s | %s | %s | %s | %s | %s | %s | %.6g |\n", r.name.c_str(),
                count_text(o.in_triangles).c_str(), o.runs, seconds_text(o.seconds).c_str(),
                fixed(o.peak_mb, 1).c_str(), count_text(o.out_vertices).c_str(), count_text(o.out_edges).c_str(),
                count_text(o.out_faces).c_str(), o.valid == 1 ? "yes" : "**NO**",
                count_text(o.rounding_crossings).c_str(), count_text(o.exact_fallbacks).c_str(), o.volume);
  }
  std::printf("\ncellforge stages (seconds of the median run) and arrangement sizes\n\n");
  std::printf("| case | soup | intersect | split | classify | output | build | candidate pairs | implicit points |\n");
  std::printf("|---|--:|--:|--:|--:|--:|--:|--:|--:|\n");
  for (const Row& r : rows) {
    if (r.cf.status != Outcome::kOk) continue;
    std::printf("| %s", r.name.c_str());
    for (double st : r.cf.stages) std::printf(" | %s", fixed(st, 4).c_str());
    std::printf(" | %s | %s |\n", count_text(r.cf.candidate_pairs).c_str(), count_text(r.cf.implicit_points).c_str());
  }
  if (rows.empty() || rows[0].peers.empty()) return;
  std::printf("\npeers: time and ratio to cellforge (peer time / cellforge time; > 1: cellforge faster)\n\n");
  std::printf("| case | cellforge");
  for (const auto& [name, o] : rows[0].peers) std::printf(" | %s", name.c_str());
  std::printf(" |\n|---|--:");
  for (std::size_t i = 0; i < rows[0].peers.size(); ++i) std::printf("|--:");
  std::printf("|\n");
  for (const Row& r : rows) {
    std::printf("| %s | %s", r.name.c_str(), r.cf.status == Outcome::kOk ? seconds_text(r.cf.seconds).c_str() : "—");
    for (const auto& [name, o] : r.peers) std::printf(" | %s", vs_cellforge(o, r.cf, s).c_str());
    std::printf(" |\n");
  }
  std::printf("\npeers: memory, output, and what they said\n\n");
  std::printf("| case | peer | input tris | runs | peak MB | V | triangles | volume vs cellforge's | self-intersecting | zero-area tris | note |\n");
  std::printf("|---|---|--:|--:|--:|--:|--:|--:|:-:|--:|---|\n");
  for (const Row& r : rows)
    for (const auto& [name, o] : r.peers) {
      if (o.status != Outcome::kOk) {
        std::printf("| %s | %s | | | | | | | | | %s%s%s |\n", r.name.c_str(), name.c_str(), status_text(o.status),
                    o.message[0] ? ": " : "", o.message);
        continue;
      }
      char dv[32] = "—";
      if (o.volume != 0 && r.cf.volume != 0) std::snprintf(dv, sizeof dv, "%+.1e", (o.volume - r.cf.volume) / r.cf.volume);
      const char* si = o.self_intersecting < 0 ? "—" : (o.self_intersecting ? "**yes**" : "no");
      std::printf("| %s | %s | %s | %d | %s | %s | %s | %s | %s | %s | |\n", r.name.c_str(), name.c_str(),
                  count_text(o.in_triangles).c_str(), o.runs,
                  fixed(o.peak_mb, 1).c_str(), count_text(o.out_vertices).c_str(), count_text(o.out_faces).c_str(),
                  dv, si, count_text(o.degenerate).c_str());
    }
}

Settings parse(int argc, char** argv) {
  Settings s;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--max-fn") s.max_fn = std::stoi(next());
    else if (a == "--menger4") s.menger4 = true;
    else if (a == "--case") s.only = next();
    else if (a == "--runs") s.runs = std::stoi(next());
    else if (a == "--threads") s.threads = std::stoi(next());
    else if (a == "--keep-lower-dim") s.keep_lower_dim = true;
    else if (a == "--convex-split") s.convex_split = true;
    else if (a == "--chains") s.chains = true;
    else if (a == "--timeout") s.timeout = std::stod(next());
    else if (a == "--peer-timeout") s.peer_timeout = std::stod(next());
    else if (a == "--peers") {
      const std::string p = next();
      s.coref = p.find("coref") != std::string::npos;
      s.nef = p.find("nef") != std::string::npos;
      s.manifold = p.find("manifold") != std::string::npos;
    } else {
      std::fprintf(stderr,
                   "usage: bench_boolean [--max-fn N (512; 2048 for the full set)] [--menger4] [--case SUBSTR]\n"
                   "                     [--runs N] [--threads N] [--timeout S] [--peers coref,nef,manifold|none]\n"
                   "                     [--peer-timeout S (60)] [--keep-lower-dim] [--chains] [--convex-split]\n");
      std::exit(a == "--help" ? 0 : 2);
    }
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  // As the command line runs (geom/memory.h), for cellforge and for CGAL alike, which
  // run in this program's children.
  prefer_huge_pages(argv);
  keep_freed_memory();
  const Settings s = parse(argc, argv);
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  std::printf("bench_boolean: %u hardware threads; max fn %d%s; GLIBC_TUNABLES=%s\n",
              std::thread::hardware_concurrency(), s.max_fn, s.menger4 ? "; menger level 4" : "",
              tunables != nullptr ? tunables : "(unset)");
#ifdef CELLFORGE_PEERS
  std::printf("peers: CGAL %s (corefinement: Epick Surface_mesh; Nef: Epeck), manifold-3d via node; timeout %.0f s\n",
              bench::cgal_version(), s.peer_timeout);
#else
  std::printf("peers: not built (configure with -DCELLFORGE_PEERS=ON)\n");
#endif
  if (s.chains) {
    std::printf("\nchains (regularized; threads = %d; one run each; Nef: the same chain as left folds)\n\n", s.threads);
    std::printf("| chain | steps | rounded between steps | exact, every step | exact, evaluated once | rounded / once | CGAL Nef | Nef / once | V | F | valid | volume |\n");
    std::printf("|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|:-:|--:|\n");
    for (const Case& c : chain_cases()) {
      if (!s.only.empty() && c.name.find(s.only) == std::string::npos) continue;
      std::fprintf(stderr, "%s ...\n", c.name.c_str());
      const Outcome rounded = run_chain(c, s, ChainWay::kRounded);
      const Outcome every = run_chain(c, s, ChainWay::kEveryStep);
      const Outcome once = run_chain(c, s, ChainWay::kOnce);
      std::string nef = "not built";
#ifdef CELLFORGE_PEERS
      nef = s.nef ? vs_cellforge(run_cgal(c, s, true), once, s) : "not run";
#endif
      auto t = [](const Outcome& o) { return o.status == Outcome::kOk ? seconds_text(o.seconds) : std::string(status_text(o.status)); };
      const std::string ratio = rounded.status == Outcome::kOk && once.status == Outcome::kOk
                                    ? fixed(rounded.seconds / once.seconds, 2) + "×" : "—";
      const std::size_t split = nef.find(" (");
      std::printf("| %s | %zu | %s | %s | %s | %s | %s | %s | %s | %s | %s | %.6g |\n", c.name.c_str(), c.make().steps.size(),
                  t(rounded).c_str(), t(every).c_str(), t(once).c_str(), ratio.c_str(),
                  nef.substr(0, split).c_str(),
                  split == std::string::npos ? "—" : nef.substr(split + 2, nef.size() - split - 3).c_str(),
                  count_text(once.out_vertices).c_str(), count_text(once.out_faces).c_str(),
                  once.valid == 1 && every.valid == 1 && rounded.valid == 1 ? "yes" : "**NO**", once.volume);
      if (once.status != Outcome::kOk) std::printf("\n%s: %s\n", c.name.c_str(), once.message);
    }
    return 0;
  }
  std::vector<Row> rows;
  std::map<std::string, std::map<std::string, bool>> timed_out;  // series -> peer -> timed out
  for (const Case& c : all_cases(s.max_fn, s.menger4)) {
    if (!s.only.empty() && c.name.find(s.only) == std::string::npos) continue;
    std::fprintf(stderr, "%s: cellforge ...\n", c.name.c_str());
    Row row{c.name, run_cellforge(c, s), {}};
#ifdef CELLFORGE_PEERS
    const auto peer = [&](const std::string& name, bool enabled, auto run) {
      if (!enabled) return;
      Outcome o;
      if (timed_out[c.series][name]) {
        o.status = Outcome::kSkipped;
        o.say("timed out on a smaller case of the series");
      } else {
        std::fprintf(stderr, "%s: %s ...\n", c.name.c_str(), name.c_str());
        o = run();
        if (o.status == Outcome::kTimeout) timed_out[c.series][name] = true;
      }
      row.peers.emplace_back(name, o);
    };
    peer("CGAL corefinement", s.coref, [&] { return run_cgal(c, s, false); });
    peer("CGAL Nef", s.nef, [&] { return run_cgal(c, s, true); });
    peer("manifold-3d", s.manifold, [&] { return run_manifold(c, s); });
#endif
    rows.push_back(std::move(row));
  }
  print_tables(rows, s);
  return 0;
}
