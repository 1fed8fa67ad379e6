// The one table of series (core/run/series_table.hpp): which series a scene gets, in which order, how a
// step fills them, and that the shapes the next issues need ([S,k,3], [S,k]) go through the layout, the
// HDF5 file and both text forms. The documents that list the series are held to the table.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/output/result_reader.hpp"
#include "core/output/result_writer.hpp"
#include "core/run/series_table.hpp"

namespace stoss::run {
namespace {

namespace fs = std::filesystem;

model::Model model_with(std::vector<std::string> effects, int pairs, bool smooth = false) {
  model::Model m;
  m.effects = std::move(effects);
  for (int k = 0; k < pairs; ++k) {
    model::ContactPair pair;
    pair.master_surface = smooth ? model::MasterSurface::smooth : model::MasterSurface::faceted;
    m.contact.push_back(pair);
  }
  return m;
}

std::vector<std::string> names(const model::SeriesLayout& layout) {
  std::vector<std::string> out;
  for (const auto& s : layout.series) out.push_back(s.name);
  return out;
}

TEST(SeriesTable, AContactFreeSceneGetsTheEnergiesMomentaAndSolverSeriesInOrder) {
  const SeriesRows rows(model_with({"inertia", "elasticity"}, 0));
  EXPECT_EQ(names(rows.layout()),
            (std::vector<std::string>{"kinetic_energy", "strain_energy", "total_energy", "linear_momentum",
                                      "angular_momentum", "newton_iterations", "residual_norm",
                                      "step_seconds", "substeps", "step_size", "rejected_steps"}));
  EXPECT_EQ(rows.layout().row_size(), 15);
}

TEST(SeriesTable, GravityFrictionAndASmoothMasterAddTheirSeriesWhereTheDocsListThem) {
  const SeriesRows rows(model_with({"inertia", "elasticity", "gravity", "contact_frictional"}, 1, true));
  EXPECT_EQ(names(rows.layout()), (std::vector<std::string>{"kinetic_energy",
                                                            "strain_energy",
                                                            "potential_energy",
                                                            "total_energy",
                                                            "dissipated_energy",
                                                            "linear_momentum",
                                                            "angular_momentum",
                                                            "active_contacts",
                                                            "max_penetration",
                                                            "contact_energy_jump",
                                                            "face_switches",
                                                            "unprojected_nodes",
                                                            "max_faceted_penetration",
                                                            "slipping_contacts",
                                                            "contact_force",
                                                            "contact_area",
                                                            "newton_iterations",
                                                            "residual_norm",
                                                            "step_seconds",
                                                            "substeps",
                                                            "step_size",
                                                            "rejected_steps"}));
  EXPECT_TRUE(rows.layout().series.at(7).integer) << "active_contacts is a count (int32)";
  EXPECT_FALSE(rows.layout().series.at(8).integer) << "max_penetration is a length";
}

// Every value of a row comes from the measures its column names, at the layout's offset.
TEST(SeriesTable, ARowIsFilledFromTheStepsMeasuresAtTheLayoutsOffsets) {
  const SeriesRows rows(model_with({"inertia", "elasticity", "contact_frictionless"}, 2));
  Balance b;
  b.kinetic = 1.5, b.strain = 0.25, b.contact = 0.125;
  b.linear = {1, 2, 3};
  b.angular = {-4, -5, -6};
  ContactRow c;
  c.active = 7, c.switches = 2, c.unprojected = 1, c.max_penetration = 1e-3, c.energy_jump = -2e-4;
  time::ReducedStep newton;
  newton.iterations = 9, newton.substeps = 2, newton.residuals = {1, 1e-11};
  const model::StepRow row = rows.row(12, 0.12, {b, c, &newton, 0.5, 0.0125, 3});
  const model::SeriesLayout& l = rows.layout();
  const auto at = [&](const char* name, int k = 0) { return row.values.at(l.index_of(name) + k); };
  EXPECT_EQ(row.step, 12);
  EXPECT_EQ(row.time, 0.12);
  ASSERT_EQ(static_cast<int>(row.values.size()), l.row_size());
  EXPECT_EQ(at("total_energy"), 1.875) << "kinetic + strain + penalty energy";
  EXPECT_EQ(at("linear_momentum", 2), 3);
  EXPECT_EQ(at("angular_momentum", 0), -4);
  EXPECT_EQ(at("active_contacts"), 7);
  EXPECT_EQ(at("contact_energy_jump"), -2e-4);
  EXPECT_EQ(at("face_switches"), 2);
  EXPECT_EQ(at("unprojected_nodes"), 1);
  EXPECT_EQ(at("newton_iterations"), 9);
  EXPECT_EQ(at("residual_norm"), 1e-11);
  EXPECT_EQ(at("step_seconds"), 0.5);
  EXPECT_EQ(at("substeps"), 2);
  EXPECT_EQ(at("step_size"), 0.0125);
  EXPECT_EQ(at("rejected_steps"), 3);
  const model::StepRow first = rows.row(0, 0, {b, c, nullptr, 0.0});
  EXPECT_EQ(first.values.at(l.index_of("newton_iterations")), 0);
  EXPECT_EQ(first.values.at(l.index_of("step_size")), 0) << "row 0 is no step";
  EXPECT_EQ(first.values.at(l.index_of("rejected_steps")), 0);
  EXPECT_EQ(first.values.at(l.index_of("substeps")), 1) << "row 0 is one (no) step";
}

// contact_force and contact_area have one item per pair, filled from the step's per-pair measures, and are
// 0 in row 0 (no measures given).
TEST(SeriesTable, ThePairsForcesAndAreasFillOneItemEach) {
  const SeriesRows rows(model_with({"inertia", "elasticity", "contact_frictionless"}, 2));
  const model::SeriesLayout& l = rows.layout();
  const Balance b;
  const ContactRow c;
  const std::vector<Eigen::Vector3d> forces = {{1, 2, 3}, {-4, 5, -6}};
  const std::vector<double> areas = {0.25, 0.5};
  StepMeasures measures{b, c, nullptr, 0};
  measures.contact_forces = &forces;
  measures.contact_areas = &areas;
  const model::StepRow row = rows.row(1, 0.1, measures);
  const int f = l.index_of("contact_force"), a = l.index_of("contact_area");
  ASSERT_GE(f, 0);
  ASSERT_GE(a, 0);
  EXPECT_EQ(std::vector<double>(row.values.begin() + f, row.values.begin() + f + 6),
            (std::vector<double>{1, 2, 3, -4, 5, -6}));
  EXPECT_EQ(std::vector<double>(row.values.begin() + a, row.values.begin() + a + 2),
            (std::vector<double>{0.25, 0.5}));
  const model::StepRow first = rows.row(0, 0, {b, c, nullptr, 0});
  for (int k = 0; k < 6; ++k) EXPECT_EQ(first.values.at(f + k), 0) << "row 0 is 0";
  for (int k = 0; k < 2; ++k) EXPECT_EQ(first.values.at(a + k), 0);
  EXPECT_LT(SeriesRows(model_with({"inertia"}, 0)).layout().index_of("contact_force"), 0)
      << "absent without contact";
}

// A synthetic per-pair vector series (as reaction_force and contact_force are) and a per-pair scalar
// (as contact_area): one row each, k = the scene's pairs.
int pair_count(const model::Model& m) {
  return static_cast<int>(m.contact.size());
}
const SeriesColumn synthetic[] = {
    {"kinetic_energy", Shape::scalar, false, Presence::always,
     [](const StepMeasures& s, int, double* v) { v[0] = s.balance.kinetic; }},
    {"pair_force", Shape::item_vectors, false, Presence::contact,
     [](const StepMeasures& s, int k, double* v) {
       for (int i = 0; i < k; ++i)
         for (int c = 0; c < 3; ++c) v[3 * i + c] = 10 * i + c + s.balance.kinetic;
     },
     pair_count},
    {"pair_area", Shape::item_scalars, false, Presence::contact,
     [](const StepMeasures&, int k, double* v) {
       for (int i = 0; i < k; ++i) v[i] = 0.5 * i;
     },
     pair_count},
    {"pair_closed", Shape::scalar, true, Presence::contact,
     [](const StepMeasures&, int, double* v) { v[0] = 3; }},
};

TEST(SeriesTable, AnItemSeriesTakesItsCountFromTheScene) {
  const SeriesRows rows(model_with({"inertia", "contact_frictionless"}, 2), synthetic);
  const model::SeriesSpec& force = rows.layout().series.at(1);
  EXPECT_EQ(force.name, "pair_force");
  EXPECT_EQ(force.components, 6);
  EXPECT_EQ(force.items, 2);
  EXPECT_EQ(force.row_shape(), (std::vector<int>{2, 3}));
  EXPECT_EQ(rows.layout().series.at(2).row_shape(), (std::vector<int>{2}));
  EXPECT_EQ(model::csv_columns(force),
            (std::vector<std::string>{"pair_force_0_x", "pair_force_0_y", "pair_force_0_z", "pair_force_1_x",
                                      "pair_force_1_y", "pair_force_1_z"}));
  EXPECT_EQ(model::csv_columns(rows.layout().series.at(2)),
            (std::vector<std::string>{"pair_area_0", "pair_area_1"}));
  Balance b;
  b.kinetic = 0.25;
  const ContactRow c;
  const model::StepRow row = rows.row(1, 0.1, {b, c, nullptr, 0});
  EXPECT_EQ(row.values, (std::vector<double>{0.25, 0.25, 1.25, 2.25, 10.25, 11.25, 12.25, 0, 0.5, 3}));
  EXPECT_EQ(model::row_json(force, row.values.data() + 1).dump(), "[[0.25,1.25,2.25],[10.25,11.25,12.25]]");
  EXPECT_EQ(SeriesRows(model_with({"inertia"}, 0), synthetic).layout().row_size(), 1)
      << "absent without contact";
}

TEST(SeriesTable, AnItemShapeWithoutACountIsRefused) {
  const SeriesColumn broken[] = {
      {"pair_force", Shape::item_vectors, false, Presence::always, [](const StepMeasures&, int, double*) {}}};
  EXPECT_THROW(SeriesRows(model_with({}, 1), broken), std::logic_error);
}

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("stoss_series_table_" + std::to_string(::getpid()));
  TempDir() { fs::remove_all(path); }
  ~TempDir() { fs::remove_all(path); }
};

/// A model of one hex8 body and two contact pairs, enough for the writer.
model::Model one_cube_two_pairs() {
  model::Model m = model_with({"inertia", "elasticity", "contact_frictionless"}, 2);
  mesh::BodyMesh body;
  for (double z : {0.0, 1.0})
    for (auto [x, y] : {std::pair{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}})
      body.nodes.emplace_back(x, y, z);
  body.hex8.push_back({0, 1, 2, 3, 4, 5, 6, 7});
  m.mesh.add_body("cube", body);
  m.scene = {{"name", "cube"}};
  m.time = {model::Scheme::energy_momentum, 0.1, 0.2};
  return m;
}

// The [S,k,3] and [S,k] series reach the file with that shape, and the JSON and CSV of GET …/series
// give them as the table's text forms say.
TEST(SeriesTable, ItemSeriesGoThroughTheFileTheJsonAndTheCsv) {
  const TempDir dir;
  const model::Model m = one_cube_two_pairs();
  const SeriesRows rows(m, synthetic);
  output::ResultWriter writer(dir.path);
  writer.begin(m, rows.layout());
  Balance b;
  const ContactRow c;
  for (int s = 0; s < 3; ++s) {
    b.kinetic = s;
    writer.step(rows.row(s, 0.1 * s, {b, c, nullptr, 0}));
  }
  model::Frame frame{0, m.mesh.reference_positions(), Eigen::VectorXd::Zero(24), {}, {}, {}};
  writer.frame(frame);
  model::Summary done;
  done.completed = true;
  writer.end(done);
  const fs::path result = dir.path / output::result_file_name;
  const output::ResultFile file = output::ResultFile::open(result);
  EXPECT_EQ(file.series_spec("pair_force").row_shape(), (std::vector<int>{2, 3}));
  EXPECT_EQ(file.series_spec("pair_area").row_shape(), (std::vector<int>{2}));
  EXPECT_TRUE(file.series_spec("pair_closed").integer);
  const nlohmann::json json = output::series_json(result);
  EXPECT_EQ(json["pair_force"][2].dump(), "[[2.0,3.0,4.0],[12.0,13.0,14.0]]");
  EXPECT_EQ(json["pair_area"][1].dump(), "[0.0,0.5]");
  EXPECT_EQ(json["pair_closed"][0].dump(), "3");
  const std::string csv = output::series_csv(result);
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "time,kinetic_energy,pair_force_0_x,pair_force_0_y,pair_force_0_z,pair_force_1_x,pair_force_1_y,"
            "pair_force_1_z,pair_area_0,pair_area_1,pair_closed");
  EXPECT_NE(csv.find("\n0.2,2,2,3,4,12,13,14,0,0.5,3\n"), std::string::npos) << csv;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// docs/results.md's table of series lists each row of the table, with its type, shape and presence.
TEST(SeriesTable, TheResultsPageListsEverySeriesWithItsTypeAndPresence) {
  const std::string page = read_text(fs::path(STOSS_SOURCE_DIR) / "docs/results.md");
  for (const SeriesColumn& column : series_columns()) {
    const std::string row = "| `" + std::string(column.name) + "` | " + type_text(column) + " | " +
                            presence_text(column.presence) + " |";
    EXPECT_NE(page.find(row), std::string::npos) << "docs/results.md lacks the row " << row;
  }
}

// The OpenAPI description of GET /v1/jobs/{id}/series names every series, and only series of the table.
TEST(SeriesTable, TheOpenApiDescriptionOfSeriesNamesEverySeries) {
  const std::string spec = read_text(fs::path(STOSS_SOURCE_DIR) / "api/openapi.yaml");
  const size_t begin = spec.find("  /v1/jobs/{id}/series:");
  ASSERT_NE(begin, std::string::npos);
  const std::string route = spec.substr(begin, spec.find("\n  /v1/", begin + 1) - begin);
  for (const SeriesColumn& column : series_columns())
    EXPECT_NE(route.find("`" + std::string(column.name) + "`"), std::string::npos)
        << "api/openapi.yaml's series description does not name " << column.name;
}

// Every series a plot of the page needs or reads (s.<name>[i]) is one of the table's: a renamed series
// cannot leave a plot empty.
TEST(SeriesTable, ThePagesPlotsUseOnlySeriesOfTheTable) {
  const std::string page = read_text(fs::path(STOSS_SOURCE_DIR) / "server/web/stoss.js");
  const size_t begin = page.find("const PLOTS = [");
  ASSERT_NE(begin, std::string::npos) << "the plot list of server/web/stoss.js was not found";
  const std::string plots = page.substr(begin, page.find("\n];", begin) - begin);
  std::set<std::string> known;
  for (const SeriesColumn& column : series_columns()) known.insert(column.name);
  const std::regex needs(R"(needs: \[([^\]]*)\])"), quoted(R"('([a-z_]+)')"),
      read(R"(\b(?:s|first)\.([a-z_]+)\b)");
  int count = 0;
  for (auto m = std::sregex_iterator(plots.begin(), plots.end(), needs); m != std::sregex_iterator();
       ++m, ++count) {
    const std::string list = (*m)[1];
    for (auto n = std::sregex_iterator(list.begin(), list.end(), quoted); n != std::sregex_iterator(); ++n)
      EXPECT_TRUE(known.count((*n)[1])) << "server/web/stoss.js needs the unknown series " << (*n)[1];
  }
  for (auto m = std::sregex_iterator(plots.begin(), plots.end(), read); m != std::sregex_iterator(); ++m)
    EXPECT_TRUE(known.count((*m)[1])) << "server/web/stoss.js plots the unknown series " << (*m)[1];
  EXPECT_GE(count, 5) << "fewer plots than the page has";
}

}  // namespace
}  // namespace stoss::run
