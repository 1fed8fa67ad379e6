#include <gtest/gtest.h>

#include "core/output/xdmf.hpp"
#include "output_test_utils.hpp"

namespace stoss::output {
namespace {

XdmfLayout two_frames(bool pressure) {
  return XdmfLayout{"result.h5", 16, 2, {0.0, 0.125}, pressure};
}

// Each frame's geometry shall be its own slab [k, 0, 0] of the [K, N, 3] position dataset.
TEST(Xdmf, GeometryIsTheFrameSlabOfPositions) {
  const std::string xdmf = xdmf_document(two_frames(false));
  EXPECT_EQ(testing::xml_structure_error(xdmf), "");
  EXPECT_EQ(testing::count_of(xdmf, "<Geometry GeometryType=\"XYZ\">"), 2);
  EXPECT_EQ(testing::count_of(xdmf, "Format=\"XML\">1 0 0  1 1 1  1 16 3</DataItem>"),
            2);  // position, velocity
  EXPECT_EQ(testing::count_of(xdmf,
                              "Dimensions=\"2 16 3\" NumberType=\"Float\" Precision=\"8\" "
                              "Format=\"HDF\">result.h5:/frames/position</DataItem>"),
            2);
  EXPECT_EQ(testing::count_of(xdmf, "<Time Value=\"0.125\"/>"), 1);
}

TEST(Xdmf, TopologyIsHexahedraFromMesh) {
  const std::string xdmf = xdmf_document(two_frames(false));
  EXPECT_EQ(testing::count_of(xdmf, "<Topology TopologyType=\"Hexahedron\" NumberOfElements=\"2\""), 2);
  EXPECT_EQ(testing::count_of(xdmf,
                              "Dimensions=\"2 8\" NumberType=\"Int\" Precision=\"8\" "
                              "Format=\"HDF\">result.h5:/mesh/hex8</DataItem>"),
            2);
  EXPECT_EQ(testing::count_of(xdmf, "result.h5:/mesh/nodes"), 2);
}

TEST(Xdmf, ContactPressureIsANodeScalarSlab) {
  EXPECT_EQ(xdmf_document(two_frames(false)).find("contact_pressure"), std::string::npos);
  const std::string xdmf = xdmf_document(two_frames(true));
  EXPECT_EQ(testing::xml_structure_error(xdmf), "");
  EXPECT_EQ(testing::count_of(
                xdmf, "<Attribute Name=\"contact_pressure\" AttributeType=\"Scalar\" Center=\"Node\">"),
            2);
  EXPECT_EQ(testing::count_of(xdmf, "Format=\"XML\">1 0  1 1  1 16</DataItem>"), 1);
}

// A file name with XML metacharacters shall be escaped, keeping the document well formed.
TEST(Xdmf, EscapesFileName) {
  XdmfLayout layout = two_frames(false);
  layout.h5_file = "a<b>&c.h5";
  const std::string xdmf = xdmf_document(layout);
  EXPECT_EQ(testing::xml_structure_error(xdmf), "");
  EXPECT_NE(xdmf.find("a&lt;b&gt;&amp;c.h5:/frames/position"), std::string::npos);
}

TEST(Xdmf, NoFramesIsAnEmptyCollection) {
  const std::string xdmf = xdmf_document(XdmfLayout{"result.h5", 16, 2, {}, false});
  EXPECT_EQ(testing::xml_structure_error(xdmf), "");
  EXPECT_EQ(testing::count_of(xdmf, "<Grid "), 1);
}

// The structure check itself must catch what it is there for.
TEST(XmlStructureCheck, CatchesMismatchedTags) {
  EXPECT_EQ(testing::xml_structure_error("<a><b></a></b>"), "unexpected </a>");
  EXPECT_EQ(testing::xml_structure_error("<a><b/>"), "unclosed <a>");
  EXPECT_EQ(testing::xml_structure_error("<?xml version=\"1.0\"?><a x=\"1\"/>"), "");
}

}  // namespace
}  // namespace stoss::output
