#include <gtest/gtest.h>

#include "core/output/xdmf.hpp"
#include "output_test_utils.hpp"

namespace stoss::output {
namespace {

XdmfLayout two_frames(bool pressure, bool stress = false) {
  return XdmfLayout{"result.h5", 16, 2, {0.0, 0.125}, pressure, stress};
}

// Each frame's geometry shall be its own whole dataset /frames/<k>/position: no HyperSlab items, which
// ParaView's Xdmf3 readers and meshio do not read.
TEST(Xdmf, GeometryIsTheFramesPositionDataset) {
  const std::string xdmf = xdmf_document(two_frames(false));
  EXPECT_EQ(testing::xml_structure_error(xdmf), "");
  EXPECT_EQ(xdmf.find("HyperSlab"), std::string::npos);
  EXPECT_EQ(testing::count_of(xdmf, "<Geometry GeometryType=\"XYZ\">"), 2);
  for (int k = 0; k < 2; ++k)
    EXPECT_EQ(testing::count_of(xdmf,
                                "<DataItem Dimensions=\"16 3\" NumberType=\"Float\" Precision=\"8\" "
                                "Format=\"HDF\">result.h5:/frames/" +
                                    std::to_string(k) + "/position</DataItem>"),
              1);
  EXPECT_EQ(testing::count_of(xdmf, "<Time Value=\"0.125\"/>"), 1);
}

// The temporal collection is the domain's only grid (ParaView shows one dataset; meshio's
// TimeSeriesReader takes the first frame's grid as its mesh).
TEST(Xdmf, OneTemporalCollectionOfUniformGrids) {
  const std::string xdmf = xdmf_document(two_frames(true, true));
  EXPECT_EQ(testing::count_of(xdmf, "<Grid "), 3);
  EXPECT_EQ(xdmf.find("<Grid Name=\"frames\" GridType=\"Collection\" CollectionType=\"Temporal\">"),
            xdmf.find("<Grid "));
  EXPECT_EQ(testing::count_of(xdmf, "GridType=\"Uniform\""), 2);
}

TEST(Xdmf, TopologyIsHexahedraFromMesh) {
  const std::string xdmf = xdmf_document(two_frames(false));
  EXPECT_EQ(testing::count_of(xdmf, "<Topology TopologyType=\"Hexahedron\" NumberOfElements=\"2\""), 2);
  EXPECT_EQ(testing::count_of(xdmf,
                              "Dimensions=\"2 8\" NumberType=\"Int\" Precision=\"8\" "
                              "Format=\"HDF\">result.h5:/mesh/hex8</DataItem>"),
            2);
  EXPECT_EQ(testing::count_of(xdmf, "result.h5:/mesh/nodes"), 2);  // reference_position
}

TEST(Xdmf, FieldsAreNodeAndCellAttributes) {
  EXPECT_EQ(xdmf_document(two_frames(false)).find("contact_pressure"), std::string::npos);
  EXPECT_EQ(xdmf_document(two_frames(false)).find("von_mises"), std::string::npos);
  const std::string xdmf = xdmf_document(two_frames(true, true));
  EXPECT_EQ(testing::xml_structure_error(xdmf), "");
  EXPECT_EQ(
      testing::count_of(xdmf, "<Attribute Name=\"displacement\" AttributeType=\"Vector\" Center=\"Node\">"),
      2);
  EXPECT_EQ(testing::count_of(
                xdmf, "<Attribute Name=\"contact_pressure\" AttributeType=\"Scalar\" Center=\"Node\">"),
            2);
  EXPECT_EQ(
      testing::count_of(xdmf, "<Attribute Name=\"von_mises\" AttributeType=\"Scalar\" Center=\"Cell\">"), 2);
  EXPECT_EQ(
      testing::count_of(xdmf, "<Attribute Name=\"cauchy_stress\" AttributeType=\"Tensor6\" Center=\"Cell\">"),
      2);
  EXPECT_EQ(testing::count_of(xdmf,
                              "Dimensions=\"2 6\" NumberType=\"Float\" Precision=\"8\" "
                              "Format=\"HDF\">result.h5:/frames/1/cauchy_stress</DataItem>"),
            1);
  EXPECT_EQ(testing::count_of(xdmf,
                              "Dimensions=\"16\" NumberType=\"Float\" Precision=\"8\" "
                              "Format=\"HDF\">result.h5:/frames/0/contact_pressure</DataItem>"),
            1);
}

// result_mesh.xdmf: one Uniform grid (meshio.read reads no collections) on the reference mesh.
TEST(Xdmf, MeshDocumentIsOneUniformGrid) {
  const std::string xdmf = xdmf_mesh_document(two_frames(true, true));
  EXPECT_EQ(testing::xml_structure_error(xdmf), "");
  EXPECT_EQ(testing::count_of(xdmf, "<Grid "), 1);
  EXPECT_NE(xdmf.find("Format=\"HDF\">result.h5:/mesh/nodes</DataItem>"), std::string::npos);
  EXPECT_NE(xdmf.find("<Attribute Name=\"body\" AttributeType=\"Scalar\" Center=\"Cell\">"),
            std::string::npos);
  EXPECT_NE(xdmf.find("<Attribute Name=\"node_body\" AttributeType=\"Scalar\" Center=\"Node\">"),
            std::string::npos);
  EXPECT_EQ(xdmf.find("/frames/"), std::string::npos);
}

// A file name with XML metacharacters shall be escaped, keeping the document well formed.
TEST(Xdmf, EscapesFileName) {
  XdmfLayout layout = two_frames(false);
  layout.h5_file = "a<b>&c.h5";
  const std::string xdmf = xdmf_document(layout);
  EXPECT_EQ(testing::xml_structure_error(xdmf), "");
  EXPECT_NE(xdmf.find("a&lt;b&gt;&amp;c.h5:/frames/0/position"), std::string::npos);
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
