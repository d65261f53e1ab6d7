// Runs the real `adasculpt` executable: exit codes, one-line errors, JSON on stdout.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace fs = std::filesystem;

namespace {

struct CliRun {
  int code = -1;
  std::string out, err;
  std::vector<std::string> err_lines() const {
    std::vector<std::string> lines;
    std::istringstream in(err);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
  }
};

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

CliRun run(const std::vector<std::string>& args) {
  static int counter = 0;
  const fs::path dir = fs::temp_directory_path() / ("adasculpt_cli_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path out = dir / ("out" + std::to_string(counter)), err = dir / ("err" + std::to_string(counter));
  ++counter;
  std::string cmd = quote(ADASCULPT_CLI_PATH);
  for (const auto& a : args) cmd += " " + quote(a);
  cmd += " >" + quote(out.string()) + " 2>" + quote(err.string()) + " </dev/null";
  CliRun r;
  const int status = std::system(cmd.c_str());
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  fs::remove(out);
  fs::remove(err);
  return r;
}

std::string data(const std::string& rel) { return std::string(ADASCULPT_SOURCE_DIR) + "/tests/data/" + rel; }

void expect_usage_error(const CliRun& r, const std::string& what) {
  EXPECT_EQ(r.code, 2) << what;
  auto lines = r.err_lines();
  ASSERT_EQ(lines.size(), 1u) << what << "\n" << r.err;
  EXPECT_EQ(lines[0].rfind("adasculpt: error: ", 0), 0u) << lines[0];
  EXPECT_TRUE(r.out.empty()) << what << ": " << r.out;
}

fs::path write_temp(const std::string& name, const std::string& text) {
  fs::path p = fs::temp_directory_path() / ("adasculpt_cli_" + std::to_string(::getpid()) + "_" + name);
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

}  // namespace

TEST(CliStats, JsonOnStdout) {
  CliRun r = run({"stats", data("meshes/eight.off"), "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  ASSERT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1);
  nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["vertices"], 766);
  EXPECT_EQ(j["faces"], 1536);
  EXPECT_EQ(j["genus"], 2);
  EXPECT_NEAR(j["min_angle_deg"].get<double>(), 21.44, 0.01);  // meshq: 21.44
  EXPECT_NEAR(j["mean_min_angle_deg"].get<double>(), 34.26, 0.01);  // meshq: 34.26
  EXPECT_FALSE(j.contains("rms_rel"));
}

TEST(CliStats, TableByDefault) {
  CliRun r = run({"stats", data("meshes/hemisphere.off")});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("mean min angle"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("boundary loops             1"), std::string::npos) << r.out;
}

TEST(CliStats, Reference) {
  CliRun r = run({"stats", data("meshes/hemisphere.off"), "--reference", data("meshes/hemisphere.off"), "--json",
               "--samples", "5000"});
  ASSERT_EQ(r.code, 0) << r.err;
  nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_LT(j["rms_rel"].get<double>(), 1e-12);
  EXPECT_LT(j["hausdorff_rel"].get<double>(), 1e-12);
}

TEST(CliStats, FeatureSectorOfTheReference) {
  // fandisk's sharp edges at 45 degrees meet at 19.4 degrees at one corner (the sweep judges a
  // remesh's min angle against that); it is closed, so without features nothing is forced.
  auto sector = [](const std::string& features) {
    CliRun r = run({"stats", data("meshes/fandisk.off"), "--reference", data("meshes/fandisk.off"), "--json",
                    "--samples", "10", "--features", features});
    EXPECT_EQ(r.code, 0) << r.err;
    return r.code == 0 ? nlohmann::json::parse(r.out)["reference_feature_sector_deg"].get<double>() : -1.0;
  };
  EXPECT_NEAR(sector("45"), 19.40, 0.01);
  EXPECT_EQ(sector("0"), 360.0);
  CliRun r = run({"stats", data("meshes/fandisk.off"), "--reference", data("meshes/fandisk.off"), "--features", "45",
                  "--samples", "10"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("smallest feature sector of the reference   19.399"), std::string::npos) << r.out;
  expect_usage_error(run({"stats", data("meshes/fandisk.off"), "--features", "45"}), "--features without --reference");
  expect_usage_error(run({"stats", data("meshes/fandisk.off"), "--reference", data("meshes/fandisk.off"), "--features",
                          "200"}),
                     "--features out of range");
}

TEST(CliStats, SelfIntersections) {
  // Two separate triangles, the second piercing the first.
  const fs::path crossing = write_temp("crossing.off",
                                       "OFF\n6 2 0\n0 0 0\n4 0 0\n0 4 0\n1 1 -1\n1 1 1\n5 5 0\n3 0 1 2\n3 3 4 5\n");
  CliRun r = run({"stats", crossing.string(), "--self-intersections", "--json"});
  fs::remove(crossing);
  ASSERT_EQ(r.code, 0) << r.err;
  nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["self_intersecting_pairs"], 1);
  EXPECT_EQ(j["self_intersections_capped"], false);
  ASSERT_EQ(j["self_intersection_examples"].size(), 1u);  // where to look: both faces' centroids
  EXPECT_NEAR(j["self_intersection_examples"][0][1]["centroid"][2].get<double>(), 0.0, 1e-12);
  r = run({"stats", data("meshes/eight.off"), "--self-intersections"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("self-intersecting pairs    0"), std::string::npos) << r.out;
  r = run({"stats", data("meshes/eight.off"), "--json"});
  EXPECT_FALSE(nlohmann::json::parse(r.out).contains("self_intersecting_pairs")) << "only on request";
}

TEST(CliStats, HelpAndVersion) {
  CliRun help = run({"--help"});
  EXPECT_EQ(help.code, 0);
  EXPECT_NE(help.out.find("stats"), std::string::npos);
  CliRun sub = run({"stats", "--help"});
  EXPECT_EQ(sub.code, 0);
  EXPECT_NE(sub.out.find("--reference"), std::string::npos);
  CliRun version = run({"--version"});
  EXPECT_EQ(version.code, 0);
  EXPECT_EQ(version.out.rfind("adasculpt ", 0), 0u);
}

TEST(CliStats, BadUsageIsOneLine) {
  expect_usage_error(run({}), "no subcommand");
  expect_usage_error(run({"frobnicate"}), "unknown subcommand");
  expect_usage_error(run({"stats"}), "missing MESH");
  expect_usage_error(run({"stats", data("meshes/eight.off"), "--frob"}), "unknown flag");
  expect_usage_error(run({"stats", data("meshes/eight.off"), "--samples", "many"}), "bad number");
  expect_usage_error(run({"stats", data("meshes/eight.off"), "--samples", "0"}), "zero samples");
  expect_usage_error(run({"stats", data("meshes/does_not_exist.off")}), "missing file");
  expect_usage_error(run({"stats", data("meshes/eight.off"), "--reference", data("nope.obj"), "--json"}),
                     "missing reference");
  expect_usage_error(run({"stats", data("meshes/CREDITS.md")}), "unknown extension");
}

TEST(CliStats, NonManifoldInputIsOneLine) {
  fs::path p = write_temp("fin.off", "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n");
  CliRun r = run({"stats", p.string(), "--json"});
  fs::remove(p);
  expect_usage_error(r, "non-manifold edge");
  EXPECT_NE(r.err.find("fin.off: non-manifold edge"), std::string::npos) << r.err;
}

TEST(CliStats, WarningsGoToStderrOnly) {
  fs::path p = write_temp("bowtie.off", "OFF\n5 2 0\n0 0 0\n1 0 0\n1 1 0\n-1 0 0\n-1 -1 0\n3 0 1 2\n3 0 3 4\n");
  CliRun r = run({"stats", p.string(), "--json"});
  fs::remove(p);
  ASSERT_EQ(r.code, 0) << r.err;
  nlohmann::json j = nlohmann::json::parse(r.out);  // stdout is pure JSON
  EXPECT_EQ(j["vertices"], 6);
  auto lines = r.err_lines();
  ASSERT_FALSE(lines.empty());
  for (const auto& l : lines) EXPECT_EQ(l.rfind("adasculpt: warning: ", 0), 0u) << l;
}

TEST(CliStats, EveryMalformedFileExitsTwoWithOneLine) {
  const fs::path dir = data("malformed");
  if (!fs::exists(dir)) GTEST_SKIP() << dir << " not found";
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (!entry.is_regular_file()) continue;
    ++files;
    for (bool json : {false, true}) {
      std::vector<std::string> args = {"stats", entry.path().string()};
      if (json) args.push_back("--json");
      expect_usage_error(run(args), entry.path().filename().string());
    }
  }
  EXPECT_GE(files, 20);
}

TEST(CliStats, SharedMeshesAgreeWithTheirReadme) {
  // Figures from ../shared/meshes/README.md (meshq --stats), rounded as printed there.
  struct Expect {
    const char* name;
    int v, f, loops, genus;
    double min_angle, mean_min_angle;
  };
  const Expect table[] = {{"fandisk.off", 6475, 12946, 0, 0, 17.05, 43.46},
                          {"dragon.off", 50000, 100000, 0, 1, 0.21, 32.29},
                          {"face.off", 25905, 51712, 1, 0, 5.54, 35.84}};
  for (const Expect& e : table) {
    const std::string path = std::string(ADASCULPT_SHARED_MESHES_DIR) + "/" + e.name;
    if (!fs::exists(path)) GTEST_SKIP() << path << " not found";
    CliRun r = run({"stats", path, "--json"});
    ASSERT_EQ(r.code, 0) << r.err;
    nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["vertices"], e.v) << e.name;
    EXPECT_EQ(j["faces"], e.f) << e.name;
    EXPECT_EQ(j["boundary_loops"], e.loops) << e.name;
    EXPECT_EQ(j["genus"], e.genus) << e.name;
    EXPECT_NEAR(j["min_angle_deg"].get<double>(), e.min_angle, 0.005) << e.name;
    EXPECT_NEAR(j["mean_min_angle_deg"].get<double>(), e.mean_min_angle, 0.005) << e.name;
  }
}

// `remesh --length L` alone remeshes uniformly at L: it used to be ignored (the default was
// adaptive), and the user got a mesh at the default tolerance without a word.
TEST(CliRemesh, LengthAloneMeansUniform) {
  const fs::path out = fs::temp_directory_path() / ("adasculpt_cli_" + std::to_string(::getpid()) + "_out.off");
  auto vertices = [&](std::vector<std::string> options) {
    std::vector<std::string> args = {"remesh", data("meshes/hemisphere.off"), out.string(), "--json"};
    args.insert(args.end(), options.begin(), options.end());
    CliRun r = run(args);
    EXPECT_EQ(r.code, 0) << r.err;
    return r.code == 0 ? nlohmann::json::parse(r.out)["vertices"].get<int>() : -1;
  };
  const int length_alone = vertices({"--length", "10%"});
  EXPECT_EQ(length_alone, vertices({"--uniform", "--length", "10%"}));
  EXPECT_NE(length_alone, vertices({}));  // the adaptive default
  EXPECT_LT(length_alone, vertices({"--length", "5%"}));
  fs::remove(out);
}

// Adaptive options with a uniform remesh would go unused: a usage error that names them.
TEST(CliRemesh, AdaptiveAndUniformOptionsConflict) {
  const std::string in = data("meshes/hemisphere.off"), out = "/nonexistent/out.off";
  for (const auto& args : std::vector<std::vector<std::string>>{{"--epsilon", "1%", "--length", "2%"},
                                                                 {"--uniform", "--min-length", "1%"},
                                                                 {"--max-length", "9%", "--uniform"}}) {
    std::vector<std::string> all = {"remesh", in, out};
    all.insert(all.end(), args.begin(), args.end());
    const CliRun r = run(all);
    expect_usage_error(r, args[0] + " " + args[2]);
    EXPECT_NE(r.err.find("exclude"), std::string::npos) << r.err;
  }
}
