#include "tools/convergence/tool_load_reference.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace vesica::convergence {
namespace {

std::string WriteFile(const std::string& name, const std::string& text) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path) << text;
  return path.string();
}

TEST(ToolLoadReferenceTest, ReadsEveryEntry) {
  const std::string path = WriteFile("vesica_ref_ok.txt",
                                     "# comment\nprescribed_m 0 0 -0.005\nforce_N 1 2 3\ncentre_m 0.1 0.2 0.3\n"
                                     "jaw_long_axis 0 1 0\ncontact 4 7\nu 0 0 0 0\nu 1 1e-3 0 -2e-3\n");
  const ToolLoadReference ref = ReadToolLoadReference(path);
  EXPECT_EQ(ref.prescribed_m, Eigen::Vector3d(0, 0, -0.005));
  EXPECT_EQ(ref.force_N, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(ref.centre_m, Eigen::Vector3d(0.1, 0.2, 0.3));
  EXPECT_EQ(ref.jaw_long_axis, Eigen::Vector3d(0, 1, 0));
  EXPECT_EQ(ref.contact, (std::vector<int>{4, 7}));
  ASSERT_EQ(ref.displacement_m.rows(), 2);
  EXPECT_EQ(ref.displacement_m(1, 2), -2e-3);
}

void ExpectError(const std::string& name, const std::string& text, const std::string& what) {
  const std::string path = WriteFile(name, text);
  try {
    ReadToolLoadReference(path);
    ADD_FAILURE() << "no error for " << text;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  }
}

TEST(ToolLoadReferenceTest, BadInputNamesTheFileAndLine) {
  ExpectError("vesica_ref_short.txt", "force_N 1 2\n", "vesica_ref_short.txt:1: force_N needs three numbers");
  ExpectError("vesica_ref_order.txt", "contact 1\nu 0 0 0 0\nu 2 0 0 0\n",
              ":3: u lines must list the vertices in order");
  ExpectError("vesica_ref_tag.txt", "contact 1\nforce 1 2 3\n", ":2: unknown entry 'force'");
  ExpectError("vesica_ref_empty.txt", "# nothing\n", "no displacements or no contact vertices");
  EXPECT_THROW(ReadToolLoadReference("/nonexistent/ref.txt"), std::runtime_error);
}

}  // namespace
}  // namespace vesica::convergence
