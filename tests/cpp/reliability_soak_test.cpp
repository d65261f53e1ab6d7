// Soak test: long runs of random sculpting through sculpt::Session (grabs with random centre, radii,
// translation, rotation, scale and substeps; brush strokes with every tool, random radius, strength,
// spacing, invert, symmetry axis and pressure along paths that walk over the surface and sometimes
// leave it; whole-mesh remeshes; runs of undo and redo), checking the invariants a user relies on:
//   - no NaN / infinite position, ever (after every step; during grabs after every frame, during
//     strokes on the touched vertices after every pointer sample);
//   - mesh().validate() passes, genus and boundary loops are those of the input (every N steps);
//   - undo and redo are exact: a fingerprint model of the history (hash of counts + positions before
//     each step) must match what undo() / redo() bring back, and undo() must fail exactly when the
//     model's bounded history is exhausted;
//   - memory stays bounded: at most Session::kMaxUndoSteps undo steps, a vertex count within a factor
//     of the remesher's sizing bounds, the change set cleared per frame, peak RSS under a limit.
//
// The same binary serves the short run in ctest (default) and the long run of scripts/soak.sh:
//   ADASCULPT_SOAK_STEPS=N        total steps, split evenly across the meshes (default 60)
//   ADASCULPT_SOAK_MESHES=a,b,..  "icosphere" or paths (relative paths: repo root, or a bare name from
//                                 ../shared/meshes); default: icosphere + tests/data/meshes/
//                                 {hemisphere,eight,fandisk}.off
//   ADASCULPT_SOAK_CHECK_EVERY=N  validate/topology period (default 20; the long run uses 100)
//   ADASCULPT_SOAK_SEED=N         random seed (default 1; deterministic for a given seed)
//   ADASCULPT_SOAK_MAX_RSS_MB=N   peak RSS limit (VmHWM, default 4096)
//   ADASCULPT_SOAK_PROGRESS_EVERY=N  a progress line every N steps per mesh (default 500)
//   ADASCULPT_SOAK_RESTART_FACES=N  after a full check, a mesh grown past N faces is loaded afresh
//                                 (a new history; default 0 = never): sculpting keeps refining, and
//                                 under sanitizers a step on 180k faces costs 10x one on 20k, so the
//                                 long run bounds the size to get through its steps
//   ADASCULPT_SOAK_SECONDS=N      wall-time budget of the whole run, shared out among the meshes in
//                                 turn: a mesh stops early when its share is spent (validate and the
//                                 closing checks still run on its last step); lines report steps run
// Every step is logged in session-file form: on a failure the steps up to it are written to
// $TMPDIR/adasculpt_soak_<mesh>.json, replayable with `adasculpt replay`.
// A closing line prints steps, meshes, frames, time, peak RSS and the number of checks passed.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "deform/brushes.h"
#include "geometry/topology.h"
#include "geometry_test_util.h"
#include "mesh/primitives.h"
#include "sculpt/brush.h"
#include "sculpt/session.h"
#include "sculpt/session_file.h"

namespace {

using namespace adasculpt;
namespace fs = std::filesystem;
using nlohmann::json;

long env_long(const char* name, long fallback) {
  const char* v = std::getenv(name);
  if (!v || !*v) return fallback;
  char* end = nullptr;
  const long x = std::strtol(v, &end, 10);
  return (end && *end == '\0' && x > 0) ? x : fallback;
}

// kB of a /proc/self/status field (VmHWM = peak RSS, VmRSS = current); 0 where unavailable.
long proc_status_kb(const char* field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  const size_t n = std::strlen(field);
  while (std::getline(in, line))
    if (line.compare(0, n, field) == 0 && line.size() > n && line[n] == ':') return std::atol(line.c_str() + n + 1);
  return 0;
}

std::vector<std::string> soak_meshes() {
  std::vector<std::string> out;
  const char* v = std::getenv("ADASCULPT_SOAK_MESHES");
  std::string list = v && *v ? v
                             : "icosphere,tests/data/meshes/hemisphere.off,tests/data/meshes/eight.off,"
                               "tests/data/meshes/fandisk.off";
  std::stringstream ss(list);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

// Path of a mesh name: absolute, relative to the repo root, or a bare name in ../shared/meshes.
std::string resolve_mesh(const std::string& name) {
  if (fs::path(name).is_absolute()) return name;
  const fs::path in_repo = fs::path(ADASCULPT_SOURCE_DIR) / name;
  if (fs::exists(in_repo)) return in_repo.string();
  return (fs::path(ADASCULPT_SHARED_MESHES_DIR) / name).string();
}

bool all_finite(const mesh::SurfaceMesh& m) {
  for (mesh::Vertex v : m.vertices()) {
    const Point& p = m.position(v);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
  }
  return true;
}

struct Totals {
  long steps = 0, frames = 0, grabs = 0, remeshes = 0, undos = 0, redos = 0;
  long brushes = 0, samples = 0, stamps = 0;  // strokes, pointer samples, stamps run
  long restarts = 0;  // fresh loads of the input after the mesh grew past ADASCULPT_SOAK_RESTART_FACES
  long stopped = 0;  // strokes stopped by their face budget (sculpt/brush.h): allowed, the mesh must stay valid
  long checks = 0;  // invariant checks passed (finite positions, validate, genus, boundaries, history, undo/redo)
};

// One mesh, `steps` random steps.
// seconds > 0: stop after the step that exceeds this wall time (the closing checks still run).
void soak_one(const std::string& name, long steps, long check_every, uint32_t seed, double seconds, Totals& totals) {
  sculpt::Session s;
  const std::string path = name == "icosphere" ? name : resolve_mesh(name);
  if (name != "icosphere" && !fs::exists(path)) GTEST_SKIP() << path << " not found";
  const std::string label = fs::path(name).stem().string();
  const bool fandisk = label == "fandisk";
  auto load_input = [&]() {
    if (name == "icosphere")
      s.load(mesh::make_icosphere(3));
    else
      s.load_file(path);
    if (fandisk) s.set_settings({{"features", 45}});  // sharp edges kept: the feature code path
  };
  load_input();
  const size_t restart_faces = size_t(env_long("ADASCULPT_SOAK_RESTART_FACES", 0));
  const int genus0 = geometry::genus(s.mesh()), loops0 = geometry::boundary_loops(s.mesh());
  const double diag = s.settings()["diagonal"].get<double>();
  const double min_len = s.settings()["min_length"].get<double>();
  const size_t faces0 = s.mesh().n_faces();

  const long progress_every = env_long("ADASCULPT_SOAK_PROGRESS_EVERY", 500);
  const auto t_mesh = std::chrono::steady_clock::now();
  std::mt19937 rng(seed);
  auto uni = [&rng](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  auto pick = [&rng](int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng); };
  auto random_vertex = [&]() {
    const auto& m = s.mesh();
    mesh::Vertex v;
    do v = mesh::Vertex(static_cast<mesh::Index>(pick(static_cast<int>(m.vertices_size()))));
    while (m.is_deleted(v) || m.is_isolated(v));
    return v;
  };
  auto unit = [&]() {
    Vec3 d;
    do d = Vec3(uni(-1, 1), uni(-1, 1), uni(-1, 1));
    while (glm::length(d) < 0.1 || glm::length(d) > 1);
    return glm::normalize(d);
  };

  // The replayable log, and the model of the history: fingerprints of the mesh before each step.
  json log = {{"version", 1}, {"settings", fandisk ? json{{"features", 45}} : json::object()}, {"steps", json::array()}};
  std::deque<uint64_t> undo_model, redo_model;
  // Appends one step to the log in its session-file form (sculpt/session_file.h).
  auto log_step = [&](sculpt::SessionStep::Kind kind, auto set) {
    sculpt::SessionFile one;
    one.steps.emplace_back();
    one.steps.back().kind = kind;
    set(one.steps.back());
    log["steps"].push_back(sculpt::to_json(one)["steps"][0]);
  };
  auto dump_log = [&]() {
    const char* tmp = std::getenv("TMPDIR");
    const fs::path p = fs::path(tmp && *tmp ? tmp : "/tmp") / ("adasculpt_soak_" + label + ".json");
    std::ofstream(p) << log.dump(1) << "\n";
    return p.string();
  };
  auto fail_here = [&](long step, const std::string& what) {
    return ::testing::AssertionFailure() << label << " step " << step << ": " << what
                                         << " (steps so far: " << dump_log() << ")";
  };
  auto push_model = [&](uint64_t before) {
    undo_model.push_back(before);
    redo_model.clear();
    while (undo_model.size() > sculpt::Session::kMaxUndoSteps) undo_model.pop_front();
  };

  for (long step = 1; step <= steps; ++step) {
    const int kind = pick(100);
    try {
      if (kind < 40) {  // grab
        sculpt::GrabStep g;
        const auto& m = s.mesh();
        const mesh::Vertex v = random_vertex();
        g.center = m.position(v) + uni(0, 0.02 * diag) * unit();
        g.handle_radius = pick(4) == 0 ? 0.0 : uni(0, 0.05 * diag);
        g.roi_radius = g.handle_radius + uni(0.02 * diag, 0.25 * diag);
        const int mode = pick(4);  // translate / rotate / scale / everything
        if (mode == 0 || mode == 3) g.translate = uni(0, 0.12 * diag) * unit();
        if (mode == 1 || mode == 3) {
          g.axis = unit();
          g.degrees = uni(-60, 60);
        }
        if (mode == 2 || mode == 3) g.scale = uni(0.7, 1.4);
        g.substeps = 1 + pick(6);
        log_step(sculpt::SessionStep::Kind::Grab, [&](sculpt::SessionStep& st) { st.grab = g; });
        const uint64_t before = test::fingerprint(s.mesh());
        s.grab_begin(g.center, g.handle_radius, g.roi_radius);
        for (int i = 1; i <= g.substeps; ++i) {
          s.grab_drag(g.total_at(double(i) / g.substeps));
          ++totals.frames;
          if (!all_finite(s.mesh())) {
            ADD_FAILURE() << fail_here(step, "non-finite position during frame " + std::to_string(i));
            return;
          }
          s.clear_changes();  // as the app does once per frame
        }
        s.grab_end();
        push_model(before);
        ++totals.grabs;
      } else if (kind < 70) {  // brush stroke
        const auto& m = s.mesh();
        sculpt::BrushStroke b;
        deform::BrushSettings& bs = b.settings;
        bs.tool = static_cast<deform::BrushTool>(pick(7));  // draw .. grab (snake hook)
        bs.radius = uni(0.01, 0.12) * diag;
        bs.strength = pick(8) == 0 ? double(pick(2)) : uni(0, 1);
        bs.spacing = pick(3) == 0 ? uni(0.05, 1.0) : 0.25;
        bs.invert = pick(3) == 0;
        bs.symmetry_axis = pick(2) == 0 ? pick(3) : -1;
        // Pointer samples: a path that walks over the surface from a random vertex (or from where
        // a random ray hits it), about `travel` apart, turning slowly; some samples leave the
        // surface (near it, or far off as when the pointer slides off the model). Grab (snake
        // hook) drags through space from a surface point instead.
        // About a dozen stamps per stroke on average (each stamp runs a remeshing iteration).
        const int n = 1 + pick(bs.spacing < 0.15 ? 4 : 10);
        const double travel = uni(0.1, 1.0) * bs.radius;
        mesh::Vertex v = random_vertex();
        Vec3 dir = unit();
        Point start = m.position(v);
        if (pick(3) == 0) {
          const Vec3 ray = unit();
          Point hit;
          if (s.pick(start - diag * ray, ray, &hit)) start = hit;
        }
        b.path.push_back(start);
        for (int i = 1; i < n; ++i) {
          dir = glm::normalize(dir + 0.4 * unit());
          if (bs.tool == deform::BrushTool::Grab) {
            b.path.push_back(b.path.back() + uni(0.2, 1.0) * travel * dir);
            continue;
          }
          double walked = 0;
          for (int hop = 0; hop < 64 && walked < travel; ++hop) {
            mesh::Vertex next;
            double best = -1e300;
            for (mesh::Vertex w : m.vertices(v)) {
              const Vec3 e = m.position(w) - m.position(v);
              const double len = glm::length(e);
              const double a = (len > 0 ? glm::dot(e, dir) / len : -1) + uni(0, 0.3);
              if (a > best) {
                best = a;
                next = w;
              }
            }
            if (!next.is_valid()) break;
            walked += glm::length(m.position(next) - m.position(v));
            v = next;
          }
          Point p = m.position(v);
          const int off = pick(20);
          if (off < 2)
            p += uni(0.5, 3) * bs.radius * unit();  // off the surface, near it
          else if (off == 2)
            p += uni(0.05, 0.3) * diag * unit();  // far off
          else
            p += uni(0, 0.1) * bs.radius * unit();
          b.path.push_back(p);
        }
        if (pick(2) == 0) {  // pen pressure, a random walk in [0, 1]
          double pr = uni(0, 1);
          for (size_t i = 0; i < b.path.size(); ++i) {
            b.pressure.push_back(pr);
            pr = std::clamp(pr + uni(-0.3, 0.3), 0.0, 1.0);
          }
        }
        log_step(sculpt::SessionStep::Kind::Brush, [&](sculpt::SessionStep& st) { st.brush = b; });
        const uint64_t before = test::fingerprint(s.mesh());
        s.brush_begin(bs);
        for (size_t i = 0; i < b.path.size(); ++i) {
          try {
            s.brush_stamp(b.path[i], b.pressure.empty() ? 1.0 : b.pressure[i]);
          } catch (const std::runtime_error& e) {
            if (std::string(e.what()).rfind("brush: stroke stopped at ", 0) != 0) throw;
            ++totals.stopped;  // later samples of this stroke are ignored; the checks go on as usual
          }
          ++totals.samples;
          totals.stamps += s.last_frame().stamps;
          for (mesh::Vertex t : s.changes().touched_vertices) {
            if (t.idx >= m.vertices_size() || m.is_deleted(t)) continue;
            const Point& p = m.position(t);
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
              ADD_FAILURE() << fail_here(step, "non-finite position during brush sample " + std::to_string(i));
              return;
            }
          }
          s.clear_changes();  // as the app does once per frame
        }
        s.brush_end();
        push_model(before);
        ++totals.brushes;
      } else if (kind < 80) {  // whole-mesh remesh
        const int it = 1 + pick(2);
        log["steps"].push_back({{"remesh", {{"iterations", it}}}});
        const uint64_t before = test::fingerprint(s.mesh());
        s.remesh(it);
        push_model(before);
        ++totals.remeshes;
      } else {  // a run of undo (62%) or redo
        const bool undo = kind < 92;
        const int n = 1 + pick(4);
        log["steps"].push_back({{undo ? "undo" : "redo", n}});
        for (int i = 0; i < n; ++i) {
          std::deque<uint64_t>& from = undo ? undo_model : redo_model;
          std::deque<uint64_t>& to = undo ? redo_model : undo_model;
          const uint64_t now = test::fingerprint(s.mesh());
          const bool did = undo ? s.undo() : s.redo();
          if (did != !from.empty()) {
            ADD_FAILURE() << fail_here(step, std::string(undo ? "undo" : "redo") + " returned " + (did ? "true" : "false") +
                                                 " with " + std::to_string(from.size()) + " steps in the model");
            return;
          }
          if (!did) break;
          if (test::fingerprint(s.mesh()) != from.back()) {
            ADD_FAILURE() << fail_here(step, std::string(undo ? "undo" : "redo") + " did not restore the exact mesh");
            return;
          }
          ++totals.checks;
          from.pop_back();
          to.push_back(now);
          ++(undo ? totals.undos : totals.redos);
        }
      }
    } catch (const std::exception& e) {
      ADD_FAILURE() << fail_here(step, std::string("exception: ") + e.what());
      return;
    }
    s.clear_changes();
    ++totals.steps;

    if (!all_finite(s.mesh())) {
      ADD_FAILURE() << fail_here(step, "non-finite position");
      return;
    }
    ++totals.checks;
    // A time-boxed run ends after this step, with the full checks on it.
    const bool stop =
        seconds > 0 && step < steps &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t_mesh).count() > seconds;
    if (step % check_every == 0 || step == steps || stop) {
      try {
        s.mesh().validate();
      } catch (const std::exception& e) {
        ADD_FAILURE() << fail_here(step, std::string("validate: ") + e.what());
        return;
      }
      const int genus = geometry::genus(s.mesh()), loops = geometry::boundary_loops(s.mesh());
      if (genus != genus0 || loops != loops0) {
        ADD_FAILURE() << fail_here(step, "topology changed: genus " + std::to_string(genus0) + " -> " +
                                             std::to_string(genus) + ", boundary loops " + std::to_string(loops0) +
                                             " -> " + std::to_string(loops));
        return;
      }
      // Bounded size: the sizing field never asks for edges shorter than min_length, so the face
      // count is bounded by area / min_length^2; a runaway refinement shows up as a blow-up.
      const size_t faces = s.mesh().n_faces();
      const size_t limit = std::max<size_t>(50 * faces0, size_t(40.0 * diag * diag / (min_len * min_len)));
      if (faces > limit) {
        ADD_FAILURE() << fail_here(step, "face count " + std::to_string(faces) + " exceeds " + std::to_string(limit));
        return;
      }
      if (!s.changes().touched_vertices.empty()) {
        ADD_FAILURE() << fail_here(step, "change set not cleared");
        return;
      }
      totals.checks += 4;
      if (restart_faces > 0 && faces > restart_faces) {
        load_input();
        undo_model.clear();
        redo_model.clear();
        log["steps"] = json::array();  // a failure replays from the fresh load
        ++totals.restarts;
      }
    }
    if (step % progress_every == 0) {  // progress of long runs
      std::printf("[soak]   %s: step %ld/%ld, %zu vertices, %zu faces, %.0f s, VmRSS %ld MB, VmHWM %ld MB, "
                  "%ld checks so far\n",
                  label.c_str(), step, steps, s.mesh().n_vertices(), s.mesh().n_faces(),
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - t_mesh).count(),
                  proc_status_kb("VmRSS") / 1024, proc_status_kb("VmHWM") / 1024, totals.checks);
      std::fflush(stdout);
    }
    if (stop) {
      std::printf("[soak]   %s: time budget %.0f s reached after step %ld of %ld (%zu vertices, %zu faces)\n",
                  label.c_str(), seconds, step, steps, s.mesh().n_vertices(), s.mesh().n_faces());
      std::fflush(stdout);
      break;
    }
  }

  // History bounded and intact: walk all the way back (each snapshot valid) and forward again.
  size_t back = 0;
  while (s.undo()) {
    ++back;
    s.mesh().validate();
    ASSERT_LE(back, sculpt::Session::kMaxUndoSteps) << label << ": undo history is not bounded";
  }
  // The history also has a byte budget (kMaxUndoBytes): on large meshes it keeps fewer than
  // kMaxUndoSteps steps, the oldest dropped first. What is kept must be the newest ones, exact.
  ASSERT_LE(back, undo_model.size()) << label;
  if (back > 0) {
    EXPECT_EQ(test::fingerprint(s.mesh()), undo_model[undo_model.size() - back]) << label << ": oldest kept snapshot";
  }
  size_t forward = 0;
  while (s.redo()) ++forward;
  EXPECT_EQ(forward, back + redo_model.size()) << label;
  s.mesh().validate();
  totals.checks += 3;
}

TEST(ReliabilitySoak, RandomSculptingKeepsInvariants) {
  const long total_steps = env_long("ADASCULPT_SOAK_STEPS", 60);
  const long check_every = env_long("ADASCULPT_SOAK_CHECK_EVERY", 20);
  const uint32_t seed = static_cast<uint32_t>(env_long("ADASCULPT_SOAK_SEED", 1));
  const long max_rss_mb = env_long("ADASCULPT_SOAK_MAX_RSS_MB", 4096);
  const double budget = double(env_long("ADASCULPT_SOAK_SECONDS", 0));  // 0: no time limit
  const std::vector<std::string> meshes = soak_meshes();
  ASSERT_FALSE(meshes.empty());

  const auto t0 = std::chrono::steady_clock::now();
  Totals totals;
  std::vector<std::string> done;
  for (size_t i = 0; i < meshes.size(); ++i) {
    const long steps = total_steps / long(meshes.size()) + (long(i) < total_steps % long(meshes.size()) ? 1 : 0);
    const Totals before = totals;
    const auto m0 = std::chrono::steady_clock::now();
    // A time budget is shared out among the meshes still to run (what one leaves goes to the next).
    const double spent = std::chrono::duration<double>(m0 - t0).count();
    const double share = budget > 0 ? std::max(1.0, (budget - spent) / double(meshes.size() - i)) : 0;
    soak_one(meshes[i], steps, check_every, seed + uint32_t(i), share, totals);
    if (HasFailure()) return;
    const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - m0).count();
    std::printf("[soak] %-28s steps %6ld grabs %6ld (frames %7ld) brushes %6ld (samples %7ld, stamps %8ld) "
                "remeshes %5ld undos %5ld redos %5ld fresh loads %3ld  %.1f s  VmHWM %ld MB\n",
                meshes[i].c_str(), totals.steps - before.steps, totals.grabs - before.grabs,
                totals.frames - before.frames, totals.brushes - before.brushes, totals.samples - before.samples,
                totals.stamps - before.stamps, totals.remeshes - before.remeshes, totals.undos - before.undos,
                totals.redos - before.redos, totals.restarts - before.restarts, sec, proc_status_kb("VmHWM") / 1024);
    std::fflush(stdout);
    if (totals.steps > before.steps) done.push_back(fs::path(meshes[i]).filename().string());
  }
  const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const long hwm_mb = proc_status_kb("VmHWM") / 1024;
  std::string names;
  for (const auto& d : done) names += (names.empty() ? "" : ",") + d;
  std::printf("[soak] total: %ld steps on %zu meshes (%s): %ld grabs (%ld frames), %ld brush strokes (%ld samples, "
              "%ld stamps, %ld stopped by their face budget), %ld remeshes, %ld undos, %ld redos, %ld fresh loads; %.1f s, "
              "peak RSS (VmHWM) %ld MB, %ld invariant checks passed, seed %u\n",
              totals.steps, done.size(), names.c_str(), totals.grabs, totals.frames, totals.brushes, totals.samples,
              totals.stamps, totals.stopped, totals.remeshes, totals.undos, totals.redos, totals.restarts, sec, hwm_mb,
              totals.checks, seed);
  if (hwm_mb > 0) {
    EXPECT_LE(hwm_mb, max_rss_mb) << "peak RSS";
  }
}

}  // namespace
