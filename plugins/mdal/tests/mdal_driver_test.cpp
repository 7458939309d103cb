// The MDAL driver library through its exported C functions only, looked up with dlopen/dlsym as
// MDAL does (no MDAL, no QGIS), and its grid reader's messages for broken files.
#include <dlfcn.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "adcirc_grid.hpp"

namespace {

class Driver {
 public:
  Driver() : lib_(dlopen(FDR_MDAL_DRIVER, RTLD_NOW | RTLD_LOCAL)) {}
  ~Driver() {
    if (lib_) dlclose(lib_);
  }
  bool loaded() const { return lib_ != nullptr; }
  template <class F>
  F* fn(const char* name) const {
    void* p = dlsym(lib_, name);
    if (!p) ADD_FAILURE() << "missing symbol " << name;
    return reinterpret_cast<F*>(p);
  }

 private:
  void* lib_;
};

const Driver& driver() {
  static Driver d;
  return d;
}

std::string write_file(const std::string& name, const std::string& text) {
  static std::string dir = [] {
    char tmpl[] = "/tmp/mdal_driver_test_XXXXXX";
    const char* d = mkdtemp(tmpl);
    return std::string(d ? d : "/tmp");
  }();
  const std::string path = dir + "/" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// Two triangles and a quad around five nodes; one open and one land boundary.
const char* kGrid =
    "title line\n"
    "3 6 ! NE NP\n"
    "1 400000.0 4100000.0 5.0\n"
    "2 401000.0 4100000.0 -1.5\n"
    "3 401000.0 4101000.0 1.5D+01\n"
    "4 400000.0 4101000.0 0\n"
    "5 402000.0 4100000.0 7\n"
    "6 402000.0 4101000.0 8\n"
    "1 3 1 2 3\n"
    "2 3 1 3 4\n"
    "3 4 2 5 6 3\n"
    "1 = Number of open boundaries\n"
    "2 = Total number of open boundary nodes\n"
    "2 0 = Number of nodes for open boundary 1\n"
    "5\n6\n"
    "1 = Number of land boundaries\n"
    "3 = Total number of land boundary nodes\n"
    "3 0 = Number of nodes for land boundary 1\n"
    "1\n2\n5\n";

int open_mesh(const std::string& path) {
  return driver().fn<int(const char*, const char*)>("MDAL_DRIVER_openMesh")(path.c_str(), "");
}
void close_mesh(int id) { driver().fn<void(int)>("MDAL_DRIVER_closeMesh")(id); }
bool can_read(const std::string& path) { return driver().fn<bool(const char*)>("MDAL_DRIVER_canReadMesh")(path.c_str()); }

}  // namespace

TEST(MdalDriver, DescribesItself) {
  ASSERT_TRUE(driver().loaded()) << dlerror();
  EXPECT_STREQ(driver().fn<const char*()>("MDAL_DRIVER_driverName")(), "FDRMESH_ADCIRC");
  EXPECT_STREQ(driver().fn<const char*()>("MDAL_DRIVER_filters")(), "*.14;;*.grd;;*.gr3;;*.ll");
  EXPECT_EQ(driver().fn<int()>("MDAL_DRIVER_capabilities")(), 1);
  EXPECT_EQ(driver().fn<int()>("MDAL_DRIVER_maxVertexPerFace")(), 4);
  // Every function MDAL 0.9 looks up, the 3D ones included.
  for (const char* name : {"MDAL_DRIVER_driverLongName", "MDAL_DRIVER_M_vertexCount", "MDAL_DRIVER_M_faceCount",
                           "MDAL_DRIVER_M_edgeCount", "MDAL_DRIVER_M_extent", "MDAL_DRIVER_M_projection",
                           "MDAL_DRIVER_M_vertices", "MDAL_DRIVER_M_faces", "MDAL_DRIVER_M_edges",
                           "MDAL_DRIVER_M_datasetGroupCount", "MDAL_DRIVER_G_groupName", "MDAL_DRIVER_G_referenceTime",
                           "MDAL_DRIVER_G_metadataCount", "MDAL_DRIVER_G_metadataKey", "MDAL_DRIVER_G_metadataValue",
                           "MDAL_DRIVER_G_datasetsDescription", "MDAL_DRIVER_D_time", "MDAL_DRIVER_D_data",
                           "MDAL_DRIVER_D_hasActiveFlagCapability", "MDAL_DRIVER_D_activeFlags",
                           "MDAL_DRIVER_D_maximumVerticalLevelCount", "MDAL_DRIVER_D_volumeCount",
                           "MDAL_DRIVER_D_verticalLevelCountData", "MDAL_DRIVER_D_verticalLevelData",
                           "MDAL_DRIVER_D_faceToVolumeData", "MDAL_DRIVER_D_unload"})
    EXPECT_NE(driver().fn<void()>(name), nullptr);
}

TEST(MdalDriver, ReadsVerticesFacesDepthAndExtent) {
  const std::string path = write_file("m.14", kGrid);
  ASSERT_TRUE(can_read(path));
  const int id = open_mesh(path);
  ASSERT_GE(id, 0);
  EXPECT_EQ(driver().fn<int(int)>("MDAL_DRIVER_M_vertexCount")(id), 6);
  EXPECT_EQ(driver().fn<int(int)>("MDAL_DRIVER_M_faceCount")(id), 3);
  EXPECT_EQ(driver().fn<int(int)>("MDAL_DRIVER_M_edgeCount")(id), 0);
  EXPECT_STREQ(driver().fn<const char*(int)>("MDAL_DRIVER_M_projection")(id), "");  // metres: unknown

  // Vertices in two calls, as MDAL's iterator asks for them: z is the bed elevation, -depth.
  auto vertices = driver().fn<int(int, int, int, double*)>("MDAL_DRIVER_M_vertices");
  std::vector<double> xyz(18, -99);
  ASSERT_EQ(vertices(id, 0, 4, xyz.data()), 4);
  ASSERT_EQ(vertices(id, 4, 10, xyz.data() + 12), 2);
  EXPECT_EQ(xyz[0], 400000.0);
  EXPECT_EQ(xyz[1], 4100000.0);
  EXPECT_EQ(xyz[2], -5.0);
  EXPECT_EQ(xyz[5], 1.5);
  EXPECT_EQ(xyz[8], -15.0);
  EXPECT_EQ(xyz[11], 0.0);
  EXPECT_EQ(xyz[17], -8.0);

  // Faces: all at once, then with a node buffer too small for the quad after two triangles.
  auto faces = driver().fn<int(int, int, int, int*, int, int*)>("MDAL_DRIVER_M_faces");
  std::vector<int> off(3), nodes(16);
  ASSERT_EQ(faces(id, 0, 3, off.data(), 16, nodes.data()), 3);
  EXPECT_EQ(off, (std::vector<int>{3, 6, 10}));
  EXPECT_EQ(std::vector<int>(nodes.begin(), nodes.begin() + 10), (std::vector<int>{0, 1, 2, 0, 2, 3, 1, 4, 5, 2}));
  ASSERT_EQ(faces(id, 0, 3, off.data(), 8, nodes.data()), 2);
  ASSERT_EQ(faces(id, 2, 3, off.data(), 8, nodes.data()), 1);
  EXPECT_EQ(off[0], 4);
  EXPECT_EQ(std::vector<int>(nodes.begin(), nodes.begin() + 4), (std::vector<int>{1, 4, 5, 2}));
  EXPECT_EQ(faces(id, 3, 3, off.data(), 8, nodes.data()), 0);

  double x0, x1, y0, y1;
  driver().fn<void(int, double*, double*, double*, double*)>("MDAL_DRIVER_M_extent")(id, &x0, &x1, &y0, &y1);
  EXPECT_EQ(x0, 400000.0);
  EXPECT_EQ(x1, 402000.0);
  EXPECT_EQ(y0, 4100000.0);
  EXPECT_EQ(y1, 4101000.0);

  // The "depth" group: one scalar dataset on the vertices holding the file's column.
  ASSERT_EQ(driver().fn<int(int)>("MDAL_DRIVER_M_datasetGroupCount")(id), 1);
  EXPECT_STREQ(driver().fn<const char*(int, int)>("MDAL_DRIVER_G_groupName")(id, 0), "depth");
  bool scalar = false;
  int location = 0, count = 0;
  ASSERT_TRUE(driver().fn<bool(int, int, bool*, int*, int*)>("MDAL_DRIVER_G_datasetsDescription")(id, 0, &scalar, &location, &count));
  EXPECT_TRUE(scalar);
  EXPECT_EQ(location, 1);
  EXPECT_EQ(count, 1);
  bool ok = false;
  EXPECT_EQ(driver().fn<double(int, int, int, bool*)>("MDAL_DRIVER_D_time")(id, 0, 0, &ok), 0.0);
  EXPECT_TRUE(ok);
  std::vector<double> depth(6, -99);
  auto data = driver().fn<int(int, int, int, int, int, double*)>("MDAL_DRIVER_D_data");
  ASSERT_EQ(data(id, 0, 0, 0, 10, depth.data()), 6);
  EXPECT_EQ(depth, (std::vector<double>{5.0, -1.5, 15.0, 0.0, 7.0, 8.0}));
  EXPECT_EQ(data(id, 0, 0, 6, 10, depth.data()), 0);

  close_mesh(id);
  EXPECT_EQ(driver().fn<int(int)>("MDAL_DRIVER_M_vertexCount")(id), -1);
  const int again = open_mesh(path);
  EXPECT_GT(again, id);  // MDAL keeps the ids it has seen: one is never handed out twice
  close_mesh(again);
}

TEST(MdalDriver, LonLatCrs) {
  const std::string ll = std::string("g\n1 3\n1 -70.5 37.0 10\n2 -70.0 37.0 12\n3 -70.0 37.5 11\n1 3 1 2 3\n");
  for (const char* name : {"hgrid.ll", "fort.14"}) {
    const int id = open_mesh(write_file(name, ll));
    ASSERT_GE(id, 0) << name;
    EXPECT_STREQ(driver().fn<const char*(int)>("MDAL_DRIVER_M_projection")(id), "EPSG:4326") << name;
    close_mesh(id);
  }
  // A .ll is lon/lat by its name, whatever its numbers.
  const int id = open_mesh(write_file("x.ll", kGrid));
  ASSERT_GE(id, 0);
  EXPECT_STREQ(driver().fn<const char*(int)>("MDAL_DRIVER_M_projection")(id), "EPSG:4326");
  close_mesh(id);
}

TEST(MdalDriver, SparseNodeIdsAndNoBoundaries) {
  const int id = open_mesh(write_file("sparse.gr3", "t\n1 3\n10 0 0 1\n30 1 0 2\n20 0 1 3\n7 3 10 30 20\n"));
  ASSERT_GE(id, 0);
  std::vector<int> off(1), nodes(4);
  ASSERT_EQ(driver().fn<int(int, int, int, int*, int, int*)>("MDAL_DRIVER_M_faces")(id, 0, 1, off.data(), 4, nodes.data()), 1);
  EXPECT_EQ(std::vector<int>(nodes.begin(), nodes.begin() + 3), (std::vector<int>{0, 1, 2}));
  close_mesh(id);
}

TEST(MdalDriver, RefusesOtherFilesAndBrokenGrids) {
  EXPECT_FALSE(can_read(write_file("surfer.grd", "DSAA\n10 20\n0 1\n0 1\n0 5\n")));
  EXPECT_FALSE(can_read(write_file("m.txt", kGrid)));
  EXPECT_FALSE(can_read("/nonexistent/fort.14"));
  EXPECT_EQ(open_mesh("/nonexistent/fort.14"), -1);

  const std::string good(kGrid);
  struct Case {
    const char* name;
    std::string text;
    const char* why;
  };
  const std::vector<Case> cases = {
      {"cut_nodes", good.substr(0, good.find("4 400000.0")), "5: the file ends where a node line"},
      {"cut_boundary", good.substr(0, good.find("6\n1 =")), "the file ends where a boundary node id"},
      {"np_too_big", "t\n3 7\n" + good.substr(good.find("1 400000.0")), "node id 1 defined twice"},
      {"np_too_small", "t\n3 5\n" + good.substr(good.find("1 400000.0")), "'402000.0' is not an integer"},
      {"ne_too_small", "t\n2 6\n" + good.substr(good.find("1 400000.0")), "the file ends where"},
      {"bad_node", std::string("t\n1 3\n1 0 0 1\n2 1 0 1\n3 0 1 1\n1 3 1 2 9\n"), "node id 9 is not defined"},
      {"pentagon", std::string("t\n1 3\n1 0 0 1\n2 1 0 1\n3 0 1 1\n1 5 1 2 3 1 2\n"), "element with 5 nodes"},
      {"bad_number", std::string("t\n0 1\n1 0 x 1\n"), "'x' is not a number"},
      {"empty", std::string(), "empty file"},
  };
  for (const Case& c : cases) {
    const std::string path = write_file(std::string(c.name) + ".14", c.text);
    EXPECT_EQ(open_mesh(path), -1) << c.name;
    fdr_mdal::Grid g;
    const std::string why = fdr_mdal::read_grid(path, g);
    EXPECT_NE(why.find(path + ":"), std::string::npos) << c.name << ": " << why;
    EXPECT_NE(why.find(c.why), std::string::npos) << c.name << ": " << why;
  }
}
