// Runs the built `anitet` binary (ANITET_BINARY) and checks exit codes and output.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "test_meshes.hpp"

namespace anitet {
namespace {

struct RunResult {
  int code = -1;
  std::string out, err;
};

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::ostringstream os;
  os << f.rdbuf();
  return os.str();
}

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    char tmpl[] = "/tmp/anitet_cli_test_XXXXXX";
    ASSERT_NE(mkdtemp(tmpl), nullptr);
    dir_ = tmpl;
  }
  void TearDown() override { std::system(("rm -rf '" + dir_ + "'").c_str()); }

  RunResult run(const std::string& args) {
    RunResult r;
    const std::string out = dir_ + "/stdout.txt", err = dir_ + "/stderr.txt";
    const std::string cmd = std::string("'") + ANITET_BINARY + "' " + args + " >'" + out + "' 2>'" + err + "'";
    const int status = std::system(cmd.c_str());
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(out);
    r.err = slurp(err);
    return r;
  }

  // The Kuhn cube as Medit .mesh (1-based) and its boundary as .off.
  void write_cube(const std::string& mesh_path, const std::string& off_path) {
    const VolumeMesh cube = test::kuhn_grid(1);
    std::ofstream m(mesh_path);
    m << "MeshVersionFormatted 2\nDimension 3\nVertices\n" << cube.num_vertices() << "\n";
    for (size_t v = 0; v < cube.num_vertices(); ++v) {
      m << cube.xyz[3 * v] << " " << cube.xyz[3 * v + 1] << " " << cube.xyz[3 * v + 2] << " 0\n";
    }
    m << "Tetrahedra\n" << cube.num_tets() << "\n";
    for (size_t t = 0; t < cube.num_tets(); ++t) {
      for (int i = 0; i < 4; ++i) m << cube.tet[4 * t + i] + 1 << " ";
      m << "1\n";
    }
    m << "End\n";
    const SurfaceMesh s = test::boundary_surface(cube);
    std::ofstream o(off_path);
    o << "OFF\n" << s.num_vertices() << " " << s.num_triangles() << " 0\n";
    for (size_t v = 0; v < s.num_vertices(); ++v) {
      o << s.xyz[3 * v] << " " << s.xyz[3 * v + 1] << " " << s.xyz[3 * v + 2] << "\n";
    }
    for (size_t t = 0; t < s.num_triangles(); ++t) {
      o << "3 " << s.tri[3 * t] << " " << s.tri[3 * t + 1] << " " << s.tri[3 * t + 2] << "\n";
    }
  }

  std::string dir_;
};

const std::string kSurfaces = ANITET_SURFACES_DIR;

TEST_F(Cli, HelpListsSubcommands) {
  const RunResult r = run("--help");
  EXPECT_EQ(r.code, 0) << r.err;
  for (const char* sub : {"check-surface", "quality", "mesh", "recover"}) {
    EXPECT_NE(r.out.find(sub), std::string::npos) << sub;
  }
}

TEST_F(Cli, VersionPrintsProjectVersion) {
  const RunResult r = run("--version");
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(r.out, "anitet 0.1.0\n");
}

TEST_F(Cli, UsageErrorsExitTwo) {
  EXPECT_EQ(run("").code, 2);
  EXPECT_EQ(run("no-such-command").code, 2);
  EXPECT_EQ(run("quality").code, 2);
  EXPECT_EQ(run("mesh in.off").code, 2);  // -o is required
}

TEST_F(Cli, CheckSurfaceOnCleanSurfaceSucceeds) {
  const RunResult r = run("check-surface '" + kSurfaces + "/decimated-knight.off'");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("1000 triangles"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("OK"), std::string::npos) << r.out;
}

TEST_F(Cli, CheckSurfaceJsonIsParseable) {
  const RunResult r = run("check-surface --json '" + kSurfaces + "/decimated-knight.off'");
  EXPECT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out, nullptr, false);
  ASSERT_FALSE(j.is_discarded()) << r.out;
  EXPECT_EQ(j.at("triangles").get<int>(), 1000);
  EXPECT_TRUE(j.at("ok").get<bool>());
}

TEST_F(Cli, CheckSurfaceOnOpenSurfaceFails) {
  const RunResult r = run("check-surface '" + kSurfaces + "/stanford-bunny.obj'");
  EXPECT_EQ(r.code, 4);
  EXPECT_NE(r.err.find("stanford-bunny.obj"), std::string::npos) << r.err;
  EXPECT_TRUE(r.err.find("open") != std::string::npos || r.err.find("boundary") != std::string::npos) << r.err;
}

TEST_F(Cli, MissingFileIsAReadError) {
  const RunResult r = run("check-surface '" + dir_ + "/nothing.off'");
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.err.find("nothing.off"), std::string::npos) << r.err;
  EXPECT_EQ(run("quality '" + dir_ + "/nothing.mesh'").code, 3);
}

TEST_F(Cli, QualityOfAWrittenMesh) {
  write_cube(dir_ + "/cube.mesh", dir_ + "/cube.off");
  const RunResult r = run("quality '" + dir_ + "/cube.mesh' --surface '" + dir_ + "/cube.off' --json --hist '" + dir_ +
                    "/hist.csv'");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out, nullptr, false);
  ASSERT_FALSE(j.is_discarded()) << r.out;
  EXPECT_EQ(j.at("tets").get<int>(), 6);
  EXPECT_TRUE(j.at("valid").get<bool>());
  EXPECT_TRUE(j.at("boundary_constrained").get<bool>());
  EXPECT_NEAR(j.at("volume").get<double>(), 1.0, 1e-12);
  EXPECT_EQ(slurp(dir_ + "/hist.csv").rfind("lo,hi,count\n", 0), 0u);

  const RunResult text = run("quality '" + dir_ + "/cube.mesh'");
  EXPECT_EQ(text.code, 0) << text.err;
  EXPECT_NE(text.out.find("radius ratio histogram"), std::string::npos) << text.out;
}

TEST_F(Cli, MeshWritesTheMeshAndRefusesBadInputFirst) {
  const std::string out = dir_ + "/out.mesh";
  RunResult r = run("mesh '" + kSurfaces + "/decimated-knight.off' --front-layers 1 -o '" + out + "' --quiet");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(std::ifstream(out).good());
  const std::string bad = dir_ + "/bad.mesh";
  r = run("recover '" + kSurfaces + "/stanford-bunny.obj' -o '" + bad + "' --quiet");
  EXPECT_EQ(r.code, 4) << r.err;  // the real error first
  EXPECT_FALSE(std::ifstream(bad).good());
}

}  // namespace
}  // namespace anitet
